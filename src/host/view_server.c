/*
 * view_server.c - connections of the view server (see view_server.h):
 * listening, accepting, reading requests, queueing answers and events,
 * writing what each client can take, closing the slow and the idle. What a
 * request is answered with is view_routes.c's job.
 *
 * Every socket is non-blocking and every buffer fixed: one turn of the loop
 * does a bounded amount of work here whatever the clients do.
 */
#include "view_server.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "clock.h"
#include "net.h"
#include "view_routes.h"

/* A lingering close (after an answer that ends the connection) waits this
 * long for the client's EOF, so unread request bytes do not turn our close
 * into a reset that destroys the answer. */
#define XGO_HOST_VIEW_LINGER_US 2000000u

static int xgo_host_view_listen(xgo_host_view_t *v, uint32_t addr, unsigned port, char *err,
                                size_t err_size)
{
    v->listen_fd = xgo_host_net_listen(addr, port, (int)XGO_HOST_VIEW_MAX_CLIENTS, v->host,
                                       sizeof v->host, &v->port);
    if (v->listen_fd < 0) {
        snprintf(err, err_size, "--view %s:%u: %s", v->host, port, strerror(errno));
        return -1;
    }
    return 0;
}

int xgo_host_view_open(xgo_host_view_t *v, uint32_t addr, unsigned port, unsigned hz, char *err,
                       size_t err_size)
{
    size_t i;
    memset(v, 0, sizeof *v);
    for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS; i++) {
        v->clients[i].fd = -1;
    }
    if (hz == 0 || hz > XGO_HOST_VIEW_MAX_HZ) {
        snprintf(err, err_size, "--view-hz must be 1..%u", XGO_HOST_VIEW_MAX_HZ);
        return -1;
    }
    v->period_us = 1000000u / hz;
    return xgo_host_view_listen(v, addr, port, err, err_size);
}

/* ------------------------------------------------------------ clients */

static void xgo_host_view_drop(xgo_host_view_client_t *c)
{
    if (c->fd >= 0) {
        close(c->fd);
    }
    c->fd = -1;
    c->state = XGO_HOST_VIEW_FREE;
}

static size_t xgo_host_view_unsent(const xgo_host_view_client_t *c)
{
    return (c->out_len - c->out_head) + (c->body != NULL ? c->body_len - c->body_sent : 0);
}

size_t xgo_host_view_room(const xgo_host_view_client_t *c)
{
    return XGO_HOST_VIEW_OUT_BYTES - (c->out_len - c->out_head);
}

int xgo_host_view_queue(xgo_host_view_client_t *c, const void *bytes, size_t n)
{
    if (n > xgo_host_view_room(c)) {
        return -1;
    }
    if (n > XGO_HOST_VIEW_OUT_BYTES - c->out_len) {
        memmove(c->out, c->out + c->out_head, c->out_len - c->out_head);
        c->out_len -= c->out_head;
        c->out_head = 0;
    }
    memcpy(c->out + c->out_len, bytes, n);
    c->out_len += n;
    return 0;
}

/* Refuses a connection beyond the limit with a status, not silence. Its
 * socket buffer is empty, so the short answer goes out whole. */
static void xgo_host_view_refuse(xgo_host_view_t *v, int fd)
{
    static const char k_body[] = "{\"error\":\"too many view clients (16)\"}";
    char head[256];
    size_t n = xgo_host_http_head(head, sizeof head, 503, "application/json", sizeof k_body - 1, 0,
                                  "");
    if (write(fd, head, n) == (ssize_t)n) {
        (void)!write(fd, k_body, sizeof k_body - 1);
    }
    close(fd);
    v->counters.clients_refused++;
}

static void xgo_host_view_adopt(xgo_host_view_t *v, xgo_host_view_client_t *c, int fd,
                                uint64_t now_us)
{
    struct sockaddr_in local;
    socklen_t len = sizeof local;
    int one = 1;
    int sndbuf = XGO_HOST_VIEW_SNDBUF_BYTES;
    c->fd = fd;
    c->state = XGO_HOST_VIEW_READING;
    c->deadline_us = now_us + XGO_HOST_VIEW_IDLE_US;
    c->in_len = 0;
    c->out_head = c->out_len = 0;
    c->body = NULL;
    c->body_len = c->body_sent = 0;
    c->close_when_sent = 0;
    /* Events are small and should leave at once. */
    (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    /* A fixed kernel send buffer: what a client that stopped reading can
     * hold is bounded there too, not only in `out` (autotuning would grow
     * it to megabytes before the client counts as fallen behind). */
    (void)setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
    strcpy(c->local_host, v->host);
    if (getsockname(fd, (struct sockaddr *)&local, &len) == 0) {
        inet_ntop(AF_INET, &local.sin_addr, c->local_host, sizeof c->local_host);
    }
    v->counters.clients_accepted++;
}

static void xgo_host_view_accept(xgo_host_view_t *v, uint64_t now_us)
{
    size_t tries;
    for (tries = 0; tries < XGO_HOST_VIEW_MAX_CLIENTS; tries++) {
        size_t i;
        int fd = accept(v->listen_fd, NULL, NULL);
        if (fd < 0) {
            return; /* EAGAIN: none waiting (or a transient error: next turn) */
        }
        for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS && v->clients[i].fd >= 0; i++) {
        }
        if (i == XGO_HOST_VIEW_MAX_CLIENTS || xgo_host_net_nonblocking(fd) != 0) {
            xgo_host_view_refuse(v, fd);
            continue;
        }
        xgo_host_view_adopt(v, &v->clients[i], fd, now_us);
    }
}

