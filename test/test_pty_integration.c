/*
 * test_pty_integration.c - xgo-emu end to end, over a real pseudo-terminal.
 *
 * Every test starts its own xgo-emu (XGO_EMU_PATH, fork/exec), talks to it
 * the way the vendor's pyserial-based library does, and stops it with a
 * signal. This is the one test that waits in real time; every wait is
 * bounded, so a broken emulator fails the test instead of hanging it.
 * The child process and the port come from test/support; the assertions on
 * them are here.
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
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
#define REPLY_TIMEOUT_MS 1000 /* the vendor library polls for replies for 1 s */

/* ------------------------------------------------------------- the child */

static xgo_test_emu_t g_emu; /* stdout and stderr captured (err: trace, counters) */
static xgo_test_emu_t g_first; /* a first emulator while g_emu is a second one */
static int g_port = -1;
static char g_dir[64];
static char g_link[128];

/* Starts xgo-emu with argv[1..] = args (NULL-terminated). */
static void emu_spawn(const char *const *args)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL),
                                  "pipe or fork failed");
}

/* Runs xgo-emu to completion (for options that make it exit at once). */
static void emu_run_to_exit(const char *const *args)
{
    emu_spawn(args);
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_wait(&g_emu, EMU_EXIT_TIMEOUT_MS),
                             "xgo-emu did not exit");
    TEST_ASSERT_TRUE(WIFEXITED(g_emu.status));
}

/* Starts xgo-emu and waits for its first stdout line (the pty path). */
static void emu_start(const char *const *args)
{
    int r;
    emu_spawn(args);
    r = xgo_test_emu_read_pty(&g_emu, EMU_START_TIMEOUT_MS);
    TEST_ASSERT_TRUE_MESSAGE(r != XGO_TEST_EMU_PTY_TIMEOUT, "no pty path on xgo-emu's stdout");
    TEST_ASSERT_TRUE_MESSAGE(r != XGO_TEST_EMU_PTY_CLOSED, "xgo-emu closed stdout without a path");
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, r);
}

/* The usual case: serve with --link g_link plus extra options. */
static void emu_start_linked(const char *extra1, const char *extra2)
{
    const char *args[5];
    size_t n = 0;
    char target[256];
    ssize_t len;
    args[n++] = "--link";
    args[n++] = g_link;
    if (extra1 != NULL) {
        args[n++] = extra1;
    }
    if (extra2 != NULL) {
        args[n++] = extra2;
    }
    args[n] = NULL;
    emu_start(args);
    len = readlink(g_link, target, sizeof target - 1);
    TEST_ASSERT_TRUE_MESSAGE(len > 0, "--link did not create the symlink");
    target[len] = '\0';
    TEST_ASSERT_EQUAL_STRING(g_emu.pty, target);
}

/* Stops the running emulator with sig and checks a clean exit: status 0,
 * link removed, counters printed. */
static void emu_stop_cleanly(int sig)
{
    TEST_ASSERT_TRUE(g_emu.pid > 0);
    TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, sig));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_wait(&g_emu, EMU_EXIT_TIMEOUT_MS),
                             "xgo-emu ignored the signal");
    TEST_ASSERT_TRUE_MESSAGE(WIFEXITED(g_emu.status), "xgo-emu did not exit normally");
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "counters at exit"), "no counters at exit");
}

static void assert_link_gone(void)
{
    struct stat st;
    TEST_ASSERT_TRUE_MESSAGE(lstat(g_link, &st) != 0 && errno == ENOENT,
                             "the link was not removed at exit");
}

/* -------------------------------------------------------------- the host */

/* Opens the port the way pyserial does (see serial_port.h). */
static int port_open_like_pyserial(const char *path, speed_t speed)
{
    int fd = xgo_test_port_open_like_pyserial(path, speed);
    TEST_ASSERT_TRUE_MESSAGE(fd >= 0, "cannot open and configure the emulator's port");
    return fd;
}

/* Opens the port without touching its settings: a host that never
 * configures the line sees whatever xgo-emu set up. */
static int port_open_untouched(const char *path)
{
    int fd = xgo_test_port_open(path);
    TEST_ASSERT_TRUE_MESSAGE(fd >= 0, "cannot open the emulator's port");
    return fd;
}

static void port_write(int fd, const uint8_t *bytes, size_t n)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_port_write(fd, bytes, n, REPLY_TIMEOUT_MS),
                                  "write to the port failed or stalled");
}

/* Reads register bytes through the port: request, then the exact reply. */
static void read_regs(int fd, uint8_t addr, uint8_t count, uint8_t *values)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    uint8_t expect_head[5] = {0x55, 0x00, 0, XGO_TYPE_READ_REPLY, 0};
    size_t len = (size_t)count + XGO_FRAME_OVERHEAD;
    size_t got;
    expect_head[2] = (uint8_t)len;
    expect_head[4] = addr;
    got = xgo_test_read_reply(fd, addr, count, reply, REPLY_TIMEOUT_MS);
    TEST_ASSERT_EQUAL_INT_MESSAGE((int)len, (int)got, "incomplete reply");
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expect_head, reply, 5);
    TEST_ASSERT_EQUAL_HEX8(xgo_frame_checksum((uint8_t)len, XGO_TYPE_READ_REPLY, addr, reply + 5,
                                              count),
                           reply[len - 3]);
    TEST_ASSERT_EQUAL_HEX8(0x00, reply[len - 2]);
    TEST_ASSERT_EQUAL_HEX8(0xAA, reply[len - 1]);
    memcpy(values, reply + 5, count);
}

