/*
 * test_view_server.c - xgo-emu --view end to end: a real emulator process,
 * its pty driven like the vendor library, its view server over loopback TCP.
 *
 * GET / serves the page byte for byte; /state is strict JSON whose joints
 * are what the board reports over the wire; /events delivers objects whose
 * time advances; POST /input tilts what the IMU reads over the wire; POST
 * /command walks the robot and is logged as a "view" frame; every bad
 * request gets its status; 64 connect/disconnect rounds leave no descriptor
 * behind; clients that never read neither block pty replies nor stay
 * connected for ever. Real time, every wait bounded.
 */
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "http_client.h"
#include "json_check.h"
#include "serial_port.h"
#include "test_clock.h"
#include "unity.h"
#include "xgo/protocol.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define START_TIMEOUT_MS 5000
#define STOP_TIMEOUT_MS 5000
#define REPLY_TIMEOUT_MS 1000

static xgo_test_emu_t g_emu;
static unsigned g_port;
static int g_tty = -1;
static xgo_test_http_response_t g_r;

/* Starts xgo-emu --view 0 plus options (NULL-terminated); g_port is the
 * port it printed, g_tty its pty opened like pyserial. */
static void start_with(const char *extra1, const char *extra2, const char *extra3)
{
    const char *args[6] = {"--view", "0", extra1, extra2, extra3, NULL};
    long long deadline = xgo_test_now_ms() + START_TIMEOUT_MS;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, START_TIMEOUT_MS));
    while ((g_port = xgo_test_http_view_port(g_emu.out)) == 0 && xgo_test_now_ms() < deadline) {
        TEST_ASSERT_FALSE_MESSAGE(xgo_test_emu_wait(&g_emu, 20), "xgo-emu exited");
    }
    TEST_ASSERT_TRUE_MESSAGE(g_port > 0, "no 'view: http://...' line on stdout");
    g_tty = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(g_tty >= 0);
}

/* The usual run: with --trace (stderr captured) and any extra options. */
static void start(const char *extra1, const char *extra2)
{
    start_with("--trace", extra1, extra2);
}

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    g_port = 0;
    g_tty = -1;
}

void tearDown(void)
{
    if (g_tty >= 0) {
        close(g_tty);
    }
    if (g_emu.pid > 0) {
        xgo_test_emu_stop(&g_emu, SIGTERM, STOP_TIMEOUT_MS);
    }
}

/* The file under the source tree, whole, into a static buffer. */
static const char *source_file(const char *rel, size_t *len)
{
    static char buf[XGO_TEST_HTTP_MAX];
    char path[512];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", XGO_SOURCE_DIR, rel);
    f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    *len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    return buf;
}

/* A read over the pty, as a host does it; the reply's data. */
static void read_regs(uint8_t addr, uint8_t n, uint8_t *out)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    TEST_ASSERT_EQUAL_UINT((size_t)n + XGO_FRAME_OVERHEAD,
                           xgo_test_read_reply(g_tty, addr, n, reply, REPLY_TIMEOUT_MS));
    memcpy(out, reply + 5, n);
}

static double get_number(const char *path)
{
    double v = 0;
    char why[128];
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/state", &g_r));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_valid(g_r.body, g_r.body_len, why, sizeof why), why);
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_number(g_r.body, path, &v), path);
    return v;
}

/* ------------------------------------------------------------ the tests */

static void test_prints_the_url_after_the_pty(void)
{
    char expected[512];
    start(NULL, NULL);
    snprintf(expected, sizeof expected, "%s\nview: http://127.0.0.1:%u/\n", g_emu.pty, g_port);
    TEST_ASSERT_EQUAL_STRING(expected, g_emu.out);
}

static void test_get_root_serves_the_page(void)
{
    char value[256];
    size_t len;
    const char *page = source_file("src/host/view/index.html", &len);
    start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/", &g_r));
    TEST_ASSERT_TRUE(xgo_test_http_header(&g_r, "Content-Type", value, sizeof value));
    TEST_ASSERT_EQUAL_STRING("text/html; charset=utf-8", value);
    TEST_ASSERT_TRUE(xgo_test_http_header(&g_r, "Content-Security-Policy", value, sizeof value));
    TEST_ASSERT_EQUAL_UINT(len, g_r.body_len);
    TEST_ASSERT_EQUAL_MEMORY(page, g_r.body, len);

    page = source_file("src/host/view/view.js", &len);
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/view.js", &g_r));
    TEST_ASSERT_TRUE(xgo_test_http_header(&g_r, "Content-Type", value, sizeof value));
    TEST_ASSERT_EQUAL_STRING("text/javascript; charset=utf-8", value);
    TEST_ASSERT_EQUAL_UINT(len, g_r.body_len);
    TEST_ASSERT_EQUAL_MEMORY(page, g_r.body, len);
}