/* ------------------------------------------------------------ reading */

/* Reads what is waiting; 0 on EOF or error (the client is gone). */
static int xgo_host_view_read(xgo_host_view_client_t *c)
{
    char sink[4096];
    ssize_t n;
    if (c->state == XGO_HOST_VIEW_READING) {
        if (c->in_len == sizeof c->in) {
            return 1; /* full: the request is answered (and consumed) first */
        }
        n = read(c->fd, c->in + c->in_len, sizeof c->in - c->in_len);
    } else {
        n = read(c->fd, sink, sizeof sink); /* nothing more is expected: drained */
    }
    if (n > 0) {
        if (c->state == XGO_HOST_VIEW_READING) {
            c->in_len += (size_t)n;
        }
        return 1;
    }
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
}

/* Answers the request at the start of c->in once it is complete (head and
 * body), then removes it; one request per client and turn. */
static void xgo_host_view_handle(xgo_host_view_t *v, xgo_host_view_client_t *c, uint64_t now_us)
{
    xgo_host_http_request_t req;
    const char *why;
    size_t used;
    int status;

    if (c->state != XGO_HOST_VIEW_READING || c->in_len == 0 || c->close_when_sent ||
        xgo_host_view_unsent(c) > 0) {
        return; /* nothing to parse, or the previous answer is still going out */
    }
    status = xgo_host_http_parse(c->in, c->in_len, &req, &why);
    if (status == XGO_HOST_HTTP_INCOMPLETE) {
        return;
    }
    if (status != 200) {
        /* The framing of anything after it is lost: answer and close. */
        xgo_host_view_answer_error(v, c, status, why, 0);
        c->in_len = 0;
        return;
    }
    used = req.head_len + req.body_len;
    if (used > c->in_len) {
        return; /* the body is still arriving */
    }
    c->deadline_us = now_us + XGO_HOST_VIEW_IDLE_US;
    xgo_host_view_route(v, c, &req, now_us);
    if (c->state != XGO_HOST_VIEW_READING) {
        c->in_len = 0; /* an event stream: nothing more is read from it */
        return;
    }
    memmove(c->in, c->in + used, c->in_len - used);
    c->in_len -= used;
}

/* ------------------------------------------------------------ writing */

/* Writes what the socket takes; 0 if the client is gone. */
static int xgo_host_view_write(xgo_host_view_client_t *c)
{
    while (c->out_head < c->out_len || (c->body != NULL && c->body_sent < c->body_len)) {
        const void *p;
        size_t n;
        ssize_t w;
        if (c->out_head < c->out_len) {
            p = c->out + c->out_head;
            n = c->out_len - c->out_head;
        } else {
            p = c->body + c->body_sent;
            n = c->body_len - c->body_sent;
        }
        w = write(c->fd, p, n);
        if (w < 0) {
            return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
        }
        if (c->out_head < c->out_len) {
            c->out_head += (size_t)w;
        } else {
            c->body_sent += (size_t)w;
        }
    }
    c->out_head = c->out_len = 0;
    c->body = NULL;
    return 1;
}

/* After the last byte of a closing answer: shut our side, wait for EOF. */
static void xgo_host_view_linger(xgo_host_view_client_t *c, uint64_t now_us)
{
    if (c->close_when_sent && c->out_len == 0 && c->body == NULL &&
        c->state != XGO_HOST_VIEW_LINGERING) {
        shutdown(c->fd, SHUT_WR);
        c->state = XGO_HOST_VIEW_LINGERING;
        c->deadline_us = now_us + XGO_HOST_VIEW_LINGER_US;
    }
}

/* ------------------------------------------------------------ events */

/* Frames rendered to JSON per step of an event's sending (~2 us each). */
#define XGO_HOST_VIEW_RENDER_STEP 8u