static void write_regs(int fd, uint8_t addr, const uint8_t *values, size_t n)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_test_write_regs(fd, addr, values, n, REPLY_TIMEOUT_MS),
                                  "write frame not built or not sent");
}

/* -------------------------------------------------------- fixtures */

static void compute_standing_reply(void);

void setUp(void)
{
    xgo_test_emu_init(&g_emu); /* tearDown closed and reaped what the last test left */
    compute_standing_reply();
    g_port = -1;
}

void tearDown(void)
{
    if (g_port >= 0) {
        close(g_port);
        g_port = -1;
    }
    xgo_test_emu_kill(&g_emu);
    xgo_test_emu_kill(&g_first);
    /* whatever a failed test left there */
    if (unlink(g_link) != 0) {
        rmdir(g_link);
    }
}

/* ------------------------------------------------------------- tests */

static const uint8_t k_spec_read[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
/* The spec's reply shows twelve 0x80 (the table's initial values); a running
 * board reports where its joints are, so the expected reply is the spec's
 * framing (55 00 14 12 50 ... SUM 00 AA) around the standing robot's joint
 * bytes, which setUp computes from the core (a board left to settle). */
static uint8_t k_spec_reply[20];

static void compute_standing_reply(void)
{
    static xgo_board_t board;
    uint8_t joints[12];
    unsigned i;
    xgo_board_init(&board, NULL);
    for (i = 0; i < 1000; i++) {
        xgo_board_tick(&board);
    }
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x50, 12, joints));
    TEST_ASSERT_EQUAL_UINT(20, xgo_frame_encode(XGO_TYPE_READ_REPLY, 0x50, joints, 12, k_spec_reply,
                                                sizeof k_spec_reply));
    TEST_ASSERT_EQUAL_HEX8(0x14, k_spec_reply[2]); /* the spec's framing */
}
static const uint8_t k_spec_write[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};

static void test_prints_pty_path_first_and_links_it(void)
{
    emu_start_linked(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, strncmp(g_emu.pty, "/dev/", 5));
    g_port = port_open_like_pyserial(g_link, B115200);
    TEST_ASSERT_TRUE(isatty(g_port));
    close(g_port);
    g_port = -1;
    emu_stop_cleanly(SIGTERM);
    assert_link_gone();
}

static void test_spec_read_example_gets_the_spec_reply(void)
{
    uint8_t reply[sizeof k_spec_reply];
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_INT((int)sizeof reply,
                          (int)xgo_test_port_read(g_port, reply, sizeof reply, REPLY_TIMEOUT_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, reply, sizeof reply);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 100)); /* nothing more */
    emu_stop_cleanly(SIGTERM);
    assert_link_gone();
}

static void test_spec_write_example_gets_no_reply_and_takes_effect(void)
{
    uint8_t vx;
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 200));
    read_regs(g_port, 0x30, 1, &vx);
    TEST_ASSERT_EQUAL_HEX8(0xFF, vx);
    emu_stop_cleanly(SIGTERM);
}

static void test_garbage_then_request_gets_its_reply(void)
{
    /* Noise, a truncated header, a frame with an impossible length, flow
     * control and line-editing bytes, then a stray header byte right before
     * the real request. */
    static const uint8_t garbage[] = {0x01, 0xFF, 0x55, 0x13, 0x11, 0x55, 0x00, 0x03,
                                      0xAA, 0x00, 0xAA, 0x0D, 0x0A, 0x03, 0x55};
    uint8_t reply[sizeof k_spec_reply];
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, garbage, sizeof garbage);
    port_write(g_port, k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_INT((int)sizeof reply,
                          (int)xgo_test_port_read(g_port, reply, sizeof reply, REPLY_TIMEOUT_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, reply, sizeof reply);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 100));
    emu_stop_cleanly(SIGTERM);
}

/* The port is raw from the start: a host that never sets raw mode still gets
 * CR, LF, XON, XOFF, ^C, ^D, ^Z, DEL, ... through unchanged both ways. */
static void test_control_bytes_pass_unchanged_without_host_setup(void)
{
    static const uint8_t values[10] = {0x0D, 0x11, 0x13, 0x03, 0x0A,
                                       0x7F, 0x04, 0x1A, 0x1C, 0x00};
    uint8_t back[10];
    emu_start_linked(NULL, NULL);
    g_port = port_open_untouched(g_link);
    write_regs(g_port, 0x30, values, sizeof values); /* vx .. period_roll: any value */
    read_regs(g_port, 0x30, sizeof back, back);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(values, back, sizeof values);
    emu_stop_cleanly(SIGTERM);
}

