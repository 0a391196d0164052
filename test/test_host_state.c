/*
 * test_host_state.c - xgo-emu's --state file.
 *
 * Two halves:
 *   - the state file module itself (src/host/state_file.c is compiled into
 *     this test): exact format, every truncation and every bit flip refused,
 *     field checks, atomic save, stale temporary files;
 *   - xgo-emu end to end (XGO_EMU_PATH, fork/exec, a real pty): a round trip
 *     of the Bluetooth name and the zero offsets across a restart, 200 kills
 *     at random points while the host renames as fast as it can, a damaged
 *     file refused.
 *
 * Waits are real time and all bounded: a broken emulator fails the test
 * instead of hanging it. About 15 s in all.
 */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "state_file.h"
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
#define KILL_ROUNDS 200
#define KILL_MAX_DELAY_US 30000

static char g_dir[64];   /* fresh temporary directory per test */
static char g_state[128]; /* g_dir/state */
static char g_err[128];   /* g_dir/emu.err: the emulator's stderr */

/* ------------------------------------------------------------ helpers */

/* Reads a whole (small) file; returns its length, -1 if it cannot be read. */
static long read_file(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "rb");
    size_t n;
    if (f == NULL) {
        return -1;
    }
    n = fread(buf, 1, size - 1, f);
    fclose(f);
    buf[n] = '\0';
    return (long)n;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT((unsigned)strlen(text), (unsigned)fwrite(text, 1, strlen(text), f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

/* CRC-32 as zlib computes it: an independent copy, to sign test files. */
static uint32_t crc32_zlib(const char *p, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    while (n-- > 0) {
        int k;
        crc ^= (uint8_t)*p++;
        for (k = 0; k < 8; k++) {
            crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
        }
    }
    return ~crc;
}

/* body + its "crc32=" line, into out. */
static void sign(const char *body, char *out, size_t size)
{
    snprintf(out, size, "%scrc32=%08lx\n", body, (unsigned long)crc32_zlib(body, strlen(body)));
}

/* Names in g_dir that start with "state.tmp.". */
static int count_tmp_files(char *last, size_t size)
{
    DIR *d = opendir(g_dir);
    struct dirent *e;
    int n = 0;
    TEST_ASSERT_NOT_NULL(d);
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, "state.tmp.", 10) == 0) {
            n++;
            snprintf(last, size, "%s", e->d_name);
        }
    }
    closedir(d);
    return n;
}

static void remove_dir_contents(void)
{
    DIR *d = opendir(g_dir);
    struct dirent *e;
    char path[512];
    if (d == NULL) {
        return;
    }
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        snprintf(path, sizeof path, "%s/%s", g_dir, e->d_name);
        if (unlink(path) != 0) {
            rmdir(path);
        }
    }
    closedir(d);
}

static xgo_board_nv_t nv_example(void)
{
    static const int32_t offsets[XGO_SERVO_COUNT] = {0, -1, 360000, -360000, 12345, 7,
                                                     -98765, 100, 0, 2, -3, 45000};
    xgo_board_nv_t nv;
    memset(&nv, 0, sizeof nv);
    memcpy(nv.bt_name, "Rex =9~", 7);
    memcpy(nv.zero_offset_mdeg, offsets, sizeof offsets);
    return nv;
}

static void assert_nv_equal(const xgo_board_nv_t *want, const xgo_board_nv_t *got)
{
    TEST_ASSERT_EQUAL_MEMORY(want->bt_name, got->bt_name, XGO_BT_NAME_LEN);
    TEST_ASSERT_EQUAL_MEMORY(want->zero_offset_mdeg, got->zero_offset_mdeg,
                             sizeof want->zero_offset_mdeg);
}

/* ------------------------------------------------------------ the child */

/* The child process and the port come from test/support; the assertions on
 * them are here. */
static xgo_test_emu_t g_emu; /* stderr goes to the file g_err; main() inits */
static int g_port = -1;

/* Starts xgo-emu with argv[1..] = args (NULL-terminated), stderr to g_err. */
static void emu_spawn(const char *const *args)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, g_err),
                                  "pipe or fork failed");
}

/* Reads stdout up to the first newline (the pty path); 0 if the child
 * closed stdout first (it exited). */
static int emu_read_pty_line(void)
{
    int r = xgo_test_emu_read_pty(&g_emu, EMU_START_TIMEOUT_MS);
    TEST_ASSERT_TRUE_MESSAGE(r != XGO_TEST_EMU_PTY_TIMEOUT, "no pty path on xgo-emu's stdout");
    TEST_ASSERT_TRUE(r != XGO_TEST_EMU_PTY_TOO_LONG);
    return r == XGO_TEST_EMU_PTY_OK;
}