/* Starts the period's event when it is due: the shared members now, the
 * clients to send it to. */
static void xgo_host_view_start_event(xgo_host_view_t *v, uint64_t now_us)
{
    size_t i;
    if (v->event_todo != 0 || now_us < v->next_event_us) {
        return; /* the last one is still going out, or not due */
    }
    v->next_event_us += v->period_us;
    if (v->next_event_us <= now_us) {
        v->next_event_us = now_us + v->period_us; /* after a stall: no burst */
    }
    for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS; i++) {
        if (v->clients[i].state == XGO_HOST_VIEW_STREAMING) {
            v->event_todo |= 1u << i;
        }
    }
    if (v->event_todo != 0) {
        xgo_host_view_begin_object(v, &v->event_prefix, v->event_object, sizeof v->event_object);
    }
}

/* Sends the period's event in steps (render a few frames, or one client's
 * copy), stopping between steps as soon as host bytes wait on the pty: the
 * next turn serves them first and this goes on after. One step always runs,
 * so the event is never starved. A client whose output cannot take its copy
 * has fallen behind and is dropped. */
static void xgo_host_view_send_events(xgo_host_view_t *v)
{
    while (v->event_todo != 0) {
        if (xgo_host_view_state_render(&v->frames, XGO_HOST_VIEW_RENDER_STEP) == 0) {
            unsigned i = 0;
            xgo_host_view_client_t *c;
            while (!(v->event_todo & (1u << i))) {
                i++;
            }
            v->event_todo &= ~(1u << i);
            c = &v->clients[i];
            if (c->state == XGO_HOST_VIEW_STREAMING &&
                xgo_host_view_send_event(v, c, &v->event_prefix) != 0) {
                v->counters.clients_dropped++;
                xgo_host_view_drop(c);
            }
        }
        if (xgo_host_loop_pty_waiting(v->loop)) {
            return;
        }
    }
}

/* ------------------------------------------------------------ the turn */

static size_t xgo_host_view_poll_fds(void *ctx, struct pollfd *fds, size_t max)
{
    xgo_host_view_t *v = ctx;
    size_t n = 0;
    size_t i;
    if (max == 0) {
        return 0;
    }
    fds[n].fd = v->listen_fd;
    fds[n++].events = POLLIN;
    for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS && n < max; i++) {
        const xgo_host_view_client_t *c = &v->clients[i];
        int pending = xgo_host_view_unsent(c) > 0;
        /* Input is polled only when it will be read: a request waiting for
         * its answer to go out would otherwise wake us in a spin. */
        int want_in = c->state != XGO_HOST_VIEW_READING ||
                      (!pending && !c->close_when_sent && c->in_len < sizeof c->in);
        if (c->fd < 0) {
            continue;
        }
        fds[n].fd = c->fd;
        fds[n++].events = (short)((want_in ? POLLIN : 0) | (pending ? POLLOUT : 0));
    }
    return n;
}

/* Idle connections and unanswered, half-sent requests do not hold a slot
 * for ever. */
static void xgo_host_view_expire(xgo_host_view_t *v, xgo_host_view_client_t *c, uint64_t now_us)
{
    if (c->state == XGO_HOST_VIEW_STREAMING || now_us < c->deadline_us) {
        return;
    }
    if (c->state == XGO_HOST_VIEW_LINGERING) {
        xgo_host_view_drop(c); /* no EOF in time: close anyway */
        return;
    }
    if (c->state == XGO_HOST_VIEW_READING && c->in_len > 0 && c->out_len == 0 && c->body == NULL) {
        xgo_host_view_answer_error(v, c, 408, "request not completed in time", 0);
        c->in_len = 0;
        c->deadline_us = now_us + XGO_HOST_VIEW_LINGER_US;
        return;
    }
    v->counters.clients_timed_out++;
    xgo_host_view_drop(c);
}

static void xgo_host_view_serve_client(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                       short revents, uint64_t now_us)
{
    size_t unsent;
    if ((revents & (POLLIN | POLLHUP | POLLERR)) && !xgo_host_view_read(c)) {
        xgo_host_view_drop(c); /* EOF or error: the client has gone */
        return;
    }
    xgo_host_view_handle(v, c, now_us);
    unsent = xgo_host_view_unsent(c);
    if (!xgo_host_view_write(c)) {
        xgo_host_view_drop(c);
        return;
    }
    if (xgo_host_view_unsent(c) < unsent && c->state == XGO_HOST_VIEW_READING) {
        /* An answer going out: the idle limit counts from its progress. */
        c->deadline_us = now_us + XGO_HOST_VIEW_IDLE_US;
    }
    xgo_host_view_linger(c, now_us);
    xgo_host_view_expire(v, c, now_us);
}

