/*
 * startup.c - reset, RAM set-up, faults and the main loop of every
 * Cortex-M port. Reset_Handler copies .data from flash, zeroes .bss and
 * paints the free RAM below the stack with a pattern, so a debugger (or
 * QEMU's monitor: tools/mcu/fw_stack.sh) can read how deep the stack ever
 * went; then it calls the port's main().
 */
#include "cortex_m.h"
#include "semihost.h"

#define STACK_PAINT 0x5AC3A55Cu

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss;

void Reset_Handler(void)
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
    (void)main();
    xgo_sh_exit(0);
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

void xgo_cm_serve(xgo_device_t *d)
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
