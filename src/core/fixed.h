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

/* sin and cos of a binary angle, Q30, within [-1, 1]. Exact at 0, 90,
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

/* ------------------------------------------------------------ bodies
 *
 * The bodies of xgo_sqrt64_near, xgo_sincos, xgo_atan2_len30 and
 * xgo_atan2_64 with what they use (tables, the octant's arctangent), for
 * fixed.c and, on a 64-bit host, for the kinematics as well
 * (kinematics.c), which inlines them: the leg IK's 20 calls a control
 * tick, where the calls, their argument moves and the registers saved
 * around them were about a sixth of the work, and the body pose's sine. A file gets
 * them by defining XGO_FIXED_BODIES before it includes this header (or
 * includes it again: this part has its own guard). With XGO_FIXED_INLINE
 * defined as well (the leg IK) the helpers are forced inline and
 * xgo_atan2_64_inline leaves its rare narrow case (both components below
 * 2^32) to the out-of-line function; without it (fixed.c) they are
 * static, as they were in fixed.c (the compiler decides: the out-of-line
 * functions' code is unchanged).
 */
#if defined(XGO_FIXED_BODIES) && !defined(XGO_FIXED_BODIES_INCLUDED)
#define XGO_FIXED_BODIES_INCLUDED

#ifdef XGO_FIXED_INLINE
#define XGO_FIXED_HOT XGO_ALWAYS_INLINE
#else
#define XGO_FIXED_HOT static
#endif

/* ---- square root */

/* round(sqrt((32 + i) * 2^25)) - 2^15, i = 0..96: the square root of a
 * normalised 32-bit value m in [2^30, 2^32) at 96 equal steps of m (the
 * chord between two entries is within 2 of floor(sqrt(m))). */
static const uint16_t sqrt_tab[97] = {
    0, 508, 1008, 1502, 1988, 2467, 2940, 3407, 3868, 4323, 4772, 5217, 5656, 6090, 6519, 6944,
    7364, 7780, 8192, 8600, 9003, 9403, 9799, 10191, 10580, 10965, 11347, 11726, 12101, 12474,
    12843, 13209, 13573, 13934, 14291, 14647, 14999, 15349, 15697, 16041, 16384, 16724, 17062,
    17398, 17731, 18062, 18391, 18718, 19043, 19366, 19686, 20005, 20322, 20637, 20951, 21262,
    21572, 21879, 22186, 22490, 22793, 23094, 23394, 23691, 23988, 24283, 24576, 24868, 25158,
    25447, 25735, 26021, 26305, 26589, 26871, 27151, 27431, 27709, 27985, 28261, 28535, 28808,
    29080, 29351, 29620, 29889, 30156, 30422, 30687, 30951, 31214, 31475, 31736, 31995, 32254,
    32511, 32768,
};

/* The table's chord for m in [2^30, 2^32): within 2 of floor(sqrt(m))
 * (isqrt_norm32 without its exact steps). Never above 65535, so no clamp:
 * i <= 95 and f < 2^16 give y < 32768 + sqrt_tab[i + 1] <= 65536. */
XGO_FIXED_HOT uint32_t sqrt_chord32(uint32_t m)
{
    const uint32_t i = (m >> 25) - 32u, f = (m >> 9) & 0xFFFFu;
    const uint32_t a = sqrt_tab[i], b = sqrt_tab[i + 1u];
    return 32768u + a + (((b - a) * f) >> 16); /* (b - a) < 2^9 */
}

#if XGO_CORE_NARROW_CPU
/* round(2^30 / sqrt((32 + i) * 2^25)), i = 0..96: the reciprocal of
 * sqrt_tab's roots at the same nodes (16384..32768). */
