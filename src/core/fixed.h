/*
 * fixed.h - integer-only math for the motion core: Q formats, saturating
 * arithmetic, square root and trigonometry.
 *
 * The board's motion core must run on an MCU without an FPU (and, on a
 * Cortex-M0, without a divider), so everything here is integer arithmetic.
 * 64-bit products are used where 32 bits cannot hold the precision; the only
 * divisions are in xgo_div_q / xgo_muldiv, two small ones per xgo_atan2 and
 * one per xgo_isqrt64.
 *
 * Formats (docs/fixed-point.md has the reasoning and the measured errors):
 *
 *   lengths        int32_t micrometres (um). 1 um resolution, +-2147 m range.
 *                  Identifiers carry the unit: foot_um, thigh_um.
 *   angles (API)   int32_t millidegrees (mdeg), as the register file uses.
 *   angles (math)  xgo_bam_t: binary angle, uint32_t, 2^32 = one turn
 *                  (1 LSB = 8.4e-8 degree). Wraps modulo a turn for free.
 *   unit values    xgo_q30_t: int32_t, 1.0 = 2^30 (sin, cos, rotation
 *                  matrix entries, ratios in [-2, 2)).
 *   general        xgo_q16_t: int32_t Q16.16, 1.0 = 65536.
 *
 * Methods (reasons in docs/fixed-point.md): sin/cos use a 129-entry
 * quarter-wave table plus a 3rd-order angle-addition correction (two
 * 32 x 32 -> 64-bit products, the rest 16-bit); atan2 turns the vector back
 * by the nearest of 33 table angles atan(i/32) (exactly, in integers) and
 * finishes with atan(e) = e - e^3/3 on the residual |e| <= 1/64 (one
 * division of 24 quotient bits); asin/acos reduce to atan2; sqrt is a
 * table seed made exact by compares (one Newton step above 32 bits). The
 * maximum errors stated below were measured against libm (or exact integer
 * arithmetic) by test/test_fixed.c over dense sweeps of each whole domain
 * plus every extreme; docs/fixed-point.md has them with the cost of each
 * function.
 *
 * Nothing here overflows, divides by zero or has undefined behaviour for any
 * argument value: results saturate, and each function documents what it
 * returns at the edges. Out-of-range arguments are expected input (no
 * assertions).
 *
 * Portable: C99, no floating point, no OS calls, no heap, no globals. Assumes
 * two's complement and an arithmetic right shift of negative integers (true
 * for GCC and Clang on every target; checked at compile time in fixed.c).
 */
#ifndef XGO_FIXED_H
#define XGO_FIXED_H

#include <stdint.h>

#include "wide.h" /* the inline angle conversions */

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t xgo_q30_t;  /* 1.0 = 2^30 */
typedef int32_t xgo_q16_t;  /* 1.0 = 2^16 */
typedef uint32_t xgo_bam_t; /* 2^32 = one turn; 0x40000000 = 90 degrees */

#define XGO_Q30_ONE ((int32_t)1 << 30)
#define XGO_Q16_ONE ((int32_t)1 << 16)

#define XGO_BAM_90 0x40000000u
#define XGO_BAM_180 0x80000000u

#define XGO_MDEG_PER_TURN 360000

/* ------------------------------------------------------------ saturation */

/* Clamp a 64-bit value to int32_t. */
int32_t xgo_sat32(int64_t v);

/* a + b, a - b, -a, |a|, saturated to [INT32_MIN, INT32_MAX]. Exact. */
int32_t xgo_sat_add(int32_t a, int32_t b);
int32_t xgo_sat_sub(int32_t a, int32_t b);
int32_t xgo_sat_neg(int32_t a);
int32_t xgo_sat_abs(int32_t a);

/* (a * b) / 2^q for q in 0..31 (larger q is treated as 31), rounded to
 * nearest (ties toward +infinity), saturated. Max error 0.5 LSB. */
int32_t xgo_mul_q(int32_t a, int32_t b, unsigned q);

