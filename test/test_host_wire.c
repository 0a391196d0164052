/*
 * test_host_wire.c - what xgo-emu does with bytes on the wire under stress:
 * nothing a host sent may be lost to the emulator's own delays.
 *
 *   - a host that writes a long stream with one blocking write() while
 *     another thread reads the replies slowly: every request answered,
 *     every write applied (the held-back input is not silence on the line);
 *   - the emulator stopped (SIGSTOP) between the two halves of a request:
 *     the second half was waiting in the pty, so the request still counts;
 *   - more checks of the wire's edge cases follow the same pattern.
 *
 * Real processes, a real pty and real time; every wait is bounded, so a
 * broken emulator fails the test instead of hanging it.
 */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "test_clock.h"
#include "unity.h"
#include "xgo/board.h"
#include "xgo/protocol.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define EMU_START_TIMEOUT_MS 5000
#define EMU_EXIT_TIMEOUT_MS 5000
#define REPLY_TIMEOUT_MS 1000

static xgo_test_emu_t g_emu;
static int g_port = -1;
static char g_dir[64];
static char g_link[128];

/* ------------------------------------------------------------ helpers */

/* Starts xgo-emu --link g_link plus up to two more arguments. */
static void emu_start(const char *extra1, const char *extra2)
{
    const char *args[5] = {"--link", g_link, extra1, extra2, NULL};
    if (extra1 == NULL) {
        args[2] = extra2;
        args[3] = NULL;
    }
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT_MESSAGE(XGO_TEST_EMU_PTY_OK,
                                  xgo_test_emu_read_pty(&g_emu, EMU_START_TIMEOUT_MS),
                                  "no pty path on xgo-emu's stdout");
}

static void emu_stop(void)
{
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_stop(&g_emu, SIGTERM, EMU_EXIT_TIMEOUT_MS),
                             "xgo-emu ignored SIGTERM");
    TEST_ASSERT_TRUE(WIFEXITED(g_emu.status));
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_emu.status));
}

static int port_open(void)
{
    int fd = xgo_test_port_open_like_pyserial(g_link, B115200);
    TEST_ASSERT_TRUE_MESSAGE(fd >= 0, "cannot open the emulator's port");
    return fd;
}

static void port_write(int fd, const uint8_t *bytes, size_t n)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_port_write(fd, bytes, n, REPLY_TIMEOUT_MS),
                                  "write to the port failed or stalled");
}

/* Reads count registers at addr over the wire; the reply frame is checked. */
static void read_regs(int fd, uint8_t addr, uint8_t count, uint8_t *values)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    size_t len = (size_t)count + XGO_FRAME_OVERHEAD;
    TEST_ASSERT_EQUAL_INT_MESSAGE((int)len,
                                  (int)xgo_test_read_reply(fd, addr, count, reply,
                                                           REPLY_TIMEOUT_MS),
                                  "incomplete reply");
    TEST_ASSERT_EQUAL_HEX8(0x55, reply[0]);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, reply[3]);
    TEST_ASSERT_EQUAL_HEX8(addr, reply[4]);
    memcpy(values, reply + 5, count);
}

/* The board's diagnostic counters, read live over the wire. */
static void read_counters(int fd, uint32_t out[XGO_DIAG_COUNT])
{
    uint8_t raw[4 * XGO_DIAG_COUNT];
    unsigned i;
    read_regs(fd, XGO_REG_DIAG, (uint8_t)sizeof raw, raw);
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        const uint8_t *p = raw + 4 * i;
        out[i] = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                 (uint32_t)p[3] << 24;
    }
}

/* ------------------------------------------------------------ fixtures */

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    g_port = -1;
}

void tearDown(void)
{
    if (g_port >= 0) {
        close(g_port);
        g_port = -1;
    }
    xgo_test_emu_kill(&g_emu);
    unlink(g_link);
}

/* --------------------------------------- 1. held-back input is not silence */

enum {
    FLOOD_REQUESTS = 2000,
    FLOOD_COUNT = XGO_FRAME_MAX_DATA,                       /* read 0x00 n=247 */
    FLOOD_REPLY = FLOOD_COUNT + XGO_FRAME_OVERHEAD,         /* 255 bytes */
    FLOOD_WRITE = 2 + XGO_FRAME_OVERHEAD,                   /* 2-byte write to 0x30 */
    FLOOD_STEP = XGO_READ_REQUEST_LEN + FLOOD_WRITE,        /* 19 bytes per request pair */
    FLOOD_READ_CHUNK = 2048,
    FLOOD_READ_PERIOD_MS = 20,
    FLOOD_DEADLINE_MS = 30000,
    FLOOD_IDLE_MS = 1500 /* nothing more for this long: the rest was lost */
};

