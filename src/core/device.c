/*
 * The device: a board driven through the port boundary (xgo/port.h).
 *
 * The receive ring is a single-producer single-consumer queue: the RX
 * interrupt only advances rx_head, the main loop only rx_tail; both are
 * 16-bit counters that wrap (their difference is the fill level, the ring
 * size being a power of two no larger than 32768). A 16-bit aligned store is
 * atomic on every target we build for, so no lock is needed. Control periods
 * work the same way: the timer interrupt counts tick_signals up, the main
 * loop counts behind it: the ticks it ran (the board's own count) and those
 * it skipped.
 */
#include "xgo/port.h"

#include <string.h>

#include "compiler.h"
#include "servos.h" /* the raw positions the port drives */

#define RING_MASK ((uint16_t)(XGO_PORT_RX_RING_SIZE - 1u))

/* The helpers with buffers or many locals of their own (a transmit chunk,
 * the servo positions, the NV record, the input's ring arithmetic) stay out
 * of line: inlined, they would sit in xgo_device_run's frame under every
 * control tick, the deepest call path of a firmware image (docs/mcu.md
 * "Sizes"): XGO_OWN_FRAME. */

void xgo_device_init(xgo_device_t *d, xgo_port_t *port, const xgo_board_config_t *cfg)
{
    xgo_board_nv_t nv;
    memset(d, 0, sizeof *d);
    d->port = port;
    xgo_board_init(&d->board, cfg);
    if (xgo_port_nv_load(port, &nv)) {
        (void)xgo_board_set_nv(&d->board, &nv); /* invalid data: defaults stay */
    }
    d->nv_changes_saved = xgo_board_nv_changes(&d->board);
    d->nv_changes_seen = d->nv_changes_saved;
    d->wire_seen_ms = xgo_port_millis(port);
}

int xgo_device_rx_accepting(const xgo_device_t *d)
{
    return !d->rx_paused;
}

int xgo_device_rx_put(xgo_device_t *d, uint8_t byte)
{
    const uint16_t head = d->rx_head;
    d->rx_ring[head & RING_MASK] = byte;
    d->rx_head = (uint16_t)(head + 1u);
    if ((uint16_t)(head + 1u - d->rx_tail) < XGO_PORT_RX_RING_SIZE) {
        return 1;
    }
    d->rx_paused = 1;
    d->counts.rx_pauses++;
    return 0;
}

void xgo_device_tick_due(xgo_device_t *d)
{
    d->tick_signals++;
}

xgo_board_t *xgo_device_board(xgo_device_t *d)
{
    return &d->board;
}

void xgo_device_stats(const xgo_device_t *d, xgo_device_stats_t *out)
{
    out->rx_bytes = d->counts.rx_bytes;
    out->rx_pauses = d->counts.rx_pauses;
    out->tx_bytes = d->counts.tx_bytes;
    out->ticks = d->board.ticks; /* only the device ticks its board */
    out->ticks_skipped = d->counts.ticks_skipped;
    out->nv_saves = d->counts.nv_saves;
    out->nv_save_failures = d->counts.nv_save_failures;
}

/* The longest reply the board queues: a whole frame, or the whole transmit
 * buffer when that is smaller (xgo/config.h: a longer reply is dropped and
 * counted, never waited for). */
#define REPLY_MAX                                                                  \
    (XGO_TX_BUFFER_SIZE < XGO_FRAME_MAX_LEN ? (size_t)XGO_TX_BUFFER_SIZE            \
                                            : (size_t)XGO_FRAME_MAX_LEN)

/* Replies that fit the board's transmit buffer whatever the requests ask.
 * When two never fit (a firmware's buffer) that is one or none: a compare,
 * no division (a library call on an M0). */
static size_t reply_room(const xgo_device_t *d)
{
    const size_t free = XGO_TX_BUFFER_SIZE - xgo_board_tx_pending(&d->board);
    if (2u * REPLY_MAX > XGO_TX_BUFFER_SIZE) {
        return free >= REPLY_MAX;
    }
    return free / REPLY_MAX;
}

/* Moves replies to the port as far as it takes them. */
XGO_OWN_FRAME static void send_replies(xgo_device_t *d)
{
    uint8_t chunk[32];
    while (xgo_board_tx_pending(&d->board) > 0) {
        size_t room = xgo_port_tx_room(d->port);
        size_t n;
        if (room == 0) {
            return; /* the port wakes us when it has room */
        }
        n = xgo_board_transmit(&d->board, chunk, room < sizeof chunk ? room : sizeof chunk);
        xgo_port_tx_write(d->port, chunk, n);
        d->counts.tx_bytes += (uint32_t)n;
    }
}

/* Feeds the ring to the board in chunks whose replies surely fit: a chunk of
 * 9k - 8 bytes completes at most k frames (a request is at least 9 bytes and
 * the first may need only one more byte), each answered by at most one reply
 * of at most REPLY_MAX bytes. */