/* The vendor's auto-detect opens and closes the port repeatedly, at
 * different speeds. Every session that reads gets exactly its own reply.
 * Some sessions leave without reading theirs: one right after writing the
 * request (the next session then flushes before asking, as the vendor
 * library does before every request), one after the reply has arrived. */
static void test_close_and_reopen_100_times(void)
{
    int i;
    int after_abandon = 0;
    emu_start_linked(NULL, NULL);
    for (i = 0; i < 100; i++) {
        uint8_t addr = (uint8_t)(0x50 + i % 12);
        uint8_t req[XGO_READ_REQUEST_LEN];
        uint8_t value = 0;
        g_port = port_open_like_pyserial(g_link, (i % 3 == 0) ? B9600 : B115200);
        if (after_abandon) {
            /* A reply to the abandoned request may be on its way (a real
             * board would send it too): flush once it has surely arrived. */
            xgo_test_sleep_ms(50);
            tcflush(g_port, TCIFLUSH);
            after_abandon = 0;
        }
        if (i % 10 == 9) {
            xgo_test_read_request(addr, 12, req);
            port_write(g_port, req, sizeof req); /* leave at once */
            after_abandon = 1;
        } else if (i % 10 == 4) {
            xgo_test_read_request(addr, 12, req);
            port_write(g_port, req, sizeof req);
            xgo_test_sleep_ms(20); /* leave with the reply unread */
        } else {
            read_regs(g_port, addr, 1, &value);
            TEST_ASSERT_EQUAL_HEX8(k_spec_reply[5 + (addr - 0x50)], value);
        }
        close(g_port);
        g_port = -1;
    }
    g_port = port_open_like_pyserial(g_link, B115200);
    xgo_test_sleep_ms(50);
    tcflush(g_port, TCIFLUSH);
    {
        uint8_t reply[sizeof k_spec_reply];
        port_write(g_port, k_spec_read, sizeof k_spec_read);
        TEST_ASSERT_EQUAL_INT(
            (int)sizeof reply,
            (int)xgo_test_port_read(g_port, reply, sizeof reply, REPLY_TIMEOUT_MS));
        TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, reply, sizeof reply);
        TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 50));
    }
    close(g_port);
    g_port = -1;
    emu_stop_cleanly(SIGTERM);
    assert_link_gone();
}

/* Replies a host left unread must not reach the next session, even one that
 * does not flush its input on open. */
static void test_unread_replies_do_not_leak_into_the_next_session(void)
{
    uint8_t req[XGO_READ_REQUEST_LEN];
    uint8_t value;
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    xgo_test_read_request(0x50, 12, req);
    port_write(g_port, req, sizeof req);
    xgo_test_sleep_ms(50); /* the reply is now waiting in the pty */
    close(g_port);
    xgo_test_sleep_ms(50); /* xgo-emu notices the hang-up within a tick */
    g_port = port_open_untouched(g_link);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 50));
    read_regs(g_port, 0x30, 1, &value);
    TEST_ASSERT_EQUAL_HEX8(0x80, value);
    close(g_port);

    /* A host that writes and leaves at once: its write is still applied
     * (the board received it), its read is not answered to the next host. */
    g_port = port_open_like_pyserial(g_link, B115200);
    value = 0x10;
    write_regs(g_port, 0x30, &value, 1);
    port_write(g_port, req, sizeof req);
    close(g_port);
    xgo_test_sleep_ms(50);
    g_port = port_open_untouched(g_link);
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 50));
    read_regs(g_port, 0x30, 1, &value);
    TEST_ASSERT_EQUAL_HEX8(0x10, value);
    emu_stop_cleanly(SIGTERM);
}

/* No busy loop, with a host attached and idle, or with none attached after a
 * hang-up (the master then polls POLLHUP continuously). */
static void test_idle_cpu_stays_low(void)
{
    long hz = sysconf(_SC_CLK_TCK);
    long before, after;
    emu_start_linked(NULL, NULL);
    if (xgo_test_cpu_ticks(g_emu.pid) < 0 || hz <= 0) {
        emu_stop_cleanly(SIGTERM);
        TEST_IGNORE_MESSAGE("no /proc/PID/stat: CPU use not measured");
    }
    g_port = port_open_like_pyserial(g_link, B115200);
    before = xgo_test_cpu_ticks(g_emu.pid);
    xgo_test_sleep_ms(1000);
    after = xgo_test_cpu_ticks(g_emu.pid);
    /* A busy loop would use ~100 % of a CPU; ticking at 500 Hz uses ~1 %.
     * The bound leaves room for sanitizers and loaded CI machines. */
    TEST_ASSERT_TRUE_MESSAGE((after - before) * 100 < hz * 30, "busy while a host is attached");
    close(g_port);
    g_port = -1;
    xgo_test_sleep_ms(50);
    before = xgo_test_cpu_ticks(g_emu.pid);
    xgo_test_sleep_ms(1000);
    after = xgo_test_cpu_ticks(g_emu.pid);
    TEST_ASSERT_TRUE_MESSAGE((after - before) * 100 < hz * 30, "busy with no host attached");
    emu_stop_cleanly(SIGTERM);
}

