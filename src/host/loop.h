/*
 * loop.h - xgo-emu's event loop: bytes from the pty into the board, replies
 * back out, and the board's control tick at a fixed rate on the monotonic
 * clock. Single-threaded; poll() never waits longer than the next tick.
 */
#ifndef XGO_HOST_LOOP_H
#define XGO_HOST_LOOP_H

#include <poll.h>
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

/* What passed the board's serial line, for on_line (the values of
 * xgo_pcap_dir_t, src/host/pcap.h). */
#define XGO_HOST_LINE_TO_BOARD 0   /* fed to the board */
#define XGO_HOST_LINE_TO_HOST 1    /* replies on their way to the host */
#define XGO_HOST_LINE_DISCARDED 2  /* replies dropped: no host attached */
#define XGO_HOST_LINE_HANGUP 4     /* the board was told the host hung up (no bytes) */

/* Something served in the same loop besides the pty (the view server, the
 * motion recorder, the capture, the TCP bridge); every function is optional
 * (NULL). In each turn the ticks that are due and the pty come first,
 * services after them, so a service never delays a reply or a tick by more
 * than its own bounded work. */
typedef struct xgo_host_service_s {
    void (*after_tick)(void *ctx); /* after every control tick */
    /* Bytes of the serial line as they pass the board (XGO_HOST_LINE_*). */
    void (*on_line)(void *ctx, int what, const uint8_t *bytes, size_t n);
    /* Descriptors to poll this turn (at most max); returns how many. */
    size_t (*poll_fds)(void *ctx, struct pollfd *fds, size_t max);
    /* Each turn, after the pty; fds as poll_fds filled them, with the
     * revents of the last poll (0 after a timeout). */
    void (*serve)(void *ctx, const struct pollfd *fds, size_t n, uint64_t now_us);
    void *ctx;
} xgo_host_service_t;

/* Tick lateness (how long after its time a round of ticks began), kept for
 * the counters at exit (bench figures): 10 us buckets up to 10 ms. */
#define XGO_HOST_LATE_BUCKET_US 10u
#define XGO_HOST_LATE_BUCKETS 1001u /* the last one: later than that */

#define XGO_HOST_MAX_SERVICES 4u
#define XGO_HOST_MAX_SERVICE_FDS 32u

typedef struct xgo_host_loop_s {
    xgo_board_t *board;
    const xgo_host_pty_t *pty;
    xgo_host_trace_t *trace;   /* NULL without --trace */
    xgo_host_state_t *state;   /* NULL without --state */
    int baud_pacing;
    uint32_t uart_baud;        /* --uart-baud: the board's UART speed; 0 = no line model */
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

    uint32_t late_hist[XGO_HOST_LATE_BUCKETS];
    uint64_t late_max_us;

    const xgo_host_service_t *services[XGO_HOST_MAX_SERVICES];
    size_t service_count;
    /* Last poll: [0] the pty, then each service's descriptors in turn. */
    struct pollfd fds[1 + XGO_HOST_MAX_SERVICE_FDS];
    size_t service_nfds[XGO_HOST_MAX_SERVICES];
} xgo_host_loop_t;

void xgo_host_loop_init(xgo_host_loop_t *l, xgo_board_t *board, const xgo_host_pty_t *pty,
                        xgo_host_trace_t *trace, int baud_pacing, volatile sig_atomic_t *stop);

/* Keep the board's non-volatile data saved in state while serving: checked
 * after every round of ticks (a save happens only when it changed). */
void xgo_host_loop_set_state(xgo_host_loop_t *l, xgo_host_state_t *state);

/* Model the board's UART at board_baud (0: off): a host whose port is set to
 * another speed gets what a real UART gives it, garbled bytes both ways
 * (uart_model.h), framing errors counted in the diagnostic block. */
void xgo_host_loop_set_uart(xgo_host_loop_t *l, uint32_t board_baud);

/* Serves s too from now on (s must outlive the loop). Returns 0, or -1
 * when XGO_HOST_MAX_SERVICES are already added. */
int xgo_host_loop_add_service(xgo_host_loop_t *l, const xgo_host_service_t *s);

/* 1 while a host has the pty open (as far as the loop has seen). */
int xgo_host_loop_host_attached(const xgo_host_loop_t *l);

/* 1 if host bytes are waiting that the loop would read at once: a service
 * doing long work stops and lets the next turn serve them first. */
int xgo_host_loop_pty_waiting(const xgo_host_loop_t *l);

/* Serves until *stop becomes non-zero. Returns 0, or -1 if poll() fails for
 * a reason other than a signal (message on stderr). */
int xgo_host_loop_run(xgo_host_loop_t *l);

/* Writes "name value" lines for the board's and the host's counters. */
void xgo_host_loop_print_counters(const xgo_host_loop_t *l, FILE *out);

#endif /* XGO_HOST_LOOP_H */
