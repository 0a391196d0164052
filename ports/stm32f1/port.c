/*
 * ports/stm32f1 - the board as firmware for an STM32F100 (Cortex-M3, 24 MHz;
 * QEMU's stm32vldiscovery machine, the STM32VL-Discovery board).
 *
 *   USART1 (PA9 TX, PA10 RX), 115200 8N1: the host's serial line. RX by
 *     interrupt into the device's ring; the interrupt masks itself while the
 *     ring is full (the USART then holds the next byte, the sender waits).
 *     TX from the main loop while TXE is set; when it is not, TXEIE wakes
 *     the loop once the data register is free.
 *   SysTick at 500 Hz: one control period per interrupt, plus the clock.
 *   Non-volatile data and servo outputs: qemu_board.c (QEMU models no flash
 *     controller; no servo bus on this board).
 */
#include <stdint.h>

#include "cortex_m.h"
#include "qemu_board.h"

#define CPU_HZ 24000000u
#define BAUD 115200u

/* RCC: clock control, configuration, APB2 peripheral clock enable. */
#define RCC_CR XGO_CM_REG(0x40021000u)
#define RCC_CFGR XGO_CM_REG(0x40021004u)
#define RCC_APB2ENR XGO_CM_REG(0x40021018u)
#define RCC_CR_HSEON (1u << 16)
#define RCC_CR_HSERDY (1u << 17)
#define RCC_CR_PLLON (1u << 24)
#define RCC_CR_PLLRDY (1u << 25)
#define RCC_CFGR_PLL_HSE_X3 ((1u << 16) | (1u << 18)) /* 8 MHz crystal x 3 */
#define RCC_CFGR_SW_PLL 2u
#define RCC_APB2ENR_IOPA_USART1 ((1u << 2) | (1u << 14))

/* GPIOA high configuration: PA9 alternate push-pull 50 MHz, PA10 floating input. */
#define GPIOA_CRH XGO_CM_REG(0x40010804u)
#define GPIOA_CRH_PA9_PA10_MASK 0x00000FF0u
#define GPIOA_CRH_PA9_AF_PA10_IN 0x000004B0u

#define USART1_SR XGO_CM_REG(0x40013800u)
#define USART1_DR XGO_CM_REG(0x40013804u)
#define USART1_BRR XGO_CM_REG(0x40013808u)
#define USART1_CR1 XGO_CM_REG(0x4001380Cu)
#define USART_SR_ORE (1u << 3)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_RE (1u << 2)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RXNEIE (1u << 5)
#define USART_CR1_TXEIE (1u << 7)
#define USART_CR1_UE (1u << 13)
#define USART1_IRQ 37u

/* Bounded waits for the clock: QEMU does not model the RCC (its registers
 * read 0) and runs the CPU at 24 MHz whatever they say. */
#define CLOCK_WAIT_LOOPS 100000u

struct xgo_port_s {
    volatile uint32_t ms;
    uint32_t rx_overruns; /* ORE seen: a byte was lost in the USART (never expected) */
    xgo_qemu_board_t board; /* NV in a host file, servo outputs (qemu_board.c) */
};

static struct xgo_port_s port;
static xgo_device_t device;

/* ---- the port boundary (xgo/port.h) ------------------------------------- */

/* CR1 is changed by the interrupt too: read-modify-write it with
 * interrupts masked (and left as they were). */
static void usart_cr1_update(uint32_t set, uint32_t clear)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
    USART1_CR1 = (USART1_CR1 & ~clear) | set;
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

uint32_t xgo_port_millis(xgo_port_t *p)
{
    return p->ms;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    (void)p;
    if (USART1_SR & USART_SR_TXE) {
        return 1;
    }
    usart_cr1_update(USART_CR1_TXEIE, 0); /* wake the loop when it is free */
    return 0;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    (void)p;
    if (n > 0) {
        USART1_DR = bytes[0];
    }
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    (void)p;
    usart_cr1_update(USART_CR1_RXNEIE, 0);
}