static const uint16_t rsqrt_tab[97] = {
    32768, 32268, 31790, 31332, 30894, 30474, 30070, 29682, 29309, 28949, 28602, 28268, 27945,
    27632, 27330, 27038, 26755, 26481, 26214, 25956, 25705, 25462, 25225, 24994, 24770, 24552,
    24339, 24132, 23930, 23733, 23541, 23354, 23170, 22992, 22817, 22646, 22479, 22315, 22155,
    21999, 21845, 21695, 21548, 21404, 21263, 21124, 20988, 20855, 20724, 20596, 20470, 20346,
    20225, 20106, 19988, 19873, 19760, 19649, 19539, 19431, 19326, 19221, 19119, 19018, 18919,
    18821, 18725, 18630, 18536, 18444, 18354, 18264, 18176, 18090, 18004, 17920, 17837, 17755,
    17674, 17594, 17515, 17438, 17361, 17285, 17211, 17137, 17064, 16992, 16921, 16851, 16782,
    16714, 16646, 16579, 16514, 16448, 16384,
};
#endif

/* floor(n / y) for the Newton step of xgo_sqrt64_near: y within a few units
 * of sqrt(m) for m in [2^30, 2^32), the quotient below 2^16. One
 * instruction with a divider; without one (Cortex-M0: libgcc's division is
 * about 100 instructions) an estimate with the reciprocal of sqrt(m) from a
 * table and its chord (within about 10 of the quotient), made exact by
 * stepping on the remainder, which fits int32 (|error| * y < 2^20). The
 * same value either way. */
XGO_FIXED_HOT uint32_t newton_quotient(uint32_t n, uint32_t y, uint32_t m)
{
#if XGO_CORE_NARROW_CPU
    const uint32_t i = (m >> 25) - 32u, f = (m >> 9) & 0xFFFFu;
    const uint32_t a = rsqrt_tab[i], b = rsqrt_tab[i + 1u];
    const uint32_t r = a - (((a - b) * f) >> 16);  /* ~ 2^30 / y, <= 2^15 */
    uint32_t q = ((n >> 16) * r) >> 14;            /* < 2^31 before the shift */
    int32_t rem = (int32_t)(n - q * y);            /* modulo 2^32: small, exact */
    while (rem < 0) {
        --q;
        rem += (int32_t)y;
    }
    while (rem >= (int32_t)y) {
        ++q;
        rem -= (int32_t)y;
    }
    return q;
#else
    (void)m;
    return n / y;
#endif
}

/* xgo_sqrt64_near */
XGO_ALWAYS_INLINE uint32_t xgo_sqrt64_near_inline(uint64_t x)
{
    uint32_t hi = (uint32_t)(x >> 32), lo, y0, rem, y;
    unsigned s;
    if (hi == 0u) {
        return xgo_isqrt32((uint32_t)x);
    }
    s = xgo_clz32_even(hi);
    x = xgo_shl64(x, s); /* [2^62, 2^64) */
    hi = (uint32_t)(x >> 32);
    lo = (uint32_t)x;
    y0 = sqrt_chord32(hi);
    if (y0 * y0 > hi) { /* at most one above the floor: the remainder >= 0 */
        --y0;
    }
    rem = hi - y0 * y0; /* < 6 y0 < 2^19 (y0 down to 2 below the floor) */
    /* the Newton step in units of 4 so the dividend fits 32 bits */
    y = (y0 << 16) + (newton_quotient((rem << 13) + (lo >> 19), y0, hi) << 2);
    return (y < (y0 << 16) ? 0xFFFFFFFFu : y) >> (s / 2u);
}

/* ---- sin / cos */

