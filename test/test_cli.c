/*
 * test_cli.c - xgo-cli end to end against xgo-emu over its pty: every
 * command, its exact output, the bytes it put into the registers (read back
 * by the test through the port, not through xgo-cli), bad arguments (exit 2,
 * one line + usage), an unplugged port and a port that never answers (exit
 * 1 with the timeout message), a board without a diagnostic block (a fake
 * board that answers every read with zeros), --json, --capture.
 * Real processes and time; every wait bounded.
 */
#include <fcntl.h>
#include <poll.h>
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
#include "xgo/board.h"
#include "xgo/protocol.h"
#include "xgo/regs.h"

#ifndef XGO_CLI_PATH
#error "XGO_CLI_PATH must name the xgo-cli executable"
#endif

#define START_MS 5000
#define RUN_MS 15000
#define REPLY_MS 1000

static xgo_test_emu_t g_emu; /* xgo-emu */
static xgo_test_emu_t g_cli; /* the xgo-cli run of the moment */
static char g_tmp[64];

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    xgo_test_emu_init(&g_cli);
    strcpy(g_tmp, "/tmp/xgo-cli-test-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(g_tmp));
}

void tearDown(void)
{
    char cmd[128];
    xgo_test_emu_kill(&g_cli);
    xgo_test_emu_kill(&g_emu);
    snprintf(cmd, sizeof cmd, "rm -rf %s", g_tmp);
    TEST_ASSERT_EQUAL_INT(0, system(cmd));
}

static void emu_start(const char *extra1, const char *extra2)
{
    const char *args[3] = {extra1, extra2, NULL};
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, START_MS));
}

/* Runs xgo-cli with the NULL-terminated words; returns its exit code. */
static int cli(const char *first, ...)
{
    const char *args[32];
    size_t n = 0;
    va_list ap;
    va_start(ap, first);
    for (args[n] = first; args[n] != NULL && n < 31; args[n] = va_arg(ap, const char *)) {
        n++;
    }
    va_end(ap);
    args[n] = NULL;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_cli, XGO_CLI_PATH, args, NULL));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_wait(&g_cli, RUN_MS), "xgo-cli did not finish");
    TEST_ASSERT_TRUE(WIFEXITED(g_cli.status));
    return WEXITSTATUS(g_cli.status);
}

/* The register bytes, read by the test itself through the port. */
static void port_read(uint8_t addr, uint8_t n, uint8_t *out)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    int fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    TEST_ASSERT_EQUAL_UINT((size_t)n + 8u, xgo_test_read_reply(fd, addr, n, reply, REPLY_MS));
    TEST_ASSERT_EQUAL_HEX8(addr, reply[4]);
    memcpy(out, reply + 5, n);
    close(fd);
}

static void port_write(uint8_t addr, const uint8_t *data, size_t n)
{
    uint8_t mode;
    int fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_write_regs(fd, addr, data, n, REPLY_MS));
    close(fd);
    port_read(0x00, 1, &mode); /* in order: the write is in */
}

static uint32_t frames_ok(void)
{
    uint8_t b[4];
    port_read(0xC4, 4, b);
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static size_t count(const char *text, const char *what)
{
    size_t n = 0;
    for (; (text = strstr(text, what)) != NULL; text++) {
        n++;
    }
    return n;
}

static size_t count_lines(const char *text)
{
    return count(text, "\n");
}

/* Misuse: exit 2, one line "xgo-cli: ..." then the usage. */
static void assert_usage_error(int rc, const char *message)
{
    const char *nl = strchr(g_cli.err, '\n');
    TEST_ASSERT_EQUAL_INT_MESSAGE(2, rc, g_cli.err);
    TEST_ASSERT_NOT_NULL(nl);
    TEST_ASSERT_EQUAL_STRING_LEN("xgo-cli: ", g_cli.err, 9);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.err, message), g_cli.err);
    TEST_ASSERT_TRUE_MESSAGE(strstr(g_cli.err, message) < nl, "message not on the first line");
    TEST_ASSERT_EQUAL_STRING_LEN("usage: xgo-cli", nl + 1, 14);
    TEST_ASSERT_EQUAL_STRING("", g_cli.out);
}

/* ---------------------------------------------------------------- read */

