/*
 * xgo/port.h - the whole contract between the portable core and a platform
 * (a microcontroller, or the host's xgo-emu). In the spirit of TinyUSB's
 * dcd.h: a port implements the handful of xgo_port_* functions below and
 * calls the xgo_device_* functions; nothing else of the core needs to be
 * known to bring the board up. ports/template/port.c is the file to copy.
 *
 *   interrupt / event side            main loop (one context)
 *   ----------------------            -----------------------
 *   UART RX:  xgo_device_rx_put()     xgo_device_run(): ring -> board,
 *     while xgo_device_rx_accepting()   replies -> xgo_port_tx_write(),
 *     else mask RX                      due ticks -> xgo_board_tick(),
 *   timer:    xgo_device_tick_due()     servo outputs, NV saves
 *                                     sleep while xgo_device_idle()
 *
 * The device owns the board, a receive ring the RX interrupt fills, and the
 * bookkeeping between them. Only xgo_device_rx_accepting(),
 * xgo_device_rx_put() and xgo_device_tick_due() may run in interrupt context (single producer, single
 * consumer: no locks); everything else belongs to one context. All state is
 * in xgo_device_t, which the port owns (on an MCU: one static instance, the
 * only global of a firmware image).
 *
 * Backpressure holds end to end: the RX interrupt stores bytes while the ring
 * has room and tells the port to mask itself when it is full (the UART then
 * holds the next byte and the sender waits); input is fed to the board only
 * in chunks whose replies surely fit its transmit buffer; replies leave only
 * as fast as the port takes them. Nothing is dropped for lack of room.
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_PORT_H
#define XGO_PORT_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/board.h"
#include "xgo/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Build options (same rules as xgo/config.h) ------------------------- */

/* Bytes of the receive ring (a power of two, 16..32768). 256 bytes hold
 * 22 ms of input at 115200 baud: longer than the longest control tick. */
#ifndef XGO_PORT_RX_RING_SIZE
#define XGO_PORT_RX_RING_SIZE 256u
#endif

/* After a stall of more than this many control periods (a debugger halt, a
 * blocked transmitter) the missed ticks beyond it are skipped and counted,
 * not replayed in a burst. */
#ifndef XGO_PORT_MAX_CATCHUP_TICKS
#define XGO_PORT_MAX_CATCHUP_TICKS 50u
#endif

/* The non-volatile data is saved once it has not changed for this many
 * ticks: a burst of zero-offset writes costs one flash write, not twelve. */
#ifndef XGO_PORT_NV_SETTLE_TICKS
#define XGO_PORT_NV_SETTLE_TICKS (XGO_TICK_HZ / 5u)
#endif

/* Both are counted in bytes of the device (xgo_device_t below). */
#if XGO_PORT_MAX_CATCHUP_TICKS < 1u || XGO_PORT_MAX_CATCHUP_TICKS > 255u
#error "XGO_PORT_MAX_CATCHUP_TICKS must be 1..255"
#endif
#if XGO_PORT_NV_SETTLE_TICKS < 1u || XGO_PORT_NV_SETTLE_TICKS > 255u
#error "XGO_PORT_NV_SETTLE_TICKS must be 1..255"
#endif

#if (XGO_PORT_RX_RING_SIZE & (XGO_PORT_RX_RING_SIZE - 1u)) != 0 || \
    XGO_PORT_RX_RING_SIZE < 16u || XGO_PORT_RX_RING_SIZE > 32768u
#error "XGO_PORT_RX_RING_SIZE must be a power of two in 16..32768"
#endif

/* ---- Implemented by the port -------------------------------------------- */

/* The platform's own state (UART registers, clocks, file descriptors...):
 * each port defines struct xgo_port_s; the core only passes the pointer. */
typedef struct xgo_port_s xgo_port_t;

/* Milliseconds of a monotonic clock (may wrap), readable from
 * xgo_device_init on: the parser's silence timeout measures gaps on the line
 * with it (time in which input waited in the ring does not count). A port
 * that holds received bytes outside the ring too (a FIFO it drains later,
 * xgo-emu's pty) lets this clock stand still while such bytes wait: they
 * were on the line, so that time was no silence. */
uint32_t xgo_port_millis(xgo_port_t *port);

/* How many reply bytes the port can take right now without blocking (0 when
 * its transmitter is busy; it must then wake the main loop - a TX-empty
 * interrupt - once room appears, because the device sleeps meanwhile). */
size_t xgo_port_tx_room(xgo_port_t *port);

/* Sends n bytes, n <= the last xgo_port_tx_room(). */
void xgo_port_tx_write(xgo_port_t *port, const uint8_t *bytes, size_t n);

/* The ring has room again after xgo_device_rx_put() returned 0: unmask the
 * RX interrupt (bytes the UART held meanwhile come in then). */
void xgo_port_rx_resume(xgo_port_t *port);

/* Reads the saved non-volatile data into nv; returns 1, or 0 when nothing
 * valid is saved (first start: the board keeps its defaults). */
int xgo_port_nv_load(xgo_port_t *port, xgo_board_nv_t *nv);

/* Saves nv (flash, a file); returns 1, or 0 when the save failed (the
 * device counts it and tries again after the next settle period). */