/* sin(k * pi / 256) in Q30, k = 0..128: a quarter wave at 128 intervals. */
static const int32_t sin_tab[129] = {
    0, 13176464, 26350943, 39521455, 52686014, 65842639,
    78989349, 92124163, 105245103, 118350194, 131437462, 144504935,
    157550647, 170572633, 183568930, 196537583, 209476638, 222384147,
    235258165, 248096755, 260897982, 273659918, 286380643, 299058239,
    311690799, 324276419, 336813204, 349299266, 361732726, 374111709,
    386434353, 398698801, 410903207, 423045732, 435124548, 447137835,
    459083786, 470960600, 482766489, 494499676, 506158392, 517740883,
    529245404, 540670223, 552013618, 563273883, 574449320, 585538248,
    596538995, 607449906, 618269338, 628995660, 639627258, 650162530,
    660599890, 670937767, 681174602, 691308855, 701339000, 711263525,
    721080937, 730789757, 740388522, 749875788, 759250125, 768510122,
    777654384, 786681534, 795590213, 804379079, 813046808, 821592095,
    830013654, 838310216, 846480531, 854523370, 862437520, 870221790,
    877875009, 885396022, 892783698, 900036924, 907154608, 914135678,
    920979082, 927683790, 934248793, 940673101, 946955747, 953095785,
    959092290, 964944360, 970651112, 976211688, 981625251, 986890984,
    992008094, 996975812, 1001793390, 1006460100, 1010975242, 1015338134,
    1019548121, 1023604567, 1027506862, 1031254418, 1034846671, 1038283080,
    1041563127, 1044686319, 1047652185, 1050460278, 1053110176, 1055601479,
    1057933813, 1060106826, 1062120190, 1063973603, 1065666786, 1067199483,
    1068571464, 1069782521, 1070832474, 1071721163, 1072448455, 1073014240,
    1073418433, 1073660973, 1073741824,
};

/* 8 pi - 25 in Q19, rounded: with 25 it turns a BAM offset into radians in
 * Q34 (d * 2 pi / 2^32 * 2^34 = d * 8 pi). */
#define EIGHT_PI_FRAC_Q19 69595

/* round(v / 3) for 0 <= v < 2^15 - 1: a multiply by ceil(2^16 / 3) = 21846
 * and a shift is exact there, and needs no division (Cortex-M0). */
XGO_FIXED_HOT int32_t div3_small(int32_t v)
{
    return (int32_t)(((uint32_t)v + 1u) * 21846u >> 16);
}

/* round(t * v / 2^34), ties up, for a table value 0 <= t <= 2^30 and
 * |v| < 2^27 (sincos's sin d: below 2^26.7). On a Cortex-M0 from 15- and
 * 14-bit pieces, t = th 2^15 + tl and v = vh 2^14 + vl (0 <= tl, vl):
 * t v = A 2^29 + B 2^14 + C with A = th vh (|A| <= 2^28), B = 2 th vl +
 * tl vh (below 2^30 + 2^28) and C = tl vl (< 2^29), each one MULS in 32
 * bits, the floors nested exactly (A split at bit 5 so nothing overflows):
 * 4 multiplies and no carries instead of a wide product. Elsewhere one
 * multiply. The same value (checked equal on 2 * 10^9 random pairs and
 * every v within +-300,000 for t = m 2^j: the ties; a throwaway harness). */
XGO_ALWAYS_INLINE int32_t mul_q34_round(int32_t t, int32_t v)
{
#if XGO_CORE_NARROW_CPU
    const int32_t th = t >> 15, tl = t & 0x7FFF, vh = v >> 14, vl = v & 0x3FFF;
    const int32_t a = th * vh;
    const int32_t d = 2 * th * vl + tl * vh + (1 << 19) + ((tl * vl) >> 14); /* B + 2^19 + floor(C / 2^14) */
    return (a >> 5) + ((((a & 31) << 15) + d) >> 20);
#else
    return (int32_t)((xgo_mul_wide(t, v) + ((int64_t)1 << 33)) >> 34);
#endif
}

/* The offset d from a table node (|d| <= 2^22 BAM) as sin d in Q34 (d in
 * radians less d^3/6) and 1 - cos d = d^2/2 in Q30: xgo_sincos's small
 * terms, shared with xgo_sincos_near0. */
