/*
 * net.h - the TCP plumbing xgo-emu's servers share (--view, --tcp):
 * "[HOST:]PORT" options, a non-blocking listening socket.
 */
#ifndef XGO_HOST_NET_H
#define XGO_HOST_NET_H

#include <stddef.h>
#include <stdint.h>

/* Non-blocking and close-on-exec; 0 or -1. */
int xgo_host_net_nonblocking(int fd);

/* "[HOST:]PORT": HOST an IPv4 address or "localhost" (the default,
 * 127.0.0.1), PORT 0..65535 (0: any free port). *addr in host byte order.
 * Returns 1, or 0 with what was wrong in err ("HOST must be ..."). */
int xgo_host_net_parse_endpoint(const char *value, uint32_t *addr, unsigned *port, char *err,
                                size_t err_size);

/* A non-blocking listening TCP socket on addr:port (SO_REUSEADDR). Fills
 * host (the address as text) and *bound (the port, chosen by the system for
 * port 0). Returns the descriptor, or -1 with errno set. */
int xgo_host_net_listen(uint32_t addr, unsigned port, int backlog, char *host, size_t host_size,
                        unsigned *bound);

#endif /* XGO_HOST_NET_H */
