/*
 * startup.c - reset, RAM set-up, faults and the main loop of every
 * Cortex-M port. Reset_Handler copies .data from flash, zeroes .bss and
 * paints the free RAM below the stack with a pattern, so a debugger (or
 * QEMU's monitor: tools/mcu/fw_stack.sh) can read how deep the stack ever
 * went; then it calls the port's main(), which serves forever.
 */
#include "cortex_m.h"
#include "semihost.h"

#define STACK_PAINT 0x5AC3A55Cu

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss;

/* Reset_Handler's C part (its own frame, gone before main runs). */
void xgo_cm_ram_init(void);

void xgo_cm_ram_init(void)
{
    const uint32_t *src = &_sidata;
    uint32_t *dst = &_sdata;
    uintptr_t sp;

    while (dst < &_edata) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss; dst++) {
        *dst = 0;
    }
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (dst = &_ebss; (uintptr_t)dst < sp - 32u; dst++) {
        *dst = STACK_PAINT;
    }
}

/* Naked: nothing of it stays on the stack under main, whose calls are the
 * deepest stack path (tools/mcu/fw_check.sh; a C function would keep its
 * saved registers there: ARMv6-M's compiler makes no tail call). main
 * serves forever; should it return, the core stops here. */
__attribute__((naked)) void Reset_Handler(void)
{
    __asm__ volatile("bl xgo_cm_ram_init\n"
                     "bl main\n"
                     "b .\n");
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

/* A fault is a bug in the firmware: report where and stop (under QEMU the
 * emulator exits with status 91). The exception frame r0 r1 r2 r3 r12 lr pc
 * xpsr is on the main stack (the firmware never uses the process stack). */
void xgo_cm_fault_report(const uint32_t *frame);

__attribute__((naked)) void xgo_cm_fault_handler(void)
{
    __asm__ volatile("mrs r0, msp\n"
                     "ldr r1, =xgo_cm_fault_report\n"
                     "bx r1\n"
                     ".ltorg\n");
}

void xgo_cm_fault_report(const uint32_t *frame)
{
    char msg[] = "xgo-fw: FAULT pc=xxxxxxxx lr=xxxxxxxx\n";
    put_hex32(&msg[17], frame[6]);
    put_hex32(&msg[29], frame[5]);
    xgo_sh_write0(msg);
    xgo_sh_exit(91);
}

/* An interrupt nobody enabled: also a bug (status 92). */
void xgo_cm_unexpected_handler(void)
{
    xgo_sh_write0("xgo-fw: unexpected exception or interrupt\n");
    xgo_sh_exit(92);
}
