/*
 * loop.c - the event loop (see loop.h).
 *
 * Each turn, in the order a firmware's interrupts and main loop would see
 * it: signal the control ticks that are due (the timer interrupt), bring the
 * line clock up to now, run the device and store the host's input in its
 * ring as it accepts it (the RX interrupt), running the device again after
 * each batch; end a departed host's session; write the replies that are due;
 * serve the services; then poll() until the next tick, the next paced
 * byte, input or output room.
 *
 * Backpressure instead of loss: the device feeds input to the board only in
 * chunks whose replies surely fit its transmit buffer; replies leave it only
 * as fast as the port's output queue takes them; the ring takes bytes only
 * while it has room, and the pty is read only when all earlier input has
 * been fed. A host that writes requests but never reads replies therefore
 * fills the pty's buffers and blocks itself; xgo-emu keeps ticking.
 *
 * Held-back input is not silence: the line clock (xgo_port_millis) stands
 * still while input waits in the port or the pty, the device's own clock
 * while it waits in the ring, so the parser's silence timeout fires only
 * when the line really was quiet that long; bytes are stamped when fed.
 */
#include "loop.h"

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <time.h>

#include "clock.h"
#include "port_posix.h"

#define XGO_HOST_TICK_US (1000000u / XGO_TICK_HZ)

void xgo_host_loop_init(xgo_host_loop_t *l, xgo_device_t *device, xgo_port_t *port,
                        xgo_host_trace_t *trace, int baud_pacing, uint32_t uart_baud,
                        volatile sig_atomic_t *stop)
{
    const uint64_t now = xgo_host_clock_us();
    memset(l, 0, sizeof *l);
    l->device = device;
    l->port = port;
    l->trace = trace;
    l->stop = stop;
    l->next_tick_us = now + XGO_HOST_TICK_US;
    xgo_host_port_attach(port, device, l, baud_pacing, uart_baud, now);
}

int xgo_host_loop_add_service(xgo_host_loop_t *l, const xgo_host_service_t *s)
{
    if (l->service_count >= XGO_HOST_MAX_SERVICES) {
        return -1;
    }
    l->services[l->service_count++] = s;
    return 0;
}

int xgo_host_loop_host_attached(const xgo_host_loop_t *l)
{
    return !l->port->host_gone;
}

int xgo_host_loop_pty_waiting(const xgo_host_loop_t *l)
{
    return !l->port->host_gone && l->port->in_len == 0 && xgo_host_port_input_waiting(l->port);
}

void xgo_host_loop_tap(xgo_host_loop_t *l, int what, const uint8_t *bytes, size_t n)
{
    size_t s;
    for (s = 0; s < l->service_count; s++) {
        if (l->services[s]->on_line != NULL) {
            l->services[s]->on_line(l->services[s]->ctx, what, bytes, n);
        }
    }
}

void xgo_host_loop_after_tick(xgo_host_loop_t *l)
{
    size_t s;
    for (s = 0; s < l->service_count; s++) {
        if (l->services[s]->after_tick != NULL) {
            l->services[s]->after_tick(l->services[s]->ctx);
        }
    }
}

static void xgo_host_loop_note_lateness(xgo_host_loop_t *l, uint64_t late_us)
{
    uint64_t bucket = late_us / XGO_HOST_LATE_BUCKET_US;
    l->late_hist[bucket < XGO_HOST_LATE_BUCKETS ? bucket : XGO_HOST_LATE_BUCKETS - 1]++;
    if (late_us > l->late_max_us) {
        l->late_max_us = late_us;
    }
}

/* The lateness below which fraction per_mille of the rounds began, in us
 * (bucket upper bound). */
static uint64_t xgo_host_loop_lateness(const xgo_host_loop_t *l, unsigned per_mille)
{
    uint64_t total = 0, seen = 0;
    size_t i;
    for (i = 0; i < XGO_HOST_LATE_BUCKETS; i++) {
        total += l->late_hist[i];
    }
    for (i = 0; i < XGO_HOST_LATE_BUCKETS && total > 0; i++) {
        seen += l->late_hist[i];
        if (seen * 1000u >= total * per_mille) {
            return (uint64_t)(i + 1) * XGO_HOST_LATE_BUCKET_US;
        }
    }
    return 0;
}

