/*
 * measure.S - SysTick harness stubs (measure.h). Each stub reads SYST_CVR,
 * calls its target with the caller's arguments untouched (r0..r3), reads
 * SYST_CVR again and returns (t0 - t1) & 0xFFFFFF (SysTick counts down).
 * Between the two reads: the BL, the target's instructions and one LDR; the
 * self test calibrates that overhead with mcu_empty.
 * ARMv6-M Thumb (Cortex-M0/M0+), AAPCS: 16 bytes pushed keep SP 8-aligned.
 */
    .syntax unified
    .thumb
    .text

    .equ SYST_CVR, 0xE000E018

.macro MEASURE name, target
    .global \name
    .type \name, %function
    .thumb_func
    .align 2
\name:
    push {r4, r6, r7, lr}
    ldr r6, =SYST_CVR
    ldr r7, [r6]
    bl \target
    ldr r1, [r6]
    subs r0, r7, r1
    ldr r2, =0x00FFFFFF
    ands r0, r2
    pop {r4, r6, r7, pc}
    .ltorg
    .size \name, . - \name
.endm

/* void mcu_empty(void): exactly 1 instruction. */
    .global mcu_empty
    .type mcu_empty, %function
    .thumb_func
    .align 2
mcu_empty:
    bx lr
    .size mcu_empty, . - mcu_empty

/* void mcu_loop4(uint32_t n), n >= 1: exactly 4n+1 instructions. */
    .global mcu_loop4
    .type mcu_loop4, %function
    .thumb_func
    .align 2
mcu_loop4:
1:  subs r0, #1
    nop
    nop
    bne 1b
    bx lr
    .size mcu_loop4, . - mcu_loop4

    MEASURE mcu_ticks_empty, mcu_empty
    MEASURE mcu_ticks_loop, mcu_loop4
    MEASURE mcu_ticks_tick, xgo_board_tick
    MEASURE mcu_ticks_receive, xgo_board_receive
    MEASURE mcu_ticks_transmit, xgo_board_transmit