/* 100 maximal reads written in one go: 25,500 reply bytes, far beyond the
 * board's transmit buffer and the pty's buffer. None may be lost. */
static void test_pipelined_large_reads_all_arrive(void)
{
    enum { REQUESTS = 100, COUNT = XGO_FRAME_MAX_DATA, REPLY = COUNT + XGO_FRAME_OVERHEAD };
    static uint8_t reqs[REQUESTS * XGO_READ_REQUEST_LEN];
    static uint8_t replies[REQUESTS * REPLY];
    uint8_t overflows[4];
    int i;
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    for (i = 0; i < REQUESTS; i++) {
        xgo_test_read_request(0x00, (uint8_t)COUNT, reqs + i * XGO_READ_REQUEST_LEN);
    }
    port_write(g_port, reqs, sizeof reqs);
    TEST_ASSERT_EQUAL_INT((int)sizeof replies,
                          (int)xgo_test_port_read(g_port, replies, sizeof replies, 10000));
    for (i = 0; i < REQUESTS; i++) {
        const uint8_t *r = replies + i * REPLY;
        TEST_ASSERT_EQUAL_HEX8(0x55, r[0]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[1]);
        TEST_ASSERT_EQUAL_HEX8(REPLY, r[2]);
        TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, r[3]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[4]);
        TEST_ASSERT_EQUAL_HEX8(0x00, r[REPLY - 2]);
        TEST_ASSERT_EQUAL_HEX8(0xAA, r[REPLY - 1]);
    }
    /* The board's own tx_overflow counter (diagnostic block) stayed 0. */
    read_regs(g_port, (uint8_t)(XGO_REG_DIAG + 4 * XGO_DIAG_TX_OVERFLOW), 4, overflows);
    TEST_ASSERT_EQUAL_HEX8(0, overflows[0] | overflows[1] | overflows[2] | overflows[3]);
    emu_stop_cleanly(SIGTERM);
}

static double timed_spec_read_ms(int fd)
{
    uint8_t reply[sizeof k_spec_reply];
    double t0 = xgo_test_now_us_f();
    port_write(fd, k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_INT((int)sizeof reply,
                          (int)xgo_test_port_read(fd, reply, sizeof reply, 2000));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, reply, sizeof reply);
    return (xgo_test_now_us_f() - t0) / 1000.0;
}

/* At 1200 bit/s the 9-byte request and the 20-byte reply take
 * 29 * 10 / 1200 s = 241.7 ms on a real wire. */
static void test_baud_pacing_delays_replies_by_wire_time(void)
{
    double ms;
    emu_start_linked("--baud-pacing", NULL);
    g_port = port_open_like_pyserial(g_link, B1200);
    ms = timed_spec_read_ms(g_port);
    TEST_ASSERT_TRUE_MESSAGE(ms >= 240.0, "paced reply arrived faster than the wire allows");
    TEST_ASSERT_TRUE_MESSAGE(ms < 1000.0, "paced reply far too slow");
    emu_stop_cleanly(SIGTERM);
}

static void test_without_pacing_replies_are_immediate(void)
{
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B1200);
    TEST_ASSERT_TRUE_MESSAGE(timed_spec_read_ms(g_port) < 150.0, "unpaced reply was slow");
    emu_stop_cleanly(SIGTERM);
}

static void test_sigint_exits_0_and_removes_link(void)
{
    emu_start_linked(NULL, NULL);
    emu_stop_cleanly(SIGINT);
    assert_link_gone();
}

static void test_link_onto_a_regular_file_is_refused(void)
{
    const char *args[] = {"--link", g_link, NULL};
    char content[16] = {0};
    FILE *f = fopen(g_link, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs("precious", f);
    fclose(f);

    emu_run_to_exit(args);
    TEST_ASSERT_NOT_EQUAL(0, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "xgo-emu: "), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "not a symlink"), g_emu.err);
    TEST_ASSERT_EQUAL_INT(0, (int)g_emu.out_len); /* no path printed */

    f = fopen(g_link, "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_TRUE(fgets(content, sizeof content, f) != NULL);
    fclose(f);
    TEST_ASSERT_EQUAL_STRING("precious", content);
}

static void test_link_onto_a_directory_is_refused(void)
{
    const char *args[] = {"--link", g_link, NULL};
    struct stat st;
    TEST_ASSERT_EQUAL_INT(0, mkdir(g_link, 0700));
    emu_run_to_exit(args);
    TEST_ASSERT_NOT_EQUAL(0, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "not a symlink"), g_emu.err);
    TEST_ASSERT_EQUAL_INT(0, lstat(g_link, &st));
    TEST_ASSERT_TRUE(S_ISDIR(st.st_mode));
    rmdir(g_link);
}

/* A name in the pty directory (where posix_openpt's slaves live) that no
 * pty has now: what a link left by a killed emulator points at. */