static void test_read_shows_physical_units(void)
{
    static const uint8_t fast[3] = {0xFF, 0x00, 0x80};
    emu_start(NULL, NULL);
    port_write(0x30, fast, 3);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "vx", NULL));
    TEST_ASSERT_EQUAL_STRING("0x30 vx 0xFF +25.00 cm/s\n", g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "0x30", "3", NULL));
    TEST_ASSERT_EQUAL_STRING("0x30 vx 0xFF +25.00 cm/s\n"
                             "0x31 vy 0x00 -18.00 cm/s\n"
                             "0x32 vyaw 0x80 0.00 deg/s\n",
                             g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "gait_type", NULL));
    TEST_ASSERT_EQUAL_STRING("0x09 gait_type 0x00 trot\n", g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "firmware", NULL));
    TEST_ASSERT_EQUAL_STRING("0x07 firmware 4D 2D 45 4D 55 2D 30 2E 31 00 \"M-EMU-0.1\"\n", g_cli.out);
}

/* The attitude as the vendor reads it: 4 bytes, float32 LE degrees. */
static void test_read_attitude_as_float(void)
{
    uint8_t pitch[4] = {0, 0, 0, 0};
    long long deadline;
    emu_start("--ground-tilt", "5,-2.5");
    /* the IMU reads the tilt from the first control tick on */
    deadline = xgo_test_now_ms() + START_MS;
    while (pitch[3] == 0 && xgo_test_now_ms() < deadline) {
        port_read(0x63, 4, pitch);
    }
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "imu_pitch", NULL));
    TEST_ASSERT_EQUAL_STRING("0x63 imu_pitch 00 00 20 C0 -2.50 deg\n", g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "imu_roll", "1", NULL));
    /* one byte: 1 LSB = 180/128 deg, 5 deg -> 0x84 = 5.625 deg */
    TEST_ASSERT_EQUAL_STRING("0x62 imu_roll 0x84 +5.63 deg\n", g_cli.out);
    /* the int16 view: 0.01 deg big-endian, 500 = 0x01F4 */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "imu_roll16", NULL));
    TEST_ASSERT_EQUAL_STRING("0x66 imu_roll16 01 F4 +5.00 deg\n", g_cli.out);
    /* the IMU block: its angles are the float view's */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "read", "imu_block", NULL));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.out, "deg/s, rpy +5.00 -2.50 +0.00 deg\n"), g_cli.out);
    TEST_ASSERT_EQUAL_STRING_LEN("0x65 imu_block ", g_cli.out, 15);
}

static void test_dump_lists_every_register(void)
{
    static const char *const some[] = {"0x00 mode 0x00 whole unit\n", "0x01 battery 0x64 100%\n",
                                       "0x35 body_z 0x80 97.59 mm\n", "0x5C servo_speed 0x80 306.16 deg/s\n",
                                       "0x80 period_x 0x00 off\n", "0xC8 bad_checksum 00 00 00 00 0\n"};
    size_t i, mini_rows = 0;
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "dump", NULL));
    /* every register of the core's table on the Mini, the diagnostic block
     * one line per counter */
    for (i = 0; i < xgo_reg_table_size(); i++) {
        char name[48];
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        snprintf(name, sizeof name, " %s ", d->name);
        if (xgo_reg_for_model(d, 0)) {
            mini_rows++;
            TEST_ASSERT_TRUE_MESSAGE(i + 1 == xgo_reg_table_size() || strstr(g_cli.out, name) != NULL, name);
        } else {
            TEST_ASSERT_NULL_MESSAGE(strstr(g_cli.out, name), name); /* the Mini2's arm */
        }
    }
    TEST_ASSERT_EQUAL_UINT(mini_rows - 1 + XGO_DIAG_COUNT, count_lines(g_cli.out));
    for (i = 0; i < sizeof some / sizeof some[0]; i++) {
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.out, some[i]), some[i]);
    }
}

/* ---------------------------------------------------------------- write */

