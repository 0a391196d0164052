/*
 * compiler.h - the core's function attributes, defined once (private).
 *
 * GCC and Clang honour them; with another compiler they fall back to plain
 * C and only cost or stack depth change, never a result.
 *
 * XGO_OWN_FRAME: keep a function out of line, so its locals do not widen
 *   the frame of a caller on the deepest stack path (the static bound,
 *   docs/mcu.md "Sizes") or the registers of a hot caller.
 * XGO_ALWAYS_INLINE: static inline even at -Os, for the few small helpers
 *   where a call would eat most of what they save.
 * XGO_INLINE_FAST: the same, except on a Cortex-M0 (ARMv6-M), where it is
 *   plain static inline and the compiler decides (at -Os often out of
 *   line): for helpers whose inline copies cost the M0's flash more than
 *   their calls cost its time. Rule of thumb, measured site by site: a
 *   helper goes to XGO_INLINE_FAST when that saves at least about 4 bytes
 *   of the nRF51 image per instruction it adds to the M0's steady trotting
 *   tick (tools/mcu/fw_check.sh, tools/mcu/run.sh): typically the 64-bit
 *   products built from MULS pieces, with many call sites, and helpers off
 *   the trotting path; the others stay XGO_ALWAYS_INLINE.
 */
#ifndef XGO_CORE_COMPILER_H
#define XGO_CORE_COMPILER_H

#if defined(__GNUC__)
#define XGO_OWN_FRAME __attribute__((noinline))
#define XGO_ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define XGO_OWN_FRAME
#define XGO_ALWAYS_INLINE static inline
#endif

#if defined(__ARM_ARCH_6M__)
#define XGO_INLINE_FAST static inline
#else
#define XGO_INLINE_FAST XGO_ALWAYS_INLINE
#endif

#endif /* XGO_CORE_COMPILER_H */
