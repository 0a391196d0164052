/*
 * test_capture.c - xgo-emu --capture and xgo-replay end to end.
 *
 * A session over the pty (reads while the robot walks, writes, stray bytes,
 * a bad checksum, a rejected write, a hang-up mid-frame, the diagnostic
 * block), then SIGKILL: the capture must hold every byte the test sent and
 * received, in order, in whole records; xgo-replay must find every reply
 * identical; a capture with one reply byte changed must be reported at that
 * record, tick and frame; --record writes the motion log. The capture and
 * the frames the test sent and received are left for the Wireshark test
 * (test_wireshark, FIXTURES) in XGO_FIXTURE_DIR.
 */
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "emu_process.h"
#include "pcap.h"
#include "serial_port.h"
#include "test_clock.h"
#include "unity.h"
#include "xgo/protocol.h"

#if !defined(XGO_EMU_PATH) || !defined(XGO_REPLAY_PATH) || !defined(XGO_FIXTURE_DIR)
#error "XGO_EMU_PATH, XGO_REPLAY_PATH and XGO_FIXTURE_DIR must be defined"
#endif

#define START_MS 5000
#define REPLY_MS 1000
#define MAX_BYTES 8192

static xgo_test_emu_t g_emu, g_run;
static char g_capture[256];
static uint8_t g_sent[MAX_BYTES], g_got[MAX_BYTES];
static size_t g_sent_len, g_got_len;
static FILE *g_expect; /* frames as the dissector must show them */

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    xgo_test_emu_init(&g_run);
}

void tearDown(void)
{
    xgo_test_emu_kill(&g_run);
    xgo_test_emu_kill(&g_emu);
}

/* "dir|0xTT|0xAA|name|dd dd|good": one frame as tshark prints its fields. */
static void expect_frame(int dir, const uint8_t *frame, const char *name, const char *status)
{
    size_t i, n = (size_t)frame[2] - XGO_FRAME_OVERHEAD;
    fprintf(g_expect, "%d|0x%02x|0x%02x|%s|", dir, frame[3], frame[4], name);
    for (i = 0; i < n; i++) {
        fprintf(g_expect, i ? " %02x" : "%02x", frame[5 + i]);
    }
    fprintf(g_expect, "|%s\n", status);
}

static void send_bytes(int fd, const uint8_t *b, size_t n)
{
    TEST_ASSERT_EQUAL_INT(0, xgo_test_port_write(fd, b, n, REPLY_MS));
    TEST_ASSERT_TRUE(g_sent_len + n <= MAX_BYTES);
    memcpy(g_sent + g_sent_len, b, n);
    g_sent_len += n;
}

/* A frame built by hand (the test's own checksum, not the core's encoder). */
static size_t frame(uint8_t type, uint8_t addr, const uint8_t *data, size_t n, uint8_t *out)
{
    unsigned sum = (unsigned)(n + 8) + type + addr;
    size_t i;
    out[0] = 0x55;
    out[1] = 0x00;
    out[2] = (uint8_t)(n + 8);
    out[3] = type;
    out[4] = addr;
    for (i = 0; i < n; i++) {
        out[5 + i] = data[i];
        sum += data[i];
    }
    out[5 + n] = (uint8_t)(~sum & 0xFFu);
    out[6 + n] = 0x00;
    out[7 + n] = 0xAA;
    return n + 8;
}

static void write_regs(int fd, uint8_t addr, const uint8_t *data, size_t n, const char *name)
{
    uint8_t f[XGO_FRAME_MAX_LEN];
    size_t len = frame(0x00, addr, data, n, f);
    send_bytes(fd, f, len);
    expect_frame(0, f, name, "good");
    xgo_test_sleep_ms(20);
}

/* A read and its reply, both noted; the reply is checked by hand. */
static void read_regs(int fd, uint8_t addr, uint8_t count, const char *name)
{
    uint8_t f[16], reply[XGO_FRAME_MAX_LEN];
    size_t len = frame(0x02, addr, &count, 1, f), got;
    send_bytes(fd, f, len);
    expect_frame(0, f, name, "good");
    got = xgo_test_port_read(fd, reply, (size_t)count + 8u, REPLY_MS);
    TEST_ASSERT_EQUAL_UINT((size_t)count + 8u, got);
    TEST_ASSERT_EQUAL_HEX8(0x12, reply[3]);
    TEST_ASSERT_EQUAL_HEX8(addr, reply[4]);
    memcpy(g_got + g_got_len, reply, got);
    g_got_len += got;
    expect_frame(1, reply, name, "good");
}