XGO_ALWAYS_INLINE void offset_terms(int32_t d, int32_t *sd_out, int32_t *half_d2_out)
{
    /* d in radians, Q34: 25 d + d (8 pi - 25), the fraction in two 16-bit
     * pieces of d (d = 256 dh + dl); |dr| <= pi/512 * 2^34 < 2^26.7 */
    const int32_t dh = d >> 8, dl = d & 0xFF;
    const int32_t dr = 25 * d + ((dh * EIGHT_PI_FRAC_Q19 + (1 << 10)) >> 11) +
                       ((dl * EIGHT_PI_FRAC_Q19) >> 19);
    /* d^2/2 in Q30 (<= 2^14.3) from |dr| in Q23 (< 2^15.7: the square fits 32 bits unsigned) */
    const uint32_t u = ((uint32_t)(dr < 0 ? -dr : dr) + (1u << 10)) >> 11;
    const int32_t half_d2 = (int32_t)((u * u + (1u << 16)) >> 17);
    /* d^3/6 = d * (d^2/2) / 3 in Q34: (dr in Q22) * half_d2 -> Q52 */
    const int32_t d3_2 = ((dr >> 12) * half_d2 + (1 << 17)) >> 18;
    *sd_out = dr - (d3_2 < 0 ? -div3_small(-d3_2) : div3_small(d3_2)); /* Q34 */
    *half_d2_out = half_d2;
}

/* xgo_sincos: the nearest table node and the angle-addition formulas:
 *   sin(a + d) = s0 cos d + c0 sin d,  cos(a + d) = c0 cos d - s0 sin d,
 * sin d = d - d^3/6 (next term < 1e-13), 1 - cos d = d^2/2 (next term
 * 6e-11). Only the two products with sin d need 32 x 32 -> 64 bits; the
 * small terms are 16 x 16-bit products (one MULS each on a Cortex-M0). */
XGO_ALWAYS_INLINE void xgo_sincos_inline(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out)
{
    const uint32_t quadrant = a >> 30;
    const uint32_t r = a & 0x3FFFFFFFu;        /* position in the quadrant */
    const uint32_t k = (r + (1u << 22)) >> 23; /* nearest table node, 0..128 */
    const int32_t d = (int32_t)r - (int32_t)(k << 23); /* |d| <= 2^22 BAM */
    int32_t sd, half_d2, s0, c0;
    offset_terms(d, &sd, &half_d2);
    s0 = sin_tab[k];
    c0 = sin_tab[128u - k];
    /* 1 - cos d terms: Q16 table value times half_d2, Q46 -> Q30 */
    const int32_t s_h = (int32_t)(((uint32_t)s0 >> 14) * (uint32_t)half_d2 >> 16);
    const int32_t c_h = (int32_t)(((uint32_t)c0 >> 14) * (uint32_t)half_d2 >> 16);
    /* sin d terms: Q30 * Q34 = Q64 -> Q30 */
    const int32_t c_s = mul_q34_round(c0, sd);
    const int32_t s_s = mul_q34_round(s0, sd);
    /* within [0, 1] without a clamp: checked for every position r in the
     * quadrant, both forms of mul_q34_round (a throwaway harness) */
    const int32_t s = s0 + c_s - s_h;
    const int32_t c = c0 - s_s - c_h;
    int32_t so, co;
    switch (quadrant) {
    case 0u:
        so = s;
        co = c;
        break;
    case 1u: /* sin(90 + x) = cos x, cos(90 + x) = -sin x */
        so = c;
        co = -s;
        break;
    case 2u:
        so = -s;
        co = -c;
        break;
    default:
        so = -c;
        co = s;
        break;
    }
    if (sin_out != 0) {
        *sin_out = so;
    }
    if (cos_out != 0) {
        *cos_out = co;
    }
}

/* ---- atan2 */

