/*
 * compiler.h - the core's two function attributes, defined once (private).
 *
 * GCC and Clang honour them; with another compiler they fall back to plain
 * C and only cost or stack depth change, never a result.
 *
 * XGO_OWN_FRAME: keep a function out of line, so its locals do not widen
 *   the frame of a caller on the deepest stack path (the static bound,
 *   docs/mcu.md "Sizes") or the registers of a hot caller.
 * XGO_ALWAYS_INLINE: static inline even at -Os, for the few small helpers
 *   where a call would eat most of what they save.
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

#endif /* XGO_CORE_COMPILER_H */