/* The session: every kind of traffic a capture must keep. */
static void session(void)
{
    static const uint8_t walk[3] = {0xFF, 0x80, 0xA0};
    static const uint8_t stray[5] = {'h', 'e', 'l', 'l', 'o'};
    static const uint8_t partial[4] = {0x55, 0x00, 0x09, 0x02};
    uint8_t bad[16], battery = 5;
    int fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    read_regs(fd, 0x02, 1, "version");
    write_regs(fd, 0x30, walk, 3, "vx");
    xgo_test_sleep_ms(150); /* the robot walks: replies depend on the ticks */
    read_regs(fd, 0x50, 12, "servo11");
    read_regs(fd, 0x64, 4, "imu_yaw");
    send_bytes(fd, stray, sizeof stray);
    frame(0x02, 0x30, walk, 1, bad);
    bad[6] ^= 0x01; /* a checksum one off */
    send_bytes(fd, bad, 9);
    expect_frame(0, bad, "vx", "bad");
    read_regs(fd, 0x30, 1, "vx");
    write_regs(fd, 0x01, &battery, 1, "battery"); /* read-only: rejected, counted */
    send_bytes(fd, partial, sizeof partial);      /* then the host hangs up */
    xgo_test_sleep_ms(30);
    close(fd);
    xgo_test_sleep_ms(60);
    fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    read_regs(fd, 0xC4, 60, "diag");
    read_regs(fd, 0x00, 1, "mode");
    close(fd);
}

static void collect(uint8_t dir_a, uint8_t dir_b, uint8_t *out, size_t *len, unsigned long *records,
                    unsigned long *hangups)
{
    static xgo_host_pcap_reader_t r;
    xgo_host_pcap_record_t rec;
    char err[256];
    int got;
    *len = 0;
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(&r, g_capture, err, sizeof err));
    while ((got = xgo_host_pcap_next(&r, &rec, err, sizeof err)) == 1) {
        if (rec.number == 1) {
            TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_NOTE, rec.dir);
            TEST_ASSERT_EQUAL_STRING_LEN("xgo-emu ", (const char *)rec.bytes, 8);
        }
        if ((rec.dir == dir_a || rec.dir == dir_b) && *len + rec.n <= MAX_BYTES) {
            memcpy(out + *len, rec.bytes, rec.n);
            *len += rec.n;
        }
        *hangups += rec.dir == XGO_PCAP_HANGUP;
        *records = rec.number;
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, got, err); /* every record whole */
    xgo_host_pcap_close_reader(&r);
}

static int run(const char *exe, ...)
{
    const char *args[16];
    size_t n = 0;
    va_list ap;
    va_start(ap, exe);
    while (n < 15 && (args[n] = va_arg(ap, const char *)) != NULL) {
        n++;
    }
    va_end(ap);
    args[n] = NULL;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_run, exe, args, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_run, 30000));
    TEST_ASSERT_TRUE(WIFEXITED(g_run.status));
    return WEXITSTATUS(g_run.status);
}

/* ---------------------------------------------------------------- tests */

static void test_capture_holds_every_byte_even_after_sigkill(void)
{
    const char *args[] = {"--capture", g_capture, NULL};
    static uint8_t in[MAX_BYTES], out[MAX_BYTES];
    size_t in_len, out_len;
    unsigned long records = 0, hangups = 0, hangups_again = 0;
    char path[300];
    snprintf(path, sizeof path, "%s/capture_fixture.expect", XGO_FIXTURE_DIR);
    g_expect = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(g_expect);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, START_MS));
    session();
    fclose(g_expect);
    xgo_test_sleep_ms(50);
    TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGKILL)); /* no chance to flush or close */
    (void)xgo_test_emu_wait(&g_emu, START_MS);
    collect(XGO_PCAP_HOST_TO_BOARD, XGO_PCAP_HOST_TO_BOARD, in, &in_len, &records, &hangups);
    TEST_ASSERT_EQUAL_UINT(g_sent_len, in_len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(g_sent, in, g_sent_len);
    collect(XGO_PCAP_BOARD_TO_HOST, XGO_PCAP_DISCARDED, out, &out_len, &records, &hangups_again);
    TEST_ASSERT_EQUAL_UINT(g_got_len, out_len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(g_got, out, g_got_len);
    TEST_ASSERT_EQUAL_UINT(2, hangups); /* the session closed the port twice */
    TEST_ASSERT_EQUAL_UINT(hangups, hangups_again);
}

static void test_replay_finds_every_reply_identical(void)
{
    char expect[64];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run(XGO_REPLAY_PATH, g_capture, NULL), g_run.err);
    snprintf(expect, sizeof expect, "identical: %lu reply bytes", (unsigned long)g_got_len);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_run.out, expect), g_run.out);
}