/* atan(i / 32) in BAM, i = 0..32 (0 .. 45 degrees). */
static const uint32_t atan_tab[33] = {
    0, 21354465, 42667331, 63897482, 85004756, 105950391, 126697423, 147211045, 167458907,
    187411349, 207041579, 226325781, 245243172, 263775993, 281909457, 299631651, 316933406,
    333808132, 350251643, 366261957, 381839095, 396984877, 411702716, 425997422, 439875013,
    453342536, 466407904, 479079736, 491367227, 503280012, 514828063, 526021581, 536870912,
};

/* 4 / pi - 1 in Q16 (17906.99): radians -> BAM is * 2^32 / (2 pi), for a
 * value in Q29 that is * 4 / pi. */
#define FOUR_PI_FRAC_Q16 17907

#if XGO_CORE_NARROW_CPU
/* round(2^39 / ((k + 16.5) * 2^19)), k = 0..48: 32 / ux at the middle of
 * each 2^19-wide step of ux in [2^23, 2^25], scaled by 2^24. */
static const uint16_t node_recip[49] = {
    63550, 59919, 56680, 53773, 51150, 48771, 46603, 44620, 42799, 41121, 39569, 38130, 36792,
    35545, 34380, 33288, 32264, 31301, 30394, 29537, 28728, 27962, 27236, 26546, 25891, 25267,
    24672, 24105, 23564, 23046, 22550, 22075, 21620, 21183, 20764, 20361, 19973, 19600, 19240,
    18893, 18559, 18236, 17924, 17623, 17332, 17050, 16777, 16513, 16257,
};
#endif

/* floor((32 uy + floor(ux / 2)) / ux), the nearest node index, for ux in
 * [2^23, 2^25] and uy <= ux (any node near the ratio would do; the nearest
 * keeps the residual within 1/64). Without a divider: an estimate by a
 * multiply with the reciprocal of ux's 2^19-wide step (off the ratio by
 * less than 1/33 of it: within one of the quotient), made exact by a
 * compare each way. */
XGO_FIXED_HOT uint32_t nearest_node(uint32_t uy, uint32_t ux)
{
    const uint32_t n = (uy << 5) + (ux >> 1); /* < 2^31 */
#if XGO_CORE_NARROW_CPU
    uint32_t i = ((uy >> 10) * node_recip[(ux >> 19) - 16u] + (1u << 23)) >> 24;
    const int32_t r = (int32_t)n - (int32_t)(i * ux); /* in [-ux, 2 ux) */
    if (r < 0) {
        --i;
    } else if ((uint32_t)r >= ux) {
        ++i;
    }
    return i;
#else
    return n / ux;
#endif
}

#if !XGO_CORE_DIV64_NATIVE && !XGO_CORE_NARROW_CPU
/* floor(n * 2^32 / d) for n < d < 2^31, and its remainder, on a core that
 * divides 32-bit numbers in hardware but not 64-bit ones (Cortex-M3/M4):
 * long division in two 16-bit digits (Hacker's Delight's divlu, with a zero
 * low word), two hardware divisions instead of a libgcc call. */
static uint32_t div_shifted(uint32_t n, uint32_t d, uint32_t *rem)
{
    const unsigned s = xgo_clz32(d); /* >= 1: normalise the divisor */
    const uint32_t v = d << s, vn1 = v >> 16, vn0 = v & 0xFFFFu;
    const uint32_t u1 = n << s; /* < v */
    uint32_t q1 = u1 / vn1, rhat = u1 - q1 * vn1;
    uint32_t un21, q0;
    /* each digit estimate is at most 2 too large: correct it */
    while (q1 > 0xFFFFu || q1 * vn0 > (rhat << 16)) {
        --q1;
        rhat += vn1;
        if (rhat > 0xFFFFu) {
            break;
        }
    }
    un21 = (u1 << 16) - q1 * v; /* modulo 2^32: the true value is < v */
    q0 = un21 / vn1;
    rhat = un21 - q0 * vn1;
    while (q0 > 0xFFFFu || q0 * vn0 > (rhat << 16)) {
        --q0;
        rhat += vn1;
        if (rhat > 0xFFFFu) {
            break;
        }
    }
    *rem = ((un21 << 16) - q0 * v) >> s;
    return (q1 << 16) | q0;
}
#endif