/* The timer interrupt: one xgo_device_tick_due per period elapsed. The
 * device runs them and, after a stall of more than XGO_PORT_MAX_CATCHUP_TICKS
 * periods, skips and counts the rest; the schedule then restarts from now. */
static void xgo_host_loop_signal_ticks(xgo_host_loop_t *l, uint64_t now_us)
{
    uint64_t due;
    if (now_us < l->next_tick_us) {
        return;
    }
    xgo_host_loop_note_lateness(l, now_us - l->next_tick_us);
    due = (now_us - l->next_tick_us) / XGO_HOST_TICK_US + 1;
    if (due > XGO_PORT_MAX_CATCHUP_TICKS) {
        l->next_tick_us = now_us + XGO_HOST_TICK_US;
    } else {
        l->next_tick_us += due * XGO_HOST_TICK_US;
    }
    for (; due > 0; due--) {
        xgo_device_tick_due(l->device);
    }
}

/* Runs the device, storing the host's input into its ring while it accepts
 * bytes, until nothing more goes in (all stored, or the ring stays full
 * because the board's replies wait for the host). */
static void xgo_host_loop_serve_line(xgo_host_loop_t *l)
{
    size_t stored;
    do {
        stored = xgo_host_port_store(l->port);
        xgo_device_run(l->device);
        xgo_host_port_fed(l->port);
    } while (stored > 0);
}

/* poll() until wake_us. Linux has ppoll() (POSIX.1-2024) with microsecond
 * timeouts, which keeps ticks and paced bytes on time; elsewhere poll()'s
 * millisecond timeout is rounded up, so nothing is ever early. */
static int xgo_host_loop_wait(struct pollfd *pfd, size_t n, uint64_t now_us, uint64_t wake_us)
{
    uint64_t wait_us = wake_us > now_us ? wake_us - now_us : 0;
#ifdef __linux__
    struct timespec ts;
    ts.tv_sec = (time_t)(wait_us / 1000000u);
    ts.tv_nsec = (long)(wait_us % 1000000u) * 1000L;
    return ppoll(pfd, (nfds_t)n, &ts, NULL);
#else
    return poll(pfd, (nfds_t)n, (int)((wait_us + 999u) / 1000u));
#endif
}

/* Each service's work of this turn, with what the last poll saw. */
static void xgo_host_loop_serve_services(xgo_host_loop_t *l, uint64_t now_us)
{
    const struct pollfd *fds = l->fds + 1;
    size_t s;
    for (s = 0; s < l->service_count; s++) {
        if (l->services[s]->serve != NULL) {
            l->services[s]->serve(l->services[s]->ctx, fds, l->service_nfds[s], now_us);
        }
        fds += l->service_nfds[s];
    }
}

/* Fills l->fds[1..] with the services' descriptors; returns how many. */
static size_t xgo_host_loop_service_fds(xgo_host_loop_t *l)
{
    size_t used = 0;
    size_t s, i;
    for (s = 0; s < l->service_count; s++) {
        struct pollfd *fds = l->fds + 1 + used;
        l->service_nfds[s] = 0;
        if (l->services[s]->poll_fds != NULL) {
            l->service_nfds[s] = l->services[s]->poll_fds(l->services[s]->ctx, fds,
                                                          XGO_HOST_MAX_SERVICE_FDS - used);
        }
        for (i = 0; i < l->service_nfds[s]; i++) {
            fds[i].revents = 0; /* stays 0 if poll is interrupted */
        }
        used += l->service_nfds[s];
    }
    return used;
}

/* One turn's work before waiting. */
static void xgo_host_loop_turn(xgo_host_loop_t *l, uint64_t now)
{
    xgo_host_loop_signal_ticks(l, now);
    if (l->trace != NULL) {
        l->trace->now_us = now;
    }
    xgo_host_port_advance_clock(l->port, now);
    xgo_host_loop_serve_line(l);
    xgo_host_port_end_session(l->port);
    if (l->port->host_gone) {
        /* After serving: replies left for the departed host are dropped
         * before a new one can attach. */
        xgo_host_port_probe(l->port, now);
    }
    xgo_host_port_write(l->port, now);
    if (l->trace != NULL) {
        xgo_host_trace_tick(l->trace, now); /* folded noise, rate-bounded */
    }
    xgo_host_loop_serve_services(l, now);
}

