/*
 * loop.h - xgo-emu's event loop: what a firmware's interrupts and main loop
 * do, on one thread. Each turn it signals the control ticks that are due on
 * the monotonic clock (xgo_device_tick_due: the timer interrupt), stores the
 * host's bytes in the device's ring and runs the device (xgo_device_run),
 * writes replies to the pty, serves the services, and poll()s - never
 * longer than until the next tick. The pty side is the port
 * (port_posix.h); the board is reached only through the device.
 */
#ifndef XGO_HOST_LOOP_H
#define XGO_HOST_LOOP_H

#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>

#include "trace.h"
#include "xgo/port.h"

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
    xgo_device_t *device;
    xgo_port_t *port;
    xgo_host_trace_t *trace;   /* NULL without --trace */
    volatile sig_atomic_t *stop; /* set by a signal handler */

    uint64_t next_tick_us;
    uint32_t late_hist[XGO_HOST_LATE_BUCKETS];
    uint64_t late_max_us;

    const xgo_host_service_t *services[XGO_HOST_MAX_SERVICES];
    size_t service_count;
    /* Last poll: [0] the pty, then each service's descriptors in turn. */
    struct pollfd fds[1 + XGO_HOST_MAX_SERVICE_FDS];
    size_t service_nfds[XGO_HOST_MAX_SERVICES];
} xgo_host_loop_t;

/* The device must be initialised on port (xgo_host_port_init, then
 * xgo_device_init); the loop attaches the port to itself (pacing and the
 * UART model as given: port_posix.h). */
void xgo_host_loop_init(xgo_host_loop_t *l, xgo_device_t *device, xgo_port_t *port,
                        xgo_host_trace_t *trace, int baud_pacing, uint32_t uart_baud,
                        volatile sig_atomic_t *stop);

/* For the port: tells the services what passed the line (XGO_HOST_LINE_*),
 * and that a control tick has run. */
void xgo_host_loop_tap(xgo_host_loop_t *l, int what, const uint8_t *bytes, size_t n);
void xgo_host_loop_after_tick(xgo_host_loop_t *l);

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

/* Writes "name value" lines for the board's, the device's and the host's
 * counters. */
void xgo_host_loop_print_counters(const xgo_host_loop_t *l, FILE *out);

#endif /* XGO_HOST_LOOP_H */
