/*
 * device_port.h - a port (xgo/port.h) for the fuzz target, so a program can
 * drive the board through the device layer too: bytes through the receive
 * ring, ticks through the timer signal and xgo_device_run(), replies through
 * xgo_port_tx_write(), the non-volatile data through load and save.
 *
 * The port's clock is the program's; its transmitter takes everything at
 * once (up to FUZZ_PORT_OUT_CAP bytes between two drains); every second NV
 * save fails, so the device's retry path runs too.
 */
#ifndef XGO_FUZZ_DEVICE_PORT_H
#define XGO_FUZZ_DEVICE_PORT_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/port.h"

#define FUZZ_PORT_OUT_CAP 4096u

struct xgo_port_s {
    uint32_t now_ms;
    uint8_t out[FUZZ_PORT_OUT_CAP]; /* bytes the device transmitted, not drained yet */
    size_t out_len;
    unsigned saves;                 /* NV saves asked for */
    int32_t servo_raw_mdeg[XGO_SERVO_COUNT];
    uint16_t servo_limp;
};

/* Starts the device of port (NV data as a port loads it: a valid name and
 * small offsets). */
void fuzz_device_init(xgo_device_t *d, xgo_port_t *port, const xgo_board_config_t *cfg);

/* Bytes from the host, as the RX interrupt stores them (the main loop runs
 * whenever the ring is full), then the main loop until they are fed. */
void fuzz_device_receive(xgo_device_t *d, const uint8_t *bytes, size_t n);

/* One control period: the timer signal, then the main loop. */
void fuzz_device_tick(xgo_device_t *d);

/* Takes what the device transmitted since the last call. */
size_t fuzz_device_output(xgo_device_t *d, uint8_t *out, size_t cap);

#endif /* XGO_FUZZ_DEVICE_PORT_H */