static void test_write_physical_raw_and_words(void)
{
    uint8_t b[10];
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "write", "vx=12.5cm/s", "body_roll=-10deg",
                                 "gait_type=walk", "period_x=2.5s", "bt_name=Rex", "0x31=0x90",
                                 "body_x=0xA0A0", NULL));
    TEST_ASSERT_EQUAL_STRING("0x30 vx 0xBF +12.45 cm/s\n"
                             "0x36 body_roll 0x40 -9.96 deg\n"
                             "0x09 gait_type 0x01 walk\n"
                             "0x80 period_x 0x27 2.495 s\n"
                             "0x13 bt_name 52 65 78 \"Rex\"\n"
                             "0x31 vy 0x90 +2.33 cm/s\n"
                             "0x33 body_x 0xA0 +8.92 mm\n"
                             "0x34 body_y 0xA0 +4.97 mm\n",
                             g_cli.out);
    /* what the board holds, read by the test: 12.5 cm/s is nearest to byte
     * 0xBF (-25 + 191 * 50 / 255 = 12.45), -10 deg to 0x40 (-9.96), 2.5 s
     * to 0x27 (1.5 + 39 * 6.5 / 255 = 2.494) */
    /* turn_to's write view: one int16 big-endian heading */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "write", "turn_to=-90deg", NULL));
    TEST_ASSERT_EQUAL_STRING("0x3F turn_to FF A6 -90 deg\n", g_cli.out);
    port_read(0x40, 1, b);
    TEST_ASSERT_EQUAL_HEX8(0x80, b[0]); /* the second byte is not leg1_x's */
    port_read(0x30, 1, b);
    TEST_ASSERT_EQUAL_HEX8(0xBF, b[0]);
    port_read(0x36, 1, b);
    TEST_ASSERT_EQUAL_HEX8(0x40, b[0]);
    port_read(0x09, 1, b);
    TEST_ASSERT_EQUAL_HEX8(0x01, b[0]);
    port_read(0x80, 1, b);
    TEST_ASSERT_EQUAL_HEX8(0x27, b[0]);
    port_read(0x13, 3, b);
    TEST_ASSERT_EQUAL_MEMORY("Rex", b, 3);
    port_read(0x31, 4, b);
    TEST_ASSERT_EQUAL_HEX8(0x90, b[0]);
    TEST_ASSERT_EQUAL_HEX8(0xA0, b[2]);
    TEST_ASSERT_EQUAL_HEX8(0xA0, b[3]);
}

/* Refused before anything is sent: the board saw no frame from xgo-cli. */
static void test_write_refuses_bad_values(void)
{
    uint32_t before;
    emu_start(NULL, NULL);
    before = frames_ok();
    assert_usage_error(cli("-p", g_emu.pty, "--profile", "mini", "write", "vx=0x80", "vx=30cm/s", NULL),
                       "vx=30cm/s is out of range: -25.00 cm/s .. +25.00 cm/s on the mini");
    assert_usage_error(cli("-p", g_emu.pty, "write", "battery=5", NULL), "battery (0x01) is read-only");
    assert_usage_error(cli("-p", g_emu.pty, "write", "gait_type=7", NULL), "0x07 is not a value gait_type takes");
    assert_usage_error(cli("-p", g_emu.pty, "write", "vx=10deg", NULL), "vx takes cm/s, mm/s, m/s, not '10deg'");
    assert_usage_error(cli("-p", g_emu.pty, "write", "nosuch=1", NULL), "unknown register 'nosuch'");
    assert_usage_error(cli("-p", g_emu.pty, "write", "roll=0x80", NULL),
                       "ambiguous register 'roll': body_roll, period_roll");
    assert_usage_error(cli("-p", g_emu.pty, "write", "vx", NULL), "write needs REG=VALUE, not 'vx'");
    TEST_ASSERT_EQUAL_UINT32(before + 1, frames_ok()); /* only the test's own read */
    /* a unit narrows a name's part to the register that takes it */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "write", "roll=5deg", NULL));
    /* 5 deg: 0x9F (-20 + 159 * 40 / 255 = 4.94) is nearer than 0xA0 (5.10) */
    TEST_ASSERT_EQUAL_STRING("0x36 body_roll 0x9F +4.94 deg\n", g_cli.out);
}

/* ---------------------------------------------------------------- watch, action, diag */

