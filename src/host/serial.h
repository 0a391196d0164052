/*
 * serial.h - a serial line in raw 8N1 at a given speed: the pty xgo-emu
 * offers and the real robot's port xgo-cli opens are set up by the same
 * code, so "the board's UART settings" exist once.
 */
#ifndef XGO_HOST_SERIAL_H
#define XGO_HOST_SERIAL_H

#include <stddef.h>
#include <stdint.h>
#include <termios.h>

/* The board's line speed (the vendor library's default). */
#define XGO_HOST_DEFAULT_BAUD 115200u

/* speed_t code of a bit rate (B115200 for 115200 ...); 0 when termios has
 * none for it. */
int xgo_host_serial_speed_code(uint32_t baud, speed_t *code);

/* The bit rate of a speed_t code, 0 when unknown or B0. */
uint32_t xgo_host_serial_baud_of(speed_t code);

/* Raw 8N1 at baud on an open terminal: no echo, no CR/NL mapping, no
 * XON/XOFF, no signals, receiver on, modem lines ignored, VMIN 1 VTIME 0.
 * Returns 0, or -1 with errno set (EINVAL for a speed termios lacks). */
int xgo_host_serial_make_raw(int fd, uint32_t baud);

/* Opens path read/write, non-blocking, close-on-exec, not as controlling
 * terminal, in raw 8N1 at baud with pending input discarded. Returns the
 * descriptor, or -1 with a one-line message in err ("cannot open PATH:
 * No such file or directory", "PATH is not a serial port", ...). */
int xgo_host_serial_open(const char *path, uint32_t baud, char *err, size_t err_size);

#endif /* XGO_HOST_SERIAL_H */
