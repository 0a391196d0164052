/*
 * pty.h - the pseudo-terminal that stands in for the board's UART.
 *
 * We hold only the master side. The host (pyserial, picocom, ...) opens the
 * slave by path as often as it likes. On Linux, while no host has the slave
 * open, the master polls as POLLHUP and reads fail with EIO (from the start
 * too: xgo_host_pty_open briefly opens the slave to configure it): that is
 * "cable unplugged", not an error.
 */
#ifndef XGO_HOST_PTY_H
#define XGO_HOST_PTY_H

#include <stddef.h>
#include <stdint.h>

typedef struct xgo_host_pty_s {
    int master_fd;       /* non-blocking, close-on-exec */
    char slave_path[64]; /* e.g. /dev/pts/3 */
} xgo_host_pty_t;

/* Opens a pty, puts the slave in raw 8N1 mode at 115200 (so a host that never
 * configures the port still passes every byte value unchanged) and makes the
 * master non-blocking. Returns 0, or -1 with a message in err. */
int xgo_host_pty_open(xgo_host_pty_t *pty, char *err, size_t err_size);

void xgo_host_pty_close(xgo_host_pty_t *pty);

/* The line speed the host last set on the slave, in bit/s (read through the
 * master: on Linux the master reports the slave's termios). Returns 0 when it
 * is unknown, B0, or cannot be read. */
uint32_t xgo_host_pty_host_baud(const xgo_host_pty_t *pty);

/* Discards bytes we wrote that no host has read yet (the slave's input
 * queue). Used when the host goes away: on a real wire, bytes sent to a
 * closed port are lost, and the next session must not see stale replies.
 * tcflush() on the master does not reach that queue, so this briefly opens
 * the slave itself. */
void xgo_host_pty_discard_unread(const xgo_host_pty_t *pty);

#endif /* XGO_HOST_PTY_H */
