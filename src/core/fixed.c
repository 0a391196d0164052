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

/* 8 pi - 25 in Q19, rounded: with 25 it turns a BAM offset into radians in
 * Q34 (d * 2 pi / 2^32 * 2^34 = d * 8 pi). */
#define EIGHT_PI_FRAC_Q19 69595

/* round(v / 3) for 0 <= v < 2^15 - 1: a multiply by ceil(2^16 / 3) = 21846
 * and a shift is exact there, and needs no division (Cortex-M0). */
static int32_t div3_small(int32_t v)
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

/* The nearest table node and the angle-addition formulas:
 *   sin(a + d) = s0 cos d + c0 sin d,  cos(a + d) = c0 cos d - s0 sin d,
 * sin d = d - d^3/6 (next term < 1e-13), 1 - cos d = d^2/2 (next term
 * 6e-11). Only the two products with sin d need 32 x 32 -> 64 bits; the
 * small terms are 16 x 16-bit products (one MULS each on a Cortex-M0). */
void xgo_sincos(xgo_bam_t a, xgo_q30_t *sin_out, xgo_q30_t *cos_out)
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

/* Near the node 0 (from -2^22 up to 2^22 BAM, signed: node 0 of the first
 * quadrant or node 128 of the fourth) the table's values are 0 and 1, so
 * xgo_sincos's products with them are shifts: sin a = round(sd / 16),
 * cos a = 1 - d^2/2 (neither can need its clamp), the same values. */
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