/* Waits (bounded) for the child; returns its wait status. */
static int emu_wait(void)
{
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_wait(&g_emu, EMU_EXIT_TIMEOUT_MS),
                             "xgo-emu did not exit");
    return g_emu.status;
}

static void emu_start(const char *const *args)
{
    emu_spawn(args);
    TEST_ASSERT_TRUE_MESSAGE(emu_read_pty_line(), "xgo-emu exited at start");
}

static void emu_start_with_state(const char *extra1, const char *extra2)
{
    const char *args[] = {"--state", g_state, extra1, extra2, NULL};
    emu_start(args);
}

/* SIGTERM, and a clean exit 0. */
static void emu_stop(void)
{
    int status;
    char err[4096];
    TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGTERM));
    status = emu_wait();
    read_file(g_err, err, sizeof err);
    TEST_ASSERT_TRUE_MESSAGE(WIFEXITED(status) && WEXITSTATUS(status) == 0, err);
}

/* Runs xgo-emu to its exit (for start-up refusals); returns the exit status
 * and leaves its stderr in err. Nothing may appear on stdout. */
static int emu_run_to_exit(const char *const *args, char *err, size_t size)
{
    int status;
    emu_spawn(args);
    TEST_ASSERT_FALSE_MESSAGE(emu_read_pty_line(), "xgo-emu started serving");
    status = emu_wait();
    TEST_ASSERT_TRUE(WIFEXITED(status));
    read_file(g_err, err, size);
    return WEXITSTATUS(status);
}

/* ------------------------------------------------------------- the host */

static int port_open(void)
{
    int fd = xgo_test_port_open(g_emu.pty);
    TEST_ASSERT_TRUE_MESSAGE(fd >= 0, "cannot open the emulator's pty");
    tcflush(fd, TCIOFLUSH);
    return fd;
}

static void write_regs(int fd, uint8_t addr, const void *values, size_t n)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_write_regs(fd, addr, values, n, REPLY_TIMEOUT_MS),
                                  "write frame not built, or the pty failed or stalled");
}

static void write_reg(int fd, uint8_t addr, uint8_t value)
{
    write_regs(fd, addr, &value, 1);
}

static void read_regs(int fd, uint8_t addr, uint8_t count, uint8_t *values)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    size_t want = (size_t)count + XGO_FRAME_OVERHEAD;
    size_t got;
    tcflush(fd, TCIFLUSH);
    got = xgo_test_read_reply(fd, addr, count, reply, REPLY_TIMEOUT_MS);
    TEST_ASSERT_EQUAL_INT_MESSAGE((int)want, (int)got, "incomplete reply");
    TEST_ASSERT_EQUAL_HEX8(addr, reply[4]);
    memcpy(values, reply + 5, count);
}

static void load_state_file(xgo_board_nv_t *nv)
{
    char why[256] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(XGO_HOST_STATE_LOADED, xgo_host_state_load(g_state, nv, why, sizeof why),
                                  why);
}

/* ------------------------------------------------------------- fixtures */

void setUp(void)
{
    strcpy(g_dir, "/tmp/xgo-state-test-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(g_dir));
    snprintf(g_state, sizeof g_state, "%s/state", g_dir);
    snprintf(g_err, sizeof g_err, "%s/emu.err", g_dir);
}

void tearDown(void)
{
    if (g_port >= 0) {
        close(g_port);
        g_port = -1;
    }
    xgo_test_emu_kill(&g_emu);
    remove_dir_contents();
    rmdir(g_dir);
}

/* ------------------------------------------------ the file, in process */

static void test_format_is_the_documented_text(void)
{
    xgo_board_nv_t nv;
    char text[XGO_HOST_STATE_MAX_BYTES];
    memset(&nv, 0, sizeof nv);
    memcpy(nv.bt_name, "XGOMINI", 7);
    TEST_ASSERT_EQUAL_UINT((unsigned)85, (unsigned)xgo_host_state_format(&nv, text, sizeof text));
    /* crc32 checked independently: python3 -c 'import zlib; ...' */
    TEST_ASSERT_EQUAL_STRING("xgo-state 1\n"
                             "bt_name=XGOMINI\n"
                             "zero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n"
                             "crc32=5aa01ab5\n",
                             text);
    /* A full 10-character name has no NUL in the struct. */
    memcpy(nv.bt_name, "ABCDEFGHIJ", 10);
    TEST_ASSERT_TRUE(xgo_host_state_format(&nv, text, sizeof text) > 0);
    TEST_ASSERT_NOT_NULL(strstr(text, "\nbt_name=ABCDEFGHIJ\n"));
    /* Too small a buffer: 0, never a cut file. */
    TEST_ASSERT_EQUAL_UINT((unsigned)0, (unsigned)xgo_host_state_format(&nv, text, 60));
}

static void test_format_parse_round_trip(void)
{
    xgo_board_nv_t nv = nv_example();
    xgo_board_nv_t back;
    char text[XGO_HOST_STATE_MAX_BYTES];
    char why[200];
    size_t len = xgo_host_state_format(&nv, text, sizeof text);
    TEST_ASSERT_TRUE(len > 0);
    memset(&back, 0x5A, sizeof back);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_parse(text, len, &back, why, sizeof why), why);
    assert_nv_equal(&nv, &back);
}

