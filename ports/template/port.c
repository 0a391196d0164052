/*
 * ports/template - the file to copy when bringing the board up on a new
 * MCU (docs/mcu.md, "A new MCU in an afternoon"). Every TODO is a register
 * access of your chip; everything else stays as it is.
 *
 *   cp -r ports/template ports/mychip     # and write ports/mychip/link.ld
 *   (from ports/stm32f1/link.ld: your flash and RAM sizes)
 *
 * The contract is include/xgo/port.h: six functions the core calls (below),
 * three it offers to your interrupts (rx_accepting, rx_put, tick_due) and a
 * main loop (xgo_cm_serve on a Cortex-M, or your own: run the device, sleep
 * while it is idle). This file builds as it is (it is compiled in CI for a
 * Cortex-M0+), so a copy starts from code that links.
 */
#include <stdint.h>

#include "cortex_m.h"

/* Your platform's state: whatever the functions below need. */
struct xgo_port_s {
    volatile uint32_t ms; /* counted by the tick interrupt */
    xgo_board_nv_t nv;    /* TODO: your flash page instead of RAM */
    int nv_valid;
};

static struct xgo_port_s port;
static xgo_device_t device; /* the board and its receive ring */

/* ---- the port boundary (xgo/port.h) ------------------------------------- */

uint32_t xgo_port_millis(xgo_port_t *p)
{
    return p->ms;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    (void)p;
    /* TODO: return 1 if the UART's data register is free (more if it has a
     * FIFO); else enable its TX-empty interrupt (the handler only disables
     * it again: a wake-up) and return 0. */
    return 1;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    (void)p;
    (void)bytes;
    (void)n;
    /* TODO: write the n bytes (n <= the room you reported) to the UART. */
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    (void)p;
    /* TODO: enable the UART's RX interrupt again. */
}

int xgo_port_nv_load(xgo_port_t *p, xgo_board_nv_t *nv)
{
    /* TODO: read your flash page; return 0 if it holds nothing valid (check
     * a CRC: ports/cortex-m/nv_file.c has a record format to reuse). */
    if (p->nv_valid) {
        *nv = p->nv;
    }
    return p->nv_valid;
}

int xgo_port_nv_save(xgo_port_t *p, const xgo_board_nv_t *nv)
{
    /* TODO: erase and program your flash page, verify, return 1 on success. */
    p->nv = *nv;
    p->nv_valid = 1;
    return 1;
}

void xgo_port_servo_write(xgo_port_t *p, const int32_t raw_mdeg[XGO_SERVO_COUNT], uint16_t limp)
{
    (void)p;
    (void)raw_mdeg;
    (void)limp;
    /* TODO: send the twelve positions to the servo bus (torque off for the
     * joints whose bit is set in limp). Called after every control tick. */
}

/* ---- interrupts --------------------------------------------------------- */

static void uart_irq(void)
{
    /* TODO: while the UART has a received byte:
     *   if (!xgo_device_rx_accepting(&device)) { disable the RX interrupt; break; }
     *   (void)xgo_device_rx_put(&device, <the byte>);
     * and if the TX-empty interrupt is enabled and the register is free,
     * disable it (the main loop sends the next byte). */
    (void)xgo_device_rx_accepting(&device);
}

static void tick_irq(void)
{
    /* TODO: acknowledge the timer (nothing to do for SysTick). */
    port.ms += 1000u / XGO_TICK_HZ;
    xgo_device_tick_due(&device);
}

#define U xgo_cm_unexpected_handler
__attribute__((section(".isr_vector"), used)) static const struct {
    xgo_cm_system_vectors_t system;
    xgo_cm_handler_t irq[4]; /* TODO: your chip's count, your UART's number */
} vectors = {XGO_CM_SYSTEM_VECTORS(tick_irq), {uart_irq, U, U, U}};
#undef U

/* ---- start-up ----------------------------------------------------------- */

int main(void)
{
    /* TODO: clocks, pins, UART at 115200 8N1 with its RX interrupt, the
     * interrupt in the NVIC: after xgo_device_init, so no byte arrives
     * before the ring exists. */
    xgo_device_init(&device, &port, NULL);
    XGO_CM_SYST_RVR = 16000000u / XGO_TICK_HZ - 1u; /* TODO: your CPU clock */
    XGO_CM_SYST_CVR = 0;
    XGO_CM_SYST_CSR = XGO_CM_SYST_CSR_ENABLE_TICKINT_CPUCLK;
    xgo_cm_serve(&device);
    return 0;
}
