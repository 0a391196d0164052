/*
 * wide.h - 32 x 32 -> 64-bit products for the core (private, not installed).
 *
 * Why: a Cortex-M0/M0+ (ARMv6-M) has only MULS, which keeps the low 32 bits
 * of a product; for every (int64_t)a * b GCC calls libgcc's general 64 x 64
 * multiply __aeabi_lmul (about 41 instructions plus the call). When both
 * operands are 32-bit values, four 16 x 16 -> 32-bit MULS and a few adds
 * give the exact product in about half that, inline. Everywhere else (x86,
 * Cortex-M3 and up: one widening multiply instruction) the plain product is
 * used. Both are exact, so results are bit-identical on every target
 * (tools/mcu/run.sh compares them).
 *
 * Define XGO_WIDE_MUL_SPLIT to use the 16-bit form (and the division loops
 * below) on any target (tests).
 */
#ifndef XGO_CORE_WIDE_H
#define XGO_CORE_WIDE_H

#include <stdint.h>

#include "compiler.h" /* XGO_ALWAYS_INLINE, XGO_INLINE_FAST */


/* XGO_CORE_NARROW_CPU: a core without a divide instruction and without
 * 64-bit or widening arithmetic (ARMv6-M). There a few hot divisions whose
 * quotient has few bits are restoring-division loops and the 64-bit square
 * root runs mostly in 32 bits; elsewhere one divide instruction or the
 * plain 64-bit loop is cheaper. Every variant is exact: same results. */
#if defined(XGO_WIDE_MUL_SPLIT) || defined(__ARM_ARCH_6M__) || defined(__ARM_ARCH_8M_BASE__)
#define XGO_CORE_NARROW_CPU 1
#else
#define XGO_CORE_NARROW_CPU 0
#endif

/* XGO_CORE_DIV64_NATIVE: the core has a 64-bit divide instruction (64-bit
 * hosts). Elsewhere a 64-bit division is a libgcc call (hundreds of cycles
 * on a Cortex-M3, more on an M0) and none may run in a tick (docs/mcu.md). */
#if !XGO_CORE_NARROW_CPU && (defined(__x86_64__) || defined(__aarch64__) || \
                             (defined(__SIZEOF_POINTER__) && __SIZEOF_POINTER__ == 8))
#define XGO_CORE_DIV64_NATIVE 1
#else
#define XGO_CORE_DIV64_NATIVE 0
#endif

#if defined(XGO_WIDE_MUL_SPLIT) || defined(__ARM_ARCH_6M__) || defined(__ARM_ARCH_8M_BASE__)

/* These products are a dozen or more instructions at each of many call
 * sites: on a Cortex-M0 left to the compiler (XGO_INLINE_FAST). */

/* Unsigned 32 x 32 -> 64 from 16-bit halves. */
XGO_INLINE_FAST uint64_t xgo_umul_wide(uint32_t a, uint32_t b)
{
    uint32_t al = a & 0xFFFFu, ah = a >> 16, bl = b & 0xFFFFu, bh = b >> 16;
    uint32_t lo = al * bl, hi = ah * bh;
    uint32_t m1 = al * bh, m2 = ah * bl; /* each < 2^32 */
    uint32_t mid = m1 + m2;              /* may wrap: the carry is worth 2^48 */
    uint32_t t;
    hi += (mid < m1 ? 0x10000u : 0u) + (mid >> 16);
    t = lo + (mid << 16);
    hi += t < lo ? 1u : 0u;
    return ((uint64_t)hi << 32) | t;
}

/* u^2: the same from three MULS, the cross product taken once (u = uh
 * 2^16 + ul: u^2 = uh^2 2^32 + uh ul 2^17 + ul^2, uh ul < 2^32). */
XGO_INLINE_FAST uint64_t xgo_usquare_wide(uint32_t u)
{
    const uint32_t ul = u & 0xFFFFu, uh = u >> 16;
    const uint32_t lo = ul * ul, m = uh * ul;
    const uint32_t t = lo + (m << 17);
    const uint32_t hi = uh * uh + (m >> 15) + (t < lo ? 1u : 0u);
    return ((uint64_t)hi << 32) | t;
}

/* Signed: the unsigned product of the two's-complement bit patterns, minus
 * 2^32 * b if a < 0 and 2^32 * a if b < 0 (modulo 2^64); the result is
 * exact since |a * b| <= 2^62. */
