/*
 * fixed.c - integer-only math (see fixed.h and docs/fixed-point.md).
 *
 * No floating point anywhere: the tables below were generated offline (the
 * generator is in docs/fixed-point.md) and are checked against libm by
 * test/test_fixed.c through the functions that use them.
 */
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

/* The table's chord for m in [2^30, 2^32): within 2 of floor(sqrt(m)),
 * clamped to 16 bits (isqrt_norm32 without its exact steps). */
static uint32_t sqrt_chord32(uint32_t m)
{
    const uint32_t i = (m >> 25) - 32u, f = (m >> 9) & 0xFFFFu;
    const uint32_t a = sqrt_tab[i], b = sqrt_tab[i + 1u];
    const uint32_t y = 32768u + a + (((b - a) * f) >> 16); /* (b - a) < 2^9 */
    return y > 65535u ? 65535u : y;
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
static uint32_t newton_quotient(uint32_t n, uint32_t y, uint32_t m)
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

uint32_t xgo_sqrt64_near(uint64_t x)
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
    const int32_t s = clamp_unit(s0 + c_s - s_h);
    const int32_t c = clamp_unit(c0 - s_s - c_h);
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
static uint32_t nearest_node(uint32_t uy, uint32_t ux)
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
static uint32_t residual_q29(uint32_t m, uint32_t e)
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
static uint32_t atan_octant(uint32_t ux, uint32_t uy)
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
static xgo_bam_t fold(uint32_t a, int swap, int xneg, int yneg)
{
    if (swap) {
        a = XGO_BAM_90 - a;
    }
    if (xneg) {
        a = XGO_BAM_180 - a;
    }
    return yneg ? 0u - a : a;
}

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

static uint32_t abs_u32(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

xgo_bam_t xgo_atan2_len30(int32_t y, int32_t x)
{
    const uint32_t ux = abs_u32(x), uy = abs_u32(y);
    const int swap = uy > ux;
    /* the larger is in [2^28.5, 2^30]: 2^5 down lands in [2^23.5, 2^25] */
    return fold(atan_octant((swap ? uy : ux) >> 5, (swap ? ux : uy) >> 5), swap, x < 0, y < 0);
}

xgo_bam_t xgo_atan2(int32_t y, int32_t x)
{
    return atan2_u32(abs_u32(x), abs_u32(y), x < 0, y < 0);
}

static uint64_t abs_u64(int64_t v)
{
    return v < 0 ? 0u - (uint64_t)v : (uint64_t)v;
}

xgo_bam_t xgo_atan2_64(int64_t y, int64_t x)
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
        return swap ? atan2_u32((uint32_t)small, (uint32_t)big, xneg, yneg)
                    : atan2_u32((uint32_t)big, (uint32_t)small, xneg, yneg);
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