static void dangling_pty_name(char *out, size_t size)
{
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    const char *slave;
    struct stat st;
    int n;
    TEST_ASSERT_TRUE(master >= 0);
    slave = ptsname(master);
    TEST_ASSERT_NOT_NULL(slave);
    for (n = 4095; n > 0; n--) {
        snprintf(out, size, "%.*s%d", (int)(strrchr(slave, '/') - slave + 1), slave, n);
        if (lstat(out, &st) != 0 && errno == ENOENT) {
            break;
        }
    }
    close(master);
    TEST_ASSERT_TRUE(n > 0);
}

/* --link with a symlink already there: refused, exit 1, the message names
 * what the link points at, the link is left exactly as it was. */
static void assert_link_refused(const char *old_target, const char *why)
{
    const char *args[] = {"--link", g_link, NULL};
    char target[256];
    ssize_t len;
    emu_run_to_exit(args);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, WEXITSTATUS(g_emu.status), g_emu.err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(g_emu.err, "xgo-emu: --link ", 16), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, old_target), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, why), g_emu.err);
    TEST_ASSERT_EQUAL_INT(0, (int)g_emu.out_len); /* no path printed */
    len = readlink(g_link, target, sizeof target - 1);
    TEST_ASSERT_TRUE_MESSAGE(len > 0, "the existing link was removed");
    target[len] = '\0';
    TEST_ASSERT_EQUAL_STRING(old_target, target);
}

/* `xgo-emu --link ~/.bashrc` must not destroy a dotfile symlink, nor take
 * over a dangling link that never was a pty's. */
static void test_link_onto_a_foreign_symlink_is_refused(void)
{
    char dotfile[160];
    snprintf(dotfile, sizeof dotfile, "%s/dotfiles-bashrc", g_dir);
    {
        FILE *f = fopen(dotfile, "w");
        TEST_ASSERT_NOT_NULL(f);
        fputs("alias ll='ls -l'\n", f);
        fclose(f);
    }
    TEST_ASSERT_EQUAL_INT(0, symlink(dotfile, g_link));
    assert_link_refused(dotfile, "not to a pty");
    xgo_test_emu_reset(&g_emu);
    TEST_ASSERT_EQUAL_INT(0, unlink(dotfile)); /* dangling now, and still no pty's */
    assert_link_refused(dotfile, "not to a pty");
    unlink(dotfile);
}

/* A second emulator must not steal the first one's name: its pty exists. */
static void test_second_instance_cannot_steal_the_link(void)
{
    char first_pty[256];
    uint8_t vx;
    emu_start_linked(NULL, NULL);
    g_first = g_emu; /* tearDown stops it too, should the test fail */
    snprintf(first_pty, sizeof first_pty, "%s", g_emu.pty);
    xgo_test_emu_init(&g_emu);
    assert_link_refused(first_pty, "a pty that exists");
    xgo_test_emu_reset(&g_emu);
    g_emu = g_first;
    xgo_test_emu_init(&g_first);
    g_port = port_open_like_pyserial(g_link, B115200); /* still the first one's */
    read_regs(g_port, 0x30, 1, &vx);
    TEST_ASSERT_EQUAL_HEX8(0x80, vx);
    emu_stop_cleanly(SIGTERM);
    assert_link_gone();
}

/* A link left by an emulator that was killed: it points into the pty
 * directory at a pty that no longer exists. Replaced, with a note. */
static void test_stale_symlink_is_replaced(void)
{
    char stale[256];
    dangling_pty_name(stale, sizeof stale);
    TEST_ASSERT_EQUAL_INT(0, symlink(stale, g_link));
    emu_start_linked(NULL, NULL); /* asserts the link now points at our pty */
    g_port = port_open_like_pyserial(g_link, B115200);
    {
        uint8_t vx;
        read_regs(g_port, 0x30, 1, &vx);
        TEST_ASSERT_EQUAL_HEX8(0x80, vx);
    }
    emu_stop_cleanly(SIGTERM);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "replaced the stale symlink"), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, stale), g_emu.err);
    assert_link_gone();
}

/* At exit the link is removed only if it still points at our pty. */
static void test_repointed_link_is_left_alone_at_exit(void)
{
    char target[64];
    ssize_t len;
    emu_start_linked(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, unlink(g_link));
    TEST_ASSERT_EQUAL_INT(0, symlink("/dev/null", g_link));
    emu_stop_cleanly(SIGTERM);
    len = readlink(g_link, target, sizeof target - 1);
    TEST_ASSERT_TRUE_MESSAGE(len > 0, "someone else's link was removed");
    target[len] = '\0';
    TEST_ASSERT_EQUAL_STRING("/dev/null", target);
}

/* Misuse: exit 2, one line "xgo-emu: ..." then the usage, nothing on stdout. */
static void assert_misuse(const char *const *args)
{
    const char *nl;
    emu_run_to_exit(args);
    TEST_ASSERT_EQUAL_INT_MESSAGE(2, WEXITSTATUS(g_emu.status), args[0]);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(g_emu.err, "xgo-emu: ", 9), g_emu.err);
    nl = strchr(g_emu.err, '\n');
    TEST_ASSERT_NOT_NULL(nl);
    /* the usage starts right after the first line (strstr keeps GCC's
     * -Wstringop-overread quiet in Release builds) */
    TEST_ASSERT_TRUE_MESSAGE(strstr(g_emu.err, "\nusage: xgo-emu") == nl, g_emu.err);
    TEST_ASSERT_EQUAL_INT(0, (int)g_emu.out_len);
}

