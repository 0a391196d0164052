/*
 * test_tcp.c - xgo-emu --tcp: the serial line over TCP, with raw sockets.
 * The printed "tcp: HOST:PORT" line (loopback by default, PORT 0 = a free
 * one), exact reply bytes to a client, writes reaching the board, a second
 * client refused with a line of text while the first is connected, the next
 * client served after the first left (its partial frame dropped, as a pty
 * host's), a TCP client refused while a host has the pty open, misuse.
 * (pyserial's socket:// client: test/tcp_pyserial.py.)
 */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "test_clock.h"
#include "unity.h"

#define START_MS 5000
#define REPLY_MS 1000

static xgo_test_emu_t g_emu;
static unsigned g_port;

static const uint8_t k_read_vx[9] = {0x55, 0x00, 0x09, 0x02, 0x30, 0x01, 0xC3, 0x00, 0xAA};
static const uint8_t k_reply_vx_80[9] = {0x55, 0x00, 0x09, 0x12, 0x30, 0x80, 0x34, 0x00, 0xAA};
static const uint8_t k_write_vx_ff[9] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
static const uint8_t k_reply_vx_ff[9] = {0x55, 0x00, 0x09, 0x12, 0x30, 0xFF, 0xB5, 0x00, 0xAA};

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
}

void tearDown(void)
{
    xgo_test_emu_kill(&g_emu);
}

/* Starts xgo-emu --tcp 0 and reads "tcp: 127.0.0.1:PORT" after the pty line. */
static void emu_start_tcp(void)
{
    const char *args[] = {"--tcp", "0", NULL};
    long long deadline = xgo_test_now_ms() + START_MS;
    const char *line;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, START_MS));
    while (strstr(g_emu.out, "\ntcp: ") == NULL || strchr(strstr(g_emu.out, "\ntcp: ") + 1, '\n') == NULL) {
        TEST_ASSERT_TRUE_MESSAGE(xgo_test_now_ms() < deadline, "no tcp: line");
        (void)xgo_test_emu_wait(&g_emu, 10);
    }
    line = strstr(g_emu.out, "\ntcp: ") + 6;
    TEST_ASSERT_EQUAL_STRING_LEN("127.0.0.1:", line, 10); /* loopback unless told */
    g_port = (unsigned)strtoul(line + 10, NULL, 10);
    TEST_ASSERT_TRUE(g_port > 0);
}

static int tcp_connect(void)
{
    struct sockaddr_in sa;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    TEST_ASSERT_TRUE(fd >= 0);
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_port = htons((uint16_t)g_port);
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    TEST_ASSERT_EQUAL_INT(0, connect(fd, (struct sockaddr *)&sa, sizeof sa));
    return fd;
}

/* Reads up to n bytes within ms; stops early at EOF. */
static size_t tcp_read(int fd, uint8_t *buf, size_t n, long ms)
{
    long long deadline = xgo_test_now_ms() + ms;
    size_t got = 0;
    while (got < n && xgo_test_now_ms() < deadline) {
        struct pollfd p;
        ssize_t k;
        p.fd = fd;
        p.events = POLLIN;
        if (poll(&p, 1, 20) <= 0) {
            continue;
        }
        k = read(fd, buf + got, n - got);
        if (k <= 0) {
            break;
        }
        got += (size_t)k;
    }
    return got;
}

static void tcp_send(int fd, const uint8_t *b, size_t n)
{
    TEST_ASSERT_EQUAL_INT((int)n, (int)write(fd, b, n));
}

/* A client connected while another is: one line, then EOF. */
static void assert_refused(const char *why)
{
    char buf[128];
    int fd = tcp_connect();
    size_t n = tcp_read(fd, (uint8_t *)buf, sizeof buf - 1, REPLY_MS);
    buf[n] = '\0';
    TEST_ASSERT_EQUAL_STRING(why, buf);
    close(fd);
}

static void test_client_gets_the_exact_replies(void)
{
    uint8_t reply[32];
    int fd;
    emu_start_tcp();
    fd = tcp_connect();
    tcp_send(fd, k_read_vx, sizeof k_read_vx);
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(fd, reply, 9, REPLY_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_reply_vx_80, reply, 9);
    /* a write reaches the board: the next read shows it, nothing else comes */
    tcp_send(fd, k_write_vx_ff, sizeof k_write_vx_ff);
    tcp_send(fd, k_read_vx, sizeof k_read_vx);
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(fd, reply, sizeof reply, 300));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_reply_vx_ff, reply, 9);
    close(fd);
}

static void test_second_client_refused_then_next_served(void)
{
    static const uint8_t partial[5] = {0x55, 0x00, 0x09, 0x02, 0x30};
    uint8_t reply[16];
    int first, next;
    emu_start_tcp();
    first = tcp_connect();
    tcp_send(first, k_read_vx, sizeof k_read_vx);
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(first, reply, 9, REPLY_MS)); /* it is being served */
    assert_refused("xgo-emu: busy, one client at a time\r\n");
    tcp_send(first, k_read_vx, sizeof k_read_vx); /* the refusal did not disturb it */
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(first, reply, 9, REPLY_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_reply_vx_80, reply, 9);
    tcp_send(first, partial, sizeof partial); /* then it leaves mid-frame */
    close(first);
    xgo_test_sleep_ms(100);
    next = tcp_connect();
    tcp_send(next, k_read_vx, sizeof k_read_vx);
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(next, reply, 9, REPLY_MS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_reply_vx_80, reply, 9);
    close(next);
    TEST_ASSERT_TRUE(xgo_test_emu_stop(&g_emu, SIGTERM, START_MS));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "tcp_clients_accepted   2\n"));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "tcp_clients_refused    1\n"));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "tcp_bytes_in           32\n"));
}

/* One line: whoever has the port. A host on the pty keeps TCP out. */
static void test_refused_while_a_host_has_the_pty(void)
{
    uint8_t reply[16];
    int pty, fd;
    emu_start_tcp();
    pty = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(pty >= 0);
    TEST_ASSERT_EQUAL_UINT(9, xgo_test_read_reply(pty, 0x30, 1, reply, REPLY_MS)); /* attached */
    assert_refused("xgo-emu: busy, a host has the serial port (pty) open\r\n");
    close(pty);
    xgo_test_sleep_ms(100);
    fd = tcp_connect();
    tcp_send(fd, k_read_vx, sizeof k_read_vx);
    /* served, although the pty host left its line at VMIN 0 (pyserial's) */
    TEST_ASSERT_EQUAL_UINT(9, tcp_read(fd, reply, 9, REPLY_MS));
    close(fd);
}

static void test_tcp_misuse_exit_2(void)
{
    const char *args[] = {"--tcp", "example.com:80", NULL};
    const char *args2[] = {"--tcp", "70000", NULL};
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_emu, START_MS));
    TEST_ASSERT_EQUAL_INT(2, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_EQUAL_STRING_LEN("xgo-emu: --tcp HOST must be an IPv4 address or localhost, not "
                                 "'example.com:80'\n",
                                 g_emu.err, 78);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args2, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_emu, START_MS));
    TEST_ASSERT_EQUAL_INT(2, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "--tcp needs [HOST:]PORT with PORT 0..65535, not '70000'"));
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    UNITY_BEGIN();
    RUN_TEST(test_client_gets_the_exact_replies);
    RUN_TEST(test_second_client_refused_then_next_served);
    RUN_TEST(test_refused_while_a_host_has_the_pty);
    RUN_TEST(test_tcp_misuse_exit_2);
    return UNITY_END();
}
