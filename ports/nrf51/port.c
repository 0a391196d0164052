/*
 * ports/nrf51 - the board as firmware for an nRF51822 (Cortex-M0, 16 MHz;
 * QEMU's microbit machine, the BBC micro:bit).
 *
 *   UART0 (P0.24 TX, P0.25 RX), 115200 8N1: the host's serial line. RX by
 *     interrupt into the device's ring; the interrupt masks itself while the
 *     ring is full (the UART's FIFO then holds the bytes, the sender waits).
 *     TX from the main loop, one byte per TXDRDY; while a byte is in flight
 *     the TXDRDY interrupt wakes the loop.
 *   TIMER0 at 1 MHz, compare 0 every 2000 us: one control period each. The
 *     handler moves the compare on by whole periods and catches up if it
 *     ran late (the COMPARE->CLEAR short would lose the time spent late).
 *   Non-volatile data and servo outputs: qemu_board.c (QEMU models no NVMC;
 *     no servo bus here).
 */
#include <stdint.h>

#include "cortex_m.h"
#include "qemu_board.h"

#define UART0_TASKS_STARTRX XGO_CM_REG(0x40002000u)
#define UART0_TASKS_STARTTX XGO_CM_REG(0x40002008u)
#define UART0_EVENTS_RXDRDY XGO_CM_REG(0x40002108u)
#define UART0_EVENTS_TXDRDY XGO_CM_REG(0x4000211Cu)
#define UART0_INTENSET XGO_CM_REG(0x40002304u)
#define UART0_INTENCLR XGO_CM_REG(0x40002308u)
#define UART0_ENABLE XGO_CM_REG(0x40002500u)
#define UART0_PSELTXD XGO_CM_REG(0x4000250Cu)
#define UART0_PSELRXD XGO_CM_REG(0x40002514u)
#define UART0_RXD XGO_CM_REG(0x40002518u)
#define UART0_TXD XGO_CM_REG(0x4000251Cu)
#define UART0_BAUDRATE XGO_CM_REG(0x40002524u)
#define UART_INT_RXDRDY (1u << 2)
#define UART_INT_TXDRDY (1u << 7)
#define UART_ENABLE_ON 4u
#define UART_BAUD_115200 0x01D7E000u
#define UART0_IRQ 2u
#define PIN_TX 24u
#define PIN_RX 25u

#define TIMER0_TASKS_START XGO_CM_REG(0x40008000u)
#define TIMER0_TASKS_CAPTURE1 XGO_CM_REG(0x40008044u)
#define TIMER0_EVENTS_COMPARE0 XGO_CM_REG(0x40008140u)
#define TIMER0_INTENSET XGO_CM_REG(0x40008304u)
#define TIMER0_MODE XGO_CM_REG(0x40008504u)
#define TIMER0_BITMODE XGO_CM_REG(0x40008508u)
#define TIMER0_PRESCALER XGO_CM_REG(0x40008510u)
#define TIMER0_CC0 XGO_CM_REG(0x40008540u)
#define TIMER0_CC1 XGO_CM_REG(0x40008544u)
#define TIMER_INT_COMPARE0 (1u << 16)
#define TIMER_BITMODE_32 3u
#define TIMER_PRESCALER_1MHZ 4u /* 16 MHz / 2^4 */
#define TIMER0_IRQ 8u
#define TICK_US (1000000u / XGO_TICK_HZ)

struct xgo_port_s {
    volatile uint32_t ms;
    uint8_t tx_busy; /* a byte is in flight: room once TXDRDY */
    xgo_qemu_board_t board; /* NV in a host file, servo outputs (qemu_board.c) */
};

static struct xgo_port_s port;
static xgo_device_t device;

/* ---- the port boundary (xgo/port.h) ------------------------------------- */

uint32_t xgo_port_millis(xgo_port_t *p)
{
    return p->ms;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    if (!p->tx_busy || UART0_EVENTS_TXDRDY) {
        return 1;
    }
    UART0_INTENSET = UART_INT_TXDRDY; /* wake the loop when it is sent */
    return 0;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    if (n > 0) {
        UART0_EVENTS_TXDRDY = 0;
        UART0_TXD = bytes[0];
        p->tx_busy = 1;
    }
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    (void)p;
    UART0_INTENSET = UART_INT_RXDRDY;
}

xgo_qemu_board_t *xgo_port_qemu_board(xgo_port_t *p)
{
    return &p->board;
}