static void test_bad_options_exit_2_with_one_line_and_usage(void)
{
    static const char *const unknown[] = {"--bogus", NULL};
    static const char *const battery[] = {"--battery", "150", NULL};
    static const char *const battery_text[] = {"--battery=abc", NULL};
    static const char *const profile[] = {"--profile", "x", NULL};
    static const char *const timeout[] = {"--timeout-ms", "-5", NULL};
    static const char *const missing[] = {"--link", NULL};
    static const char *const flag_value[] = {"--trace=yes", NULL};
    static const char *const positional[] = {"/dev/ttyUSB0", NULL};
    const char *const *cases[] = {unknown, battery, battery_text, profile,
                                  timeout, missing, flag_value, positional};
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_misuse(cases[i]);
        xgo_test_emu_reset(&g_emu);
    }
}

static void test_help_and_version_exit_0(void)
{
    static const char *const help[] = {"--help", NULL};
    static const char *const version[] = {"--version", NULL};
    emu_run_to_exit(help);
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_EQUAL_INT(0, strncmp(g_emu.out, "usage: xgo-emu", 14));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.out, "--baud-pacing"));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.out, "replaces only a stale pty link"), g_emu.out);
    xgo_test_emu_reset(&g_emu);
    emu_run_to_exit(version);
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_EQUAL_STRING("xgo-emu 0.1.0\n", g_emu.out);
}

/* The line of the trace that contains `what`, copied into line. */
static int find_trace_line(const char *what, char *line, size_t size)
{
    const char *hit = strstr(g_emu.err, what);
    const char *start, *end;
    if (hit == NULL) {
        return 0;
    }
    start = hit;
    while (start > g_emu.err && start[-1] != '\n') {
        start--;
    }
    end = strchr(hit, '\n');
    if (end == NULL || (size_t)(end - start) >= size) {
        return 0;
    }
    memcpy(line, start, (size_t)(end - start));
    line[end - start] = '\0';
    return 1;
}

static void test_trace_prints_one_line_per_frame(void)
{
    static const uint8_t bad_sum[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x99, 0x00, 0xAA};
    static const uint8_t battery = 5;
    static const uint8_t wheels_on = 1;
    static const uint8_t turn_left_90[2] = {0x00, 0x5A};
    uint8_t reply[sizeof k_spec_reply];
    char line[512];
    char expect[64];
    emu_start_linked("--trace", NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_INT((int)sizeof reply,
                          (int)xgo_test_port_read(g_port, reply, sizeof reply, REPLY_TIMEOUT_MS));
    port_write(g_port, bad_sum, sizeof bad_sum);
    port_write(g_port, k_spec_write, sizeof k_spec_write);
    write_regs(g_port, 0x01, &battery, 1); /* read-only */
    write_regs(g_port, 0xB0, &wheels_on, 1); /* wheel control: not on the Mini */
    write_regs(g_port, 0x3F, turn_left_90, 2);  /* one heading, not a foot */
    TEST_ASSERT_EQUAL_INT(0, (int)xgo_test_port_silence(g_port, 100));
    emu_stop_cleanly(SIGTERM);

    TEST_ASSERT_TRUE_MESSAGE(find_trace_line(" rx read 0x50 servo11 n=12", line, sizeof line),
                             g_emu.err);
    {
        char want[80];
        int k, at = snprintf(want, sizeof want, " tx reply 0x50 servo11 n=12 [");
        for (k = 0; k < 12; k++) {
            at += snprintf(want + at, sizeof want - (size_t)at, k < 11 ? "%02X " : "%02X]",
                           k_spec_reply[5 + k]);
        }
        TEST_ASSERT_TRUE_MESSAGE(find_trace_line(want, line, sizeof line), g_emu.err);
    }
    snprintf(expect, sizeof expect, " drop %s", xgo_drop_reason_name(XGO_DROP_BAD_CHECKSUM));
    TEST_ASSERT_TRUE_MESSAGE(find_trace_line(expect, line, sizeof line), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(line, "55 00 09 02 50 0C 99 00 AA"), line);
    TEST_ASSERT_TRUE_MESSAGE(find_trace_line(" rx write 0x30 vx n=1 [FF] vx=FF(+100%)", line,
                                             sizeof line),
                             g_emu.err);
    snprintf(expect, sizeof expect, " drop %s", xgo_drop_reason_name(XGO_DROP_READ_ONLY));
    TEST_ASSERT_TRUE_MESSAGE(find_trace_line(expect, line, sizeof line), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(line, "battery"), line);
    TEST_ASSERT_TRUE_MESSAGE(find_trace_line("ignored (not on the Mini)", line, sizeof line),
                             g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(line, "rx write 0xB0"), line);
    TEST_ASSERT_TRUE_MESSAGE(find_trace_line("rx write 0x3F turn_to n=2 [00 5A] turn_to=005A(+90 deg)",
                                             line, sizeof line),
                             g_emu.err);
}

/* --profile and --battery reach the board: firmware string and battery. */
static void test_profile_and_battery_options_reach_the_board(void)
{
    uint8_t fw[10];
    uint8_t battery;
    emu_start_linked("--profile=lite", "--battery=42");
    g_port = port_open_like_pyserial(g_link, B115200);
    read_regs(g_port, 0x07, sizeof fw, fw);
    TEST_ASSERT_EQUAL_HEX8('L', fw[0]); /* the vendor library's Lite marker */
    read_regs(g_port, 0x01, 1, &battery);
    TEST_ASSERT_EQUAL_INT(42, battery);
    emu_stop_cleanly(SIGTERM);
}

/* A 4-byte IMU read: float32 little-endian degrees. */
static float read_angle(int fd, uint8_t addr)
{
    uint8_t b[4];
    uint32_t u;
    float f;
    read_regs(fd, addr, 4, b);
    u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    memcpy(&f, &u, sizeof f);
    return f;
}

static void test_ground_tilt_misuse_exits_2(void)
{
    static const char *const bad[] = {"",      "5",      "5,",      ",5",     "a,b",
                                      "46,0",  "0,-45.001", "5;3",  "5,3,1",  "1e1,0",
                                      "nan,0", " 5,3",   "5,3 ",    "5.,3",   ".5,3",
                                      "--5,3", "0x10,0", "99999999999999999999,0"};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *args[] = {"--ground-tilt", bad[i], NULL};
        assert_misuse(args);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(g_emu.err, "xgo-emu: --ground-tilt must be", 30),
                                      g_emu.err);
        xgo_test_emu_reset(&g_emu);
    }
}