XGO_INLINE_FAST int64_t xgo_mul_wide(int32_t a, int32_t b)
{
    uint64_t p = xgo_umul_wide((uint32_t)a, (uint32_t)b);
    uint32_t hi = (uint32_t)(p >> 32);
    if (a < 0) {
        hi -= (uint32_t)b;
    }
    if (b < 0) {
        hi -= (uint32_t)a;
    }
    p = ((uint64_t)hi << 32) | (uint32_t)p;
    /* two's complement view (the core assumes it; see fixed.c) */
    return p <= (uint64_t)INT64_MAX ? (int64_t)p : -(int64_t)(~p) - 1;
}

#else

XGO_ALWAYS_INLINE uint64_t xgo_umul_wide(uint32_t a, uint32_t b)
{
    return (uint64_t)a * b;
}

XGO_ALWAYS_INLINE uint64_t xgo_usquare_wide(uint32_t u)
{
    return (uint64_t)u * u;
}

XGO_ALWAYS_INLINE int64_t xgo_mul_wide(int32_t a, int32_t b)
{
    return (int64_t)a * b;
}

#endif

/* floor((a c + 2^(q-1)) / 2^q), 21 <= q <= 31, for |a| < 2^20 and |c >>
 * 20| < 2^11, without a wide product: from c's 10-bit pieces, c = c2 2^20
 * + c1 2^10 + c0 (0 <= c1, c0 < 2^10),
 *   floor((a c2 + floor((a c1 + floor((a c0 + 2^(q-1)) / 2^10)) / 2^10)) / 2^(q-20)),
 * each product and nested sum within int32: exact, three MULS (by
 * constants when c is one). For a Cortex-M0's hot products (the IMU
 * model's rotations, the gait's planted-foot steps); callers check the
 * range of a and fall back to the wide product beyond it. */
XGO_ALWAYS_INLINE int32_t xgo_mul_round_pieces10(int32_t a, int32_t c, unsigned q)
{
    const int32_t low = (a * (c & 1023) + (1 << (q - 1u))) >> 10;
    const int32_t mid = (a * ((c >> 10) & 1023) + low) >> 10;
    return (a * (c >> 20) + mid) >> (q - 20u);
}

/* Variable shifts of 64-bit values are libgcc calls on a Cortex-M0
 * (__aeabi_llsl/llsr/lasr, about 12 instructions plus the call) and a
 * dozen conditional instructions on a Cortex-M3; where the result fits 32
 * bits the two halves do it inline on every 32-bit core. On a 64-bit
 * host the plain shift. The same value either way. */

/* round(v / 2^k) (ties up) for 1 <= k <= 63 when it fits 32 bits:
 * floor(v / 2^k) plus bit k - 1 of v (no 64-bit add). */
XGO_ALWAYS_INLINE uint32_t xgo_round_shr64(uint64_t v, unsigned k)
{
#if !XGO_CORE_DIV64_NATIVE /* any 32-bit core: a 64-bit add and shift cost more there too */
    const uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;
    if (k >= 32u) {
        return (hi >> (k - 32u)) + (k == 32u ? lo >> 31 : (hi >> (k - 33u)) & 1u);
    }
    return ((hi << (32u - k)) | (lo >> k)) + ((lo >> (k - 1u)) & 1u);
#else /* floor((floor(v / 2^(k-1)) + 1) / 2), the same: two shifts and an add, no constant */
    return (uint32_t)(((v >> (k - 1u)) + 1u) >> 1);
#endif
}

/* floor(v / 2^k) for 0 <= k <= 63 when it fits int32 (an arithmetic
 * shift: the low 32 bits of v >> k). */
XGO_ALWAYS_INLINE int32_t xgo_shr64_to32(int64_t v, unsigned k)
{
#if !XGO_CORE_DIV64_NATIVE
    const uint32_t lo = (uint32_t)(uint64_t)v;
    const int32_t hi = (int32_t)(v >> 32);
    if (k >= 32u) {
        return hi >> (k - 32u);
    }
    if (k == 0u) {
        return (int32_t)lo;
    }
    return (int32_t)((lo >> k) | ((uint32_t)hi << (32u - k)));
#else
    return (int32_t)(v >> k);
#endif
}

/* v << k for 0 <= k <= 31 when v << k fits 64 bits. */
XGO_ALWAYS_INLINE uint64_t xgo_shl64(uint64_t v, unsigned k)
{
#if !XGO_CORE_DIV64_NATIVE
    const uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;
    if (k == 0u) {
        return v;
    }
    return ((uint64_t)((hi << k) | (lo >> (32u - k))) << 32) | (uint32_t)(lo << k);
#else
    return v << k;
#endif
}

#endif /* XGO_CORE_WIDE_H */