static void test_watch_prints_rows_until_count_or_ctrl_c(void)
{
    const char *args[] = {"-p", NULL, "watch", "vx", "mode", NULL};
    long long deadline;
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "watch", "vx", "mode", "--hz", "20", "--count", "3", NULL));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, "    time_s                vx              mode\n"));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, "     0.000         0.00 cm/s        whole unit\n"));
    TEST_ASSERT_EQUAL_UINT(4, count_lines(g_cli.out)); /* the header and 3 rows */
    TEST_ASSERT_EQUAL_UINT(3, count(g_cli.out, " cm/s        whole unit\n"));
    /* Ctrl-C ends it with status 0 */
    args[1] = g_emu.pty;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_cli, XGO_CLI_PATH, args, NULL));
    deadline = xgo_test_now_ms() + RUN_MS;
    while (strstr(g_cli.out, "whole unit\n") == NULL && xgo_test_now_ms() < deadline) {
        (void)xgo_test_emu_wait(&g_cli, 20);
    }
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.out, "whole unit\n"), "no row before Ctrl-C");
    TEST_ASSERT_TRUE(xgo_test_emu_stop(&g_cli, SIGINT, RUN_MS));
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_cli.status));
}

static void test_action_starts_and_waits(void)
{
    uint8_t id;
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "action", "sit", NULL));
    TEST_ASSERT_EQUAL_STRING("action 12 sit: 5.000 s\n", g_cli.out);
    port_read(0x3E, 1, &id);
    TEST_ASSERT_EQUAL_UINT8(12, id); /* running */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "action", "255", "--wait", NULL));
    TEST_ASSERT_EQUAL_STRING("action 255 reset: 1.000 s, done\n", g_cli.out);
    port_read(0x3E, 1, &id);
    TEST_ASSERT_EQUAL_UINT8(0, id); /* over */
    assert_usage_error(cli("-p", g_emu.pty, "action", "fly", NULL), "action needs a preset");
    assert_usage_error(cli("-p", g_emu.pty, "action", "30", NULL), "action needs a preset");
}

static void test_diag_shows_the_parser_counters(void)
{
    static const uint8_t bad[9] = {0x55, 0x00, 0x09, 0x02, 0x30, 0x01, 0x00, 0x00, 0xAA};
    int fd;
    emu_start(NULL, NULL);
    fd = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_port_write(fd, bad, sizeof bad, REPLY_MS));
    close(fd);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "diag", NULL));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.out, "0xC4 frames_ok 01 00 00 00 1\n"), g_cli.out);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.out, "0xC8 bad_checksum 01 00 00 00 1\n"), g_cli.out);
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, "0xF0 tx_overflow 00 00 00 00 0\n"));
}

/* A fake board on a pty of the test's own: answers every read with zeros,
 * as a board without the diagnostic block would (a child process). */
static pid_t fake_board(char *slave, size_t size)
{
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    pid_t pid;
    TEST_ASSERT_TRUE(master >= 0);
    TEST_ASSERT_EQUAL_INT(0, grantpt(master));
    TEST_ASSERT_EQUAL_INT(0, unlockpt(master));
    snprintf(slave, size, "%s", ptsname(master));
    pid = fork();
    TEST_ASSERT_TRUE(pid >= 0);
    if (pid == 0) {
        uint8_t in[64];
        size_t have = 0;
        for (;;) {
            ssize_t k = read(master, in + have, sizeof in - have);
            if (k <= 0) {
                usleep(1000); /* no host yet (EIO) */
                continue;
            }
            have += (size_t)k;
            while (have >= 9) { /* whole read requests only, in this test */
                uint8_t zeros[XGO_FRAME_MAX_DATA] = {0}, out[XGO_FRAME_MAX_LEN];
                size_t n = xgo_frame_encode(XGO_TYPE_READ_REPLY, in[4], zeros, in[5], out, sizeof out);
                if (write(master, out, n) < 0) {
                    _exit(1);
                }
                memmove(in, in + 9, have - 9);
                have -= 9;
            }
        }
    }
    close(master);
    return pid;
}

static void test_diag_on_a_board_without_the_block(void)
{
    char slave[128];
    pid_t pid = fake_board(slave, sizeof slave);
    int rc = cli("-p", slave, "diag", NULL);
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    TEST_ASSERT_EQUAL_INT(1, rc);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_cli.err, "has no diagnostic block, as on a real robot's board"),
                                 g_cli.err);
    TEST_ASSERT_EQUAL_STRING("", g_cli.out);
}

/* ---------------------------------------------------------------- raw, checksum, decode */

