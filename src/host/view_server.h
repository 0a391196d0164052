/*
 * view_server.h - xgo-emu --view: a small HTTP/1.1 server in the event
 * loop (a service of loop.h: no threads), serving only what is compiled in:
 *
 *   GET /            the view page (and its files: view_assets.h)
 *   GET /meta        constant facts for the page (view_meta.h), JSON
 *   GET /state       one state object (view_state.h), JSON
 *   GET /events      the same object as Server-Sent Events, --view-hz a second
 *   POST /input      emulator inputs (view_api.h)
 *   POST /command    register writes, as a host's write frames (view_api.h)
 *
 * Bounded everywhere: at most XGO_HOST_VIEW_MAX_CLIENTS connections (the
 * next gets 503), request heads and bodies of 8 KiB (http.h), a fixed
 * output buffer per client - a client that does not read its events fast
 * enough is disconnected instead of buffered for. Sockets are non-blocking;
 * the loop serves the pty and the ticks before this server in every turn.
 * docs/view.md describes the protocol and the limits.
 */
#ifndef XGO_HOST_VIEW_SERVER_H
#define XGO_HOST_VIEW_SERVER_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "http.h"
#include "loop.h"
#include "trace.h"
#include "view_frames.h"
#include "view_state.h"
#include "xgo/board.h"

#define XGO_HOST_VIEW_MAX_CLIENTS 16u
#define XGO_HOST_VIEW_DEFAULT_HZ 30u
#define XGO_HOST_VIEW_MAX_HZ 500u /* one event per control tick */
/* A request (head and body) is read whole before it is answered. */
#define XGO_HOST_VIEW_IN_BYTES (XGO_HOST_HTTP_HEAD_MAX + XGO_HOST_HTTP_BODY_MAX)
/* Output a client may have pending; an event that does not fit drops it. */
#define XGO_HOST_VIEW_OUT_BYTES (128u * 1024u)
/* The kernel's send buffer per client (Linux doubles the figure). */
#define XGO_HOST_VIEW_SNDBUF_BYTES (64 * 1024)
/* One state object at most (64 frames of at most 512 characters each). */
#define XGO_HOST_VIEW_OBJECT_BYTES (64u * 1024u)
/* A connection that neither completes a request nor reads its answer for
 * this long is closed (408 if a request had begun). */
#define XGO_HOST_VIEW_IDLE_US 10000000u

typedef struct xgo_host_view_counters_s {
    uint64_t clients_accepted;
    uint64_t clients_refused; /* 503: all slots taken */
    uint64_t clients_dropped; /* fell behind on their events */
    uint64_t clients_timed_out;
    uint64_t requests;        /* answered with 2xx */
    uint64_t bad_requests;    /* answered with 4xx or 5xx */
    uint64_t events;          /* SSE events queued */
} xgo_host_view_counters_t;

/* How long the server's work in one turn of the loop took (the most it can
 * delay a pty byte that arrives meanwhile): 5 us buckets up to 5 ms. */
#define XGO_HOST_VIEW_BUSY_BUCKET_US 5u
#define XGO_HOST_VIEW_BUSY_BUCKETS 1001u

typedef enum xgo_host_view_client_state_e {
    XGO_HOST_VIEW_FREE = 0,
    XGO_HOST_VIEW_READING,   /* waiting for (the rest of) a request */
    XGO_HOST_VIEW_STREAMING, /* GET /events: sent an event per period */
    XGO_HOST_VIEW_LINGERING  /* answered, write side shut: draining input until EOF */
} xgo_host_view_client_state_t;

typedef struct xgo_host_view_client_s {
    int fd;
    xgo_host_view_client_state_t state;
    char local_host[48];      /* the address it connected to (trust check) */
    uint64_t deadline_us;     /* idle / linger limit */
    uint64_t frame_cursor;    /* next frame it has not been sent */
    int close_when_sent;      /* answer sent in full: shut down */
    size_t in_len;
    char in[XGO_HOST_VIEW_IN_BYTES];
    size_t out_head;          /* pending output: out[out_head..out_len) */
    size_t out_len;
    char out[XGO_HOST_VIEW_OUT_BYTES];
    const unsigned char *body; /* a compiled-in file, sent after out */
    size_t body_len;
    size_t body_sent;
} xgo_host_view_client_t;

typedef struct xgo_host_view_s {
    int listen_fd;
    char host[48];   /* the bound address as text */
    unsigned port;   /* the bound port (the real one when 0 was asked) */
    uint64_t period_us;
    uint64_t next_event_us;
    uint64_t seq;    /* state objects built */

    xgo_board_t *board;
    const xgo_host_loop_t *loop;
    unsigned model;               /* xgo_model_t of the board */
    const xgo_profile_t *profile; /* its profile */
    xgo_host_view_frames_t frames;
    xgo_host_service_t service;

    xgo_host_view_client_t clients[XGO_HOST_VIEW_MAX_CLIENTS];
    char object[XGO_HOST_VIEW_OBJECT_BYTES]; /* scratch for one answer */
    /* The period's event, sent client by client, possibly over several
     * turns (the pty is served in between). */
    char event_object[XGO_HOST_VIEW_OBJECT_BYTES];
    xgo_host_json_t event_prefix; /* its shared members, in event_object */
    uint32_t event_todo;          /* bit i: client i still to be sent it */
    xgo_host_view_counters_t counters;
    uint32_t busy_hist[XGO_HOST_VIEW_BUSY_BUCKETS];
    uint64_t busy_max_us;
} xgo_host_view_t;

/* Listens on addr:port (IPv4, host byte order; port 0 = any free port).
 * Returns 0, or -1 with a one-line message in err. */
int xgo_host_view_open(xgo_host_view_t *v, uint32_t addr, unsigned port, unsigned hz, char *err,
                       size_t err_size);

/* Serves `board` (initialised for `model`, xgo_model_t): becomes its trace
 * observer (passing events on to trace_out when --trace is on) and a service
 * of `loop`. Returns 0, or -1 if the loop has no room for a service. */
int xgo_host_view_attach(xgo_host_view_t *v, xgo_board_t *board, unsigned model,
                         xgo_host_loop_t *loop, xgo_host_trace_t *trace_out);

/* Closes every connection and the listening socket. */
void xgo_host_view_close(xgo_host_view_t *v);

/* "name value" lines of the counters above. */
void xgo_host_view_print_counters(const xgo_host_view_t *v, FILE *out);

#endif /* XGO_HOST_VIEW_SERVER_H */
