/*
 * measure.h - exact instruction counts on QEMU's Cortex-M0 (-M microbit).
 *
 * QEMU counts retired instructions, not cycles. With -icount shift=8 one
 * instruction takes 256 ns of virtual time and SysTick (16 MHz CPU clock on
 * the microbit) advances 4.096 ticks per instruction, so
 *   instructions = round(ticks * 125 / 512)
 * (docs/mcu.md). The 24-bit counter limits one interval to about 4.1 M
 * instructions. Built with -DMCU_MPS2_AN385 (the Cortex-M3 comparison run,
 * -M mps2-an385 -icount shift=7, SysTick at 25 MHz: 3.2 ticks per
 * instruction): instructions = round(ticks * 5 / 16), about 5.2 M at most.
 *
 * The mcu_ticks_* stubs (measure.S) read SysTick, call the function, read it
 * again and return the elapsed ticks. The fixed harness overhead is
 * calibrated at run time with an empty function and a 4n+1 loop.
 *
 * The host variant (host_port.c) calls the same functions and returns 0:
 * the self test runs the same sequence of calls on both, so the results
 * compare bit for bit.
 */
#ifndef MCU_MEASURE_H
#define MCU_MEASURE_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/board.h"

/* Starts SysTick (free running, no interrupt). 1 when counts are real (MCU),
 * 0 on the host. */
int mcu_count_start(void);

/* Ticks -> instructions (see above). */
uint32_t mcu_ticks_to_insns(uint32_t ticks);

/* SysTick ticks across one call. */
uint32_t mcu_ticks_empty(void);        /* a function of 1 instruction (bx lr) */
uint32_t mcu_ticks_loop(uint32_t n);   /* a function of 4n+1 instructions, n >= 1 */
uint32_t mcu_ticks_tick(xgo_board_t *b);
uint32_t mcu_ticks_receive(xgo_board_t *b, const uint8_t *bytes, size_t n, uint32_t now_ms);
uint32_t mcu_ticks_transmit(xgo_board_t *b, uint8_t *out, size_t max);

/* Deepest stack use since reset (painted RAM), and the RAM never touched
 * between .bss and that depth. 0 on the host. */
uint32_t mcu_stack_used(void);
uint32_t mcu_stack_free_min(void);

/* Stack depth of the calls made between the two: _begin paints the free
 * stack below the caller, _end returns how many bytes below the caller's
 * stack pointer they reached (a few bytes more than the callees' own use).
 * 0 on the host. */
uintptr_t mcu_stack_probe_begin(void);
uint32_t mcu_stack_probe_end(uintptr_t mark);

#endif /* MCU_MEASURE_H */