static void test_raw_sends_exactly_and_fix_fills_in(void)
{
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "raw", "55", "00", "09", "02", "30", "01", "C3", "00", "AA", NULL));
    TEST_ASSERT_EQUAL_STRING("sent 55 00 09 02 30 01 C3 00 AA\n"
                             "   0.000000 tx reply 0x30 vx n=1 [80]\n",
                             g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "raw", "--fix", "5500000201010000AA", NULL));
    TEST_ASSERT_EQUAL_STRING("sent 55 00 09 02 01 01 F2 00 AA\n"
                             "   0.000000 tx reply 0x01 battery n=1 [64] battery=100%\n",
                             g_cli.out);
    /* a write is never answered */
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "raw", "55 00 09 00 30 ff c7 00 aa", NULL));
    TEST_ASSERT_EQUAL_STRING("sent 55 00 09 00 30 FF C7 00 AA\nreceived nothing\n", g_cli.out);
    assert_usage_error(cli("-p", g_emu.pty, "raw", "5G", NULL), "'5G' is not hex bytes");
    assert_usage_error(cli("-p", g_emu.pty, "raw", "--fix", "55", "00", "01", NULL), "--fix needs one whole frame");
}

static void test_checksum_offline(void)
{
    TEST_ASSERT_EQUAL_INT(0, cli("checksum", "02", "50", "0c", NULL));
    TEST_ASSERT_EQUAL_STRING("checksum 0x98\nframe 55 00 09 02 50 0C 98 00 AA\n", g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("checksum", "55 00 09 00 30 ff 00 00 aa", NULL));
    TEST_ASSERT_EQUAL_STRING("checksum 0xC7 (the frame given has LEN 0x09 and SUM 0x00: wrong)\n"
                             "frame 55 00 09 00 30 FF C7 00 AA\n",
                             g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("checksum", "55 00 09 00 30 ff c7 00 aa", NULL));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, "(the frame given is right)"));
    assert_usage_error(cli("checksum", "02", NULL), "checksum needs TYPE ADDR DATA");
}

static void write_text(const char *name, const void *data, size_t n, char *path, size_t size)
{
    FILE *f;
    snprintf(path, size, "%s/%s", g_tmp, name);
    f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT(n, fwrite(data, 1, n, f));
    fclose(f);
}

static void test_decode_hex_and_binary_streams(void)
{
    static const char hex[] = "55 00 09 02 50 0c 98 00 aa\n0x55,0x00,0x09,0x00,0x30,0xff,0xc7,0x00,0xaa\n"
                              "5500 0912 3080 3400 aa 55 00 09 00 30 ff 00 00 aa\n";
    static const uint8_t bin[] = {0x68, 0x69, 0x55, 0x00, 0x09, 0x00, 0x01, 0x05, 0xF0, 0x00, 0xAA, 0x55, 0x00};
    static const char expect_hex[] =
        "   0.000000 rx read 0x50 servo11 n=12\n"
        "   0.000000 rx write 0x30 vx n=1 [FF] vx=FF(+100%)\n"
        "   0.000000 tx reply 0x30 vx n=1 [80]\n"
        "   0.000000 drop bad checksum [55 00 09 00 30 FF 00 00 AA] checksum 00, expected C7\n"
        "   0.000000 drop noise n=8 [00 09 00 30 FF 00 00 AA]\n";
    char path[128];
    write_text("hex.txt", hex, sizeof hex - 1, path, sizeof path);
    TEST_ASSERT_EQUAL_INT(0, cli("decode", path, NULL));
    TEST_ASSERT_EQUAL_STRING(expect_hex, g_cli.out);
    write_text("bytes.bin", bin, sizeof bin, path, sizeof path);
    TEST_ASSERT_EQUAL_INT(0, cli("decode", path, NULL));
    TEST_ASSERT_EQUAL_STRING("   0.000000 drop noise n=2 [68 69]\n"
                             "   0.000000 rx write 0x01 battery n=1 [05] battery=05\n"
                             "   0.000000 drop timeout [55 00]\n"
                             "   0.000000 drop noise n=1 [00]\n", /* the rescan after it */
                             g_cli.out);
    TEST_ASSERT_EQUAL_INT(1, cli("decode", "/nonexistent/file", NULL));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.err, "xgo-cli: cannot open /nonexistent/file"));
}

