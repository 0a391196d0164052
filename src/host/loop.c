/*
 * loop.c - the event loop (see loop.h).
 *
 * Each turn: run the control ticks that are due, feed pending input to the
 * board, move its replies to the output queue, write what is due, then
 * poll() until the next tick, the next paced byte, input or output room.
 *
 * "No host" (Linux: the master polls POLLHUP and reads fail with EIO while
 * nobody has the slave open) is a normal state. In it the master is left out
 * of poll() - POLLHUP cannot be masked, so polling it would spin - and
 * probed once per tick instead; replies for the departed host are dropped.
 *
 * Backpressure instead of loss: input is fed to the board only in chunks
 * whose replies are sure to fit both the board's transmit buffer and our
 * output queue, and the master is read only when all earlier input has been
 * fed. A host that writes requests but never reads replies therefore fills
 * the pty's buffers and blocks itself; xgo-emu keeps ticking.
 *
 * Held-back input is not silence: the parser's clock (wire_us) stands still
 * while input waits for us, in `in` or unread in the pty, so its silence
 * timeout fires only when the line really was quiet that long, and bytes are
 * stamped when they are fed, not when they were read.
 */
#include "loop.h"

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"
#include "uart_model.h"

#define XGO_HOST_TICK_US (1000000u / XGO_TICK_HZ)

/* After a stall longer than this many periods (the process was stopped, the
 * machine suspended) the missed ticks are skipped, not replayed in a burst. */
#define XGO_HOST_MAX_CATCHUP_TICKS 50u

/* Pacing without a known host speed assumes the board's own 115200 8N1. */
#define XGO_HOST_DEFAULT_BAUD 115200u

/* 10 bits per byte on the wire: start, 8 data, stop. */
#define XGO_HOST_BITS_PER_BYTE 10u

static uint64_t xgo_host_max_u64(uint64_t a, uint64_t b)
{
    return a > b ? a : b;
}

void xgo_host_loop_init(xgo_host_loop_t *l, xgo_board_t *board, const xgo_host_pty_t *pty,
                        xgo_host_trace_t *trace, int baud_pacing, volatile sig_atomic_t *stop)
{
    memset(l, 0, sizeof *l);
    l->board = board;
    l->pty = pty;
    l->trace = trace;
    l->baud_pacing = baud_pacing;
    l->stop = stop;
    xgo_host_outq_init(&l->out);
    /* Nobody has the slave open yet; the first probe finds out. */
    l->host_gone = 1;
    l->next_tick_us = xgo_host_clock_us() + XGO_HOST_TICK_US;
    l->wire_seen_us = l->next_tick_us - XGO_HOST_TICK_US;
}

void xgo_host_loop_set_state(xgo_host_loop_t *l, xgo_host_state_t *state)
{
    l->state = state;
}

void xgo_host_loop_set_uart(xgo_host_loop_t *l, uint32_t board_baud)
{
    l->uart_baud = board_baud;
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
    return !l->host_gone;
}

static uint32_t xgo_host_loop_bytes_per_s(const xgo_host_loop_t *l)
{
    uint32_t baud = xgo_host_pty_host_baud(l->pty);
    if (baud == 0) {
        baud = XGO_HOST_DEFAULT_BAUD;
    }
    return baud / XGO_HOST_BITS_PER_BYTE;
}

