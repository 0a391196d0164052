/*
 * measure.c - SysTick set-up and tick conversion for the MCU build
 * (measure.h; the stubs are in measure.S).
 */
#include <stdint.h>

#include "measure.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

int mcu_count_start(void)
{
    SYST_CSR = 0u;
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 5u; /* enable, processor clock, no interrupt */
    return 1;
}

uint32_t mcu_ticks_to_insns(uint32_t ticks)
{
#ifdef MCU_MPS2_AN385
    return (ticks * 5u + 8u) / 16u;
#else
    /* ticks < 2^24, so ticks * 125 + 256 < 2^31 */
    return (ticks * 125u + 256u) / 512u;
#endif
}