/* Joints in /state against the servo registers read over the pty: the
 * register byte is the angle quantised over the joint's limits (docs/
 * registers.md), so they agree within one step of 255. */
static void test_state_joints_match_the_board(void)
{
    uint8_t bytes[12];
    char path[48];
    int i;
    start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_write_regs(g_tty, 0x35, (const uint8_t[]){0x30}, 1,
                                                 REPLY_TIMEOUT_MS)); /* crouch: joints move */
    xgo_test_sleep_ms(600);
    read_regs(0x50, 12, bytes);
    get_number("t_ms");
    for (i = 0; i < 12; i++) {
        double lo, hi, deg, from_byte;
        snprintf(path, sizeof path, "joint_limits_deg.%d.0", i);
        TEST_ASSERT_TRUE(xgo_test_json_number(g_r.body, path, &lo));
        snprintf(path, sizeof path, "joint_limits_deg.%d.1", i);
        TEST_ASSERT_TRUE(xgo_test_json_number(g_r.body, path, &hi));
        snprintf(path, sizeof path, "joints_deg.%d", i);
        TEST_ASSERT_TRUE(xgo_test_json_number(g_r.body, path, &deg));
        from_byte = lo + bytes[i] * (hi - lo) / 255.0;
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE((hi - lo) / 255.0 + 0.01, from_byte, deg, path);
    }
    TEST_ASSERT_TRUE(xgo_test_json_is_true(g_r.body, "host_connected"));
}

static void test_events_arrive_and_time_advances(void)
{
    static xgo_test_sse_t sse;
    static char event[65536];
    char why[128];
    double t_prev = -1, seq_prev = -1;
    int i;
    start("--view-hz", "50");
    TEST_ASSERT_EQUAL_INT(0, xgo_test_sse_open(&sse, g_port, 2000));
    for (i = 0; i < 5; i++) {
        double t, seq;
        TEST_ASSERT_TRUE_MESSAGE(xgo_test_sse_next(&sse, event, sizeof event, 2000), "no event");
        TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_valid(event, strlen(event), why, sizeof why), why);
        TEST_ASSERT_TRUE(xgo_test_json_number(event, "t_ms", &t));
        TEST_ASSERT_TRUE(xgo_test_json_number(event, "seq", &seq));
        TEST_ASSERT_TRUE(t > t_prev);
        TEST_ASSERT_TRUE(seq > seq_prev);
        t_prev = t;
        seq_prev = seq;
    }
    TEST_ASSERT_NOT_NULL(strstr(event, "\"frames\":["));
    close(sse.fd);
}

/* Roll over the wire: the float32 at 0x62. */
static double imu_roll_over_the_wire(void)
{
    uint8_t b[4];
    uint32_t bits;
    float f;
    read_regs(0x62, 4, b);
    bits = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static void test_post_input_tilts_what_the_imu_reads(void)
{
    start(NULL, NULL);
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 0.0, imu_roll_over_the_wire());
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_post(g_port, "/input",
                                                  "{\"ground_tilt\":{\"roll_deg\":12.5,"
                                                  "\"pitch_deg\":0},\"battery_pct\":61}",
                                                  &g_r));
    TEST_ASSERT_EQUAL_STRING("{\"ok\":true}", g_r.body);
    xgo_test_sleep_ms(50);
    TEST_ASSERT_DOUBLE_WITHIN(0.2, 12.5, imu_roll_over_the_wire());
    TEST_ASSERT_DOUBLE_WITHIN(0.2, 12.5, get_number("imu.roll_deg"));
    TEST_ASSERT_EQUAL_DOUBLE(12.5, get_number("inputs.ground_roll_deg"));
    {
        uint8_t battery;
        read_regs(0x01, 1, &battery);
        TEST_ASSERT_EQUAL_UINT8(61, battery);
    }
}