/* (a * 2^q) / b for q in 0..31, rounded to nearest (ties away from zero),
 * saturated. b == 0 gives INT32_MAX for a > 0, INT32_MIN for a < 0 and 0 for
 * a == 0. Max error 0.5 LSB. */
int32_t xgo_div_q(int32_t a, int32_t b, unsigned q);

/* a * b / c with a 64-bit intermediate, rounded to nearest (ties away from
 * zero), saturated; c == 0 handled as in xgo_div_q. Max error 0.5 LSB. */
int32_t xgo_muldiv(int32_t a, int32_t b, int32_t c);

/* min(floor(n / d), cap); d == 0 gives cap. Without a 64-bit division (a
 * libgcc call on 32-bit cores, and never run in a tick: docs/mcu.md): a
 * restoring division over the bits of cap, so it costs more the larger cap
 * is. Exact while d < 2^(63 - bit length of cap); beyond, both are halved
 * until it is (the quotient then may be one lower). */
uint32_t xgo_udiv64_cap(uint64_t n, uint64_t d, uint32_t cap);

/* Q16.16 conveniences. */
#define xgo_q16_mul(a, b) xgo_mul_q((a), (b), 16u)
#define xgo_q16_div(a, b) xgo_div_q((a), (b), 16u)

/* Leading zero bits of v (32 for 0). GCC and Clang have a builtin (one
 * instruction on most cores, a small libgcc routine on Cortex-M0); the
 * portable fallback is a 5-step binary search. */
static inline unsigned xgo_clz32(uint32_t v)
{
#if defined(__GNUC__) && UINT32_MAX == 0xFFFFFFFFu && defined(__SIZEOF_INT__) && __SIZEOF_INT__ == 4
    return v == 0u ? 32u : (unsigned)__builtin_clz(v);
#else
    unsigned n = 0;
    if (v == 0u) {
        return 32u;
    }
    if (v <= 0x0000FFFFu) {
        n += 16u;
        v <<= 16;
    }
    if (v <= 0x00FFFFFFu) {
        n += 8u;
        v <<= 8;
    }
    if (v <= 0x0FFFFFFFu) {
        n += 4u;
        v <<= 4;
    }
    if (v <= 0x3FFFFFFFu) {
        n += 2u;
        v <<= 2;
    }
    if (v <= 0x7FFFFFFFu) {
        n += 1u;
    }
    return n;
#endif
}

/* The hot paths' leading zeros (the square roots' and the wide atan2's
 * normalisation, the leg IK's cut; 20 a tick). Where the core has a CLZ
 * instruction the builtin is that instruction. ARMv6-M (Cortex-M0) has none:
 * the builtin is a libgcc call (__clzsi2, about 18 instructions plus the
 * call and the registers it clobbers), so there (and in the host's _narrow
 * build, which tests this path) a binary search inline, four steps of a
 * shift and a branch. The same values either way. */
#if defined(__GNUC__) && UINT32_MAX == 0xFFFFFFFFu && defined(__SIZEOF_INT__) && __SIZEOF_INT__ == 4 && \
    !XGO_CORE_NARROW_CPU
#define XGO_CLZ_BUILTIN 1
#else
#define XGO_CLZ_BUILTIN 0
#endif

/* clz(v) & ~1u for v != 0: the even shift that brings v to [2^30, 2^32). */
XGO_ALWAYS_INLINE unsigned xgo_clz32_even(uint32_t v)
{
#if XGO_CLZ_BUILTIN
    return (unsigned)__builtin_clz(v) & ~1u;
#else
    unsigned n = 0;
    if ((v >> 16) == 0u) {
        n = 16u;
        v <<= 16;
    }
    if ((v >> 24) == 0u) {
        n += 8u;
        v <<= 8;
    }
    if ((v >> 28) == 0u) {
        n += 4u;
        v <<= 4;
    }
    if ((v >> 30) == 0u) {
        n += 2u;
    }
    return n;
#endif
}

