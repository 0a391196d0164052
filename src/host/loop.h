/*
 * loop.h - xgo-emu's event loop: bytes from the pty into the board, replies
 * back out, and the board's control tick at a fixed rate on the monotonic
 * clock. Single-threaded; poll() never waits longer than the next tick.
 */
#ifndef XGO_HOST_LOOP_H
#define XGO_HOST_LOOP_H

#include <signal.h>
#include <stdint.h>
#include <stdio.h>

#include "outq.h"
#include "pty.h"
#include "state_file.h"
#include "trace.h"
#include "xgo/board.h"

/* Host-side outcomes, printed at exit next to the board's own counters. */
typedef struct xgo_host_counters_s {
    uint64_t bytes_in;          /* read from the host */
    uint64_t bytes_out;         /* written to the host */
    uint64_t bytes_discarded;   /* replies dropped because the host had gone away */
    uint64_t host_attaches;     /* times a host was seen opening the port */
    uint64_t host_hangups;      /* times the host was seen closing it */
    uint64_t write_stalls;      /* writes refused (EAGAIN): the host was not reading */
    uint64_t ticks;             /* control ticks run */
    uint64_t ticks_skipped;     /* ticks given up after a long stall (see loop.c) */
} xgo_host_counters_t;

#define XGO_HOST_INBUF_BYTES 4096u

typedef struct xgo_host_loop_s {
    xgo_board_t *board;
    const xgo_host_pty_t *pty;
    xgo_host_trace_t *trace;   /* NULL without --trace */
    xgo_host_state_t *state;   /* NULL without --state */
    int baud_pacing;
    volatile sig_atomic_t *stop; /* set by a signal handler */

    uint8_t in[XGO_HOST_INBUF_BYTES]; /* read from the host, not yet fed */
    size_t in_len;
    size_t in_fed;
    int in_orphaned;            /* `in` was read after its host hung up */
    uint64_t in_wire_start_us;  /* pacing: when in[0] started arriving on the wire */
    uint32_t in_bytes_per_s;    /* pacing: line speed while `in` arrived */
    uint64_t rx_wire_free_us;   /* pacing: when the host's last byte has fully arrived */

    xgo_host_outq_t out;
    uint64_t tx_wire_free_us;   /* pacing: when our last queued byte leaves */
    int out_blocked;            /* last write hit EAGAIN: wait for POLLOUT */
    int host_gone;              /* no host has the slave open */
    int hangup_pending;         /* the host left; its partial frame goes once its input is fed */

    /* The parser's clock: real time minus the time input was waiting (in
     * `in` or unread in the pty). Its silence timeout must measure silence
     * on the line, not our own delays (a full output queue, a stall). */
    uint64_t wire_us;
    uint64_t wire_seen_us;      /* real time wire_us was last brought up to */

    uint64_t next_tick_us;
    xgo_host_counters_t counters;
} xgo_host_loop_t;

void xgo_host_loop_init(xgo_host_loop_t *l, xgo_board_t *board, const xgo_host_pty_t *pty,
                        xgo_host_trace_t *trace, int baud_pacing, volatile sig_atomic_t *stop);

/* Keep the board's non-volatile data saved in state while serving: checked
 * after every round of ticks (a save happens only when it changed). */
void xgo_host_loop_set_state(xgo_host_loop_t *l, xgo_host_state_t *state);

/* Serves until *stop becomes non-zero. Returns 0, or -1 if poll() fails for
 * a reason other than a signal (message on stderr). */
int xgo_host_loop_run(xgo_host_loop_t *l);

/* Writes "name value" lines for the board's and the host's counters. */
void xgo_host_loop_print_counters(const xgo_host_loop_t *l, FILE *out);

#endif /* XGO_HOST_LOOP_H */