/* Changes byte `at` of the first board->host record holding reply frame
 * `nth` (1-based), writing the altered copy to path; returns that record's
 * number and its time since the first record. */
static unsigned long alter_reply(unsigned nth, size_t at, const char *path, uint64_t *t_us)
{
    static xgo_host_pcap_reader_t r;
    xgo_host_pcap_record_t rec;
    char err[256];
    unsigned frames = 0;
    uint64_t origin = 0;
    long offset = 24; /* file header */
    unsigned long number = 0;
    FILE *f;
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(&r, g_capture, err, sizeof err));
    while (number == 0 && xgo_host_pcap_next(&r, &rec, err, sizeof err) == 1) {
        origin = rec.number == 1 ? rec.wall_us : origin;
        if (rec.dir == XGO_PCAP_BOARD_TO_HOST && rec.n > 0 && rec.bytes[0] == 0x55 && ++frames == nth) {
            number = rec.number;
            *t_us = rec.wall_us - origin;
            offset += 16 + 5 + (long)at;
            break;
        }
        offset += 16 + 5 + (long)rec.n;
    }
    xgo_host_pcap_close_reader(&r);
    TEST_ASSERT_TRUE(number > 0);
    {
        char cmd[600];
        snprintf(cmd, sizeof cmd, "cp '%s' '%s'", g_capture, path);
        TEST_ASSERT_EQUAL_INT(0, system(cmd));
    }
    f = fopen(path, "r+b");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(0, fseek(f, offset, SEEK_SET));
    {
        int c = fgetc(f);
        TEST_ASSERT_EQUAL_INT(0, fseek(f, offset, SEEK_SET));
        fputc(c ^ 0x01, f);
    }
    fclose(f);
    return number;
}

static void test_replay_reports_the_first_difference(void)
{
    char path[300], expect[160];
    uint64_t t_us = 0;
    unsigned long record;
    snprintf(path, sizeof path, "%s/capture_altered.pcap", XGO_FIXTURE_DIR);
    /* reply frame 2 (the twelve servos while walking), its data byte 3 */
    record = alter_reply(2, 5 + 3, path, &t_us);
    TEST_ASSERT_EQUAL_INT(1, run(XGO_REPLAY_PATH, path, NULL));
    snprintf(expect, sizeof expect, "xgo-replay: first difference at %lu.%06lu s (record %lu, board tick ",
             (unsigned long)(t_us / 1000000u), (unsigned long)(t_us % 1000000u), record);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_run.err, expect), g_run.err);
    /* reply frame 2, its byte 8: the first 9 reply bytes (frame 1) came before */
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_run.err, "), reply frame 2, reply byte 17 (byte 8 of the frame):\n"),
                                 g_run.err);
    /* both sides over the frame's 20 bytes: equal but for that byte */
    {
        const char *cap = strstr(g_run.err, "  capture: 55 00 14 12 50 ");
        const char *rep = strstr(g_run.err, "  replay:  55 00 14 12 50 ");
        TEST_ASSERT_NOT_NULL(cap);
        TEST_ASSERT_NOT_NULL(rep);
        TEST_ASSERT_EQUAL_STRING_LEN(cap + 11, rep + 11, 3 * 8);            /* bytes 0..7 */
        TEST_ASSERT_TRUE(strncmp(cap + 11 + 3 * 8, rep + 11 + 3 * 8, 2) != 0); /* byte 8 */
        TEST_ASSERT_EQUAL_STRING_LEN(cap + 11 + 3 * 9, rep + 11 + 3 * 9, 3 * 11 - 1);
    }
    TEST_ASSERT_EQUAL_STRING("", g_run.out);
}