static void xgo_host_loop_set_trace_time(xgo_host_loop_t *l, uint64_t now_us)
{
    if (l->trace != NULL) {
        l->trace->now_us = now_us;
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

static void xgo_host_loop_run_ticks(xgo_host_loop_t *l, uint64_t now_us)
{
    uint64_t due;
    uint64_t i;
    if (now_us < l->next_tick_us) {
        return;
    }
    xgo_host_loop_note_lateness(l, now_us - l->next_tick_us);
    due = (now_us - l->next_tick_us) / XGO_HOST_TICK_US + 1;
    if (due > XGO_HOST_MAX_CATCHUP_TICKS) {
        l->counters.ticks_skipped += due - XGO_HOST_MAX_CATCHUP_TICKS;
        due = XGO_HOST_MAX_CATCHUP_TICKS;
        l->next_tick_us = now_us; /* restart the schedule from now */
    } else {
        l->next_tick_us += (due - 1) * XGO_HOST_TICK_US;
    }
    for (i = 0; i < due; i++) {
        size_t s;
        xgo_board_tick(l->board);
        for (s = 0; s < l->service_count; s++) {
            if (l->services[s]->after_tick != NULL) {
                l->services[s]->after_tick(l->services[s]->ctx);
            }
        }
    }
    l->next_tick_us += XGO_HOST_TICK_US;
    l->counters.ticks += due;
}

/* Is input waiting for us: read but not fed, or unread in the pty? */
static int xgo_host_loop_input_waiting(const xgo_host_loop_t *l)
{
    int unread = 0;
    if (l->in_fed < l->in_len) {
        return 1;
    }
    if (ioctl(l->pty->master_fd, FIONREAD, &unread) != 0) {
        return 0;
    }
    return unread > 0;
}

/* Brings the parser's clock up to now_us. Time in which input was found
 * waiting does not count: those bytes (or some of them) were on the line
 * during it, we only had not taken them yet. */
static void xgo_host_loop_advance_wire(xgo_host_loop_t *l, uint64_t now_us)
{
    if (now_us > l->wire_seen_us && !xgo_host_loop_input_waiting(l)) {
        l->wire_us += now_us - l->wire_seen_us;
    }
    if (now_us > l->wire_seen_us) {
        l->wire_seen_us = now_us;
    }
}

static uint32_t xgo_host_loop_wire_ms(const xgo_host_loop_t *l)
{
    return (uint32_t)(l->wire_us / 1000u);
}

/* Tells the services what passed the line (the capture records it). */
static void xgo_host_loop_tap(xgo_host_loop_t *l, int what, const uint8_t *bytes, size_t n)
{
    size_t s;
    for (s = 0; s < l->service_count; s++) {
        if (l->services[s]->on_line != NULL) {
            l->services[s]->on_line(l->services[s]->ctx, what, bytes, n);
        }
    }
}

int xgo_host_loop_pty_waiting(const xgo_host_loop_t *l)
{
    int unread = 0;
    return !l->host_gone && l->in_len == 0 && ioctl(l->pty->master_fd, FIONREAD, &unread) == 0 &&
           unread > 0;
}

/* Replies for a host that has gone are dropped, as on a real wire. */
static void xgo_host_loop_discard_replies(xgo_host_loop_t *l)
{
    uint8_t scratch[256];
    size_t n;
    while ((n = xgo_board_transmit(l->board, scratch, sizeof scratch)) > 0) {
        l->counters.bytes_discarded += n;
        xgo_host_loop_tap(l, XGO_HOST_LINE_DISCARDED, scratch, n);
    }
}

/* Moves the board's replies into the output queue. ready_us: the earliest a
 * reply can start on the wire (its request's last byte has arrived). */
/* --uart-baud: reply bytes as the host's port hears them at its speed
 * (uart_model.h); n <= sizeof chunk / XGO_HOST_UART_GROWTH. */
static size_t xgo_host_loop_uart_out(const xgo_host_loop_t *l, uint8_t *chunk, size_t n, size_t cap)
{
    uint8_t sent[512u / XGO_HOST_UART_GROWTH];
    memcpy(sent, chunk, n);
    return xgo_host_uart_to_host(l->uart_baud, xgo_host_pty_host_baud(l->pty), sent, n, chunk,
                                 cap);
}

static void xgo_host_loop_take_replies(xgo_host_loop_t *l, uint64_t now_us, uint64_t ready_us)
{
    uint8_t chunk[512];
    if (l->host_gone || (l->in_orphaned && l->in_len > 0)) {
        xgo_host_loop_discard_replies(l);
        return;
    }
    while (xgo_board_tx_pending(l->board) > 0) {
        size_t room = xgo_host_outq_room(&l->out);
        size_t n, want = room < sizeof chunk ? room : sizeof chunk;
        if (l->uart_baud != 0) {
            want /= XGO_HOST_UART_GROWTH; /* what the host hears may be longer */
        }
        if (want == 0) {
            return; /* stays in the board until the host reads */
        }
        n = xgo_board_transmit(l->board, chunk, want);
        if (n == 0) {
            return;
        }
        xgo_host_loop_tap(l, XGO_HOST_LINE_TO_HOST, chunk, n); /* as the board sent it */
        if (l->uart_baud != 0) {
            n = xgo_host_loop_uart_out(l, chunk, n, room < sizeof chunk ? room : sizeof chunk);
        }
        if (l->baud_pacing) {
            uint32_t bytes_per_s = xgo_host_loop_bytes_per_s(l);
            uint64_t start = xgo_host_max_u64(xgo_host_max_u64(now_us, ready_us),
                                              l->tx_wire_free_us);
            xgo_host_outq_push(&l->out, chunk, n, start, bytes_per_s);
            l->tx_wire_free_us = start + (uint64_t)n * 1000000u / bytes_per_s;
        } else {
            xgo_host_outq_push(&l->out, chunk, n, now_us, 0);
        }
    }
}

/* Feeds buffered input to the board in chunks whose replies surely fit. A
 * chunk of 9k - 8 bytes completes at most k frames (a request is at least 9
 * bytes and the first may need only one more), each answered by at most one
 * reply of at most XGO_FRAME_MAX_LEN bytes. */
static void xgo_host_loop_feed(xgo_host_loop_t *l, uint64_t now_us)
{
    while (l->in_fed < l->in_len) {
        size_t board_room = XGO_TX_BUFFER_SIZE - xgo_board_tx_pending(l->board);
        size_t out_room = (l->host_gone || l->in_orphaned) ? XGO_TX_BUFFER_SIZE
                                                            : xgo_host_outq_room(&l->out);
        size_t room = board_room < out_room ? board_room : out_room;
        size_t replies = room / XGO_FRAME_MAX_LEN;
        size_t chunk;
        uint64_t ready_us = now_us;

        if (replies == 0) {
            return; /* wait for the host to read */
        }
        chunk = replies * XGO_READ_REQUEST_LEN - (XGO_READ_REQUEST_LEN - 1);
        if (chunk > l->in_len - l->in_fed) {
            chunk = l->in_len - l->in_fed;
        }
        xgo_host_loop_set_trace_time(l, now_us);
        xgo_host_loop_tap(l, XGO_HOST_LINE_TO_BOARD, l->in + l->in_fed, chunk);
        xgo_board_receive(l->board, l->in + l->in_fed, chunk, xgo_host_loop_wire_ms(l));
        l->in_fed += chunk;
        if (l->baud_pacing) {
            ready_us = l->in_wire_start_us +
                       (uint64_t)l->in_fed * 1000000u / l->in_bytes_per_s;
        }
        xgo_host_loop_take_replies(l, now_us, ready_us);
    }
    l->in_len = 0;
    l->in_fed = 0;
    l->in_orphaned = 0;
}

/* After a hang-up, once everything the departed host wrote has been fed: a
 * partial frame it left must not prefix the next host's first request
 * (with --timeout-ms 0 nothing else would ever end it). */
static void xgo_host_loop_end_session(xgo_host_loop_t *l)
{
    if (l->hangup_pending) {
        l->hangup_pending = 0;
        xgo_host_loop_tap(l, XGO_HOST_LINE_HANGUP, NULL, 0);
        xgo_board_hangup(l->board);
        if (l->host_gone) {
            xgo_host_loop_discard_replies(l); /* what a frame found inside it asked */
        }
    }
}

static void xgo_host_loop_host_left(xgo_host_loop_t *l)
{
    if (l->host_gone) {
        return;
    }
    l->host_gone = 1;
    l->hangup_pending = 1;
    l->counters.host_hangups++;
    l->counters.bytes_discarded += xgo_host_outq_clear(&l->out);
    xgo_host_loop_discard_replies(l);
    xgo_host_pty_discard_unread(l->pty);
    l->out_blocked = 0;
    l->tx_wire_free_us = 0;
    l->rx_wire_free_us = 0;
}

/* --uart-baud: the board's UART hears the host's bytes at the speed the
 * host's port is set to (uart_model.h); bytes with a framing error are
 * counted by the board and dropped. Returns the bytes left in l->in. */
static size_t xgo_host_loop_uart_in(xgo_host_loop_t *l, size_t n)
{
    uint8_t sent[XGO_HOST_INBUF_BYTES / XGO_HOST_UART_GROWTH];
    uint32_t framing = 0;
    size_t kept;
    memcpy(sent, l->in, n);
    kept = xgo_host_uart_to_board(xgo_host_pty_host_baud(l->pty), l->uart_baud, sent, n, l->in,
                                  sizeof l->in, &framing);
    xgo_board_framing_errors(l->board, framing);
    return kept;
}

static void xgo_host_loop_read(xgo_host_loop_t *l, uint64_t now_us)
{
    ssize_t n;
    if (l->in_len != 0) {
        return; /* earlier input not fed yet: leave the rest in the kernel */
    }
    do {
        n = read(l->pty->master_fd, l->in,
                 l->uart_baud != 0 ? sizeof l->in / XGO_HOST_UART_GROWTH : sizeof l->in);
    } while (n < 0 && errno == EINTR);
    if (n > 0) {
        l->counters.bytes_in += (uint64_t)n;
        if (l->uart_baud != 0 && (n = (ssize_t)xgo_host_loop_uart_in(l, (size_t)n)) == 0) {
            return; /* nothing the board's UART could take */
        }
        l->in_orphaned = l->host_gone;
        l->in_len = (size_t)n;
        l->in_fed = 0;
        if (l->baud_pacing) {
            /* A real UART would still be receiving: the bytes arrive one
             * wire time after another, starting now or when the previous
             * burst finished, whichever is later. */
            l->in_bytes_per_s = xgo_host_loop_bytes_per_s(l);
            l->in_wire_start_us = xgo_host_max_u64(now_us, l->rx_wire_free_us);
            l->rx_wire_free_us =
                l->in_wire_start_us + (uint64_t)n * 1000000u / l->in_bytes_per_s;
        }
        return;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
        xgo_host_loop_host_left(l); /* EIO: the last host closed the slave */
    }
}

/* Is a host there? Called once per turn while we believe none is. Input a
 * departed host left behind is read here too (POLLIN with POLLHUP): it is
 * applied, but its replies are dropped rather than handed to the next host. */
static void xgo_host_loop_probe_host(xgo_host_loop_t *l, uint64_t now_us)
{
    struct pollfd pfd;
    pfd.fd = l->pty->master_fd;
    pfd.events = POLLIN;
    pfd.revents = 0;
    if (poll(&pfd, 1, 0) < 0) {
        return; /* EINTR: probe again next turn */
    }
    if ((pfd.revents & (POLLHUP | POLLERR)) == 0) {
        if (!xgo_host_loop_input_waiting(l)) {
            xgo_host_loop_end_session(l); /* before the new host's bytes arrive */
        }
        l->host_gone = 0;
        l->counters.host_attaches++;
        return;
    }
    if (pfd.revents & POLLIN) {
        xgo_host_loop_read(l, now_us);
    }
}

static void xgo_host_loop_write(xgo_host_loop_t *l, uint64_t now_us)
{
    size_t due = xgo_host_outq_due(&l->out, now_us);
    while (due > 0) {
        ssize_t n = write(l->pty->master_fd, l->out.bytes, due);
        if (n > 0) {
            xgo_host_outq_consume(&l->out, (size_t)n);
            l->counters.bytes_out += (uint64_t)n;
            due -= (size_t)n;
            l->out_blocked = 0;
            continue;
        }
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            l->out_blocked = 1;
            l->counters.write_stalls++;
            return;
        }
        xgo_host_loop_host_left(l);
        return;
    }
}

/* When the loop must wake next: the next tick, or the next paced byte. */
static uint64_t xgo_host_loop_wake_us(const xgo_host_loop_t *l)
{
    uint64_t wake = l->next_tick_us;
    if (!l->host_gone && !l->out_blocked && l->out.len > 0) {
        uint64_t due = xgo_host_outq_next_due_us(&l->out);
        if (due < wake) {
            wake = due;
        }
    }
    return wake;
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

int xgo_host_loop_run(xgo_host_loop_t *l)
{
    while (!*l->stop) {
        uint64_t now = xgo_host_clock_us();
        struct pollfd *pfd = &l->fds[0];
        size_t nfds;
        int ready;

        xgo_host_loop_run_ticks(l, now);
        if (l->state != NULL) {
            /* Cheap when nothing changed (a counter compare); a failure is
             * reported once and retried at the next change or at exit. */
            (void)xgo_host_state_sync(l->state, l->board, stderr);
        }
        if (l->host_gone) {
            xgo_host_loop_probe_host(l, now);
        }
        xgo_host_loop_advance_wire(l, now);
        xgo_host_loop_feed(l, now);
        if (!xgo_host_loop_input_waiting(l)) {
            /* Only with no input waiting: bytes held back by us, or still
             * in the pty, are not silence on the wire. */
            xgo_host_loop_set_trace_time(l, now);
            xgo_board_poll(l->board, xgo_host_loop_wire_ms(l));
            xgo_host_loop_end_session(l);
        }
        xgo_host_loop_take_replies(l, now, now);
        if (!l->host_gone) {
            xgo_host_loop_write(l, now);
        }
        if (l->trace != NULL) {
            xgo_host_trace_tick(l->trace, now); /* folded noise, rate-bounded */
        }
        xgo_host_loop_serve_services(l, now);

        pfd->fd = l->host_gone ? -1 : l->pty->master_fd; /* negative fd: ignored */
        pfd->events = (short)((l->in_len == 0 ? POLLIN : 0) | (l->out_blocked ? POLLOUT : 0));
        pfd->revents = 0;
        nfds = 1 + xgo_host_loop_service_fds(l);
        /* A signal landing between the stop check and poll() is noticed
         * at the latest one tick later: the timeout never exceeds a tick. */
        ready = xgo_host_loop_wait(l->fds, nfds, now, xgo_host_loop_wake_us(l));
        if (ready < 0) {
            if (errno == EINTR) {
                continue;
            }
            fprintf(stderr, "xgo-emu: poll: %s\n", strerror(errno));
            return -1;
        }
        if (ready == 0) {
            continue;
        }
        now = xgo_host_clock_us();
        /* Hang-up first: input still readable after it was written by a
         * host that has gone, and its replies must not reach the next one. */
        if (pfd->revents & (POLLHUP | POLLERR)) {
            xgo_host_loop_host_left(l);
        }
        if (pfd->revents & POLLIN) {
            xgo_host_loop_read(l, now);
        }
    }
    return 0;
}

void xgo_host_loop_print_counters(const xgo_host_loop_t *l, FILE *out)
{
    uint32_t board[XGO_DIAG_COUNT];
    const xgo_host_counters_t *c = &l->counters;
    int i;

    xgo_board_counters(l->board, board);
    fputs("xgo-emu: counters at exit\n", out);
    for (i = 0; i < (int)XGO_DIAG_COUNT; i++) {
        fprintf(out, "  %-22s %lu\n", xgo_diag_name((xgo_diag_t)i), (unsigned long)board[i]);
    }
    fprintf(out, "  %-22s %llu\n", "host_bytes_in", (unsigned long long)c->bytes_in);
    fprintf(out, "  %-22s %llu\n", "host_bytes_out", (unsigned long long)c->bytes_out);
    fprintf(out, "  %-22s %llu\n", "host_bytes_discarded", (unsigned long long)c->bytes_discarded);
    fprintf(out, "  %-22s %llu\n", "host_attaches", (unsigned long long)c->host_attaches);
    fprintf(out, "  %-22s %llu\n", "host_hangups", (unsigned long long)c->host_hangups);
    fprintf(out, "  %-22s %llu\n", "host_write_stalls", (unsigned long long)c->write_stalls);
    fprintf(out, "  %-22s %llu\n", "ticks", (unsigned long long)c->ticks);
    fprintf(out, "  %-22s %llu\n", "ticks_skipped", (unsigned long long)c->ticks_skipped);
    fprintf(out, "  %-22s %llu\n", "tick_late_p50_us", (unsigned long long)xgo_host_loop_lateness(l, 500));
    fprintf(out, "  %-22s %llu\n", "tick_late_p99_us", (unsigned long long)xgo_host_loop_lateness(l, 990));
    fprintf(out, "  %-22s %llu\n", "tick_late_max_us", (unsigned long long)l->late_max_us);
}