#if XGO_CORE_NARROW_CPU
/* round(2^22 / (128 + k)), k = 0..129: 2^45 / x at the 128 equal steps of
 * x in [2^30, 2^31] (the chord between two entries is at most half a unit
 * above the curve). The entry past 2^31 is read only at x = 2^31 itself (a
 * diagonal, where the residual is 0), with weight 0, but it must exist. */
static const uint16_t recip_tab[130] = {
    32768, 32514, 32264, 32018, 31775, 31536, 31301, 31069, 30840, 30615, 30394, 30175, 29959,
    29747, 29537, 29331, 29127, 28926, 28728, 28533, 28340, 28150, 27962, 27777, 27594, 27414,
    27236, 27060, 26887, 26715, 26546, 26379, 26214, 26052, 25891, 25732, 25575, 25420, 25267,
    25116, 24966, 24818, 24672, 24528, 24385, 24245, 24105, 23967, 23831, 23697, 23564, 23432,
    23302, 23173, 23046, 22920, 22795, 22672, 22550, 22429, 22310, 22192, 22075, 21960, 21845,
    21732, 21620, 21509, 21400, 21291, 21183, 21077, 20972, 20867, 20764, 20662, 20560, 20460,
    20361, 20262, 20165, 20068, 19973, 19878, 19784, 19692, 19600, 19508, 19418, 19329, 19240,
    19152, 19065, 18979, 18893, 18809, 18725, 18641, 18559, 18477, 18396, 18316, 18236, 18157,
    18079, 18001, 17924, 17848, 17772, 17697, 17623, 17549, 17476, 17404, 17332, 17261, 17190,
    17120, 17050, 16981, 16913, 16845, 16777, 16710, 16644, 16578, 16513, 16448, 16384, 16320,
};

#endif

/* floor(m * 2^29 / e) for m * 2^6 <= e <= 2^31 (2^31 only on a diagonal,
 * with m = 0): the residual ratio, at most
 * 2^23. Exact on every target (same result): one instruction on a 64-bit
 * host, two 16-bit digit steps with a 32-bit divider, two table-reciprocal
 * steps without one. */
XGO_FIXED_HOT uint32_t residual_q29(uint32_t m, uint32_t e)
{
#if XGO_CORE_DIV64_NATIVE
    return (uint32_t)(((uint64_t)m << 29) / e);
#elif XGO_CORE_NARROW_CPU
    /* Two 12-bit digits from the reciprocal rc ~ 2^45 / (e 2^s) of the
     * table's chord (never above it, less than 3.5 below, >= 2^14):
     * - the top, qt = floor(m 2^17 / e): the estimate ((m >> 8) rc) >> (20
     *   - s) is qt or qt - 1, its remainder (in [0, 2e): exact modulo
     *   2^32) decides;
     * - the low, floor(r 2^12 / e) for that remainder r < e: the estimate
     *   (((r 2^s) >> 15) rc) >> 18 (a product below 2^31) falls short of
     *   r 2^12 / e by less than 0.875 (rc's error times a quotient below
     *   2^12) + 0.125 (the truncated r, 2^27 / (e 2^s)) = 1, so it is the
     *   digit or one less, and again the remainder (in [0, 2e)) decides.
     * It replaced 12 restoring steps (M0: about 70 instructions). Checked
     * equal to the 64-bit division on 2 * 10^8 random pairs, 7.7 * 10^7
     * pairs around every table node at the three shifts and 1.5 * 10^9
     * pairs with e over its whole range (a throwaway harness). */
    uint32_t big = e, q, r, rc, lo;
    unsigned s = 0;
    while (big < 0x40000000u) { /* e >= 2^28: at most twice */
        big <<= 1;
        ++s;
    }
    {
        const uint32_t k = (big >> 23) - 128u, f = (big >> 7) & 0xFFFFu;
        const uint32_t a = recip_tab[k], b = recip_tab[k + 1u];
        rc = a - (((a - b) * f) >> 16) - 2u; /* <= 2^45 / big, within 3.5 */
    }
    q = ((m >> 8) * rc) >> (20u - s); /* m >> 8 < 2^17, rc <= 2^15 */
    r = (m << 17) - q * e;            /* modulo 2^32; the true value is in [0, 2e) */
    if (r >= e) {
        r -= e;
        ++q;
    }
    lo = (((r << s) >> 15) * rc) >> 18; /* r 2^s < 2^31 */
    if ((r << 12) - lo * e >= e) {      /* the remainder, modulo 2^32 as above */
        ++lo;
    }
    return (q << 12) | lo;
#else
    uint32_t rem;
    return div_shifted(m, e, &rem) >> 3;
#endif
}