/* ---------------------------------------------------------------- misuse, ports */

static void test_bad_arguments_exit_2(void)
{
    assert_usage_error(cli(NULL), "no command");
    assert_usage_error(cli("fly", NULL), "unknown command 'fly'");
    assert_usage_error(cli("--bogus", "read", "vx", NULL), "unknown option '--bogus'");
    assert_usage_error(cli("-p", NULL), "-p needs a value");
    assert_usage_error(cli("-p", "/dev/null", "read", NULL), "read needs REG|ADDR [N]");
    assert_usage_error(cli("-p", "/dev/null", "read", "vx", "0", NULL), "N must be 1..247");
    assert_usage_error(cli("-p", "/dev/null", "read", "0x30", "250", NULL), "N must be 1..247");
    assert_usage_error(cli("--baud", "12345", "read", "vx", NULL), "--baud must be a standard line speed");
    assert_usage_error(cli("--timeout", "0", "read", "vx", NULL), "--timeout must be 1..600000 ms");
    assert_usage_error(cli("--profile", "max", "read", "vx", NULL), "--profile must be mini, lite or mini2");
    assert_usage_error(cli("-p", "/dev/null", "watch", "--hz", "0", "vx", NULL), "--hz needs a number 1..100");
    unsetenv("XGO_PORT");
    assert_usage_error(cli("read", "vx", NULL), "no port: give -p PORT or set XGO_PORT");
    TEST_ASSERT_EQUAL_INT(0, cli("--help", NULL));
    TEST_ASSERT_EQUAL_STRING_LEN("usage: xgo-cli", g_cli.out, 14);
}

static void test_unplugged_port_exit_1(void)
{
    TEST_ASSERT_EQUAL_INT(1, cli("-p", "/dev/ttyUSB-not-there", "read", "vx", NULL));
    TEST_ASSERT_EQUAL_STRING("xgo-cli: cannot open /dev/ttyUSB-not-there: No such file or directory\n",
                             g_cli.err);
    TEST_ASSERT_EQUAL_INT(1, cli("-p", "/dev/null", "read", "vx", NULL));
    TEST_ASSERT_EQUAL_STRING("xgo-cli: /dev/null is not a serial port\n", g_cli.err);
}

/* A pty nobody serves: the request goes out, no reply ever comes. */
static void test_port_that_never_answers_exit_1(void)
{
    char expect[256];
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    const char *slave;
    long long t0;
    TEST_ASSERT_TRUE(master >= 0);
    TEST_ASSERT_EQUAL_INT(0, grantpt(master));
    TEST_ASSERT_EQUAL_INT(0, unlockpt(master));
    slave = ptsname(master);
    t0 = xgo_test_now_ms();
    TEST_ASSERT_EQUAL_INT(1, cli("-p", slave, "--timeout", "300", "read", "vx", NULL));
    TEST_ASSERT_TRUE(xgo_test_now_ms() - t0 >= 300);
    snprintf(expect, sizeof expect,
             "xgo-cli: no reply from %s within 300 ms to read 0x30 vx n=1 "
             "(sent 55 00 09 02 30 01 C3 00 AA)\n",
             slave);
    TEST_ASSERT_EQUAL_STRING(expect, g_cli.err);
    /* a write is confirmed by a read of the mode register: that times out */
    TEST_ASSERT_EQUAL_INT(1, cli("-p", slave, "--timeout", "200", "write", "vx=0xFF", NULL));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.err, "no reply from"));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.err, "to read 0x00 mode n=1"));
    TEST_ASSERT_EQUAL_STRING("", g_cli.out);
    close(master);
}

/* ---------------------------------------------------------------- --json, $XGO_PORT, --capture */

static void test_json_output(void)
{
    char expect[512];
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, cli("--json", "-p", g_emu.pty, "read", "vx", NULL));
    snprintf(expect, sizeof expect,
             "{\"ok\":true,\"port\":\"%s\",\"registers\":[{\"addr\":48,\"name\":\"vx\",\"bytes\":\"80\","
             "\"value\":0.0000,\"unit\":\"cm/s\",\"text\":\"0.00 cm/s\"}]}\n",
             g_emu.pty);
    TEST_ASSERT_EQUAL_STRING(expect, g_cli.out);
    TEST_ASSERT_EQUAL_INT(0, cli("--json", "checksum", "02", "50", "0c", NULL));
    TEST_ASSERT_EQUAL_STRING("{\"ok\":true,\"checksum\":152,\"frame\":\"55000902500C9800AA\"}\n",
                             g_cli.out);
    TEST_ASSERT_EQUAL_INT(1, cli("--json", "-p", "/dev/null", "read", "vx", NULL));
    TEST_ASSERT_EQUAL_STRING("{\"ok\":false,\"error\":\"/dev/null is not a serial port\"}\n", g_cli.out);
}

