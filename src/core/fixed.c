/*
 * fixed.c - integer-only math (see fixed.h and docs/fixed-point.md).
 *
 * No floating point anywhere: the tables below were generated offline (the
 * generator is in docs/fixed-point.md) and are checked against libm by
 * test/test_fixed.c through the functions that use them.
 */
#define XGO_FIXED_BODIES /* fixed.h's bodies part: the atan2 and sqrt64_near machinery */
#include "fixed.h"

#include "wide.h"

/* The shifts below rely on >> of a negative value being arithmetic (GCC and
 * Clang guarantee it). Refuse to compile where it is not. */
typedef char xgo_fixed_asr_check_[((-1 >> 1) == -1 && ((int64_t)-1 >> 1) == -1) ? 1 : -1];

/* ------------------------------------------------------------ saturation */

int32_t xgo_sat32(int64_t v)
{
    if (v > INT32_MAX) {
        return INT32_MAX;
    }
    if (v < INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)v;
}

int32_t xgo_sat_add(int32_t a, int32_t b)
{
    return xgo_sat32((int64_t)a + b);
}

int32_t xgo_sat_sub(int32_t a, int32_t b)
{
    return xgo_sat32((int64_t)a - b);
}

int32_t xgo_sat_neg(int32_t a)
{
    return a == INT32_MIN ? INT32_MAX : -a;
}

int32_t xgo_sat_abs(int32_t a)
{
    return a < 0 ? xgo_sat_neg(a) : a;
}

int32_t xgo_mul_q(int32_t a, int32_t b, unsigned q)
{
    int64_t p = xgo_mul_wide(a, b); /* |p| <= 2^62: exact */
    if (q > 31u) {
        q = 31u;
    }
    if (q > 0u) {
        /* p + 2^(q-1) cannot overflow: |p| <= 2^62, the half is <= 2^30. */
        p = (p + ((int64_t)1 << (q - 1u))) >> q;
    }
    return xgo_sat32(p);
}

/* Rounded quotient n / d for d > 0, ties away from zero; |n| < 2^63. */
static int64_t div_round_pos(int64_t n, int64_t d)
{
    if (n >= 0) {
        return (n + d / 2) / d;
    }
    return -((-n + d / 2) / d);
}

static int32_t sat_div(int64_t n, int64_t d)
{
    if (d == 0) {
        return n > 0 ? INT32_MAX : (n < 0 ? INT32_MIN : 0);
    }
    if (d < 0) {
        n = -n;
        d = -d;
    }
    /* Saturate before dividing so the rounding add cannot overflow: the
     * quotient exceeds int32 whenever |n| >= 2^31 * d. */
    if (n >= 0 && (uint64_t)n / (uint64_t)d >= 0x80000000u) {
        return INT32_MAX;
    }
    if (n < 0 && (uint64_t)(-n) / (uint64_t)d > 0x80000000u) {
        return INT32_MIN;
    }
    return xgo_sat32(div_round_pos(n, d));
}

int32_t xgo_div_q(int32_t a, int32_t b, unsigned q)
{
    if (q > 31u) {
        q = 31u;
    }
    /* |a * 2^q| <= 2^62 */
    return sat_div((int64_t)a * ((int64_t)1 << q), b);
}

int32_t xgo_muldiv(int32_t a, int32_t b, int32_t c)
{
    return sat_div((int64_t)a * b, c);
}

/* Restoring division over the bits of cap: if the true quotient has more
 * bits than cap, every bit comes out set, which is above cap too. */
uint32_t xgo_udiv64_cap(uint64_t n, uint64_t d, uint32_t cap)
{
    unsigned bit = xgo_bit_length(cap);
    uint32_t q = 0;
    if (d == 0u) {
        return cap;
    }
#if XGO_CORE_DIV64_NATIVE
    if (d >> (63u - bit) == 0u) { /* one instruction on a 64-bit host */
        const uint64_t full = n / d;
        return full < cap ? (uint32_t)full : cap;
    }
#endif
    while (d >> (63u - bit) != 0u) { /* d << bit must fit: keep the top bits */
        d >>= 1;
        n >>= 1;
    }
    while (bit-- > 0u) {
        const uint64_t t = d << bit;
        if (n >= t) {
            n -= t;
            q |= 1u << bit;
        }
    }
    return q < cap ? q : cap;
}