/* ---- interrupts --------------------------------------------------------- */

/* One byte an entry: while the FIFO holds more, reading RXD raises RXDRDY
 * again and the interrupt is taken again. No loop: the handler keeps only
 * its return address on the stack (tools/mcu/fw_check.sh adds the deepest
 * handler to the bound). */
static void uart0_irq(void)
{
    /* Asked before anything: no value is kept across the call. A full ring
     * holds the line (the FIFO keeps the bytes); checked before every byte:
     * a byte arriving while the handler ran leaves the interrupt pending,
     * so it runs once more after masking. */
    const int accepting = xgo_device_rx_accepting(&device);
    if (UART0_EVENTS_TXDRDY) {
        UART0_INTENCLR = UART_INT_TXDRDY; /* only a wake-up for the loop */
    }
    if (!UART0_EVENTS_RXDRDY) {
        return;
    }
    if (!accepting) {
        UART0_INTENCLR = UART_INT_RXDRDY;
        return;
    }
    /* Clear first: reading RXD raises it again while the FIFO has more. */
    UART0_EVENTS_RXDRDY = 0;
    (void)xgo_device_rx_put(&device, (uint8_t)UART0_RXD);
}

/* One period per compare; if the handler ran late past the next compare,
 * it sets itself pending again and runs once more at once for each period
 * missed, so the tick rate holds on average and the timer never waits for
 * a wrap. No loop: nothing is kept across the call, the handler's frame is
 * its return address (tools/mcu/fw_check.sh adds the deepest handler to
 * the bound). */
static void timer0_irq(void)
{
    TIMER0_EVENTS_COMPARE0 = 0;
    TIMER0_CC0 += TICK_US;
    port.ms += 1000u / XGO_TICK_HZ;
    TIMER0_TASKS_CAPTURE1 = 1;
    if ((int32_t)(TIMER0_CC1 - TIMER0_CC0) >= 0) {
        XGO_CM_NVIC_ISPR(0) = 1u << TIMER0_IRQ; /* the next compare passed already */
    }
    xgo_device_tick_due(&device);
}

/* The table below ends at TIMER0: every interrupt enabled must be in it. */
typedef char uart0_irq_in_the_table[UART0_IRQ < TIMER0_IRQ ? 1 : -1];

#define U xgo_cm_unexpected_handler
__attribute__((section(".isr_vector"), used)) static const struct {
    xgo_cm_system_vectors_t system;
    /* IRQ 0..8 of the nRF51's 32: the table ends with the last one enabled
     * (TIMER0). An interrupt above it is never enabled, so never taken (92
     * bytes of flash less). */
    xgo_cm_handler_t irq[TIMER0_IRQ + 1u]; /* its last entry is timer0_irq */
} vectors = {XGO_CM_SYSTEM_VECTORS(U),
             {U, U, uart0_irq /* 2 */, U, U, U, U, U, timer0_irq /* 8 */}};
#undef U

/* ---- start-up ----------------------------------------------------------- */

/* Out of line: main's frame is under every call the firmware makes (the
 * stack bound, docs/mcu.md), and these constants need registers. */
__attribute__((noinline)) static void start(void)
{
    xgo_nv_file_init(&port.board.nv);
    xgo_device_init(&device, &port, NULL);
    UART0_ENABLE = UART_ENABLE_ON; /* first: the UART ignores the rest until then */
    UART0_PSELTXD = PIN_TX;
    UART0_PSELRXD = PIN_RX;
    UART0_BAUDRATE = UART_BAUD_115200;
    UART0_EVENTS_RXDRDY = 0;
    UART0_EVENTS_TXDRDY = 0;
    UART0_TASKS_STARTTX = 1;
    UART0_TASKS_STARTRX = 1;
    UART0_INTENSET = UART_INT_RXDRDY;
    XGO_CM_NVIC_ISER(0) = (1u << UART0_IRQ) | (1u << TIMER0_IRQ);
    TIMER0_MODE = 0; /* timer */
    TIMER0_BITMODE = TIMER_BITMODE_32;
    TIMER0_PRESCALER = TIMER_PRESCALER_1MHZ;
    TIMER0_CC0 = TICK_US;
    TIMER0_INTENSET = TIMER_INT_COMPARE0;
    TIMER0_TASKS_START = 1;
}

int main(void)
{
    start();
    xgo_cm_serve(&device);
    return 0;
}