/* clz(v) for v != 0, inline as xgo_clz32_even. */
XGO_INLINE_FAST unsigned xgo_clz32_nz(uint32_t v)
{
#if XGO_CLZ_BUILTIN
    return (unsigned)__builtin_clz(v);
#else
    const unsigned n = xgo_clz32_even(v);
    return n + 1u - ((v << n) >> 31); /* v << n has a 1 in its top two bits */
#endif
}

/* Number of significant bits of v (0 for 0, 64 for 2^63 and up): what to
 * shift by before a product must fit 64 bits. */
static inline unsigned xgo_bit_length(uint64_t v)
{
    if ((v >> 32) != 0u) {
        return 64u - xgo_clz32((uint32_t)(v >> 32));
    }
    return 32u - xgo_clz32((uint32_t)v);
}

/* The same with the inline CLZ forms above (no libgcc call on a
 * Cortex-M0): for the hot paths. */
XGO_ALWAYS_INLINE unsigned xgo_bit_length_inline(uint64_t v)
{
    const uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;
    if (hi != 0u) {
        return 64u - xgo_clz32_nz(hi);
    }
    return lo != 0u ? 32u - xgo_clz32_nz(lo) : 0u;
}

/* ------------------------------------------------------------ square root */

/* floor(sqrt(x)), exact for every x. */
uint32_t xgo_isqrt32(uint32_t x);
uint32_t xgo_isqrt64(uint64_t x);

/* sqrt(x) near floor(sqrt(x)): exact below 2^32; above, the table's chord
 * and one Newton step (in 32-bit division) without the exact root's
 * compares, for callers that round anyway (the leg IK). Measured error:
 * see docs/fixed-point.md (within a few units of a 32-bit root, relative
 * 2^-29). */
uint32_t xgo_sqrt64_near(uint64_t x);

/* sqrt(x) in Q16.16, rounded to nearest; x <= 0 gives 0. Max error 0.5 LSB. */
xgo_q16_t xgo_q16_sqrt(xgo_q16_t x);

/* ------------------------------------------------------------ angles */

/* The three conversions are inline (the leg IK uses them several times per
 * leg, every tick); their products are 32 x 32 -> 64 bits (wide.h). */

/* The binary angle as a signed value in [-2^31, 2^31) (portable cast). */
static inline int32_t xgo_bam_signed(xgo_bam_t a)
{
    return a < 0x80000000u ? (int32_t)a : -(int32_t)(0xFFFFFFFFu - a) - 1;
}

/* mdeg -> binary angle, rounded, wrapped modulo one turn; any int32 input.
 * One mdeg is 2^32 / 360000 = 11930 + 5228/11250 BAM: the integer part is
 * applied modulo 2^32 (exact), the fraction as a Q32 multiplier,
 * round(5228/11250 * 2^32) = 1995919024. Measured max error: 0.50 LSB for
 * |mdeg| <= 360000, 0.66 LSB over all int32 (bound 0.75). */
static inline xgo_bam_t xgo_mdeg_to_bam(int32_t mdeg)
{
    const uint32_t whole = (uint32_t)mdeg * 11930u; /* modulo 2^32 */
    int64_t frac;
#if XGO_CORE_NARROW_CPU
    /* Below 65.5 degrees (the body's angles, most joints') the multiplier
     * in 16-bit halves, 30455 2^16 + 20144: two MULS within int32 and the
     * floors nested exactly, floor((A 2^16 + B + 2^31) / 2^32) =
     * floor((A + 2^15 + floor(B / 2^16)) / 2^16), instead of a wide product
     * (M0: four MULS and carries). The same value. */
    if ((uint32_t)mdeg + 65535u < 131071u) {
        return whole + (uint32_t)((mdeg * 30455 + 32768 + ((mdeg * 20144) >> 16)) >> 16);
    }
#endif
    /* |product| < 2^62; the multiplier's rounding adds at most 0.25 LSB */
    frac = (xgo_mul_wide(mdeg, 1995919024) + ((int64_t)1 << 31)) >> 32;
    return whole + (uint32_t)(uint64_t)frac;
}