typedef struct flood_io_s {
    int fd;
    const uint8_t *bytes; /* writer */
    size_t n;
    int write_rc;
    uint8_t *buf; /* reader */
    size_t want;
    size_t got;
    long long deadline_ms;
} flood_io_t;

/* One blocking write() of the whole stream, as a careless host does. */
static void *flood_writer(void *arg)
{
    flood_io_t *io = arg;
    size_t done = 0;
    while (done < io->n) {
        ssize_t w = write(io->fd, io->bytes + done, io->n - done);
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w <= 0) {
            io->write_rc = -1;
            return NULL;
        }
        done += (size_t)w;
    }
    io->write_rc = 0;
    return NULL;
}

/* A slow reader: at most 2 KB every 20 ms, until everything or nothing more
 * arrives. */
static void *flood_reader(void *arg)
{
    flood_io_t *io = arg;
    long long last_byte_ms = xgo_test_now_ms();
    while (io->got < io->want && xgo_test_now_ms() < io->deadline_ms &&
           xgo_test_now_ms() - last_byte_ms < FLOOD_IDLE_MS) {
        size_t room = io->want - io->got;
        ssize_t r;
        xgo_test_sleep_ms(FLOOD_READ_PERIOD_MS);
        r = read(io->fd, io->buf + io->got, room < FLOOD_READ_CHUNK ? room : FLOOD_READ_CHUNK);
        if (r > 0) {
            io->got += (size_t)r;
            last_byte_ms = xgo_test_now_ms();
        }
    }
    return NULL;
}

static void flood_build(uint8_t *stream)
{
    size_t i;
    for (i = 0; i < FLOOD_REQUESTS; i++) {
        uint8_t *p = stream + i * FLOOD_STEP;
        const uint8_t speed[2] = {(uint8_t)(0x80 + (i & 1u)), 0x80};
        TEST_ASSERT_EQUAL_UINT(XGO_READ_REQUEST_LEN, xgo_test_read_request(0x00, FLOOD_COUNT, p));
        TEST_ASSERT_EQUAL_UINT(FLOOD_WRITE,
                               xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_VX, speed, 2,
                                                p + XGO_READ_REQUEST_LEN, FLOOD_WRITE));
    }
}

/* Every reply whole: header, length, type, address, checksum, tail. */
static void flood_check_replies(const uint8_t *r, size_t n)
{
    size_t i;
    TEST_ASSERT_EQUAL_UINT_MESSAGE((unsigned)(FLOOD_REQUESTS * FLOOD_REPLY), (unsigned)n,
                                   "replies lost");
    for (i = 0; i < FLOOD_REQUESTS; i++, r += FLOOD_REPLY) {
        TEST_ASSERT_EQUAL_HEX8(0x55, r[0]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[1]);
        TEST_ASSERT_EQUAL_HEX8(FLOOD_REPLY, r[2]);
        TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, r[3]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[4]);
        TEST_ASSERT_EQUAL_HEX8(xgo_frame_checksum(FLOOD_REPLY, XGO_TYPE_READ_REPLY, 0x00, r + 5,
                                                  FLOOD_COUNT),
                               r[FLOOD_REPLY - 3]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[FLOOD_REPLY - 2]);
        TEST_ASSERT_EQUAL_HEX8(0xAA, r[FLOOD_REPLY - 1]);
    }
}

/* The stream: 2000 x [read 0x00 n=247, write 0x30 two bytes] in one
 * blocking write, replies read 2 KB every 20 ms (~5 s). The emulator holds
 * input back while its output is full; that wait must not count as silence
 * on the line. */
static void test_slow_reader_loses_no_request_and_no_write(void)
{
    static uint8_t stream[FLOOD_REQUESTS * FLOOD_STEP];
    static uint8_t replies[FLOOD_REQUESTS * FLOOD_REPLY];
    flood_io_t io, wio;
    pthread_t writer, reader;
    uint32_t c[XGO_DIAG_COUNT];
    uint8_t speed[2];
    int wfd;

    flood_build(stream);
    emu_start(NULL, NULL);
    g_port = port_open();
    wfd = open(g_link, O_WRONLY | O_NOCTTY); /* blocking, shares the port's settings */
    TEST_ASSERT_TRUE(wfd >= 0);
    memset(&io, 0, sizeof io);
    io.fd = g_port;
    io.buf = replies;
    io.want = sizeof replies;
    io.deadline_ms = xgo_test_now_ms() + FLOOD_DEADLINE_MS;
    wio = io;
    wio.fd = wfd;
    wio.bytes = stream;
    wio.n = sizeof stream;
    wio.write_rc = -2;
    TEST_ASSERT_EQUAL_INT(0, pthread_create(&reader, NULL, flood_reader, &io));
    TEST_ASSERT_EQUAL_INT(0, pthread_create(&writer, NULL, flood_writer, &wio));
    pthread_join(reader, NULL);
    if (wio.write_rc == -2) {
        xgo_test_emu_kill(&g_emu); /* unblocks a writer stuck on a dead emulator */
    }
    pthread_join(writer, NULL);
    close(wfd);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, wio.write_rc, "the stream could not be written");
    flood_check_replies(replies, io.got);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 50));

    read_counters(g_port, c);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(2u * FLOOD_REQUESTS + 1u, c[XGO_DIAG_FRAMES_OK],
                                     "requests or writes lost");
    TEST_ASSERT_EQUAL_UINT32(0, c[XGO_DIAG_TIMEOUTS]);
    TEST_ASSERT_EQUAL_UINT32(0, c[XGO_DIAG_BYTES_DISCARDED]);
    read_regs(g_port, XGO_REG_VX, 2, speed);
    TEST_ASSERT_EQUAL_HEX8(0x80 + ((FLOOD_REQUESTS - 1) & 1), speed[0]); /* the last write */
    emu_stop();
}