/* Whatever a crash or a bad disk leaves - any prefix of a valid file, any
 * single flipped bit - is refused, never half-applied. */
static void test_every_truncation_and_bit_flip_is_refused(void)
{
    xgo_board_nv_t nv = nv_example();
    xgo_board_nv_t back;
    char text[XGO_HOST_STATE_MAX_BYTES];
    char bad[XGO_HOST_STATE_MAX_BYTES];
    char why[200];
    size_t len = xgo_host_state_format(&nv, text, sizeof text);
    size_t i;
    for (i = 0; i < len; i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, xgo_host_state_parse(text, i, &back, why, sizeof why),
                                      "a truncated file was accepted");
    }
    for (i = 0; i < len * 8; i++) {
        memcpy(bad, text, len);
        bad[i / 8] = (char)(bad[i / 8] ^ (1 << (i % 8)));
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, xgo_host_state_parse(bad, len, &back, why, sizeof why),
                                      "a file with a flipped bit was accepted");
    }
    /* and a trailing extra byte */
    memcpy(bad, text, len);
    bad[len] = '\n';
    TEST_ASSERT_EQUAL_INT(-1, xgo_host_state_parse(bad, len + 1, &back, why, sizeof why));
}

/* Files with a correct crc but a wrong layout (hand-edited and re-signed). */
/* A valid file saved by a Windows editor (CR LF line ends, signed again or
 * not): the reason says what is wrong, without a CR of its own. */
static void assert_crlf_refused_plainly(void)
{
    static const char *const bodies[] = {
        "xgo-state 1\r\nbt_name=A\r\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\r\n",
        "xgo-state 1\nbt_name=A\r\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n",
    };
    char text[512];
    char why[200];
    xgo_board_nv_t nv;
    size_t i;
    for (i = 0; i < sizeof bodies / sizeof bodies[0]; i++) {
        sign(bodies[i], text, sizeof text);
        why[0] = '\0';
        TEST_ASSERT_EQUAL_INT(-1, xgo_host_state_parse(text, strlen(text), &nv, why, sizeof why));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(why, "line endings must be LF"), why);
        TEST_ASSERT_NULL_MESSAGE(strchr(why, '\r'), why);
    }
}

static void test_layout_errors_are_refused_with_a_reason(void)
{
    static const struct {
        const char *body;
        const char *reason;
    } cases[] = {
        {"xgo-state 2\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n", "unsupported"},
        {"xgo-state 1\nbt_name=\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n", "line 2"},
        {"xgo-state 1\nbt_name=ABCDEFGHIJK\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n", "line 2"},
        {"xgo-state 1\nbt_name=A\tB\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n", "line 2"},
        {"xgo-state 1\nname=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\n", "line 2"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0 0\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 x\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0  0 0 0 0 0 0 0 0 0 0 0\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 -\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 2147483648\n", "line 3"},
        {"xgo-state 1\nbt_name=A\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\nextra=1\n",
         "unexpected"},
        {"xgo-state 1\nbt_name=A\n", "line 3"},
        {"#!/bin/sh\necho hello\n", "not an xgo-emu state file"},
    };
    char text[512];
    char why[200];
    xgo_board_nv_t nv;
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sign(cases[i].body, text, sizeof text);
        why[0] = '\0';
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            -1, xgo_host_state_parse(text, strlen(text), &nv, why, sizeof why), cases[i].body);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(why, cases[i].reason), why);
    }
    /* The extremes of the syntax are accepted (range is the board's call). */
    sign("xgo-state 1\nbt_name= ~ \nzero_offsets_mdeg=-2147483648 0 0 0 0 0 0 0 0 0 0 "
         "2147483647\n",
         text, sizeof text);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_parse(text, strlen(text), &nv, why, sizeof why),
                                  why);
    TEST_ASSERT_EQUAL_MEMORY(" ~ \0", nv.bt_name, 4);
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, nv.zero_offset_mdeg[0]);
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, nv.zero_offset_mdeg[11]);
    assert_crlf_refused_plainly();
}

