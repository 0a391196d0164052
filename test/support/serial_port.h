/*
 * serial_port.h - the host side of xgo-emu's pty, as the vendor's
 * pyserial-based library uses it, for the programs that drive the emulator
 * end to end (test_pty_integration, test_host_state, bench_latency).
 *
 * Descriptors are non-blocking and every wait is bounded by a timeout, so a
 * broken emulator fails the caller instead of hanging it. Nothing here
 * asserts: results are return codes, and the Unity tests assert on them
 * while the bench just reports. Frames are built by xgo_frame_encode.
 */
#ifndef XGO_TEST_SERIAL_PORT_H
#define XGO_TEST_SERIAL_PORT_H

#include <stddef.h>
#include <stdint.h>
#include <termios.h>

/* Opens path read/write, non-blocking, not as controlling terminal, without
 * touching its settings: a host that never configures the line sees
 * whatever xgo-emu set up. Returns the descriptor or -1. */
int xgo_test_port_open(const char *path);

/* Opens path the way pyserial does: non-blocking, raw 8N1 at speed, no flow
 * control, VMIN = VTIME = 0, pending input flushed. Returns the descriptor
 * or -1 (nothing left open). */
int xgo_test_port_open_like_pyserial(const char *path, speed_t speed);

/* Writes all n bytes, retrying while the port is full for up to timeout_ms.
 * Returns 0, or -1 on a write error or if it stalled past the timeout. */
int xgo_test_port_write(int fd, const void *bytes, size_t n, long timeout_ms);

/* Reads up to n bytes, waiting at most timeout_ms overall; returns the count. */
size_t xgo_test_port_read(int fd, void *buf, size_t n, long timeout_ms);

/* Bytes that arrive within ms (a caller expecting silence wants 0). */
size_t xgo_test_port_silence(int fd, long ms);

/* The read request for count bytes at addr into out (XGO_READ_REQUEST_LEN
 * bytes); returns its length. */
size_t xgo_test_read_request(uint8_t addr, uint8_t count, uint8_t *out);

/* Sends the read request for count bytes at addr and reads its reply frame
 * (count + XGO_FRAME_OVERHEAD bytes) into reply, waiting up to timeout_ms for
 * the write and again for the reply. Returns the number of reply bytes
 * received (fewer than expected: incomplete), 0 if the request could not be
 * sent. The caller checks the frame. */
size_t xgo_test_read_reply(int fd, uint8_t addr, uint8_t count, uint8_t *reply, long timeout_ms);

/* Sends a write frame of n bytes at addr. Returns 0, or -1 if no frame can
 * hold them or the write failed (see xgo_test_port_write). */
int xgo_test_write_regs(int fd, uint8_t addr, const void *values, size_t n, long timeout_ms);

#endif /* XGO_TEST_SERIAL_PORT_H */