static void xgo_host_view_note_busy(xgo_host_view_t *v, uint64_t busy_us)
{
    uint64_t bucket = busy_us / XGO_HOST_VIEW_BUSY_BUCKET_US;
    v->busy_hist[bucket < XGO_HOST_VIEW_BUSY_BUCKETS ? bucket : XGO_HOST_VIEW_BUSY_BUCKETS - 1]++;
    if (busy_us > v->busy_max_us) {
        v->busy_max_us = busy_us;
    }
}

/* Turns with work, the time below which per_mille of them ended, in us. */
static uint64_t xgo_host_view_busy(const xgo_host_view_t *v, unsigned per_mille)
{
    uint64_t total = 0, seen = 0;
    size_t i;
    for (i = 0; i < XGO_HOST_VIEW_BUSY_BUCKETS; i++) {
        total += v->busy_hist[i];
    }
    for (i = 0; i < XGO_HOST_VIEW_BUSY_BUCKETS && total > 0; i++) {
        seen += v->busy_hist[i];
        if (seen * 1000u >= total * per_mille) {
            return (uint64_t)(i + 1) * XGO_HOST_VIEW_BUSY_BUCKET_US;
        }
    }
    return 0;
}

/* One turn's work: new connections, the event due, then every client. */
static void xgo_host_view_serve_turn(xgo_host_view_t *v, const struct pollfd *fds, size_t n,
                                     uint64_t now_us)
{
    size_t i;
    if (n > 0 && (fds[0].revents & POLLIN)) {
        xgo_host_view_accept(v, now_us);
    }
    xgo_host_view_start_event(v, now_us);
    xgo_host_view_send_events(v);
    for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS; i++) {
        xgo_host_view_client_t *c = &v->clients[i];
        short revents = 0;
        size_t k;
        if (c->fd < 0) {
            continue;
        }
        for (k = 1; k < n; k++) {
            if (fds[k].fd == c->fd) {
                revents = fds[k].revents;
            }
        }
        xgo_host_view_serve_client(v, c, revents, now_us);
    }
}

static void xgo_host_view_serve(void *ctx, const struct pollfd *fds, size_t n, uint64_t now_us)
{
    xgo_host_view_t *v = ctx;
    uint64_t start_us = xgo_host_clock_us(); /* now_us is the turn's start, before the pty */
    xgo_host_view_serve_turn(v, fds, n, now_us);
    xgo_host_view_note_busy(v, xgo_host_clock_us() - start_us);
}

int xgo_host_view_attach(xgo_host_view_t *v, xgo_board_t *board, unsigned model,
                         xgo_host_loop_t *loop, xgo_host_trace_t *trace_out)
{
    v->board = board;
    v->model = model;
    v->profile = xgo_profile_get(model);
    v->loop = loop;
    xgo_host_view_frames_init(&v->frames, board, trace_out);
    xgo_board_set_trace(board, xgo_host_view_frames_event, &v->frames);
    v->service.after_tick = NULL;
    v->service.poll_fds = xgo_host_view_poll_fds;
    v->service.serve = xgo_host_view_serve;
    v->service.ctx = v;
    return xgo_host_loop_add_service(loop, &v->service);
}

void xgo_host_view_close(xgo_host_view_t *v)
{
    size_t i;
    for (i = 0; i < XGO_HOST_VIEW_MAX_CLIENTS; i++) {
        xgo_host_view_drop(&v->clients[i]);
    }
    if (v->listen_fd >= 0) {
        close(v->listen_fd);
    }
    v->listen_fd = -1;
}

void xgo_host_view_print_counters(const xgo_host_view_t *v, FILE *out)
{
    const xgo_host_view_counters_t *c = &v->counters;
    fprintf(out, "  %-22s %llu\n", "view_clients", (unsigned long long)c->clients_accepted);
    fprintf(out, "  %-22s %llu\n", "view_refused", (unsigned long long)c->clients_refused);
    fprintf(out, "  %-22s %llu\n", "view_dropped_slow", (unsigned long long)c->clients_dropped);
    fprintf(out, "  %-22s %llu\n", "view_timed_out", (unsigned long long)c->clients_timed_out);
    fprintf(out, "  %-22s %llu\n", "view_requests", (unsigned long long)c->requests);
    fprintf(out, "  %-22s %llu\n", "view_bad_requests", (unsigned long long)c->bad_requests);
    fprintf(out, "  %-22s %llu\n", "view_events", (unsigned long long)c->events);
    fprintf(out, "  %-22s %llu\n", "view_busy_p99_us", (unsigned long long)xgo_host_view_busy(v, 990));
    fprintf(out, "  %-22s %llu\n", "view_busy_max_us", (unsigned long long)v->busy_max_us);
}