/* ------------------------------------------------------------ square root */

/* sqrt_tab, its chord and xgo_sqrt64_near's body are in fixed.h's bodies
 * part. */

/* floor(sqrt(m)) for m in [2^30, 2^32): the table's chord, then exact by
 * stepping (at most 2 steps; y <= 65535 keeps every square in 32 bits). */
static uint32_t isqrt_norm32(uint32_t m)
{
    const uint32_t i = (m >> 25) - 32u, f = (m >> 9) & 0xFFFFu;
    const uint32_t a = sqrt_tab[i], b = sqrt_tab[i + 1u];
    uint32_t y = 32768u + a + (((b - a) * f) >> 16); /* (b - a) < 2^9 */
    if (y > 65535u) {
        y = 65535u;
    }
    while (y * y > m) {
        --y;
    }
    while (y < 65535u && (y + 1u) * (y + 1u) <= m) {
        ++y;
    }
    return y;
}

/* Normalise (an even shift, so the root shifts by half), table + chord,
 * exact by stepping: floor(floor(sqrt(x * 4^k)) / 2^k) = floor(sqrt(x)). */
uint32_t xgo_isqrt32(uint32_t x)
{
    unsigned s;
    if (x == 0u) {
        return 0u;
    }
    s = xgo_clz32(x) & ~1u;
    return isqrt_norm32(x << s) >> (s / 2u);
}

/* Above 2^32: normalise to [2^62, 2^64), the root of the high word (16
 * bits), one Newton step for the low 16 bits with a 32-bit division (the
 * remainder is below 2^49 and the divisor 2^17 times the root: both cut by
 * 2^17 so it fits), then exact by stepping (the step lands within 2). */
/* The root of m in [2^62, 2^64) before the exact fix: within 2 of it. */
static uint32_t isqrt_norm64_step(uint64_t m)
{
    const uint32_t hi = (uint32_t)(m >> 32), lo = (uint32_t)m;
    const uint32_t y0 = isqrt_norm32(hi); /* 2^15 <= y0 < 2^16 */
    const uint32_t rem = hi - y0 * y0;    /* <= 2 y0 < 2^17 */
    const uint32_t y = (y0 << 16) + ((rem << 15) + (lo >> 17)) / y0; /* (rem << 15) + .. < 2^32 */
    return y < (y0 << 16) ? 0xFFFFFFFFu : y; /* the step passed 2^32: the root is just below */
}

uint32_t xgo_isqrt64(uint64_t x)
{
    const uint32_t hi = (uint32_t)(x >> 32);
    unsigned s;
    uint64_t m;
    uint32_t y;
    if (hi == 0u) {
        return xgo_isqrt32((uint32_t)x);
    }
    s = xgo_clz32(hi) & ~1u;
    m = x << s;
    y = isqrt_norm64_step(m);
    while (xgo_umul_wide(y, y) > m) {
        --y;
    }
    while (y < 0xFFFFFFFFu && xgo_umul_wide(y + 1u, y + 1u) <= m) {
        ++y;
    }
    return y >> (s / 2u);
}

uint32_t xgo_sqrt64_near(uint64_t x)
{
    return xgo_sqrt64_near_inline(x);
}

xgo_q16_t xgo_q16_sqrt(xgo_q16_t x)
{
    uint64_t v;
    uint32_t r;
    if (x <= 0) {
        return 0;
    }
    v = (uint64_t)(uint32_t)x << 16; /* sqrt(x / 2^16) * 2^16 = sqrt(x * 2^16) */
    r = xgo_isqrt64(v);
    /* round: (r + 1/2)^2 = r^2 + r + 1/4, so round up iff v - r^2 > r */
    if (v - xgo_umul_wide(r, r) > r) {
        ++r;
    }
    return (xgo_q16_t)r; /* <= sqrt(2^47) < 2^24 */
}