/* The emulator stopped for 30 ms between the halves of a request (a
 * scheduler hiccup, a debugger): the second half waited in the pty, so the
 * line was never silent. Reads and writes, several rounds. */
static void test_stalled_emulator_loses_no_request(void)
{
    enum { ROUNDS = 6, SPLIT = 5 };
    uint32_t c[XGO_DIAG_COUNT];
    int i;
    emu_start(NULL, NULL);
    g_port = port_open();
    for (i = 0; i < ROUNDS; i++) {
        uint8_t frame[XGO_READ_REQUEST_LEN + 1];
        const uint8_t value = (uint8_t)(0x40 + i);
        size_t len;
        if (i % 2 == 0) {
            len = xgo_test_read_request(0x30, 1, frame);
        } else {
            len = xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_VX, &value, 1, frame, sizeof frame);
        }
        port_write(g_port, frame, SPLIT);
        xgo_test_sleep_ms(10); /* the emulator has read the first half */
        TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGSTOP));
        xgo_test_sleep_ms(30);
        port_write(g_port, frame + SPLIT, len - SPLIT);
        TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGCONT));
        if (i % 2 == 0) {
            uint8_t reply[XGO_FRAME_OVERHEAD + 1];
            TEST_ASSERT_EQUAL_INT_MESSAGE((int)sizeof reply,
                                          (int)xgo_test_port_read(g_port, reply, sizeof reply,
                                                                  REPLY_TIMEOUT_MS),
                                          "the stalled read request was lost");
            TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, reply[3]);
            TEST_ASSERT_EQUAL_HEX8(i == 0 ? 0x80 : 0x40 + i - 1, reply[5]);
        }
    }
    read_counters(g_port, c);
    TEST_ASSERT_EQUAL_UINT32(0, c[XGO_DIAG_TIMEOUTS]);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)ROUNDS + 1u, c[XGO_DIAG_FRAMES_OK]);
    emu_stop();
}

/* ------------------------- 5. a hang-up takes its partial frame with it */

/* With --timeout-ms 0 nothing else ever ends a partial frame: the part of a
 * request a host wrote before it hung up must not swallow the next
 * session's requests. It is dropped (drop reason "hang-up", counted) once
 * the hang-up is seen. */
static void test_hangup_discards_the_partial_frame(void)
{
    enum { REQUESTS = 20 };
    static const uint8_t partial[] = {0x55, 0x00, 0xFF, 0x00, 0x30}; /* a long write, begun */
    uint32_t c[XGO_DIAG_COUNT];
    char expect[64];
    int i, answered = 0;
    emu_start("--timeout-ms=0", "--trace");
    g_port = port_open();
    port_write(g_port, partial, sizeof partial);
    xgo_test_sleep_ms(20); /* read and fed */
    close(g_port);
    xgo_test_sleep_ms(50); /* the hang-up is seen within a tick */
    g_port = port_open();
    for (i = 0; i < REQUESTS; i++) {
        uint8_t reply[XGO_FRAME_OVERHEAD + 1];
        answered += xgo_test_read_reply(g_port, (uint8_t)(0x30 + i % 3), 1, reply, 100) ==
                    sizeof reply;
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(REQUESTS, answered, "requests swallowed by the old partial frame");
    read_counters(g_port, c);
    TEST_ASSERT_EQUAL_UINT32(1, c[XGO_DIAG_HANGUP_DISCARDS]);
    TEST_ASSERT_EQUAL_UINT32(sizeof partial, c[XGO_DIAG_BYTES_DISCARDED]);
    TEST_ASSERT_EQUAL_UINT32(REQUESTS + 1, c[XGO_DIAG_FRAMES_OK]);
    emu_stop();
    snprintf(expect, sizeof expect, " drop %s [55 00 FF 00 30]\n",
             xgo_drop_reason_name(XGO_DROP_HANGUP));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, expect), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  hangup_discards        1\n"), g_emu.err);
}