xgo_qemu_board_t *xgo_port_qemu_board(xgo_port_t *p)
{
    return &p->board;
}

/* ---- interrupts --------------------------------------------------------- */

/* One byte an entry: while RXNE stays set the interrupt is taken again (the
 * USART holds one byte). Every interrupt has the same priority, none
 * preempts another, so CR1 is changed here without masking; the byte is
 * stored last, a tail call: the handler keeps one frame of 8 bytes on the
 * stack (tools/mcu/fw_check.sh adds the deepest handler to the bound). */
static void usart1_irq(void)
{
    const uint32_t sr = USART1_SR;
    if ((USART1_CR1 & USART_CR1_TXEIE) && (sr & USART_SR_TXE)) {
        USART1_CR1 &= ~USART_CR1_TXEIE; /* only a wake-up for the loop */
    }
    if ((sr & USART_SR_RXNE) == 0) {
        return;
    }
    /* Full ring: hold the line (the USART keeps the byte). Checked first:
     * a byte arriving while the handler ran leaves the interrupt pending,
     * so it runs once more after masking. */
    if (!xgo_device_rx_accepting(&device)) {
        USART1_CR1 &= ~USART_CR1_RXNEIE;
        return;
    }
    if (sr & USART_SR_ORE) {
        port.rx_overruns++;
    }
    (void)xgo_device_rx_put(&device, (uint8_t)USART1_DR);
}

static void systick_irq(void)
{
    port.ms += 1000u / XGO_TICK_HZ;
    xgo_device_tick_due(&device);
}

#define U xgo_cm_unexpected_handler
__attribute__((section(".isr_vector"), used)) static const struct {
    xgo_cm_system_vectors_t system;
    /* IRQ 0..37 of the STM32F100's 56: the table ends with the last one
     * enabled (USART1). An interrupt above it is never enabled, so never
     * taken (72 bytes of flash less). */
    xgo_cm_handler_t irq[USART1_IRQ + 1u]; /* its last entry is usart1_irq */
} vectors = {
    XGO_CM_SYSTEM_VECTORS(systick_irq),
    {U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U,
     U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, U, usart1_irq /* 37 */}};
#undef U

/* ---- start-up ----------------------------------------------------------- */

static void clock_init(void)
{
    unsigned i;
    RCC_CR |= RCC_CR_HSEON;
    for (i = 0; i < CLOCK_WAIT_LOOPS && !(RCC_CR & RCC_CR_HSERDY); i++) {
    }
    RCC_CFGR |= RCC_CFGR_PLL_HSE_X3;
    RCC_CR |= RCC_CR_PLLON;
    for (i = 0; i < CLOCK_WAIT_LOOPS && !(RCC_CR & RCC_CR_PLLRDY); i++) {
    }
    if (RCC_CR & RCC_CR_PLLRDY) {
        RCC_CFGR |= RCC_CFGR_SW_PLL;
    }
    RCC_APB2ENR |= RCC_APB2ENR_IOPA_USART1;
    GPIOA_CRH = (GPIOA_CRH & ~GPIOA_CRH_PA9_PA10_MASK) | GPIOA_CRH_PA9_AF_PA10_IN;
}

int main(void)
{
    clock_init();
    xgo_nv_file_init(&port.board.nv);
    xgo_device_init(&device, &port, NULL);
    /* Bytes sent before this point are lost (the USART is off): hosts sync
     * with a read request they repeat until it is answered. */
    USART1_BRR = CPU_HZ / BAUD;
    USART1_CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
    XGO_CM_NVIC_ISER(USART1_IRQ / 32u) = 1u << (USART1_IRQ % 32u);
    XGO_CM_SYST_RVR = CPU_HZ / XGO_TICK_HZ - 1u;
    XGO_CM_SYST_CVR = 0;
    XGO_CM_SYST_CSR = XGO_CM_SYST_CSR_ENABLE_TICKINT_CPUCLK;
    xgo_cm_serve(&device);
    return 0;
}