static void test_save_load_missing_and_permissions(void)
{
    xgo_board_nv_t nv = nv_example();
    xgo_board_nv_t back;
    char why[300] = "";
    char tmp[256];
    struct stat st;
    TEST_ASSERT_EQUAL_INT(XGO_HOST_STATE_MISSING, xgo_host_state_load(g_state, &back, why, sizeof why));
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_save(g_state, &nv, why, sizeof why), why);
    load_state_file(&back);
    assert_nv_equal(&nv, &back);
    TEST_ASSERT_EQUAL_INT(0, count_tmp_files(tmp, sizeof tmp));
    /* A replaced file keeps the permissions its owner gave it. */
    TEST_ASSERT_EQUAL_INT(0, chmod(g_state, 0600));
    memcpy(nv.bt_name, "Other\0\0\0\0\0", 10);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_save(g_state, &nv, why, sizeof why), why);
    TEST_ASSERT_EQUAL_INT(0, stat(g_state, &st));
    TEST_ASSERT_EQUAL_INT(0600, st.st_mode & 0777);
    load_state_file(&back);
    assert_nv_equal(&nv, &back);
}

/* A save that cannot complete leaves the old file exactly as it was. */
static void test_failed_save_leaves_the_old_file(void)
{
    xgo_board_nv_t nv = nv_example();
    char before[512], after[512], tmp[256], why[300] = "";
    struct rlimit saved, small;
    int rc;
    TEST_ASSERT_EQUAL_INT(0, xgo_host_state_save(g_state, &nv, why, sizeof why));
    TEST_ASSERT_TRUE(read_file(g_state, before, sizeof before) > 0);
    /* No file may grow past 16 bytes (works for root too, unlike a
     * read-only directory): the write of the temporary file fails. */
    TEST_ASSERT_EQUAL_INT(0, getrlimit(RLIMIT_FSIZE, &saved));
    small = saved;
    small.rlim_cur = 16;
    signal(SIGXFSZ, SIG_IGN);
    TEST_ASSERT_EQUAL_INT(0, setrlimit(RLIMIT_FSIZE, &small));
    memcpy(nv.bt_name, "New\0\0\0\0\0\0\0", 10);
    rc = xgo_host_state_save(g_state, &nv, why, sizeof why);
    TEST_ASSERT_EQUAL_INT(0, setrlimit(RLIMIT_FSIZE, &saved));
    signal(SIGXFSZ, SIG_DFL);
    TEST_ASSERT_EQUAL_INT(-1, rc);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(why, "cannot write"), why);
    TEST_ASSERT_TRUE(read_file(g_state, after, sizeof after) > 0);
    TEST_ASSERT_EQUAL_STRING(before, after);
    TEST_ASSERT_EQUAL_INT(0, count_tmp_files(tmp, sizeof tmp)); /* nothing left behind */
}

/* Nothing at the old, predictable temporary name (FILE.tmp.<pid>) is ever
 * opened or followed: a directory, a FIFO, a symlink to a victim file. And a
 * symlink at FILE is replaced by our own file; its target keeps its data and
 * mode. */
static void test_save_never_opens_or_follows_what_is_planted(void)
{
    xgo_board_nv_t nv = nv_example();
    xgo_board_nv_t back;
    char plant[160], victim[160], text[64], why[300] = "";
    struct stat st;
    snprintf(victim, sizeof victim, "%s/victim", g_dir);
    write_file(victim, "precious\n");
    TEST_ASSERT_EQUAL_INT(0, chmod(victim, 0644));
    snprintf(plant, sizeof plant, "%s.tmp.%ld", g_state, (long)getpid());
    TEST_ASSERT_EQUAL_INT(0, symlink(victim, plant));
    TEST_ASSERT_EQUAL_INT(0, symlink(victim, g_state));
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_save(g_state, &nv, why, sizeof why), why);
    TEST_ASSERT_EQUAL_INT(0, lstat(g_state, &st));
    TEST_ASSERT_TRUE(S_ISREG(st.st_mode));
    TEST_ASSERT_EQUAL_INT(0600, st.st_mode & 0777); /* not the link target's 0644 */
    load_state_file(&back);
    assert_nv_equal(&nv, &back);
    TEST_ASSERT_TRUE(read_file(victim, text, sizeof text) > 0);
    TEST_ASSERT_EQUAL_STRING("precious\n", text);
    TEST_ASSERT_EQUAL_INT(0, lstat(plant, &st));
    TEST_ASSERT_TRUE(S_ISLNK(st.st_mode));
    TEST_ASSERT_EQUAL_INT(0, unlink(plant));
    TEST_ASSERT_EQUAL_INT(0, mkdir(plant, 0700)); /* the old way to make a save fail */
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_host_state_save(g_state, &nv, why, sizeof why), why);
    TEST_ASSERT_EQUAL_INT(0, rmdir(plant));
}