/* Angle of (ux, uy), ux >= uy > 0, ux in [2^23, 2^25] (callers: at least
 * 2^23.5): BAM 0..2^29. The
 * vector is turned back by the nearest table angle atan(i/32) exactly in
 * integers (multiplied by (32 - i j): x' = 32 x + i y, y' = 32 y - i x),
 * which leaves a residual e = y'/x' within +-1/64; atan e = e - e^3/3 (the
 * next term is below 2e-10 rad). */
XGO_FIXED_HOT uint32_t atan_octant(uint32_t ux, uint32_t uy)
{
    const uint32_t i = nearest_node(uy, ux);
    const int32_t ey = (int32_t)(uy << 5) - (int32_t)(i * ux); /* |ey| <= ux / 2 */
    const uint32_t ex = (ux << 5) + i * uy;                       /* [2^29, 2^31] */
    const uint32_t m = ey < 0 ? (uint32_t)-ey : (uint32_t)ey;
    uint32_t q = residual_q29(m, ex); /* e in Q29, < 2^23 (0 on the axes and diagonals) */
    uint32_t u, w, c, ah, al, b;
    /* e^3/3 in Q29 from 15-bit pieces (u = e in Q21) */
    u = q >> 8;
    w = (u * u) >> 15;               /* e^2 in Q27 */
    c = (w * u) >> 19;               /* e^3 in Q29, < 2^11 */
    q -= ((c + 1u) * 21846u) >> 16;  /* (c + 1) / 3: rounded third */
    /* radians Q29 -> BAM: q * 4/pi = q + q * (4/pi - 1), the product in
     * two 16-bit pieces of q */
    ah = q >> 8;
    al = q & 0xFFu;
    b = q + ((ah * FOUR_PI_FRAC_Q16 + (1u << 7)) >> 8) + ((al * FOUR_PI_FRAC_Q16) >> 16);
    return ey < 0 ? atan_tab[i] - b : atan_tab[i] + b;
}

/* From the octant's angle a of (big, small) back to the angle of (x, y):
 * swap said small was the x component. */
XGO_FIXED_HOT xgo_bam_t fold(uint32_t a, int swap, int xneg, int yneg)
{
    if (swap) {
        a = XGO_BAM_90 - a;
    }
    if (xneg) {
        a = XGO_BAM_180 - a;
    }
    return yneg ? 0u - a : a;
}

#ifndef XGO_FIXED_INLINE /* fixed.c's own */
/* The angle of (ux, uy) with the signs given apart: the octant (swap so the
 * smaller is uy), atan_octant with the larger component scaled to [2^24,
 * 2^25] (exact when scaled up, rounded once when scaled down: 25 bits of
 * the ratio kept; the larger may round up to 2^25 itself, still in range),
 * folded back. Axes and diagonals come out exact by themselves (the
 * residual is 0 there); atan2(0, 0) = 0. */
