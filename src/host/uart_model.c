/*
 * uart_model.c - one UART's bytes as another UART hears them (see
 * uart_model.h).
 *
 * Time is an integer in units of 1 / (2 * tx_baud * rx_baud) s: a sent bit
 * lasts 2 * rx_baud units, a received bit 2 * tx_baud, half a received bit
 * tx_baud, so every sample time is exact (no rounding decides a bit).
 */
#include "uart_model.h"

#include <string.h>

#define BITS_PER_FRAME 10u

/* Level of sent bit k: before the first and after the last frame the line
 * is idle (1). */
static unsigned xgo_host_uart_bit(const xgo_host_uart_rx_t *rx, int64_t k)
{
    uint64_t pos;
    if (k < 0 || (uint64_t)k >= rx->bits) {
        return 1u;
    }
    pos = (uint64_t)k % BITS_PER_FRAME;
    if (pos == 0) {
        return 0u; /* start */
    }
    if (pos == BITS_PER_FRAME - 1u) {
        return 1u; /* stop */
    }
    return (rx->bytes[(uint64_t)k / BITS_PER_FRAME] >> (pos - 1u)) & 1u;
}

static unsigned xgo_host_uart_level(const xgo_host_uart_rx_t *rx, uint64_t t)
{
    return xgo_host_uart_bit(rx, (int64_t)(t / rx->tx_bit));
}

/* The first falling edge at or after t (a 1 bit followed by a 0 bit whose
 * boundary is not before t); 0 when there is none before the line goes idle
 * for good. */
static int xgo_host_uart_next_edge(const xgo_host_uart_rx_t *rx, uint64_t t, uint64_t *edge)
{
    uint64_t k = (t + rx->tx_bit - 1u) / rx->tx_bit;
    for (; k < rx->bits; k++) {
        if (xgo_host_uart_bit(rx, (int64_t)k) == 0u && xgo_host_uart_bit(rx, (int64_t)k - 1) == 1u) {
            *edge = k * rx->tx_bit;
            return 1;
        }
    }
    return 0;
}

static int xgo_host_uart_speed_ok(uint32_t baud)
{
    return baud >= XGO_HOST_UART_MIN_BAUD && baud <= XGO_HOST_UART_MAX_BAUD;
}

void xgo_host_uart_rx_begin(xgo_host_uart_rx_t *rx, uint32_t tx_baud, uint32_t rx_baud,
                            const uint8_t *in, size_t n)
{
    memset(rx, 0, sizeof *rx);
    rx->bytes = in;
    rx->n = n;
    rx->same = tx_baud == rx_baud || !xgo_host_uart_speed_ok(tx_baud) ||
               !xgo_host_uart_speed_ok(rx_baud);
    rx->bits = (uint64_t)n * BITS_PER_FRAME;
    rx->tx_bit = 2u * (uint64_t)rx_baud;
    rx->half = tx_baud;
}

int xgo_host_uart_rx_next(xgo_host_uart_rx_t *rx, uint8_t *byte, int *framing_error)
{
    const uint64_t rx_bit = 2u * rx->half;
    uint64_t edge, mid;
    unsigned value = 0, bit;
    if (rx->same) {
        if (rx->t >= rx->n) {
            return 0;
        }
        *byte = rx->bytes[rx->t++];
        *framing_error = 0;
        return 1;
    }
    for (;;) {
        if (!xgo_host_uart_next_edge(rx, rx->t, &edge)) {
            return 0;
        }
        mid = edge + rx->half;
        if (xgo_host_uart_level(rx, mid) == 0u) {
            break;
        }
        rx->t = mid; /* too short to be a start bit */
    }
    for (bit = 0; bit < 8u; bit++) {
        value |= xgo_host_uart_level(rx, mid + (bit + 1u) * rx_bit) << bit;
    }
    rx->t = mid + 9u * rx_bit; /* the stop bit's sample */
    *byte = (uint8_t)value;
    *framing_error = xgo_host_uart_level(rx, rx->t) == 0u;
    return 1;
}

size_t xgo_host_uart_to_board(uint32_t host_baud, uint32_t board_baud, const uint8_t *in, size_t n,
                              uint8_t *out, size_t cap, uint32_t *framing_errors)
{
    xgo_host_uart_rx_t rx;
    size_t kept = 0;
    uint8_t byte;
    int bad;
    xgo_host_uart_rx_begin(&rx, host_baud, board_baud, in, n);
    while (kept < cap && xgo_host_uart_rx_next(&rx, &byte, &bad)) {
        if (bad) {
            (*framing_errors)++;
        } else {
            out[kept++] = byte;
        }
    }
    return kept;
}

size_t xgo_host_uart_to_host(uint32_t board_baud, uint32_t host_baud, const uint8_t *in, size_t n,
                             uint8_t *out, size_t cap)
{
    xgo_host_uart_rx_t rx;
    size_t got = 0;
    uint8_t byte;
    int bad;
    xgo_host_uart_rx_begin(&rx, board_baud, host_baud, in, n);
    while (got < cap && xgo_host_uart_rx_next(&rx, &byte, &bad)) {
        out[got++] = bad ? 0x00u : byte;
    }
    return got;
}