/* Leftovers of killed processes go; a live process's file and names that
 * only look similar stay. */
static void test_stale_temporary_files_are_removed(void)
{
    char path[256];
    char tmp[256];
    pid_t dead = fork();
    TEST_ASSERT_TRUE(dead >= 0);
    if (dead == 0) {
        _exit(0);
    }
    TEST_ASSERT_EQUAL_INT(dead, waitpid(dead, NULL, 0)); /* reaped: the pid is free */
    snprintf(path, sizeof path, "%s.tmp.%ld", g_state, (long)dead);
    write_file(path, "half a fi");
    snprintf(path, sizeof path, "%s.tmp.%ld", g_state, (long)getpid());
    write_file(path, "in progress");
    snprintf(path, sizeof path, "%s.tmp.x1", g_state);
    write_file(path, "not ours");
    snprintf(path, sizeof path, "%s/other.tmp.%ld", g_dir, (long)dead);
    write_file(path, "not ours either");
    snprintf(path, sizeof path, "%s.tmp.%ld.a1B2c3", g_state, (long)dead); /* today's name */
    write_file(path, "half a file");
    snprintf(path, sizeof path, "%s.tmp.%ld.d4E5f6", g_state, (long)dead);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(path, 0600)); /* no save of ours leaves a FIFO */
    TEST_ASSERT_EQUAL_INT(2, xgo_host_state_remove_stale(g_state));
    TEST_ASSERT_EQUAL_INT(3, count_tmp_files(tmp, sizeof tmp));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_state_remove_stale(g_state));
}

/* ------------------------------------------------------ xgo-emu, live */

/* Rename and calibrate over the wire, stop, restart: both come back. */
static void test_name_and_zero_offsets_survive_a_restart(void)
{
    static const char name[] = "Rex-01";
    xgo_board_nv_t first, second;
    uint8_t back[XGO_BT_NAME_LEN];
    unsigned i;
    int nonzero = 0;

    emu_start_with_state(NULL, NULL);
    load_state_file(&first); /* created at start, with the defaults */
    TEST_ASSERT_EQUAL_MEMORY("XGOMINI\0\0\0", first.bt_name, XGO_BT_NAME_LEN);
    g_port = port_open();
    write_regs(g_port, 0x13, name, strlen(name));
    write_reg(g_port, 0x04, 1); /* calibration: joints limp where they stand */
    xgo_test_sleep_us(100000);
    write_reg(g_port, 0x21, 1); /* record: the standing angles become zero */
    xgo_test_sleep_us(100000);
    write_reg(g_port, 0x04, 0);
    xgo_test_sleep_us(100000);
    close(g_port);
    g_port = -1;
    emu_stop();

    load_state_file(&first);
    TEST_ASSERT_EQUAL_MEMORY("Rex-01\0\0\0", first.bt_name, XGO_BT_NAME_LEN);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        nonzero += first.zero_offset_mdeg[i] != 0;
    }
    TEST_ASSERT_TRUE_MESSAGE(nonzero >= 4, "calibration recorded no offsets");

    emu_start_with_state(NULL, NULL);
    g_port = port_open();
    read_regs(g_port, 0x13, XGO_BT_NAME_LEN, back);
    TEST_ASSERT_EQUAL_MEMORY("Rex-01\0\0\0", back, XGO_BT_NAME_LEN);
    /* A rename makes the board save again what it holds: the offsets it
     * was started with. */
    write_regs(g_port, 0x13, "Rex-02", 6);
    read_regs(g_port, 0x13, XGO_BT_NAME_LEN, back); /* the write was handled (a loaded machine) */
    xgo_test_sleep_us(50000);
    close(g_port);
    g_port = -1;
    emu_stop();
    load_state_file(&second);
    TEST_ASSERT_EQUAL_MEMORY("Rex-02\0\0\0", second.bt_name, XGO_BT_NAME_LEN);
    TEST_ASSERT_EQUAL_MEMORY(first.zero_offset_mdeg, second.zero_offset_mdeg,
                             sizeof first.zero_offset_mdeg);
}

