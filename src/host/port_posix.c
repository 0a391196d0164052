/*
 * port_posix.c - xgo-emu's port of the core (see port_posix.h).
 *
 * "No host" (Linux: the master polls POLLHUP and reads fail with EIO while
 * nobody has the slave open) is a normal state: the loop then leaves the
 * master out of poll() and probes it once per turn; replies made meanwhile
 * are dropped, as bytes sent to a closed port are on a real wire.
 */
#include "port_posix.h"

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "loop.h"
#include "uart_model.h"

/* Pacing without a known host speed assumes the board's own 115200 8N1. */
#define XGO_HOST_DEFAULT_BAUD 115200u

/* 10 bits per byte on the wire: start, 8 data, stop. */
#define XGO_HOST_BITS_PER_BYTE 10u

/* The most reply bytes taken at once through the UART model (its output
 * may be XGO_HOST_UART_GROWTH times longer). */
#define XGO_HOST_UART_CHUNK 64u

/* A failed --state save is tried again after this long. */
#define XGO_HOST_NV_RETRY_US 1000000u

static uint64_t xgo_host_max_u64(uint64_t a, uint64_t b)
{
    return a > b ? a : b;
}

void xgo_host_port_init(xgo_port_t *p, const xgo_host_pty_t *pty, xgo_host_state_t *state)
{
    memset(p, 0, sizeof *p);
    p->pty = pty;
    p->state = state;
    xgo_host_outq_init(&p->out);
    p->host_gone = 1; /* nobody has the slave open yet; the first probe finds out */
}

void xgo_host_port_attach(xgo_port_t *p, xgo_device_t *device, struct xgo_host_loop_s *loop,
                          int baud_pacing, uint32_t uart_baud, uint64_t now_us)
{
    p->device = device;
    p->loop = loop;
    p->baud_pacing = baud_pacing;
    p->uart_baud = uart_baud;
    p->now_us = now_us;
    p->wire_seen_us = now_us;
}

static uint32_t xgo_host_port_bytes_per_s(const xgo_port_t *p)
{
    uint32_t baud = xgo_host_pty_host_baud(p->pty);
    if (baud == 0) {
        baud = XGO_HOST_DEFAULT_BAUD;
    }
    return baud / XGO_HOST_BITS_PER_BYTE;
}

static void xgo_host_port_tap_fed(xgo_port_t *p);

/* ---- the port boundary (xgo/port.h) ------------------------------------- */

uint32_t xgo_port_millis(xgo_port_t *p)
{
    return (uint32_t)(p->wire_us / 1000u);
}

/* Replies for a host that has gone (or to input it left behind) are
 * dropped, as on a real wire. */
static int xgo_host_port_discarding(const xgo_port_t *p)
{
    return p->host_gone || p->in_orphaned;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    size_t room;
    if (xgo_host_port_discarding(p)) {
        return XGO_TX_BUFFER_SIZE;
    }
    room = xgo_host_outq_room(&p->out);
    if (p->uart_baud != 0) {
        room /= XGO_HOST_UART_GROWTH; /* what the host hears may be longer */
        room = room < XGO_HOST_UART_CHUNK ? room : XGO_HOST_UART_CHUNK;
    }
    return room;
}

/* When a reply may start on the wire: once its request's last byte has
 * arrived (the bytes of `in` arrive one wire time after another). */
static uint64_t xgo_host_port_reply_ready_us(const xgo_port_t *p)
{
    xgo_device_stats_t st;
    if (!p->baud_pacing || p->in_len == 0) {
        return p->now_us;
    }
    xgo_device_stats(p->device, &st);
    return p->in_wire_start_us +
           (uint64_t)(uint32_t)(st.rx_bytes - p->in_base) * 1000000u / p->in_bytes_per_s;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    uint8_t heard[XGO_HOST_UART_CHUNK * XGO_HOST_UART_GROWTH];
    xgo_host_port_tap_fed(p); /* the requests before their replies */
    if (xgo_host_port_discarding(p)) {
        p->counters.bytes_discarded += n;
        xgo_host_loop_tap(p->loop, XGO_HOST_LINE_DISCARDED, bytes, n);
        return;
    }
    xgo_host_loop_tap(p->loop, XGO_HOST_LINE_TO_HOST, bytes, n); /* as the board sent it */
    if (p->uart_baud != 0) {
        n = xgo_host_uart_to_host(p->uart_baud, xgo_host_pty_host_baud(p->pty), bytes, n, heard,
                                  sizeof heard);
        bytes = heard;
    }
    if (p->baud_pacing) {
        uint32_t bytes_per_s = xgo_host_port_bytes_per_s(p);
        uint64_t start = xgo_host_max_u64(xgo_host_port_reply_ready_us(p), p->tx_wire_free_us);
        xgo_host_outq_push(&p->out, bytes, n, xgo_host_max_u64(start, p->now_us), bytes_per_s);
        p->tx_wire_free_us = xgo_host_max_u64(start, p->now_us) +
                             (uint64_t)n * 1000000u / bytes_per_s;
    } else {
        xgo_host_outq_push(&p->out, bytes, n, p->now_us, 0);
    }
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    (void)p; /* the loop stores more as soon as xgo_device_rx_accepting says so */
}