/* The IMU reads the ground's tilt; self-stabilisation (0x61 = 1) levels the
 * body so it reads about zero. Decimals reach the board exactly. */
static void test_ground_tilt_and_self_levelling(void)
{
    const uint8_t on = 1, off = 0;
    float roll, pitch;

    emu_start_linked("--ground-tilt", "10,-4");
    g_port = port_open_like_pyserial(g_link, B115200);
    xgo_test_sleep_us(100000);
    roll = read_angle(g_port, 0x62);
    pitch = read_angle(g_port, 0x63);
    TEST_ASSERT_FLOAT_WITHIN(0.2f, 10.0f, roll);
    TEST_ASSERT_FLOAT_WITHIN(0.2f, -4.0f, pitch);
    write_regs(g_port, 0x61, &on, 1);
    xgo_test_sleep_us(1200000);
    roll = read_angle(g_port, 0x62);
    pitch = read_angle(g_port, 0x63);
    TEST_ASSERT_FLOAT_WITHIN(1.0f, 0.0f, roll);
    TEST_ASSERT_FLOAT_WITHIN(1.0f, 0.0f, pitch);
    write_regs(g_port, 0x61, &off, 1); /* and back onto the slope */
    xgo_test_sleep_us(1200000);
    TEST_ASSERT_FLOAT_WITHIN(0.5f, 10.0f, read_angle(g_port, 0x62));
    close(g_port);
    g_port = -1;
    emu_stop_cleanly(SIGTERM);
    xgo_test_emu_reset(&g_emu);

    emu_start_linked("--ground-tilt=-2.5,7.125", NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    xgo_test_sleep_us(50000);
    TEST_ASSERT_FLOAT_WITHIN(0.01f, -2.5f, read_angle(g_port, 0x62));
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 7.125f, read_angle(g_port, 0x63));
    emu_stop_cleanly(SIGTERM);
}

/* A partial frame followed by silence is abandoned after --timeout-ms (the
 * loop polls the board on its own, without new bytes), not before. */
static void test_silence_timeout_follows_the_option(void)
{
    static const uint8_t partial[] = {0x55, 0x00, 0x09, 0x02};
    char expect[64];
    snprintf(expect, sizeof expect, " drop %s [55 00 09 02]",
             xgo_drop_reason_name(XGO_DROP_TIMEOUT));

    emu_start_linked("--trace", NULL); /* default: 20 ms */
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, partial, sizeof partial);
    xgo_test_sleep_ms(150);
    close(g_port);
    g_port = -1;
    emu_stop_cleanly(SIGTERM);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, expect), g_emu.err);
    xgo_test_emu_reset(&g_emu);

    emu_start_linked("--trace", "--timeout-ms=5000");
    g_port = port_open_like_pyserial(g_link, B115200);
    port_write(g_port, partial, sizeof partial);
    xgo_test_sleep_ms(150);
    emu_stop_cleanly(SIGTERM);
    TEST_ASSERT_NULL_MESSAGE(strstr(g_emu.err, expect), g_emu.err);
}

static void test_counters_are_printed_at_exit(void)
{
    uint8_t vx;
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    read_regs(g_port, 0x30, 1, &vx);
    read_regs(g_port, 0x31, 1, &vx);
    emu_stop_cleanly(SIGTERM);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  frames_ok              2\n"), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  bad_checksum           0\n"), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  host_bytes_in          18\n"), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  host_bytes_out         18\n"), g_emu.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "  ticks "), g_emu.err);
}