XGO_OWN_FRAME static void feed_input(xgo_device_t *d, uint32_t now_ms)
{
    for (;;) {
        const uint16_t tail = d->rx_tail;
        const size_t held = (uint16_t)(d->rx_head - tail);
        const size_t to_end = XGO_PORT_RX_RING_SIZE - (size_t)(tail & RING_MASK);
        size_t replies, chunk;

        send_replies(d);
        replies = reply_room(d);
        if (held == 0 || replies == 0) {
            return; /* nothing to feed, or wait for the port to take replies */
        }
        chunk = replies * XGO_READ_REQUEST_LEN - (XGO_READ_REQUEST_LEN - 1u);
        chunk = chunk < held ? chunk : held;
        chunk = chunk < to_end ? chunk : to_end;
        xgo_board_receive(&d->board, &d->rx_ring[tail & RING_MASK], chunk, now_ms);
        d->rx_tail = (uint16_t)(tail + chunk);
        d->counts.rx_bytes += (uint32_t)chunk;
        if (d->rx_paused) {
            /* Cleared before resuming: the producer sets it again only
             * after the port has unmasked it, so no pause is missed. */
            d->rx_paused = 0;
            xgo_port_rx_resume(d->port);
        }
    }
}

XGO_OWN_FRAME static void write_servos(xgo_device_t *d)
{
    const xgo_servos_t *s = &d->board.motion.servos;
    int32_t raw[XGO_SERVO_COUNT];
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        raw[i] = xgo_servos_raw(s, i);
    }
    xgo_port_servo_write(d->port, raw, s->unloaded);
}

/* Saves the non-volatile data once it has stopped changing. */
XGO_OWN_FRAME static void track_nv(xgo_device_t *d)
{
    const uint32_t changes = xgo_board_nv_changes(&d->board);
    xgo_board_nv_t nv;
    if (changes != d->nv_changes_seen) {
        d->nv_changes_seen = changes;
        d->nv_quiet_ticks = 0;
        return;
    }
    if (changes == d->nv_changes_saved || ++d->nv_quiet_ticks < XGO_PORT_NV_SETTLE_TICKS) {
        return;
    }
    d->nv_quiet_ticks = 0; /* a failed save is retried one settle period later */
    xgo_board_get_nv(&d->board, &nv);
    if (xgo_port_nv_save(d->port, &nv)) {
        d->nv_changes_saved = changes;
        d->counts.nv_saves++;
    } else {
        d->counts.nv_save_failures++;
    }
}

/* Control periods signalled and not yet handled (run or skipped): the
 * device keeps no count of its own for them. */
static uint32_t ticks_owed(const xgo_device_t *d)
{
    return d->tick_signals - (d->board.ticks + d->counts.ticks_skipped);
}

/* The ticks due when called, at most XGO_PORT_MAX_CATCHUP_TICKS of them (a
 * longer stall's are skipped). Their count is kept in the device, not in a
 * register across the tick: only d is, so xgo_device_run's frame under
 * every tick (the deepest stack path) holds one saved register. */
static void run_due_ticks(xgo_device_t *d)
{
    uint32_t due = ticks_owed(d);
    if (due > XGO_PORT_MAX_CATCHUP_TICKS) {
        d->counts.ticks_skipped += due - XGO_PORT_MAX_CATCHUP_TICKS;
        due = XGO_PORT_MAX_CATCHUP_TICKS;
    }
    d->ticks_now = (uint8_t)due;
    while (d->ticks_now > 0) {
        d->ticks_now--;
        xgo_board_tick(&d->board); /* counts it */
        write_servos(d);
        track_nv(d);
    }
}

/* The parser's clock: the port's milliseconds, except the time input was
 * found waiting in the ring. Bytes the interrupt stored while the main loop
 * was busy (a burst of catch-up ticks, a slow flash save) were on the line
 * meanwhile, so that time is not silence and must not let the parser's
 * timeout drop a frame in progress. (A partial frame never waits for bytes
 * held back by the chunk rule of feed_input: the board has room for a reply
 * whenever one was fed.) The price: silence just before bytes arrive counts
 * only up to the previous run, at most one tick earlier. */
static uint32_t wire_clock(xgo_device_t *d)
{
    const uint32_t now = xgo_port_millis(d->port);
    if (d->rx_head == d->rx_tail) {
        d->wire_ms += now - d->wire_seen_ms;
    }
    d->wire_seen_ms = now;
    return d->wire_ms;
}

/* The departed host's partial frame, once nothing it sent waits in the
 * ring; what the drop's rescan finds is answered like any frame. */
static void end_session(xgo_device_t *d)
{
    d->hangup_pending = 0;
    xgo_board_hangup(&d->board);
    send_replies(d);
}

void xgo_device_hangup(xgo_device_t *d)
{
    d->hangup_pending = 1;
    if (d->rx_head == d->rx_tail) {
        end_session(d);
    }
}

/* Input, the silence timeout, a hang-up and replies, at the parser's time
 * now_ms. */
XGO_OWN_FRAME static void serve_input(xgo_device_t *d, uint32_t now_ms)
{
    feed_input(d, now_ms);
    if (d->rx_head == d->rx_tail) {
        /* Only with nothing held back: bytes waiting in the ring are not
         * silence on the line. */
        xgo_board_poll(&d->board, now_ms);
        if (d->hangup_pending) {
            end_session(d);
        }
    }
    send_replies(d);
}

/* The control ticks are the deepest call path of a firmware image: the
 * frame they are called from holds only the device and the count (the
 * parser's time is taken before them, kept in wire_ms, and used after). */
void xgo_device_run(xgo_device_t *d)
{
    (void)wire_clock(d);
    run_due_ticks(d);
    serve_input(d, d->wire_ms);
}

int xgo_device_idle(xgo_device_t *d)
{
    if (ticks_owed(d) != 0) {
        return 0;
    }
    if (d->rx_head != d->rx_tail && reply_room(d) > 0) {
        return 0;
    }
    return xgo_board_tx_pending(&d->board) == 0 || xgo_port_tx_room(d->port) == 0;
}