int xgo_port_nv_load(xgo_port_t *p, xgo_board_nv_t *nv)
{
    return p->state != NULL && xgo_host_state_loaded(p->state, nv);
}

/* Without --state the data lives as long as the process, like RAM. The
 * device retries a failed save every settle period (one tick here): the
 * file system is tried again at most once a second meanwhile. */
int xgo_port_nv_save(xgo_port_t *p, const xgo_board_nv_t *nv)
{
    if (p->state == NULL) {
        return 1;
    }
    if (p->nv_failed_us != 0 && p->now_us - p->nv_failed_us < XGO_HOST_NV_RETRY_US) {
        return 0;
    }
    if (xgo_host_state_store(p->state, nv, stderr) == 0) {
        p->nv_failed_us = 0;
        return 1;
    }
    p->nv_failed_us = p->now_us != 0 ? p->now_us : 1u;
    return 0;
}

/* The host has no servo bus: its "servos" are the services that look at
 * the board after every tick (the live view, the motion log), through the
 * board's observers. */
void xgo_port_servo_write(xgo_port_t *p, const int32_t raw_mdeg[XGO_SERVO_COUNT], uint16_t limp)
{
    (void)raw_mdeg;
    (void)limp;
    if (p->loop != NULL) {
        xgo_host_loop_after_tick(p->loop);
    }
}

/* ---- input -------------------------------------------------------------- */

int xgo_host_port_input_waiting(const xgo_port_t *p)
{
    int unread = 0;
    if (p->in_len > 0) {
        return 1; /* in `in` or in the ring */
    }
    if (ioctl(p->pty->master_fd, FIONREAD, &unread) != 0) {
        return 0;
    }
    return unread > 0;
}

/* Time in which input was found waiting does not count: those bytes (or
 * some of them) were on the line during it, we only had not taken them yet. */
void xgo_host_port_advance_clock(xgo_port_t *p, uint64_t now_us)
{
    p->now_us = now_us;
    if (now_us > p->wire_seen_us && !xgo_host_port_input_waiting(p)) {
        p->wire_us += now_us - p->wire_seen_us;
    }
    if (now_us > p->wire_seen_us) {
        p->wire_seen_us = now_us;
    }
}

size_t xgo_host_port_store(xgo_port_t *p)
{
    const size_t before = p->in_put;
    while (p->in_put < p->in_len && xgo_device_rx_accepting(p->device)) {
        (void)xgo_device_rx_put(p->device, p->in[p->in_put++]);
    }
    return p->in_put - before;
}

/* Tells the services the bytes of `in` the device has fed to the board
 * since last time (its rx_bytes counts them). */
static void xgo_host_port_tap_fed(xgo_port_t *p)
{
    xgo_device_stats_t st;
    size_t fed;
    if (p->in_len == 0) {
        return;
    }
    xgo_device_stats(p->device, &st);
    fed = (size_t)(uint32_t)(st.rx_bytes - p->in_base);
    if (fed > p->in_tapped) {
        xgo_host_loop_tap(p->loop, XGO_HOST_LINE_TO_BOARD, p->in + p->in_tapped,
                          fed - p->in_tapped);
        p->in_tapped = fed;
    }
}

/* `in` is released only here, after a run: until then its replies know
 * where they came from (their wire time, an orphaned host). */
void xgo_host_port_fed(xgo_port_t *p)
{
    xgo_host_port_tap_fed(p);
    if (p->in_len > 0 && p->in_tapped == p->in_len) {
        p->in_len = 0;
        p->in_put = 0;
        p->in_tapped = 0;
        p->in_orphaned = 0;
    }
}

/* --uart-baud: the board's UART hears the host's bytes at the speed the
 * host's port is set to (uart_model.h); bytes with a framing error are
 * dropped there and counted, as a UART's error flag would be. Returns the
 * bytes left in p->in. */
static size_t xgo_host_port_uart_in(xgo_port_t *p, size_t n)
{
    uint8_t sent[XGO_HOST_INBUF_BYTES / XGO_HOST_UART_GROWTH];
    uint32_t framing = 0;
    size_t kept;
    memcpy(sent, p->in, n);
    kept = xgo_host_uart_to_board(xgo_host_pty_host_baud(p->pty), p->uart_baud, sent, n, p->in,
                                  sizeof p->in, &framing);
    xgo_board_framing_errors(xgo_device_board(p->device), framing);
    return kept;
}