/* Another local user who can write the directory plants something at the
 * temporary name the running emulator's saves used to take (FILE.tmp.<pid>,
 * predictable); the save that follows a rename over the wire must neither
 * hang on it nor adopt it. */

/* A FIFO at the temporary name: opening it for writing would block until
 * someone reads it, freezing the emulator at its next save. */
static void test_planted_fifo_at_the_temporary_name_is_not_used(void)
{
    char plant[160];
    uint8_t back[XGO_BT_NAME_LEN];
    xgo_board_nv_t nv;
    struct stat st;
    emu_start_with_state(NULL, NULL); /* creates the file, saved before serving */
    snprintf(plant, sizeof plant, "%s.tmp.%ld", g_state, (long)g_emu.pid);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(plant, 0666));
    g_port = port_open();
    write_regs(g_port, 0x13, "Fifo", 4); /* saved once a tick passes without a change */
    xgo_test_sleep_us(50000);
    read_regs(g_port, 0x13, XGO_BT_NAME_LEN, back); /* still serving */
    TEST_ASSERT_EQUAL_MEMORY("Fifo\0\0\0\0\0", back, XGO_BT_NAME_LEN);
    close(g_port);
    g_port = -1;
    emu_stop();
    load_state_file(&nv);
    TEST_ASSERT_EQUAL_MEMORY("Fifo\0\0\0\0\0", nv.bt_name, XGO_BT_NAME_LEN);
    TEST_ASSERT_EQUAL_INT(0, lstat(plant, &st));
    TEST_ASSERT_TRUE_MESSAGE(S_ISFIFO(st.st_mode), "the planted FIFO was replaced");
}

/* A file of another user's at the temporary name, writable by us: writing
 * into it and renaming it would make their file our state file (they could
 * edit it at will afterwards). The save must create its own file. */
static void test_planted_file_at_the_temporary_name_is_not_adopted(void)
{
    char plant[160];
    char text[256];
    uint8_t back[XGO_BT_NAME_LEN];
    xgo_board_nv_t nv;
    struct stat planted, saved;
    emu_start_with_state(NULL, NULL);
    snprintf(plant, sizeof plant, "%s.tmp.%ld", g_state, (long)g_emu.pid);
    write_file(plant, "theirs\n");
    TEST_ASSERT_EQUAL_INT(0, chmod(plant, 0666));
    if (geteuid() == 0) {
        TEST_ASSERT_EQUAL_INT(0, chown(plant, 65534, 65534)); /* nobody's */
    }
    TEST_ASSERT_EQUAL_INT(0, stat(plant, &planted));
    g_port = port_open();
    write_regs(g_port, 0x13, "Mine", 4);
    read_regs(g_port, 0x13, XGO_BT_NAME_LEN, back); /* the write was handled (a loaded machine) */
    xgo_test_sleep_us(50000);
    close(g_port);
    g_port = -1;
    emu_stop();
    load_state_file(&nv);
    TEST_ASSERT_EQUAL_MEMORY("Mine\0\0\0\0\0", nv.bt_name, XGO_BT_NAME_LEN);
    TEST_ASSERT_EQUAL_INT(0, lstat(g_state, &saved));
    TEST_ASSERT_TRUE_MESSAGE(saved.st_ino != planted.st_ino, "the planted file became the state file");
    TEST_ASSERT_EQUAL_UINT(geteuid(), saved.st_uid);
    TEST_ASSERT_EQUAL_INT(0600, saved.st_mode & 0777); /* private unless its owner said otherwise */
    TEST_ASSERT_TRUE(read_file(plant, text, sizeof text) > 0);
    TEST_ASSERT_EQUAL_STRING("theirs\n", text);
}

/* Is name (a NUL-padded 10-byte field) in the list of names? */
static int name_in(const char *name, char (*names)[XGO_BT_NAME_LEN + 1], int n)
{
    int i;
    for (i = 0; i < n; i++) {
        if (strncmp(name, names[i], XGO_BT_NAME_LEN) == 0) {
            return 1;
        }
    }
    return 0;
}

