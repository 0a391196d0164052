/* tcp_bridge.c - the serial line over TCP (see tcp_bridge.h). */
#include "tcp_bridge.h"

#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "net.h"
#include "serial.h"

static const char xgo_host_tcp_busy[] = "xgo-emu: busy, one client at a time\r\n";
static const char xgo_host_tcp_pty_busy[] = "xgo-emu: busy, a host has the serial port (pty) open\r\n";

/* Says why and closes: the client sees a line of text, then EOF. */
static void xgo_host_tcp_refuse(xgo_host_tcp_t *t, int fd, const char *why)
{
    (void)send(fd, why, strlen(why), MSG_DONTWAIT); /* SIGPIPE is ignored (main.c) */
    close(fd);
    t->counters.refused++;
}

/* The client is gone (or we end it): the bridge lets go of the pty, which
 * the loop sees as the host hanging up. */
static void xgo_host_tcp_drop_client(xgo_host_tcp_t *t)
{
    if (t->client_fd >= 0) {
        close(t->client_fd);
        t->client_fd = -1;
    }
    if (t->slave_fd >= 0) {
        close(t->slave_fd);
        t->slave_fd = -1;
    }
    t->to_board_len = 0;
    t->to_client_len = 0;
}

static void xgo_host_tcp_accept(xgo_host_tcp_t *t)
{
    int one = 1;
    int fd = accept(t->listen_fd, NULL, NULL);
    if (fd < 0) {
        return; /* EAGAIN, or a client that left already */
    }
    if (t->client_fd >= 0) {
        xgo_host_tcp_refuse(t, fd, xgo_host_tcp_busy);
        return;
    }
    if (xgo_host_loop_host_attached(t->loop)) {
        xgo_host_tcp_refuse(t, fd, xgo_host_tcp_pty_busy);
        return;
    }
    /* The line as the board's UART is (raw 8N1, 115200), whatever a host
     * before left it at: TCP carries bytes, not terminal settings. */
    t->slave_fd = open(t->pty_path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (t->slave_fd < 0 || xgo_host_serial_make_raw(t->slave_fd, XGO_HOST_DEFAULT_BAUD) != 0 ||
        xgo_host_net_nonblocking(fd) != 0) {
        xgo_host_tcp_refuse(t, fd, xgo_host_tcp_busy);
        if (t->slave_fd >= 0) {
            close(t->slave_fd);
            t->slave_fd = -1;
        }
        return;
    }
    (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one); /* replies go at once */
    t->client_fd = fd;
    t->counters.accepted++;
}

/* Reads what fits from `from` into buf; 0 when the other end is gone. A
 * pty slave reads 0 bytes when it has none (VMIN 0), never end of file. */
static int xgo_host_tcp_pull(int from, int is_pty, uint8_t *buf, size_t *len, uint64_t *count)
{
    ssize_t n;
    if (*len == XGO_HOST_TCP_BUF) {
        return 1;
    }
    n = read(from, buf + *len, XGO_HOST_TCP_BUF - *len);
    if (n > 0) {
        *len += (size_t)n;
        *count += (uint64_t)n;
        return 1;
    }
    return (n == 0 && is_pty) || (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR));
}

/* Writes what `to` takes from buf; 0 when the other end is gone. */
static int xgo_host_tcp_push(int to, uint8_t *buf, size_t *len)
{
    ssize_t n;
    if (*len == 0) {
        return 1;
    }
    n = write(to, buf, *len); /* both non-blocking; SIGPIPE is ignored (main.c) */
    if (n > 0) {
        memmove(buf, buf + n, *len - (size_t)n);
        *len -= (size_t)n;
        return 1;
    }
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
}

/* Copies both ways as far as the buffers and the other ends allow. */
static void xgo_host_tcp_shuttle(xgo_host_tcp_t *t)
{
    uint64_t from_pty = 0;
    int ok = xgo_host_tcp_pull(t->client_fd, 0, t->to_board, &t->to_board_len, &t->counters.bytes_in) &&
             xgo_host_tcp_push(t->slave_fd, t->to_board, &t->to_board_len) &&
             xgo_host_tcp_pull(t->slave_fd, 1, t->to_client, &t->to_client_len, &from_pty) &&
             xgo_host_tcp_push(t->client_fd, t->to_client, &t->to_client_len);
    t->counters.bytes_out += from_pty;
    if (!ok) {
        xgo_host_tcp_drop_client(t);
    }
}

static size_t xgo_host_tcp_poll_fds(void *ctx, struct pollfd *fds, size_t max)
{
    xgo_host_tcp_t *t = ctx;
    size_t n = 0;
    if (max < 3) {
        return 0;
    }
    fds[n].fd = t->listen_fd;
    fds[n++].events = POLLIN;
    if (t->client_fd >= 0) {
        fds[n].fd = t->client_fd;
        fds[n++].events = (short)((t->to_board_len < XGO_HOST_TCP_BUF ? POLLIN : 0) |
                                  (t->to_client_len > 0 ? POLLOUT : 0));
        fds[n].fd = t->slave_fd;
        fds[n++].events = (short)((t->to_client_len < XGO_HOST_TCP_BUF ? POLLIN : 0) |
                                  (t->to_board_len > 0 ? POLLOUT : 0));
    }
    return n;
}

static void xgo_host_tcp_serve(void *ctx, const struct pollfd *fds, size_t n, uint64_t now_us)
{
    xgo_host_tcp_t *t = ctx;
    (void)now_us;
    if (n > 0 && (fds[0].revents & POLLIN)) {
        xgo_host_tcp_accept(t);
    }
    if (t->client_fd >= 0) {
        xgo_host_tcp_shuttle(t);
    }
}

int xgo_host_tcp_open(xgo_host_tcp_t *t, uint32_t addr, unsigned port, const char *pty_path,
                      const xgo_host_loop_t *loop, char *err, size_t err_size)
{
    memset(t, 0, sizeof *t);
    t->client_fd = -1;
    t->slave_fd = -1;
    t->pty_path = pty_path;
    t->loop = loop;
    t->listen_fd = xgo_host_net_listen(addr, port, 4, t->host, sizeof t->host, &t->port);
    if (t->listen_fd < 0) {
        snprintf(err, err_size, "--tcp %s:%u: %s", t->host, port, strerror(errno));
        return -1;
    }
    t->service.poll_fds = xgo_host_tcp_poll_fds;
    t->service.serve = xgo_host_tcp_serve;
    t->service.ctx = t;
    return 0;
}

void xgo_host_tcp_print_counters(const xgo_host_tcp_t *t, FILE *out)
{
    fprintf(out, "  %-22s %lu\n", "tcp_clients_accepted", t->counters.accepted);
    fprintf(out, "  %-22s %lu\n", "tcp_clients_refused", t->counters.refused);
    fprintf(out, "  %-22s %llu\n", "tcp_bytes_in", (unsigned long long)t->counters.bytes_in);
    fprintf(out, "  %-22s %llu\n", "tcp_bytes_out", (unsigned long long)t->counters.bytes_out);
}

void xgo_host_tcp_close(xgo_host_tcp_t *t)
{
    xgo_host_tcp_drop_client(t);
    if (t->listen_fd >= 0) {
        close(t->listen_fd);
        t->listen_fd = -1;
    }
}