/* Waits for the pty, the services or the next tick; reads what came. Returns
 * -1 if poll() failed for a reason other than a signal. */
static int xgo_host_loop_wait_and_read(xgo_host_loop_t *l, uint64_t now)
{
    xgo_port_t *p = l->port;
    struct pollfd *pfd = &l->fds[0];
    uint64_t wake = l->next_tick_us;
    const uint64_t due = xgo_host_port_next_due_us(p);
    size_t nfds;
    int ready;

    pfd->fd = p->host_gone ? -1 : p->pty->master_fd; /* negative fd: ignored */
    pfd->events = (short)((p->in_len == 0 ? POLLIN : 0) | (p->out_blocked ? POLLOUT : 0));
    pfd->revents = 0;
    nfds = 1 + xgo_host_loop_service_fds(l);
    /* A signal landing between the stop check and poll() is noticed at the
     * latest one tick later: the timeout never exceeds a tick. */
    ready = xgo_host_loop_wait(l->fds, nfds, now, due < wake ? due : wake);
    if (ready < 0) {
        if (errno == EINTR) {
            return 0;
        }
        fprintf(stderr, "xgo-emu: poll: %s\n", strerror(errno));
        return -1;
    }
    if (ready == 0) {
        return 0;
    }
    now = xgo_host_clock_us();
    /* Hang-up first: input still readable after it was written by a host
     * that has gone, and its replies must not reach the next one. */
    if (pfd->revents & (POLLHUP | POLLERR)) {
        xgo_host_port_host_left(p);
    }
    if (pfd->revents & POLLIN) {
        xgo_host_port_read(p, now);
    }
    return 0;
}

int xgo_host_loop_run(xgo_host_loop_t *l)
{
    while (!*l->stop) {
        const uint64_t now = xgo_host_clock_us();
        xgo_host_loop_turn(l, now);
        if (xgo_host_loop_wait_and_read(l, now) != 0) {
            return -1;
        }
    }
    return 0;
}

static void xgo_host_loop_print(FILE *out, const char *name, unsigned long long value)
{
    fprintf(out, "  %-22s %llu\n", name, value);
}

void xgo_host_loop_print_counters(const xgo_host_loop_t *l, FILE *out)
{
    uint32_t board[XGO_DIAG_COUNT];
    const xgo_host_counters_t *c = &l->port->counters;
    xgo_device_stats_t d;
    int i;

    xgo_board_counters(xgo_device_board(l->device), board);
    xgo_device_stats(l->device, &d);
    fputs("xgo-emu: counters at exit\n", out);
    for (i = 0; i < (int)XGO_DIAG_COUNT; i++) {
        xgo_host_loop_print(out, xgo_diag_name((xgo_diag_t)i), board[i]);
    }
    xgo_host_loop_print(out, "device_rx_bytes", d.rx_bytes);
    xgo_host_loop_print(out, "device_rx_pauses", d.rx_pauses);
    xgo_host_loop_print(out, "device_tx_bytes", d.tx_bytes);
    xgo_host_loop_print(out, "device_nv_saves", d.nv_saves);
    xgo_host_loop_print(out, "device_nv_failures", d.nv_save_failures);
    xgo_host_loop_print(out, "host_bytes_in", c->bytes_in);
    xgo_host_loop_print(out, "host_bytes_out", c->bytes_out);
    xgo_host_loop_print(out, "host_bytes_discarded", c->bytes_discarded);
    xgo_host_loop_print(out, "host_attaches", c->host_attaches);
    xgo_host_loop_print(out, "host_hangups", c->host_hangups);
    xgo_host_loop_print(out, "host_write_stalls", c->write_stalls);
    xgo_host_loop_print(out, "ticks", d.ticks);
    xgo_host_loop_print(out, "ticks_skipped", d.ticks_skipped);
    xgo_host_loop_print(out, "tick_late_p50_us", xgo_host_loop_lateness(l, 500));
    xgo_host_loop_print(out, "tick_late_p99_us", xgo_host_loop_lateness(l, 990));
    xgo_host_loop_print(out, "tick_late_max_us", l->late_max_us);
}