int xgo_port_nv_save(xgo_port_t *port, const xgo_board_nv_t *nv);

/* After every control tick: the raw position of each servo (joint angle +
 * zero offset, mdeg, register order 0x50..0x5B) and the limp joints (bit i:
 * joint i unloaded, torque off). A real board sends them on its servo bus. */
void xgo_port_servo_write(xgo_port_t *port, const int32_t raw_mdeg[XGO_SERVO_COUNT],
                          uint16_t limp);

/* ---- The device: called by the port ------------------------------------- */

typedef struct xgo_device_stats_s {
    uint32_t rx_bytes;       /* bytes fed to the board */
    uint32_t rx_pauses;      /* times the ring was full and RX was masked */
    uint32_t tx_bytes;       /* bytes handed to xgo_port_tx_write */
    uint32_t ticks;          /* control ticks run */
    uint32_t ticks_skipped;  /* ticks given up after a stall */
    uint32_t nv_saves;       /* successful xgo_port_nv_save calls */
    uint32_t nv_save_failures;
} xgo_device_stats_t;

/* The bookkeeping comes first, the board last: every field the device and
 * the RX interrupt touch is then within the short offsets of a Cortex-M0's
 * loads and stores (no offset constant held in a saved register). */
typedef struct xgo_device_s {
    xgo_port_t *port;
    volatile uint16_t rx_head;        /* next byte to store: producer only */
    volatile uint16_t rx_tail;        /* next byte to feed: consumer only */
    volatile uint8_t rx_paused;       /* the producer found the ring full */
    uint8_t hangup_pending;           /* xgo_device_hangup() waits for the ring */
    uint8_t ticks_now;                /* ticks xgo_device_run still runs this call
                                         (<= XGO_PORT_MAX_CATCHUP_TICKS) */
    uint8_t nv_quiet_ticks;           /* ticks since the NV data last moved
                                         (<= XGO_PORT_NV_SETTLE_TICKS) */
    volatile uint32_t tick_signals;   /* control periods elapsed: producer only;
                                         handled (run or skipped): the board's
                                         ticks + counts.ticks_skipped */
    uint32_t nv_changes_saved;        /* xgo_board_nv_changes() at the last save */
    uint32_t nv_changes_seen;         /* ... when last looked at */
    uint32_t wire_ms;                 /* the parser's clock (see device.c) */
    uint32_t wire_seen_ms;            /* xgo_port_millis() when last read */
    struct {                          /* xgo_device_stats_t but its ticks: the ticks
                                         run are the board's own count */
        uint32_t rx_bytes;
        uint32_t rx_pauses;
        uint32_t tx_bytes;
        uint32_t ticks_skipped;
        uint32_t nv_saves;
        uint32_t nv_save_failures;
    } counts;
    uint8_t rx_ring[XGO_PORT_RX_RING_SIZE];
    xgo_board_t board;
} xgo_device_t;

/* Initialises the board (cfg may be NULL for the defaults) and restores the
 * saved non-volatile data through xgo_port_nv_load. */
void xgo_device_init(xgo_device_t *d, xgo_port_t *port, const xgo_board_config_t *cfg);

/* RX interrupt: may a received byte be taken from the UART? 1 while the
 * ring has room; 0 once it is full: the port then masks its RX interrupt,
 * leaves the byte in the UART (which holds the sender back) and reads no
 * more until the device calls xgo_port_rx_resume(). Check it before every
 * byte: the handler may run once more after masking (an interrupt that
 * arrived meanwhile stays pending in the NVIC). */
int xgo_device_rx_accepting(const xgo_device_t *d);

/* RX interrupt: store one received byte (only when accepting). Returns
 * xgo_device_rx_accepting() after it. */
int xgo_device_rx_put(xgo_device_t *d, uint8_t byte);

/* Timer interrupt: one control period (1 / XGO_TICK_HZ s) has elapsed. */
void xgo_device_tick_due(xgo_device_t *d);

/* Main loop: the host went away (a USB CDC port closed, a Bluetooth link
 * dropped, xgo-emu's pty closed by its last host). A frame it left half sent
 * must not prefix the next host's first request, so once the bytes already
 * in the ring are fed (at once if it is empty), the parser drops its partial
 * frame (drop reason hang-up, counter hangup_discards). Call it after
 * storing the last byte the departed host sent. A plain UART cannot tell:
 * there the parser's silence timeout does this job. */
void xgo_device_hangup(xgo_device_t *d);

/* Main loop: does all work that is due (ticks, input, replies, NV save).
 * Never blocks. */
void xgo_device_run(xgo_device_t *d);

/* 1 when xgo_device_run() has nothing to do until the next interrupt: the
 * port may sleep (check it with interrupts masked, then WFI). */
int xgo_device_idle(xgo_device_t *d);

/* The board, for the public observers of xgo/board.h (and a trace hook);
 * only the device ticks it (its tick count is the device's ticks run). */
xgo_board_t *xgo_device_board(xgo_device_t *d);

/* What the device did: a copy of its counters. */
void xgo_device_stats(const xgo_device_t *d, xgo_device_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif /* XGO_PORT_H */