/* The counter `name` from the lines xgo-emu printed at exit. */
static unsigned long exit_counter(const char *name)
{
    char key[64];
    const char *at;
    snprintf(key, sizeof key, "\n  %s ", name);
    at = strstr(g_emu.err, key);
    TEST_ASSERT_NOT_NULL_MESSAGE(at, name);
    return strtoul(at + strlen(key), NULL, 10);
}

/* xgo-emu drives the board through the core's device layer (xgo/port.h),
 * as the firmware does, with no path of its own: 1000 bytes of noise and a
 * request, written while it is stopped so that one read takes them all,
 * fill its 256-byte receive ring, which pauses input (device_rx_pauses)
 * until the board has taken them; every byte read is fed by the device,
 * the reply leaves through it, and a rename is saved by it once settled. */
static void test_the_board_is_driven_through_the_device(void)
{
    static const uint8_t name[] = "Dev";
    uint8_t burst[1000 + sizeof k_spec_read];
    uint8_t reply[sizeof k_spec_reply];
    emu_start_linked(NULL, NULL);
    g_port = port_open_like_pyserial(g_link, B115200);
    memset(burst, 0x11, 1000);
    memcpy(burst + 1000, k_spec_read, sizeof k_spec_read);
    xgo_test_sleep_ms(20); /* it has seen the host attach */
    TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGSTOP));
    port_write(g_port, burst, sizeof burst);
    xgo_test_sleep_ms(20); /* all of it readable on the master */
    TEST_ASSERT_EQUAL_INT(0, kill(g_emu.pid, SIGCONT));
    TEST_ASSERT_EQUAL_INT((int)sizeof reply,
                          (int)xgo_test_port_read(g_port, reply, sizeof reply, REPLY_TIMEOUT_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, reply, sizeof reply);
    write_regs(g_port, 0x13, name, 3);
    xgo_test_sleep_ms(50); /* settled: a tick without another change */
    emu_stop_cleanly(SIGTERM);
    TEST_ASSERT_EQUAL_UINT32(sizeof burst + XGO_FRAME_OVERHEAD + 3u, exit_counter("host_bytes_in"));
    TEST_ASSERT_EQUAL_UINT32(sizeof burst + XGO_FRAME_OVERHEAD + 3u, exit_counter("device_rx_bytes"));
    TEST_ASSERT_TRUE_MESSAGE(exit_counter("device_rx_pauses") >= 1, g_emu.err);
    TEST_ASSERT_EQUAL_UINT32(sizeof reply, exit_counter("device_tx_bytes"));
    TEST_ASSERT_EQUAL_UINT32(sizeof reply, exit_counter("host_bytes_out"));
    TEST_ASSERT_EQUAL_UINT32(1, exit_counter("device_nv_saves"));
}

int main(void)
{
    int rc;
    strcpy(g_dir, "/tmp/xgo-emu-test-XXXXXX");
    if (mkdtemp(g_dir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(g_link, sizeof g_link, "%s/ttyXGO", g_dir);
    signal(SIGPIPE, SIG_IGN);
    xgo_test_emu_init(&g_first);

    UNITY_BEGIN();
    RUN_TEST(test_prints_pty_path_first_and_links_it);
    RUN_TEST(test_spec_read_example_gets_the_spec_reply);
    RUN_TEST(test_spec_write_example_gets_no_reply_and_takes_effect);
    RUN_TEST(test_garbage_then_request_gets_its_reply);
    RUN_TEST(test_control_bytes_pass_unchanged_without_host_setup);
    RUN_TEST(test_close_and_reopen_100_times);
    RUN_TEST(test_unread_replies_do_not_leak_into_the_next_session);
    RUN_TEST(test_idle_cpu_stays_low);
    RUN_TEST(test_pipelined_large_reads_all_arrive);
    RUN_TEST(test_baud_pacing_delays_replies_by_wire_time);
    RUN_TEST(test_without_pacing_replies_are_immediate);
    RUN_TEST(test_sigint_exits_0_and_removes_link);
    RUN_TEST(test_link_onto_a_regular_file_is_refused);
    RUN_TEST(test_link_onto_a_directory_is_refused);
    RUN_TEST(test_stale_symlink_is_replaced);
    RUN_TEST(test_link_onto_a_foreign_symlink_is_refused);
    RUN_TEST(test_second_instance_cannot_steal_the_link);
    RUN_TEST(test_repointed_link_is_left_alone_at_exit);
    RUN_TEST(test_bad_options_exit_2_with_one_line_and_usage);
    RUN_TEST(test_help_and_version_exit_0);
    RUN_TEST(test_trace_prints_one_line_per_frame);
    RUN_TEST(test_counters_are_printed_at_exit);
    RUN_TEST(test_the_board_is_driven_through_the_device);
    RUN_TEST(test_profile_and_battery_options_reach_the_board);
    RUN_TEST(test_ground_tilt_misuse_exits_2);
    RUN_TEST(test_ground_tilt_and_self_levelling);
    RUN_TEST(test_silence_timeout_follows_the_option);
    rc = UNITY_END();

    rmdir(g_dir);
    return rc;
}