/* A new burst: a real UART would still be receiving it, the bytes arriving
 * one wire time after another, from now or from when the previous burst
 * finished, whichever is later. */
static void xgo_host_port_take_burst(xgo_port_t *p, size_t n, uint64_t now_us)
{
    xgo_device_stats_t st;
    xgo_device_stats(p->device, &st);
    p->in_orphaned = p->host_gone;
    p->in_len = n;
    p->in_put = 0;
    p->in_tapped = 0;
    p->in_base = st.rx_bytes;
    if (p->baud_pacing) {
        p->in_bytes_per_s = xgo_host_port_bytes_per_s(p);
        p->in_wire_start_us = xgo_host_max_u64(now_us, p->rx_wire_free_us);
        p->rx_wire_free_us = p->in_wire_start_us + (uint64_t)n * 1000000u / p->in_bytes_per_s;
    }
}

void xgo_host_port_read(xgo_port_t *p, uint64_t now_us)
{
    ssize_t n;
    if (p->in_len != 0) {
        return; /* earlier input not fed yet: leave the rest in the kernel */
    }
    do {
        n = read(p->pty->master_fd, p->in,
                 p->uart_baud != 0 ? sizeof p->in / XGO_HOST_UART_GROWTH : sizeof p->in);
    } while (n < 0 && errno == EINTR);
    if (n > 0) {
        p->counters.bytes_in += (uint64_t)n;
        if (p->uart_baud != 0 && (n = (ssize_t)xgo_host_port_uart_in(p, (size_t)n)) == 0) {
            return; /* nothing the board's UART could take */
        }
        xgo_host_port_take_burst(p, (size_t)n, now_us);
        return;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
        xgo_host_port_host_left(p); /* EIO: the last host closed the slave */
    }
}

/* ---- hosts coming and going --------------------------------------------- */

void xgo_host_port_end_session(xgo_port_t *p)
{
    if (p->hangup_pending && !xgo_host_port_input_waiting(p)) {
        p->hangup_pending = 0;
        xgo_host_loop_tap(p->loop, XGO_HOST_LINE_HANGUP, NULL, 0);
        xgo_device_hangup(p->device); /* the ring is empty: at once */
    }
}

void xgo_host_port_host_left(xgo_port_t *p)
{
    if (p->host_gone) {
        return;
    }
    p->host_gone = 1;
    p->hangup_pending = 1;
    p->counters.host_hangups++;
    p->counters.bytes_discarded += xgo_host_outq_clear(&p->out);
    xgo_host_pty_discard_unread(p->pty);
    p->out_blocked = 0;
    p->tx_wire_free_us = 0;
    p->rx_wire_free_us = 0;
}

/* Input a departed host left behind is read here too (POLLIN with
 * POLLHUP): it is applied, but its replies are dropped rather than handed
 * to the next host. */
void xgo_host_port_probe(xgo_port_t *p, uint64_t now_us)
{
    struct pollfd pfd;
    pfd.fd = p->pty->master_fd;
    pfd.events = POLLIN;
    pfd.revents = 0;
    if (poll(&pfd, 1, 0) < 0) {
        return; /* EINTR: probe again next turn */
    }
    if ((pfd.revents & (POLLHUP | POLLERR)) == 0) {
        xgo_host_port_end_session(p); /* before the new host's bytes arrive */
        p->host_gone = 0;
        p->counters.host_attaches++;
        return;
    }
    if (pfd.revents & POLLIN) {
        xgo_host_port_read(p, now_us);
    }
}

/* ---- output ------------------------------------------------------------- */

void xgo_host_port_write(xgo_port_t *p, uint64_t now_us)
{
    size_t due = p->host_gone ? 0 : xgo_host_outq_due(&p->out, now_us);
    while (due > 0) {
        ssize_t n = write(p->pty->master_fd, p->out.bytes, due);
        if (n > 0) {
            xgo_host_outq_consume(&p->out, (size_t)n);
            p->counters.bytes_out += (uint64_t)n;
            due -= (size_t)n;
            p->out_blocked = 0;
            continue;
        }
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            p->out_blocked = 1;
            p->counters.write_stalls++;
            return;
        }
        xgo_host_port_host_left(p);
        return;
    }
}

uint64_t xgo_host_port_next_due_us(const xgo_port_t *p)
{
    if (p->host_gone || p->out_blocked || p->out.len == 0) {
        return UINT64_MAX;
    }
    return xgo_host_outq_next_due_us(&p->out);
}
