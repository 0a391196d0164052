/*
 * cortex_m.h - what every Cortex-M port of the board shares (ARMv6-M and
 * ARMv7-M alike): the core's interrupt controller and SysTick registers,
 * interrupt masking, the start-up code's symbols, and the main loop.
 */
#ifndef XGO_PORT_CORTEX_M_H
#define XGO_PORT_CORTEX_M_H

#include <stdint.h>

#include "xgo/port.h"

#define XGO_CM_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

/* NVIC: set-enable and set-pending registers, one bit per external
 * interrupt. */
#define XGO_CM_NVIC_ISER(n) XGO_CM_REG(0xE000E100u + 4u * (n))
#define XGO_CM_NVIC_ISPR(n) XGO_CM_REG(0xE000E200u + 4u * (n))
/* SysTick: control/status, reload, current value. */
#define XGO_CM_SYST_CSR XGO_CM_REG(0xE000E010u)
#define XGO_CM_SYST_RVR XGO_CM_REG(0xE000E014u)
#define XGO_CM_SYST_CVR XGO_CM_REG(0xE000E018u)
#define XGO_CM_SYST_CSR_ENABLE_TICKINT_CPUCLK 7u

typedef void (*xgo_cm_handler_t)(void);

/* The first 16 entries of every vector table: initial stack pointer, then
 * Reset .. SysTick (ARMv6-M leaves 4..10 and 12..13 reserved; on ARMv7-M
 * MemManage, BusFault, UsageFault are disabled at reset and escalate to
 * HardFault, so one fault handler serves both). */
typedef struct xgo_cm_system_vectors_s {
    uint32_t *initial_sp;
    xgo_cm_handler_t handler[15];
} xgo_cm_system_vectors_t;

extern uint32_t _estack;
void Reset_Handler(void);
void xgo_cm_fault_handler(void);
void xgo_cm_unexpected_handler(void);

/* Fills a port's system vectors; systick may be 0 (not used). */
#define XGO_CM_SYSTEM_VECTORS(systick)                                                   \
    {                                                                                    \
        &_estack,                                                                        \
        {Reset_Handler, xgo_cm_unexpected_handler, xgo_cm_fault_handler,                 \
         xgo_cm_fault_handler, xgo_cm_fault_handler, xgo_cm_fault_handler, 0, 0, 0, 0,   \
         xgo_cm_unexpected_handler, xgo_cm_unexpected_handler, 0,                        \
         xgo_cm_unexpected_handler, (systick)}                                           \
    }

/* The port's entry point, called by Reset_Handler once RAM is set up
 * (Reset_Handler keeps no frame under it). It must not return: it ends in
 * xgo_cm_serve. */
int main(void);

static inline void xgo_cm_irq_disable(void)
{
    __asm__ volatile("cpsid i" ::: "memory");
}

static inline void xgo_cm_irq_enable(void)
{
    __asm__ volatile("cpsie i" ::: "memory");
}

/* Serves forever: runs the device's work, and sleeps (WFI) whenever it has
 * none. The idle check and the WFI happen with interrupts masked: an
 * interrupt arriving in between stays pending and ends the WFI at once, so
 * no byte or tick waits for the next interrupt. Inline, in main: main's is
 * then the only frame between the reset and xgo_device_run, under every
 * control tick (the deepest stack path, tools/mcu/fw_check.sh). */
__attribute__((always_inline, noreturn)) static inline void xgo_cm_serve(xgo_device_t *d)
{
    for (;;) {
        xgo_cm_irq_disable();
        if (xgo_device_idle(d)) {
            __asm__ volatile("wfi" ::: "memory");
        }
        xgo_cm_irq_enable();
        xgo_device_run(d);
    }
}

#endif /* XGO_PORT_CORTEX_M_H */
