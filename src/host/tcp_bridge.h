/*
 * tcp_bridge.h - xgo-emu --tcp [HOST:]PORT: the board's serial line over
 * TCP, for hosts that cannot open our pty (Windows, macOS, a container's
 * host, a VM; pyserial's socket://HOST:PORT).
 *
 * The bridge is one more host of the pty: while a client is connected it
 * holds the pty's slave open and copies bytes both ways, unchanged. So the
 * TCP byte stream is exactly the pty's - the same parser, replies,
 * hang-up handling, --trace and --capture - and the event loop needs no
 * second line. One client at a time: a second one, or one arriving while
 * another host has the pty open, gets a one-line reason and is closed.
 * Loopback unless HOST says otherwise. Buffers are fixed; a client that
 * does not read stalls only its own replies (the loop keeps ticking).
 */
#ifndef XGO_HOST_TCP_BRIDGE_H
#define XGO_HOST_TCP_BRIDGE_H

#include <stdint.h>
#include <stdio.h>

#include "loop.h"

#define XGO_HOST_TCP_BUF 4096u

typedef struct xgo_host_tcp_counters_s {
    unsigned long accepted;
    unsigned long refused;
    uint64_t bytes_in;  /* client -> board */
    uint64_t bytes_out; /* board -> client */
} xgo_host_tcp_counters_t;

typedef struct xgo_host_tcp_s {
    int listen_fd;
    int client_fd;  /* -1: none */
    int slave_fd;   /* the pty's slave while a client is connected */
    char host[64];
    unsigned port;
    const char *pty_path;
    const xgo_host_loop_t *loop;
    uint8_t to_board[XGO_HOST_TCP_BUF]; /* from the client, not yet in the pty */
    size_t to_board_len;
    uint8_t to_client[XGO_HOST_TCP_BUF]; /* from the pty, not yet sent */
    size_t to_client_len;
    xgo_host_tcp_counters_t counters;
    xgo_host_service_t service;
} xgo_host_tcp_t;

/* Listens on addr:port (host byte order; port 0 = any free one). Returns 0,
 * or -1 with a one-line message in err. */
int xgo_host_tcp_open(xgo_host_tcp_t *t, uint32_t addr, unsigned port, const char *pty_path,
                      const xgo_host_loop_t *loop, char *err, size_t err_size);

void xgo_host_tcp_print_counters(const xgo_host_tcp_t *t, FILE *out);

void xgo_host_tcp_close(xgo_host_tcp_t *t);

#endif /* XGO_HOST_TCP_BRIDGE_H */