/* ------------------------------------ 6. --trace shows every rejected byte */

/* The sum of n= over all "drop noise n=" lines, and their number. */
static unsigned long noise_in_trace(const char *err, int *lines)
{
    unsigned long total = 0;
    const char *p = err;
    *lines = 0;
    while ((p = strstr(p, " drop noise n=")) != NULL) {
        p += strlen(" drop noise n=");
        total += strtoul(p, NULL, 10);
        (*lines)++;
    }
    return total;
}

/* Noise without a 55 00 header: counted in bytes_discarded and traced, the
 * first bytes shown; a bad checksum shows the one expected. */
static void test_trace_shows_noise_and_the_expected_checksum(void)
{
    static const char text[] = "hello, this is a terminal talking to the wrong port; "
                                "none of it is a frame at all!!..."; /* 86 bytes, no 0x55 */
    static const uint8_t bad_sum[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x99, 0x00, 0xAA};
    uint32_t c[XGO_DIAG_COUNT];
    uint8_t vx;
    int lines;
    TEST_ASSERT_EQUAL_UINT(86, sizeof text - 1);
    emu_start("--trace", NULL);
    g_port = port_open();
    port_write(g_port, (const uint8_t *)text, sizeof text - 1);
    read_regs(g_port, XGO_REG_VX, 1, &vx); /* still answered after the noise */
    port_write(g_port, bad_sum, sizeof bad_sum);
    read_counters(g_port, c);
    /* The bad frame: its 0x55 is dropped, the 8 bytes after it are searched
     * again for a header and skipped as noise. */
    TEST_ASSERT_EQUAL_UINT32(86 + 1 + 8, c[XGO_DIAG_BYTES_DISCARDED]);
    emu_stop();
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, " drop noise n=86 [68 65 6C 6C 6F 2C 20 74 "),
                                 g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, " drop noise n=8 [00 09 02 50 0C 99 00 AA]\n"),
                                 g_emu.err);
    TEST_ASSERT_EQUAL_UINT32(86 + 8, noise_in_trace(g_emu.err, &lines));
    TEST_ASSERT_NOT_NULL_MESSAGE(
        strstr(g_emu.err, " drop bad checksum [55 00 09 02 50 0C 99 00 AA] checksum 99, expected 98\n"),
        g_emu.err);
}

/* A flood of noise cannot drown stderr: at most one noise line per 10 ms,
 * and together the lines still account for every byte. */
static void test_noise_flood_is_traced_in_bounded_lines(void)
{
    enum { WRITES = 400, EACH = 50 };
    uint8_t noise[EACH];
    unsigned long total;
    long long t0, elapsed;
    int i, lines;
    for (i = 0; i < EACH; i++) {
        noise[i] = (uint8_t)('a' + i % 26);
    }
    emu_start("--trace", NULL);
    g_port = port_open();
    t0 = xgo_test_now_ms();
    for (i = 0; i < WRITES; i++) {
        port_write(g_port, noise, sizeof noise);
        if (i % 40 == 0) {
            xgo_test_sleep_ms(3);
        }
    }
    xgo_test_sleep_ms(50);
    emu_stop();
    elapsed = xgo_test_now_ms() - t0;
    total = noise_in_trace(g_emu.err, &lines);
    printf("noise flood: %d bytes in %lld ms traced in %d lines\n", WRITES * EACH, elapsed, lines);
    TEST_ASSERT_EQUAL_UINT32(WRITES * EACH, total);
    /* one line per 10 ms, plus the rest flushed at exit */
    TEST_ASSERT_TRUE_MESSAGE(lines <= elapsed / 10 + 2, "more than one noise line per 10 ms");
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  bytes_discarded        20000\n"), g_emu.err);
}

int main(void)
{
    int rc;
    strcpy(g_dir, "/tmp/xgo-wire-test-XXXXXX");
    if (mkdtemp(g_dir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(g_link, sizeof g_link, "%s/ttyXGO", g_dir);
    signal(SIGPIPE, SIG_IGN);

    UNITY_BEGIN();
    RUN_TEST(test_stalled_emulator_loses_no_request);
    RUN_TEST(test_slow_reader_loses_no_request_and_no_write);
    RUN_TEST(test_hangup_discards_the_partial_frame);
    RUN_TEST(test_trace_shows_noise_and_the_expected_checksum);
    RUN_TEST(test_noise_flood_is_traced_in_bounded_lines);
    rc = UNITY_END();

    rmdir(g_dir);
    return rc;
}