static void test_port_from_environment(void)
{
    emu_start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, setenv("XGO_PORT", g_emu.pty, 1));
    TEST_ASSERT_EQUAL_INT(0, cli("read", "battery", NULL));
    unsetenv("XGO_PORT");
    TEST_ASSERT_EQUAL_STRING("0x01 battery 0x64 100%\n", g_cli.out);
}

/* xgo-cli --capture: the exact bytes both ways, in order, as records. */
static void test_capture_records_both_directions(void)
{
    static xgo_host_pcap_reader_t r;
    static const uint8_t req[9] = {0x55, 0x00, 0x09, 0x02, 0x30, 0x01, 0xC3, 0x00, 0xAA};
    static const uint8_t reply[9] = {0x55, 0x00, 0x09, 0x12, 0x30, 0x80, 0x34, 0x00, 0xAA};
    xgo_host_pcap_record_t rec;
    uint8_t in[64], out[64];
    size_t n_in = 0, n_out = 0;
    char path[128], err[256];
    int got;
    emu_start(NULL, NULL);
    snprintf(path, sizeof path, "%s/cli.pcap", g_tmp);
    TEST_ASSERT_EQUAL_INT(0, cli("-p", g_emu.pty, "--capture", path, "read", "vx", NULL));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(&r, path, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(&r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_NOTE, rec.dir);
    while ((got = xgo_host_pcap_next(&r, &rec, err, sizeof err)) == 1) {
        TEST_ASSERT_EQUAL_HEX32(XGO_PCAP_TICK_UNKNOWN, rec.tick);
        if (rec.dir == XGO_PCAP_HOST_TO_BOARD && n_in + rec.n <= sizeof in) {
            memcpy(in + n_in, rec.bytes, rec.n);
            n_in += rec.n;
        } else if (rec.dir == XGO_PCAP_BOARD_TO_HOST && n_out + rec.n <= sizeof out) {
            memcpy(out + n_out, rec.bytes, rec.n);
            n_out += rec.n;
        }
    }
    xgo_host_pcap_close_reader(&r);
    TEST_ASSERT_EQUAL_INT(0, got);
    /* the read of vx, then of the model (0x02) for the units */
    TEST_ASSERT_EQUAL_UINT(18, n_in);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(req, in, 9);
    TEST_ASSERT_EQUAL_UINT(18, n_out);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(reply, out, 9);
    /* and xgo-cli decodes it */
    TEST_ASSERT_EQUAL_INT(0, cli("decode", path, NULL));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, " rx read 0x30 vx n=1\n"));
    TEST_ASSERT_NOT_NULL(strstr(g_cli.out, " tx reply 0x30 vx n=1 [80]\n"));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_read_shows_physical_units);
    RUN_TEST(test_read_attitude_as_float);
    RUN_TEST(test_dump_lists_every_register);
    RUN_TEST(test_write_physical_raw_and_words);
    RUN_TEST(test_write_refuses_bad_values);
    RUN_TEST(test_watch_prints_rows_until_count_or_ctrl_c);
    RUN_TEST(test_action_starts_and_waits);
    RUN_TEST(test_diag_shows_the_parser_counters);
    RUN_TEST(test_diag_on_a_board_without_the_block);
    RUN_TEST(test_raw_sends_exactly_and_fix_fills_in);
    RUN_TEST(test_checksum_offline);
    RUN_TEST(test_decode_hex_and_binary_streams);
    RUN_TEST(test_bad_arguments_exit_2);
    RUN_TEST(test_unplugged_port_exit_1);
    RUN_TEST(test_port_that_never_answers_exit_1);
    RUN_TEST(test_json_output);
    RUN_TEST(test_port_from_environment);
    RUN_TEST(test_capture_records_both_directions);
    return UNITY_END();
}