static xgo_bam_t atan2_u32(uint32_t ux, uint32_t uy, int xneg, int yneg)
{
    const int swap = uy > ux;
    uint32_t big = swap ? uy : ux, small = swap ? ux : uy;
    const unsigned n = xgo_clz32(big);
    if (n >= 7u) {
        if (big == 0u) {
            return 0u;
        }
        big <<= n - 7u;
        small <<= n - 7u;
    } else { /* round(v / 2^k) as (v / 2 + 2^(k-2)) / 2^(k-1) for k >= 2: no overflow */
        const unsigned k = 7u - n;
        const uint32_t half = (1u << (k - 1u)) >> 1;
        big = ((big >> 1) + half + (k == 1u ? (big & 1u) : 0u)) >> (k - 1u);
        small = ((small >> 1) + half + (k == 1u ? (small & 1u) : 0u)) >> (k - 1u);
    }
    return fold(atan_octant(big, small), swap, xneg, yneg);
}
#endif

XGO_FIXED_HOT uint32_t abs_u32(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/* xgo_atan2_len30 */
XGO_ALWAYS_INLINE xgo_bam_t xgo_atan2_len30_inline(int32_t y, int32_t x)
{
    const uint32_t ux = abs_u32(x), uy = abs_u32(y);
    const int swap = uy > ux;
    /* the larger is in [2^28.5, 2^30]: 2^5 down lands in [2^23.5, 2^25] */
    return fold(atan_octant((swap ? uy : ux) >> 5, (swap ? ux : uy) >> 5), swap, x < 0, y < 0);
}

XGO_FIXED_HOT uint64_t abs_u64(int64_t v)
{
    return v < 0 ? 0u - (uint64_t)v : (uint64_t)v;
}

/* xgo_atan2_64 */
XGO_ALWAYS_INLINE xgo_bam_t xgo_atan2_64_inline(int64_t y, int64_t x)
{
    /* the signs kept apart and the pair ordered in place (fewer live
     * 64-bit values: the M0 spilled them) */
    const int xneg = x < 0, yneg = y < 0;
    uint64_t big = abs_u64(x), small = abs_u64(y); /* <= 2^63 */
    int swap = 0;
    uint32_t hi;
    unsigned k;
    if (small > big) {
        const uint64_t t = big;
        big = small;
        small = t;
        swap = 1;
    }
    hi = (uint32_t)(big >> 32); /* the larger has the bit length of both */
    if (hi == 0u) {
#ifdef XGO_FIXED_INLINE /* rare there: the out-of-line function's registers and code */
        return xgo_atan2_64(y, x);
#else
        return swap ? atan2_u32((uint32_t)small, (uint32_t)big, xneg, yneg)
                    : atan2_u32((uint32_t)big, (uint32_t)small, xneg, yneg);
#endif
    }
    /* round(v / 2^k) to 25 bits (the larger may round up to 2^25): k is
     * the bit length, 64 - clz(hi), less 25 */
    k = 39u - xgo_clz32_nz(hi);
#if XGO_CORE_DIV64_NATIVE
    return fold(atan_octant(xgo_round_shr64(big, k), xgo_round_shr64(small, k)), swap, xneg, yneg);
#else
    {
        /* On a 32-bit core the top words, shifted left by clz(hi) = 39 - k
         * so the larger's is in [2^31, 2^32): each is floor(v / 2^(k - 7)),
         * whose bits 7 up are floor(v / 2^k) and bit 6 is v's bit k - 1,
         * the rounding's. Two 32-bit shifts a value instead of a 64-bit
         * shift by a variable k either side of 32 (xgo_round_shr64). */
        const unsigned n = 39u - k;
        uint32_t bt = hi, st = (uint32_t)(small >> 32);
        if (n != 0u) {
            bt = (bt << n) | ((uint32_t)big >> (32u - n));
            st = (st << n) | ((uint32_t)small >> (32u - n));
        }
        return fold(atan_octant((bt >> 7) + ((bt >> 6) & 1u), (st >> 7) + ((st >> 6) & 1u)), swap, xneg, yneg);
    }
#endif
}

#endif /* XGO_FIXED_BODIES */