/* binary angle -> mdeg in [-180000, 180000] (angles past half a turn are
 * negative), rounded to nearest. Max error 0.5 mdeg (exact rounding). */
XGO_ALWAYS_INLINE int32_t xgo_bam_to_mdeg(xgo_bam_t a)
{
#if XGO_CORE_NARROW_CPU
    /* The same rounded product in 32-bit pieces (a Cortex-M0 has no
     * widening multiply): 360000 = 5625 * 2^6 and a = ah 2^16 + al, so
     * (a * 360000 + 2^31) / 2^32 = (ah 5625 + (al 5625 + 2^25) / 2^16) / 2^10,
     * each division a floor (exact: the nested floors of a floor). */
    const int32_t s = xgo_bam_signed(a);
    const int32_t ah = s >> 16, al = s & 0xFFFF;
    return (ah * 5625 + ((al * 5625 + (1 << 25)) >> 16)) >> 10;
#else
    const int64_t p = xgo_mul_wide(xgo_bam_signed(a), XGO_MDEG_PER_TURN); /* |p| < 2^50 */
    return (int32_t)((p + ((int64_t)1 << 31)) >> 32);
#endif
}

/* An angle in mdeg wrapped into [-180000, 180000); any int32 input. Angles
 * within a few turns (the usual case) cost two compares, no division. */
int32_t xgo_wrap_mdeg(int32_t mdeg);

/* ------------------------------------------------------------ trigonometry */

/* sin and cos of a binary angle, Q30, clamped to [-1, 1]. Exact at 0, 90,
 * 180, 270 degrees. Measured max error over all angles: 2.82 LSB of Q30
 * (2.6e-9); asserted bound 3.5 LSB. */
void xgo_sincos(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out);
/* The same values for an angle near 0 (a tick's turn): from -2^22 up to
 * 2^22 BAM (0.35 degrees) without the table's products (M0: about half
 * the instructions); other angles go to xgo_sincos. Both outputs needed. */
void xgo_sincos_near0(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out);
xgo_q30_t xgo_sin(xgo_bam_t a);
xgo_q30_t xgo_cos(xgo_bam_t a);

/* Angle of the vector (x, y), any int32 pair (x, y are in the same unit).
 * Returns a binary angle; read it with xgo_bam_signed / xgo_bam_to_mdeg
 * (-180 degrees for y == 0, x < 0). atan2(0, 0) == 0; exact on the axes and
 * diagonals. Measured max error over all inputs: 45.3 LSB of BAM (6.6e-8
 * rad, 3.8e-6 degree) relative to the exact angle of the integer pair (the
 * larger component keeps 25 bits); asserted bound 64 LSB. */
xgo_bam_t xgo_atan2(int32_t y, int32_t x);

/* The same for a vector whose length is within [2^29, 2^30] (|x|, |y| <=
 * 2^30): no normalisation, the components cut by 2^5 (truncated: 23.5 bits
 * of the ratio kept). The leg IK's knee angle: sin and cos scaled to 30 bits.
 * Measured max error over that domain: see docs/fixed-point.md. */
xgo_bam_t xgo_atan2_len30(int32_t y, int32_t x);

/* Same for 64-bit components (both are scaled down together first, so the
 * angle keeps 25 bits of relative precision). Measured max error 25.8 LSB of
 * BAM; asserted bound 64 LSB. */
xgo_bam_t xgo_atan2_64(int64_t y, int64_t x);

/* asin / acos of a Q30 value; arguments outside [-1, 1] are clamped.
 * asin returns [-90, 90] degrees (as a signed binary angle), acos [0, 180];
 * exact at -1, 0, 1. Measured max error: 39.4 LSB of BAM (5.8e-8 rad)
 * relative to libm on the same Q30 input; asserted bound 64 LSB. */
xgo_bam_t xgo_asin(xgo_q30_t x);
xgo_bam_t xgo_acos(xgo_q30_t x);

#ifdef __cplusplus
}
#endif

#endif /* XGO_FIXED_H */
