/*
 * unit_startup.c - start-up for the Unity suites on a Cortex-M7 in QEMU
 * (tools/mcu/unit_tests.sh): FPU on, copy .data, zero .bss, open newlib's
 * semihosting streams, run the constructors, exit(main()) - the exit status
 * reaches the host through semihosting. (newlib's own rdimon start-up asks
 * QEMU where the heap is and gets unmapped memory: docs/mcu.md.) Faults
 * print where they happened and exit with 91.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;

int main(void);
void initialise_monitor_handles(void);
void __libc_init_array(void);
void Reset_Handler(void);
void Fault_Handler(void);

/* newlib calls these around the constructors; nothing to do here. */
void _init(void);
void _fini(void);
void _init(void)
{
}
void _fini(void)
{
}

typedef void (*handler_t)(void);

__attribute__((section(".isr_vector"), used)) static const struct {
    uint32_t *sp;
    handler_t handler[15];
} vectors = {&_estack,
             {Reset_Handler, Fault_Handler, Fault_Handler, Fault_Handler, Fault_Handler,
              Fault_Handler, 0, 0, 0, 0, Fault_Handler, Fault_Handler, 0, Fault_Handler,
              Fault_Handler}};

#define CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)

void Reset_Handler(void)
{
    const uint32_t *src = &_sidata;
    uint32_t *dst;
    /* The tests' double references use the Cortex-M7's FPU: turn it on. */
    CPACR |= CPACR_CP10_CP11_FULL;
    __asm__ volatile("dsb\n isb" ::: "memory");
    for (dst = &_sdata; dst < &_edata;) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss; dst++) {
        *dst = 0;
    }
    initialise_monitor_handles();
    __libc_init_array();
    exit(main());
}

void Fault_Handler(void)
{
    uint32_t psr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(psr));
    printf("\nFAULT exception %lu\n", (unsigned long)(psr & 0x1FFu));
    exit(91);
}