/* Renames the board every 5 ms for delay_us, recording every name sent.
 * The device saves once a control tick (2 ms) passed without a change
 * (xgo-emu's XGO_PORT_NV_SETTLE_TICKS), so each rename is followed by a save
 * under way while the next one arrives. */
static int rename_burst(int round, long delay_us, char (*names)[XGO_BT_NAME_LEN + 1], int max)
{
    long long end = xgo_test_now_us() + delay_us;
    int n = 0;
    do {
        uint8_t frame[32];
        size_t len;
        if (n < max) {
            snprintf(names[n], XGO_BT_NAME_LEN + 1, "K%03u-%04u", (unsigned)round % 1000u,
                     (unsigned)n % 10000u);
            len = xgo_frame_encode(XGO_TYPE_WRITE, 0x13, (const uint8_t *)names[n], 9, frame,
                                   sizeof frame);
            if (write(g_port, frame, len) == (ssize_t)len) {
                n++; /* a partial write is at worst a name never sent whole */
            }
        }
        xgo_test_sleep_us(5000);
    } while (xgo_test_now_us() < end);
    return n;
}

/* SIGKILL at random moments while saves are under way: the file is always
 * complete and holds a name that was really sent; at most the killed
 * process's own temporary file is left, and the next start removes it. */
static void test_state_file_survives_kill_at_random_points(void)
{
    static char names[1024][XGO_BT_NAME_LEN + 1];
    xgo_board_nv_t nv;
    char left[256];
    char expect_left[256] = "";
    int round, torn = 0, changed = 0;
    unsigned seed = 12345u;

    emu_start_with_state(NULL, NULL);
    emu_stop(); /* the file exists from here on */
    load_state_file(&nv);
    snprintf(names[0], sizeof names[0], "%.10s", nv.bt_name);

    for (round = 0; round < KILL_ROUNDS; round++) {
        long delay_us;
        int n;
        seed = seed * 1103515245u + 12345u; /* fixed sequence, any libc */
        delay_us = (long)((seed >> 8) % (KILL_MAX_DELAY_US + 1));
        emu_start_with_state(NULL, NULL);
        /* The previous round's leftover is gone once we are serving. */
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, count_tmp_files(left, sizeof left),
                                      "a stale temporary file survived a start");
        g_port = port_open();
        n = 1 + rename_burst(round, delay_us, names + 1, 1023);
        TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGKILL));
        snprintf(expect_left, sizeof expect_left, "state.tmp.%ld.", (long)g_emu.pid);
        TEST_ASSERT_TRUE(WIFSIGNALED(emu_wait()));
        close(g_port);
        g_port = -1;

        load_state_file(&nv); /* complete and valid, or the test fails here */
        TEST_ASSERT_TRUE_MESSAGE(name_in(nv.bt_name, names, n), "a name that was never sent");
        changed += strncmp(nv.bt_name, names[0], XGO_BT_NAME_LEN) != 0;
        snprintf(names[0], sizeof names[0], "%.10s", nv.bt_name);
        switch (count_tmp_files(left, sizeof left)) {
        case 0:
            break;
        case 1: /* the killed process's own: state.tmp.<pid>.XXXXXX */
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(expect_left, left, strlen(expect_left)),
                                          left);
            TEST_ASSERT_EQUAL_UINT(strlen(expect_left) + 6, strlen(left));
            torn++;
            break;
        default:
            TEST_FAIL_MESSAGE("more than one temporary file left");
        }
    }
    printf("kill test: %d rounds, the name changed in %d, killed mid-save %d times\n",
           KILL_ROUNDS, changed, torn);
    TEST_ASSERT_TRUE_MESSAGE(changed > KILL_ROUNDS / 4, "renames were hardly ever saved");
}

static void assert_refused(const char *what)
{
    const char *args[] = {"--state", g_state, NULL};
    char before[512], after[512], err[2048];
    const char *nl;
    TEST_ASSERT_TRUE(read_file(g_state, before, sizeof before) >= 0);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, emu_run_to_exit(args, err, sizeof err), what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(err, "xgo-emu: --state ", 17), err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "refusing to start"), err);
    nl = strchr(err, '\n');
    TEST_ASSERT_TRUE_MESSAGE(nl != NULL && nl[1] == '\0', err); /* one line */
    TEST_ASSERT_TRUE(read_file(g_state, after, sizeof after) >= 0);
    TEST_ASSERT_EQUAL_STRING_MESSAGE(before, after, "the refused file was changed");
}

/* A damaged, foreign or out-of-range file: exit 1, one line, file untouched,
 * no pty. */