static void test_replay_writes_the_motion_log(void)
{
    char path[300], line[4096];
    unsigned long rows = 0, ticks = 0;
    const char *p;
    FILE *f;
    snprintf(path, sizeof path, "%s/replay_motion.csv", XGO_FIXTURE_DIR);
    TEST_ASSERT_EQUAL_INT(0, run(XGO_REPLAY_PATH, "--record", path, g_capture, NULL));
    p = strstr(g_run.out, " ticks)");
    TEST_ASSERT_NOT_NULL(p);
    while (p > g_run.out && p[-1] >= '0' && p[-1] <= '9') {
        p--;
    }
    ticks = strtoul(p, NULL, 10);
    f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_NOT_NULL(fgets(line, sizeof line, f));
    TEST_ASSERT_EQUAL_STRING_LEN("t_ms,mode,action,j11_deg,", line, 25);
    while (fgets(line, sizeof line, f) != NULL) {
        rows++;
    }
    fclose(f);
    TEST_ASSERT_TRUE(ticks > 100);
    TEST_ASSERT_EQUAL_UINT32(ticks, rows); /* a row per tick replayed */
}

/* The settings note carries the model: a Mini2 session (its arm moving)
 * replays on a Mini2. */
static void test_replay_takes_the_model_from_the_note(void)
{
    static const uint8_t arm[2] = {0x90, 0x60}; /* arm_x, arm_z */
    char path[300];
    const char *args[] = {"--profile", "mini2", "--capture", path, NULL};
    uint8_t reply[64];
    int fd;
    snprintf(path, sizeof path, "%s/capture_mini2.pcap", XGO_FIXTURE_DIR);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, START_MS));
    fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_write_regs(fd, 0x73, arm, 2, REPLY_MS));
    xgo_test_sleep_ms(100);
    TEST_ASSERT_EQUAL_UINT(8 + 12, xgo_test_read_reply(fd, 0x50, 12, reply, REPLY_MS));
    TEST_ASSERT_EQUAL_UINT(8 + 3, xgo_test_read_reply(fd, 0x5C, 3, reply, REPLY_MS)); /* claw, arm */
    TEST_ASSERT_EQUAL_UINT(8 + 1, xgo_test_read_reply(fd, 0x02, 1, reply, REPLY_MS));
    TEST_ASSERT_EQUAL_HEX8(0x03, reply[5]); /* a Mini2 answered */
    close(fd);
    TEST_ASSERT_TRUE(xgo_test_emu_stop(&g_emu, SIGTERM, START_MS));
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run(XGO_REPLAY_PATH, path, NULL), g_run.err);
    TEST_ASSERT_NOT_NULL(strstr(g_run.out, "identical: 40 reply bytes"));
    /* on a Mini the same requests get other answers: the model matters */
    TEST_ASSERT_EQUAL_INT(1, run(XGO_REPLAY_PATH, "--profile", "mini", path, NULL));
}

static void test_replay_misuse_and_bad_files(void)
{
    TEST_ASSERT_EQUAL_INT(2, run(XGO_REPLAY_PATH, NULL));
    TEST_ASSERT_EQUAL_STRING_LEN("xgo-replay: no capture given\nusage: xgo-replay", g_run.err, 46);
    TEST_ASSERT_EQUAL_INT(2, run(XGO_REPLAY_PATH, "--bogus", "x", g_capture, NULL));
    TEST_ASSERT_EQUAL_INT(2, run(XGO_REPLAY_PATH, "--record-hz", "5", g_capture, NULL));
    TEST_ASSERT_EQUAL_INT(1, run(XGO_REPLAY_PATH, "/nonexistent.pcap", NULL));
    TEST_ASSERT_EQUAL_STRING("xgo-replay: cannot open /nonexistent.pcap: No such file or directory\n",
                             g_run.err);
}

int main(void)
{
    snprintf(g_capture, sizeof g_capture, "%s/capture_fixture.pcap", XGO_FIXTURE_DIR);
    UNITY_BEGIN();
    RUN_TEST(test_capture_holds_every_byte_even_after_sigkill);
    RUN_TEST(test_replay_finds_every_reply_identical);
    RUN_TEST(test_replay_reports_the_first_difference);
    RUN_TEST(test_replay_writes_the_motion_log);
    RUN_TEST(test_replay_takes_the_model_from_the_note);
    RUN_TEST(test_replay_misuse_and_bad_files);
    return UNITY_END();
}