static void test_post_command_walks_and_is_traced_as_view(void)
{
    char source[16], text[128];
    long frames, i;
    int found = 0;
    start(NULL, NULL);
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_post(g_port, "/command",
                                                  "{\"writes\":[{\"addr\":\"vx\",\"data\":[255]}]}",
                                                  &g_r));
    TEST_ASSERT_EQUAL_STRING("{\"results\":[{\"addr\":48,\"n\":1,\"result\":\"ok\"}]}", g_r.body);
    xgo_test_sleep_ms(1000);
    TEST_ASSERT_TRUE(get_number("world.x_mm") > 100.0); /* ~250 mm/s after the ramp */
    frames = xgo_test_json_count(g_r.body, "frames");
    for (i = 0; i < frames && !found; i++) {
        char path[48];
        snprintf(path, sizeof path, "frames.%ld.source", i);
        TEST_ASSERT_TRUE(xgo_test_json_string(g_r.body, path, source, sizeof source));
        snprintf(path, sizeof path, "frames.%ld.text", i);
        TEST_ASSERT_TRUE(xgo_test_json_string(g_r.body, path, text, sizeof text));
        found = strcmp(source, "view") == 0 && strcmp(text, "write 0x30 vx n=1 [FF] vx=FF(+100%)") == 0;
    }
    TEST_ASSERT_TRUE_MESSAGE(found, "the write is not in /state's frames as source view");
    {
        uint8_t vx;
        read_regs(0x30, 1, &vx); /* and the host sees the register written */
        TEST_ASSERT_EQUAL_HEX8(0xFF, vx);
    }
    xgo_test_emu_stop(&g_emu, SIGTERM, STOP_TIMEOUT_MS); /* --trace went to stderr */
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "write 0x30 vx n=1 [FF] vx=FF(+100%)"));
}

/* One raw request on its own connection: status and an {"error":...}. */
static void expect_status(int status, const char *request)
{
    char error[256];
    TEST_ASSERT_EQUAL_INT_MESSAGE(status,
                                  xgo_test_http_exchange(g_port, request, strlen(request), &g_r,
                                                         2000),
                                  request);
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_string(g_r.body, "error", error, sizeof error), request);
}

static void test_bad_requests_get_their_status(void)
{
    static char big[12000];
    char request[512];
    start(NULL, NULL);
    expect_status(404, "GET /nope HTTP/1.1\r\nHost: x\r\n\r\n");
    expect_status(405, "POST /state HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n\r\n");
    expect_status(405, "GET /input HTTP/1.1\r\nHost: x\r\n\r\n");
    expect_status(405, "DELETE / HTTP/1.1\r\nHost: x\r\n\r\n");
    expect_status(400, "GET  / HTTP/1.1\r\n\r\n");
    expect_status(400, "GET / HTTP/1.1\r\n\r\n"); /* no Host */
    expect_status(505, "GET / HTTP/2.0\r\nHost: x\r\n\r\n");
    expect_status(411, "POST /input HTTP/1.1\r\nHost: x\r\n\r\n");
    expect_status(501, "POST /input HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n");
    expect_status(413, "POST /input HTTP/1.1\r\nHost: x\r\nContent-Length: 9000\r\n\r\n");
    memset(big, 'a', sizeof big - 1);
    memcpy(big, "GET / HTTP/1.1\r\nHost: x\r\nX: ", 28);
    expect_status(431, big);
    snprintf(request, sizeof request,
             "POST /input HTTP/1.1\r\nHost: evil.example:%u\r\nContent-Length: 17\r\n\r\n"
             "{\"battery_pct\":1}",
             g_port);
    expect_status(403, request);
    snprintf(request, sizeof request,
             "POST /command HTTP/1.1\r\nHost: 127.0.0.1:%u\r\nOrigin: http://evil.example\r\n"
             "Content-Length: 37\r\n\r\n{\"writes\":[{\"addr\":48,\"data\":[255]}]}",
             g_port);
    expect_status(403, request);
    TEST_ASSERT_EQUAL_INT(400, xgo_test_http_post(g_port, "/input", "{\"battery_pct\":150}", &g_r));
    TEST_ASSERT_EQUAL_STRING("{\"error\":\"battery_pct must be a whole number 0..100\"}",
                             g_r.body);
    TEST_ASSERT_EQUAL_INT(400, xgo_test_http_post(g_port, "/command", "{\"writes\":", &g_r));
    /* None of it reached the board. */
    {
        uint8_t b[2];
        read_regs(0x00, 2, b);
        TEST_ASSERT_EQUAL_UINT8(100, b[1]);
        read_regs(0x30, 1, b);
        TEST_ASSERT_EQUAL_HEX8(0x80, b[0]);
    }
}

/* Sixteen connections at once; the next is answered 503, not ignored. */
static void test_seventeenth_client_gets_503(void)
{
    int fds[16];
    int i, extra;
    start(NULL, NULL);
    for (i = 0; i < 16; i++) {
        fds[i] = xgo_test_http_connect(g_port);
        TEST_ASSERT_TRUE(fds[i] >= 0);
    }
    xgo_test_sleep_ms(100); /* all accepted */
    extra = xgo_test_http_connect(g_port);
    TEST_ASSERT_TRUE(extra >= 0);
    TEST_ASSERT_EQUAL_INT(503, xgo_test_http_read(extra, &g_r, 2000));
    close(extra);
    close(fds[0]);
    xgo_test_sleep_ms(100); /* a slot is free again */
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/state", &g_r));
    for (i = 1; i < 16; i++) {
        close(fds[i]);
    }
}

