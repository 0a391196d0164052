/*
 * startup.c - bare-metal start for a Cortex-M0/M0+ (ARMv6-M): vector table,
 * Reset_Handler (copy .data, zero .bss, paint the stack, run main, exit with
 * its return value through semihosting) and fault handlers that report and
 * exit with a distinct code each:
 *   90 NMI, 91 HardFault (prints the faulting PC), 92 SVCall/PendSV/SysTick,
 *   93 any external interrupt (none is enabled).
 */
#include <stdint.h>

#include "measure.h"
#include "semihost.h"

#define STACK_PAINT 0x5AC3A55Cu
#define IRQ_COUNT 32u /* nRF51: 32 external interrupts */

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;

int main(void);

void Reset_Handler(void);
void NMI_Handler(void);
void HardFault_Handler(void);
void System_Handler(void);
void IRQ_Handler(void);
void mcu_hardfault_report(const uint32_t *frame);

typedef void (*handler_t)(void);

typedef struct vectors_s {
    uint32_t *initial_sp;
    handler_t system[15]; /* Reset .. SysTick */
    handler_t irq[IRQ_COUNT];
} vectors_t;

__attribute__((section(".isr_vector"), used)) static const vectors_t vectors = {
    &_estack,
    {
        Reset_Handler,     /* 1 */
        NMI_Handler,       /* 2 */
        HardFault_Handler, /* 3 */
        0, 0, 0, 0, 0, 0, 0, /* 4..10 reserved on ARMv6-M (on an M3, 4..6 are
                                 MemManage/BusFault/UsageFault: disabled at
                                 reset, they escalate to HardFault) */
        System_Handler,    /* 11 SVCall */
        0, 0,              /* 12, 13 reserved */
        System_Handler,    /* 14 PendSV */
        System_Handler     /* 15 SysTick */
    },
    {
        IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler,
        IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler,
        IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler,
        IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler,
        IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler, IRQ_Handler,
        IRQ_Handler, IRQ_Handler
    }
};

static uintptr_t current_sp(void)
{
    uintptr_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

void Reset_Handler(void)
{
    uint32_t *src = &_sidata;
    uint32_t *dst = &_sdata;
    uintptr_t limit;

    while (dst < &_edata) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss; dst++) {
        *dst = 0;
    }
    /* Paint the free RAM below this frame: mcu_stack_used() finds the deepest
     * word main's calls ever wrote. */
    limit = current_sp() - 64u;
    for (dst = &_ebss; (uintptr_t)dst < limit; dst++) {
        *dst = STACK_PAINT;
    }
    sh_exit(main());
    for (;;) {
    }
}

/* Lowest stack address written since the last painting. */
static uintptr_t lowest_touched(void)
{
    const uint32_t *p = &_ebss;
    while ((uintptr_t)p < (uintptr_t)&_estack && *p == STACK_PAINT) {
        p++;
    }
    return (uintptr_t)p;
}

/* Deepest use before the last repainting (mcu_stack_probe_begin). */
static uint32_t deepest_before;

uint32_t mcu_stack_used(void)
{
    uint32_t now = (uint32_t)((uintptr_t)&_estack - lowest_touched());
    return now > deepest_before ? now : deepest_before;
}

uintptr_t mcu_stack_probe_begin(void)
{
    uintptr_t sp = current_sp();
    uint32_t *p;
    deepest_before = mcu_stack_used();
    for (p = &_ebss; (uintptr_t)p < sp - 64u; p++) {
        *p = STACK_PAINT;
    }
    return sp;
}

uint32_t mcu_stack_probe_end(uintptr_t mark)
{
    uintptr_t low = lowest_touched();
    return low < mark ? (uint32_t)(mark - low) : 0u;
}

uint32_t mcu_stack_free_min(void)
{
    return (uint32_t)((uintptr_t)&_estack - (uintptr_t)&_ebss) - mcu_stack_used();
}

static void put_hex32(char *out, uint32_t v)
{
    static const char hex[] = "0123456789abcdef";
    int i;
    for (i = 7; i >= 0; i--) {
        out[i] = hex[v & 15u];
        v >>= 4;
    }
}

void NMI_Handler(void)
{
    sh_write0("FAULT NMI\n");
    sh_exit(90);
}

/* The exception frame (r0 r1 r2 r3 r12 lr pc xpsr) is on the main stack. */
__attribute__((naked)) void HardFault_Handler(void)
{
    __asm__ volatile("mrs r0, msp\n"
                     "ldr r1, =mcu_hardfault_report\n"
                     "bx r1\n"
                     ".ltorg\n");
}

void mcu_hardfault_report(const uint32_t *frame)
{
    char msg[] = "FAULT HardFault pc=xxxxxxxx lr=xxxxxxxx\n";
    put_hex32(&msg[19], frame[6]);
    put_hex32(&msg[31], frame[5]);
    sh_write0(msg);
    sh_exit(91);
}

void System_Handler(void)
{
    sh_write0("FAULT unexpected SVCall/PendSV/SysTick exception\n");
    sh_exit(92);
}

void IRQ_Handler(void)
{
    sh_write0("FAULT unexpected interrupt\n");
    sh_exit(93);
}