/* ------------------------------------------------------------ angles */

int32_t xgo_wrap_mdeg(int32_t mdeg)
{
    int32_t v = mdeg;
    if (v < -900000 || v >= 900000) {
        v %= 360000; /* far away: one remainder (truncating) first */
    }
    while (v >= 180000) {
        v -= 360000;
    }
    while (v < -180000) {
        v += 360000;
    }
    return v;
}


/* ------------------------------------------------------------ sin / cos */

/* sin_tab, the offset's terms and xgo_sincos's body are in fixed.h's
 * bodies part. */

void xgo_sincos(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out)
{
    xgo_sincos_inline(a, sin_out, cos_out);
}

/* Near the node 0 (from -2^22 up to 2^22 BAM, signed: node 0 of the first
 * quadrant or node 128 of the fourth) the table's values are 0 and 1, so
 * xgo_sincos's products with them are shifts: sin a = round(sd / 16),
 * cos a = 1 - d^2/2 (no clamp, as there), the same values. */
void xgo_sincos_near0(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out)
{
    const int32_t d = xgo_bam_signed(a);
    int32_t sd, half_d2;
    if (d < -(1 << 22) || d >= (1 << 22)) {
        xgo_sincos(a, sin_out, cos_out);
        return;
    }
    offset_terms(d, &sd, &half_d2);
    *sin_out = (sd + 8) >> 4;
    *cos_out = XGO_Q30_ONE - half_d2;
}

xgo_q30_t xgo_sin(xgo_bam_t a)
{
    xgo_q30_t s;
    xgo_sincos(a, &s, 0);
    return s;
}

xgo_q30_t xgo_cos(xgo_bam_t a)
{
    xgo_q30_t c;
    xgo_sincos(a, 0, &c);
    return c;
}

/* ------------------------------------------------------------ atan2 */

/* The machinery (tables, the octant's arctangent, the wide form) is in
 * fixed.h's bodies part. */

xgo_bam_t xgo_atan2_len30(int32_t y, int32_t x)
{
    return xgo_atan2_len30_inline(y, x);
}

xgo_bam_t xgo_atan2(int32_t y, int32_t x)
{
    return atan2_u32(abs_u32(x), abs_u32(y), x < 0, y < 0);
}

xgo_bam_t xgo_atan2_64(int64_t y, int64_t x)
{
    return xgo_atan2_64_inline(y, x);
}

/* ------------------------------------------------------------ asin / acos */

static int32_t clamp_unit(int32_t v)
{
    if (v > XGO_Q30_ONE) {
        return XGO_Q30_ONE;
    }
    if (v < -XGO_Q30_ONE) {
        return -XGO_Q30_ONE;
    }
    return v;
}

/* sqrt(1 - x^2) in Q30 for x in [-1, 1] (Q30), from (1 - x)(1 + x) so there
 * is no cancellation near |x| = 1. */
static int32_t unit_complement(int32_t x)
{
    /* both factors are in [0, 2^31]: compute them in 64 bits */
    uint64_t p = xgo_umul_wide((uint32_t)XGO_Q30_ONE - (uint32_t)x, (uint32_t)XGO_Q30_ONE + (uint32_t)x); /* Q60 */
    uint32_t r = xgo_isqrt64(p);
    if (p - xgo_umul_wide(r, r) > r) {
        ++r; /* round to nearest */
    }
    return (int32_t)r; /* <= 2^30 */
}

xgo_bam_t xgo_asin(xgo_q30_t x)
{
    x = clamp_unit(x);
    return xgo_atan2(x, unit_complement(x));
}

xgo_bam_t xgo_acos(xgo_q30_t x)
{
    x = clamp_unit(x);
    return xgo_atan2(unit_complement(x), x);
}
