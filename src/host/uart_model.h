/*
 * uart_model.h - what a UART receiver clocked at one speed makes of bytes
 * sent at another (xgo-emu --uart-baud). Pure functions: no OS calls.
 *
 * The model, 8N1 on both ends: the transmitter sends the bytes back to back
 * (start bit 0, eight data bits LSB first, stop bit 1) from an idle (1)
 * line, which stays idle after the last stop bit. The receiver waits for a
 * falling edge (a line already low when it gets ready must first go high),
 * checks the start bit in its middle (still low, or it was a glitch and the
 * wait goes on), samples the eight data bits and the stop bit in their
 * middles at its own bit time, and flags a framing error when the stop bit
 * reads 0. It is ready for the next edge at the stop bit's sample.
 *
 * At equal speeds the bytes come through unchanged. A host at 2 Mbaud
 * talking to a 115200 board delivers a few garbled bytes per frame; a host
 * at 9600 delivers zeros with framing errors. Each received byte starts at
 * its own falling edge and a frame has at most five, so the output is never
 * longer than XGO_HOST_UART_GROWTH times the input (plus nothing).
 */
#ifndef XGO_HOST_UART_MODEL_H
#define XGO_HOST_UART_MODEL_H

#include <stddef.h>
#include <stdint.h>

/* Received bytes per sent byte, at most (falling edges per 8N1 frame). */
#define XGO_HOST_UART_GROWTH 5u

/* Slowest and fastest speeds the model takes (termios's range). */
#define XGO_HOST_UART_MIN_BAUD 50u
#define XGO_HOST_UART_MAX_BAUD 4000000u

/* A receiver at rx_baud listening to n bytes sent at tx_baud, one received
 * byte at a time. Speeds outside the range above, or equal ones, pass the
 * bytes through unchanged. in must stay valid while it is used. */
typedef struct xgo_host_uart_rx_s {
    const uint8_t *bytes;
    size_t n;
    int same;        /* pass-through */
    uint64_t bits;   /* 10 per byte */
    uint64_t tx_bit; /* time units per sent bit */
    uint64_t half;   /* time units per half a received bit */
    uint64_t t;      /* ready from this time (pass-through: next byte) */
} xgo_host_uart_rx_t;

void xgo_host_uart_rx_begin(xgo_host_uart_rx_t *rx, uint32_t tx_baud, uint32_t rx_baud,
                            const uint8_t *in, size_t n);
/* 1 and the next received byte with its framing error flag, or 0 when the
 * line has gone idle for good. */
int xgo_host_uart_rx_next(xgo_host_uart_rx_t *rx, uint8_t *byte, int *framing_error);

/* Into the board (host at host_baud, board at board_baud): a byte with a
 * framing error is dropped and counted in *framing_errors, as the board's
 * UART driver would. Returns the bytes kept in out (cap >= n *
 * XGO_HOST_UART_GROWTH always suffices; more are not produced). */
size_t xgo_host_uart_to_board(uint32_t host_baud, uint32_t board_baud, const uint8_t *in, size_t n,
                              uint8_t *out, size_t cap, uint32_t *framing_errors);

/* Out to the host: a byte with a framing error arrives as 0x00, as Linux's
 * tty delivers it to a program that sets neither IGNPAR nor PARMRK (pyserial
 * does not). Returns the bytes in out. */
size_t xgo_host_uart_to_host(uint32_t board_baud, uint32_t host_baud, const uint8_t *in, size_t n,
                             uint8_t *out, size_t cap);

#endif /* XGO_HOST_UART_MODEL_H */