static void test_bad_state_file_refuses_to_start(void)
{
    char text[512];
    const char *args[] = {"--state", g_state, NULL};
    char err[2048];
    xgo_board_nv_t nv = nv_example();
    char why[200];
    size_t len = xgo_host_state_format(&nv, text, sizeof text);

    text[len - 20] = '7'; /* damaged: crc mismatch */
    write_file(g_state, text);
    assert_refused("damaged");
    write_file(g_state, "export PATH=/usr/bin\n"); /* not ours */
    assert_refused("foreign");
    text[len / 2] = '\0'; /* cut short */
    write_file(g_state, text);
    assert_refused("truncated");
    sign("xgo-state 1\r\nbt_name=Rex\r\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0\r\n", text,
         sizeof text); /* a Windows editor's line ends */
    write_file(g_state, text);
    assert_refused("CRLF");
    TEST_ASSERT_TRUE(read_file(g_err, text, sizeof text) > 0);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(text, "line endings must be LF"), text);
    TEST_ASSERT_NULL_MESSAGE(strchr(text, '\r'), text);
    sign("xgo-state 1\nbt_name=Rex\nzero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 400000\n", text,
         sizeof text); /* syntax fine, the board refuses 400 degrees */
    TEST_ASSERT_EQUAL_INT(0, xgo_host_state_parse(text, strlen(text), &nv, why, sizeof why));
    write_file(g_state, text);
    assert_refused("out of range");

    /* A path that cannot be created is reported at start too. */
    snprintf(text, sizeof text, "%s/no-such-dir/state", g_dir);
    args[1] = text;
    TEST_ASSERT_EQUAL_INT(1, emu_run_to_exit(args, err, sizeof err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "no-such-dir/state"), err);
}

/* A FIFO (or any file that is not a regular file) as --state: a plain open
 * of a FIFO waits for a writer forever. Refused at once instead: exit 1,
 * one line saying what it is, nothing created. */
static void test_non_regular_state_file_is_refused_at_once(void)
{
    static const struct {
        const char *path; /* NULL: g_state, a FIFO */
        const char *what;
    } cases[] = {{NULL, "a FIFO"}, {"/dev/null", "a character device"}, {"/tmp", "a directory"}};
    struct stat st;
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *path = cases[i].path != NULL ? cases[i].path : g_state;
        const char *args[] = {"--state", path, NULL};
        char err[2048];
        const char *nl;
        long long t0;
        if (cases[i].path == NULL) {
            TEST_ASSERT_EQUAL_INT(0, mkfifo(g_state, 0600));
        }
        t0 = xgo_test_now_ms();
        TEST_ASSERT_EQUAL_INT_MESSAGE(1, emu_run_to_exit(args, err, sizeof err), path);
        printf("--state %s refused after %lld ms\n", path, xgo_test_now_ms() - t0);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(err, "xgo-emu: --state ", 17), err);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, "not a regular file"), err);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err, cases[i].what), err);
        nl = strchr(err, '\n');
        TEST_ASSERT_TRUE_MESSAGE(nl != NULL && nl[1] == '\0', err); /* one line */
        TEST_ASSERT_EQUAL_INT(0, lstat(path, &st));
        xgo_test_emu_reset(&g_emu);
    }
    TEST_ASSERT_EQUAL_INT(0, lstat(g_state, &st));
    TEST_ASSERT_TRUE(S_ISFIFO(st.st_mode)); /* left as it was */
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    xgo_test_emu_init(&g_emu);
    UNITY_BEGIN();
    RUN_TEST(test_format_is_the_documented_text);
    RUN_TEST(test_format_parse_round_trip);
    RUN_TEST(test_every_truncation_and_bit_flip_is_refused);
    RUN_TEST(test_layout_errors_are_refused_with_a_reason);
    RUN_TEST(test_save_load_missing_and_permissions);
    RUN_TEST(test_failed_save_leaves_the_old_file);
    RUN_TEST(test_save_never_opens_or_follows_what_is_planted);
    RUN_TEST(test_stale_temporary_files_are_removed);
    RUN_TEST(test_name_and_zero_offsets_survive_a_restart);
    RUN_TEST(test_state_file_survives_kill_at_random_points);
    RUN_TEST(test_planted_fifo_at_the_temporary_name_is_not_used);
    RUN_TEST(test_planted_file_at_the_temporary_name_is_not_adopted);
    RUN_TEST(test_bad_state_file_refuses_to_start);
    RUN_TEST(test_non_regular_state_file_is_refused_at_once);
    return UNITY_END();
}