static int count_fds(pid_t pid)
{
    char path[64];
    DIR *d;
    struct dirent *e;
    int n = 0;
    snprintf(path, sizeof path, "/proc/%d/fd", (int)pid);
    d = opendir(path);
    if (d == NULL) {
        return -1;
    }
    while ((e = readdir(d)) != NULL) {
        n += e->d_name[0] != '.';
    }
    closedir(d);
    return n;
}

static void test_connections_leave_no_descriptor_behind(void)
{
    static xgo_test_sse_t sse;
    static char event[65536];
    int before, after = -1;
    int i;
    long long deadline;
    start(NULL, NULL);
    if (count_fds(g_emu.pid) < 0) {
        TEST_IGNORE_MESSAGE("no /proc/PID/fd");
    }
    TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/state", &g_r));
    xgo_test_sleep_ms(100);
    before = count_fds(g_emu.pid);
    for (i = 0; i < 64; i++) {
        switch (i % 4) {
        case 0: /* connect and go */
            close(xgo_test_http_connect(g_port));
            break;
        case 1:
            TEST_ASSERT_EQUAL_INT(200, xgo_test_http_get(g_port, "/state", &g_r));
            break;
        case 2:
            TEST_ASSERT_EQUAL_INT(0, xgo_test_sse_open(&sse, g_port, 2000));
            TEST_ASSERT_TRUE(xgo_test_sse_next(&sse, event, sizeof event, 2000));
            close(sse.fd);
            break;
        default: /* refused before its body, then gone */
            expect_status(413, "POST /input HTTP/1.1\r\nHost: x\r\nContent-Length: 99999\r\n\r\n");
            break;
        }
    }
    deadline = xgo_test_now_ms() + 3000; /* closes are noticed in the next turns */
    while ((after = count_fds(g_emu.pid)) != before && xgo_test_now_ms() < deadline) {
        xgo_test_sleep_ms(20);
    }
    TEST_ASSERT_EQUAL_INT(before, after);
}

/* Clients that never read: one event stream with a tiny receive buffer and
 * one page download. The pty keeps answering every request, and the stream
 * is dropped once its bounded output is full. */
static void test_clients_that_never_read_do_not_block_the_pty(void)
{
    int stuck_stream, stuck_page;
    char request[256];
    int i;
    start_with("--view-hz", "200", NULL); /* no --trace: the counters must fit the capture */
    stuck_stream = xgo_test_http_connect_rcvbuf(g_port, 2048);
    stuck_page = xgo_test_http_connect_rcvbuf(g_port, 2048);
    TEST_ASSERT_TRUE(stuck_stream >= 0 && stuck_page >= 0);
    snprintf(request, sizeof request, "GET /events HTTP/1.1\r\nHost: 127.0.0.1:%u\r\n\r\n", g_port);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_http_send(stuck_stream, request, strlen(request), 1000));
    for (i = 0; i < 20; i++) {
        snprintf(request, sizeof request, "GET /view.js HTTP/1.1\r\nHost: 127.0.0.1:%u\r\n\r\n",
                 g_port);
        TEST_ASSERT_EQUAL_INT(0, xgo_test_http_send(stuck_page, request, strlen(request), 1000));
    }
    for (i = 0; i < 1500; i++) { /* ~3 s of requests while the stream piles up */
        uint8_t b[12];
        read_regs(0x50, 12, b);
        xgo_test_sleep_ms(1);
    }
    xgo_test_emu_stop(&g_emu, SIGTERM, STOP_TIMEOUT_MS);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_emu.err, "view_dropped_slow      1\n"), g_emu.err);
    close(stuck_stream);
    close(stuck_page);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    UNITY_BEGIN();
    RUN_TEST(test_prints_the_url_after_the_pty);
    RUN_TEST(test_get_root_serves_the_page);
    RUN_TEST(test_state_joints_match_the_board);
    RUN_TEST(test_events_arrive_and_time_advances);
    RUN_TEST(test_post_input_tilts_what_the_imu_reads);
    RUN_TEST(test_post_command_walks_and_is_traced_as_view);
    RUN_TEST(test_bad_requests_get_their_status);
    RUN_TEST(test_seventeenth_client_gets_503);
    RUN_TEST(test_connections_leave_no_descriptor_behind);
    RUN_TEST(test_clients_that_never_read_do_not_block_the_pty);
    return UNITY_END();
}
