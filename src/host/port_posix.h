/*
 * port_posix.h - xgo-emu as a port of the core (include/xgo/port.h), like
 * the firmware in ports/: the pty stands in for the UART, CLOCK_MONOTONIC for
 * the timer, the --state file for the flash. The board is driven only
 * through the device layer (src/core/device.c): bytes go into its receive
 * ring with xgo_device_rx_put while it accepts them, ticks are signalled with
 * xgo_device_tick_due, xgo_device_run does the rest and hands replies,
 * servo outputs and non-volatile saves back to the xgo_port_* functions here.
 *
 * What a UART does in hardware the port does on the pty:
 * - input: read from the master into `in` (4 KiB) only when everything read
 *   before has been fed, then stored into the ring as it accepts (the ring's
 *   backpressure holds: a full ring stops the storing, as a masked RX
 *   interrupt does, and the pty's buffer holds the host back);
 * - output: replies go into an output queue (outq.h) with their wire times
 *   (--baud-pacing) and through the UART model (--uart-baud); a full queue
 *   makes xgo_port_tx_room 0 and replies wait in the board;
 * - the line clock (xgo_port_millis) stands still while input waits here
 *   (in `in`, in the ring, or unread in the pty): those bytes were on the
 *   line, so the parser's silence timeout must not count that time;
 * - hang-ups (the last host closed the slave) end the session through
 *   xgo_device_hangup once everything the departed host sent is fed.
 * Bytes are told to the loop's services (--capture, --trace's time) as the
 * board is fed them and as replies leave it.
 */
#ifndef XGO_HOST_PORT_POSIX_H
#define XGO_HOST_PORT_POSIX_H

#include <stddef.h>
#include <stdint.h>

#include "outq.h"
#include "pty.h"
#include "state_file.h"
#include "xgo/port.h"

struct xgo_host_loop_s;

#define XGO_HOST_INBUF_BYTES 4096u

/* Host-side outcomes, printed at exit next to the board's and the device's
 * counters. */
typedef struct xgo_host_counters_s {
    uint64_t bytes_in;          /* read from the host */
    uint64_t bytes_out;         /* written to the host */
    uint64_t bytes_discarded;   /* replies dropped because the host had gone away */
    uint64_t host_attaches;     /* times a host was seen opening the port */
    uint64_t host_hangups;      /* times the host was seen closing it */
    uint64_t write_stalls;      /* writes refused (EAGAIN): the host was not reading */
} xgo_host_counters_t;

struct xgo_port_s {
    xgo_device_t *device;
    struct xgo_host_loop_s *loop; /* services: taps, after-tick hooks */
    const xgo_host_pty_t *pty;
    xgo_host_state_t *state;      /* NULL without --state */
    int baud_pacing;
    uint32_t uart_baud;           /* --uart-baud: the board's UART speed; 0 = no line model */
    uint64_t now_us;              /* the loop's time for this turn */

    uint8_t in[XGO_HOST_INBUF_BYTES]; /* read from the host, not all fed yet */
    size_t in_len;                /* 0 once every byte of it was fed */
    size_t in_put;                /* of which stored in the device's ring */
    size_t in_tapped;             /* of which fed and told to the services */
    uint32_t in_base;             /* the device's rx_bytes when `in` was read */
    int in_orphaned;              /* `in` was read after its host hung up */
    uint64_t in_wire_start_us;    /* pacing: when in[0] started arriving on the wire */
    uint32_t in_bytes_per_s;      /* pacing: line speed while `in` arrived */
    uint64_t rx_wire_free_us;     /* pacing: when the host's last byte has fully arrived */

    xgo_host_outq_t out;
    uint64_t tx_wire_free_us;     /* pacing: when our last queued byte leaves */
    int out_blocked;              /* last write hit EAGAIN: wait for POLLOUT */
    int host_gone;                /* no host has the slave open */
    int hangup_pending;           /* the host left; its partial frame goes once its input is fed */

    /* The line clock (xgo_port_millis): real time minus the time input was
     * waiting here. */
    uint64_t wire_us;
    uint64_t wire_seen_us;        /* real time wire_us was last brought up to */
    uint64_t nv_failed_us;        /* when a --state save last failed (0: it did not) */

    xgo_host_counters_t counters;
};

/* Before xgo_device_init (which asks xgo_port_nv_load): the pty (may be
 * opened later) and the --state file (opened already, or NULL). */
void xgo_host_port_init(xgo_port_t *p, const xgo_host_pty_t *pty, xgo_host_state_t *state);

/* Before serving: the device on this port, the loop whose services hear the
 * line, --baud-pacing and --uart-baud (0 = off). */
void xgo_host_port_attach(xgo_port_t *p, xgo_device_t *device, struct xgo_host_loop_s *loop,
                          int baud_pacing, uint32_t uart_baud, uint64_t now_us);

/* Is input waiting here: read but not fed, or unread in the pty? */
int xgo_host_port_input_waiting(const xgo_port_t *p);

/* Brings the line clock up to now_us (see above). */
void xgo_host_port_advance_clock(xgo_port_t *p, uint64_t now_us);

/* Stores read input into the device's ring while it accepts bytes. Returns
 * how many bytes were stored. */
size_t xgo_host_port_store(xgo_port_t *p);

/* After xgo_device_run: tells the services what the board was fed, and
 * frees `in` once all of it was. */
void xgo_host_port_fed(xgo_port_t *p);

/* Reads the pty (when `in` is free); a read error other than EAGAIN is the
 * host hanging up. */
void xgo_host_port_read(xgo_port_t *p, uint64_t now_us);

/* Is a host there? Called once per turn while none is. */
void xgo_host_port_probe(xgo_port_t *p, uint64_t now_us);

/* The last host closed the slave (POLLHUP, EIO). */
void xgo_host_port_host_left(xgo_port_t *p);

/* After a hang-up, once nothing the departed host sent waits here: tells
 * the device (which drops the partial frame). */
void xgo_host_port_end_session(xgo_port_t *p);

/* Writes the replies that are due to the pty. */
void xgo_host_port_write(xgo_port_t *p, uint64_t now_us);

/* When the next paced reply byte becomes due (UINT64_MAX: none waits, or
 * the pty is full and POLLOUT will say when). */
uint64_t xgo_host_port_next_due_us(const xgo_port_t *p);

#endif /* XGO_HOST_PORT_POSIX_H */
