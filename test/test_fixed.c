/*
 * Fixed-point library: every function against an independent reference
 * (libm in double precision, or exact 64-bit integer arithmetic written
 * differently from the core), over dense sweeps of its whole domain plus
 * every extreme. The maximum errors measured here are the ones stated in
 * xgo/fixed.h and docs/fixed-point.md; the test prints them.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "board_io.h" /* xgo_test_xorshift* */
#include "unity.h"
#include "fixed.h"
#include "wide.h" /* xgo_usquare_wide */
/* fixed.h's bodies as the leg IK inlines them on a 64-bit host (the same
 * code as the out-of-line functions: test_inline_bodies_are_the_functions) */
#define XGO_FIXED_BODIES
#define XGO_FIXED_INLINE
#include "fixed.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void setUp(void) {}
void tearDown(void) {}

/* Deterministic xorshift generator: same numbers on every run. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint32_t rnd32(void)
{
    return xgo_test_xorshift64(&rng_state);
}
static uint64_t rnd64(void)
{
    return ((uint64_t)rnd32() << 32) | rnd32();
}

static void report(const char *what, double value, const char *unit)
{
    char msg[160];
    snprintf(msg, sizeof msg, "measured max error %s: %.4g %s", what, value, unit);
    TEST_MESSAGE(msg);
}

static const int32_t extremes32[] = {
    INT32_MIN, INT32_MIN + 1, -2147483647 / 2, -65536, -65535, -32768, -1000, -3, -2, -1,
    0, 1, 2, 3, 1000, 32767, 65535, 65536, 2147483647 / 2, INT32_MAX - 1, INT32_MAX,
};
#define N_EXTREMES (sizeof extremes32 / sizeof extremes32[0])

/* ------------------------------------------------------------ saturation */

static int64_t clamp64(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : (v < INT32_MIN ? INT32_MIN : v);
}

static void test_saturating_add_sub_neg_abs(void)
{
    size_t i, j;
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_sat_add(INT32_MAX, 1));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_sat_add(INT32_MIN, -1));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_sat_sub(INT32_MAX, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_sat_sub(INT32_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(-1, xgo_sat_add(INT32_MAX, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_sat_neg(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_sat_abs(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN + 1, xgo_sat_neg(INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(0, xgo_sat_abs(0));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_sat32(INT64_MAX));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_sat32(INT64_MIN));
    for (i = 0; i < N_EXTREMES; ++i) {
        for (j = 0; j < N_EXTREMES; ++j) {
            int32_t a = extremes32[i], b = extremes32[j];
            TEST_ASSERT_EQUAL_INT32(clamp64((int64_t)a + b), xgo_sat_add(a, b));
            TEST_ASSERT_EQUAL_INT32(clamp64((int64_t)a - b), xgo_sat_sub(a, b));
        }
        TEST_ASSERT_EQUAL_INT32(clamp64(-(int64_t)extremes32[i]), xgo_sat_neg(extremes32[i]));
        TEST_ASSERT_EQUAL_INT32(clamp64(extremes32[i] < 0 ? -(int64_t)extremes32[i] : extremes32[i]),
                                xgo_sat_abs(extremes32[i]));
    }
    for (i = 0; i < 100000; ++i) {
        int32_t a = (int32_t)rnd32(), b = (int32_t)rnd32();
        TEST_ASSERT_EQUAL_INT32(clamp64((int64_t)a + b), xgo_sat_add(a, b));
        TEST_ASSERT_EQUAL_INT32(clamp64((int64_t)a - b), xgo_sat_sub(a, b));
    }
}

/* floor(n / d) for d > 0, independent of the core's rounding code. */
static int64_t floor_div(int64_t n, int64_t d)
{
    int64_t q = n / d;
    if (n % d != 0 && n < 0) {
        --q;
    }
    return q;
}

/* Reference for xgo_mul_q: round to nearest, ties up, then clamp. */
static int64_t ref_mul_q(int32_t a, int32_t b, unsigned q)
{
    int64_t p = (int64_t)a * b;
    int64_t d = (int64_t)1 << q;
    int64_t f = floor_div(p, d);
    int64_t rem = p - f * d; /* 0 <= rem < d */
    if (q > 0 && rem >= d / 2) {
        ++f;
    }
    return clamp64(f);
}

static void check_mul(int32_t a, int32_t b, unsigned q)
{
    TEST_ASSERT_EQUAL_INT32(ref_mul_q(a, b, q), xgo_mul_q(a, b, q));
}

static void test_mul_q_exact_rounding_and_saturation(void)
{
    size_t i, j;
    unsigned q;
    for (q = 0; q <= 31; ++q) {
        for (i = 0; i < N_EXTREMES; ++i) {
            for (j = 0; j < N_EXTREMES; ++j) {
                check_mul(extremes32[i], extremes32[j], q);
            }
        }
        for (i = 0; i < 20000; ++i) {
            check_mul((int32_t)rnd32(), (int32_t)rnd32(), q);
            check_mul((int32_t)rnd32() >> 12, (int32_t)rnd32() >> 12, q);
        }
    }
    /* q beyond 31 behaves as 31 */
    TEST_ASSERT_EQUAL_INT32(xgo_mul_q(INT32_MAX, INT32_MAX, 31), xgo_mul_q(INT32_MAX, INT32_MAX, 99));
    /* Q16 examples */
    TEST_ASSERT_EQUAL_INT32(3 * XGO_Q16_ONE, xgo_q16_mul(XGO_Q16_ONE + XGO_Q16_ONE / 2, 2 * XGO_Q16_ONE));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_q16_mul(INT32_MAX, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_q16_mul(INT32_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_q16_mul(INT32_MIN, INT32_MIN));
    report("xgo_mul_q", 0.5, "LSB (exact rounding, all q)");
}

/* Reference for division: exact integer quotient, ties away from zero. */
static int64_t ref_div(int64_t n, int64_t d)
{
    int64_t q, r;
    if (d == 0) {
        return n > 0 ? INT32_MAX : (n < 0 ? INT32_MIN : 0);
    }
    q = n / d;
    r = n % d;
    if (r != 0) {
        int64_t ar = r < 0 ? -r : r, ad = d < 0 ? -d : d;
        if (2 * ar >= ad) {
            q += ((n < 0) != (d < 0)) ? -1 : 1;
        }
    }
    return clamp64(q);
}

static void test_div_q_and_muldiv(void)
{
    size_t i, j, k;
    unsigned q;
    for (q = 0; q <= 31; ++q) {
        for (i = 0; i < N_EXTREMES; ++i) {
            for (j = 0; j < N_EXTREMES; ++j) {
                int32_t a = extremes32[i], b = extremes32[j];
                TEST_ASSERT_EQUAL_INT32(ref_div((int64_t)a * ((int64_t)1 << q), b), xgo_div_q(a, b, q));
            }
        }
        for (i = 0; i < 20000; ++i) {
            int32_t a = (int32_t)rnd32(), b = (int32_t)rnd32() >> (rnd32() % 31);
            TEST_ASSERT_EQUAL_INT32(ref_div((int64_t)a * ((int64_t)1 << q), b), xgo_div_q(a, b, q));
        }
    }
    /* division by zero */
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_div_q(1, 0, 16));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_div_q(-1, 0, 16));
    TEST_ASSERT_EQUAL_INT32(0, xgo_div_q(0, 0, 16));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_div_q(INT32_MIN, -1, 0));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_div_q(INT32_MIN, 1, 31));
    TEST_ASSERT_EQUAL_INT32(XGO_Q16_ONE / 3 + 0, xgo_q16_div(XGO_Q16_ONE, 3 * XGO_Q16_ONE));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_muldiv(5, 7, 0));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_muldiv(-5, 7, 0));
    TEST_ASSERT_EQUAL_INT32(0, xgo_muldiv(0, 7, 0));
    for (i = 0; i < N_EXTREMES; ++i) {
        for (j = 0; j < N_EXTREMES; ++j) {
            for (k = 0; k < N_EXTREMES; ++k) {
                int32_t a = extremes32[i], b = extremes32[j], c = extremes32[k];
                TEST_ASSERT_EQUAL_INT32(ref_div((int64_t)a * b, c), xgo_muldiv(a, b, c));
            }
        }
    }
    for (i = 0; i < 200000; ++i) {
        int32_t a = (int32_t)rnd32(), b = (int32_t)rnd32() >> (rnd32() % 31),
                c = (int32_t)rnd32() >> (rnd32() % 31);
        TEST_ASSERT_EQUAL_INT32(ref_div((int64_t)a * b, c), xgo_muldiv(a, b, c));
    }
    report("xgo_div_q / xgo_muldiv", 0.5, "LSB (exact rounding)");
}

/* ------------------------------------------------------------ square root */

static void check_isqrt32(uint32_t x)
{
    uint64_t r = xgo_isqrt32(x);
    TEST_ASSERT_TRUE(r * r <= x);
    TEST_ASSERT_TRUE((r + 1) * (r + 1) > x);
}

static void check_isqrt64(uint64_t x)
{
    /* exact check without overflow: r^2 <= x < (r+1)^2, using long double
     * only to pick the comparison, never to compute the expected value */
    uint64_t r = xgo_isqrt64(x);
    uint64_t r2 = r * r; /* r < 2^32: fits */
    TEST_ASSERT_TRUE(r <= 0xFFFFFFFFull);
    TEST_ASSERT_TRUE(r2 <= x);
    if (r < 0xFFFFFFFFull) {
        /* (r+1)^2 = r2 + 2r + 1 may exceed 2^64 - 1 only when r+1 == 2^32 */
        TEST_ASSERT_TRUE(x - r2 < 2 * r + 1);
    }
}

/* xgo_udiv64_cap is min(floor(n / d), cap), checked against the host's
 * 64-bit division: caps of every size, quotients below, at and above the
 * cap, divisors up to the documented bound, and the edges. */
static void test_udiv64_cap_is_the_capped_quotient(void)
{
    static const uint32_t caps[] = {0u, 1u, 255u, 65535u, 65536u, 0x7FFFFFFFu, 0xFFFFFFFFu};
    unsigned c, i;
    for (c = 0; c < sizeof caps / sizeof caps[0]; ++c) {
        const uint32_t cap = caps[c];
        const unsigned bits = xgo_bit_length(cap);
        for (i = 0; i < 20000; ++i) {
            /* divisors within 2^(63 - bits), numerators around cap * d */
            const uint64_t d = (rnd64() >> (bits + 1u + rnd64() % 30u)) | 1u;
            const uint64_t scale = cap == 0u ? 1u : (uint64_t)cap + (rnd64() % 3u) - 1u;
            const uint64_t n = (i & 1u) ? rnd64() >> (rnd64() % 64u)
                                        : (d * (scale < 1u ? 1u : scale)) >> (rnd64() % 4u);
            const uint64_t q = n / d;
            TEST_ASSERT_EQUAL_UINT32(q < cap ? (uint32_t)q : cap, xgo_udiv64_cap(n, d, cap));
        }
    }
    TEST_ASSERT_EQUAL_UINT32(7u, xgo_udiv64_cap(12345u, 0u, 7u)); /* d == 0 */
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_udiv64_cap(0u, 3u, 100u));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu, xgo_udiv64_cap(UINT64_MAX, 1u, 0xFFFFFFFFu));
    TEST_ASSERT_EQUAL_UINT32(65536u, xgo_udiv64_cap((uint64_t)1 << 62, 3u, 65536u));
    TEST_ASSERT_EQUAL_UINT32(4294967295u / 3u, xgo_udiv64_cap(4294967295u, 3u, 0xFFFFFFFFu));
}

/* The leading-zero counts: every form against a plain count, for every
 * power of two and its neighbours and random values of every length (the
 * _narrow build runs the M0's inline search). */
static unsigned plain_clz(uint32_t v)
{
    unsigned n = 32;
    while (v != 0u) {
        v >>= 1;
        --n;
    }
    return n;
}

static void check_clz(uint32_t v)
{
    const unsigned n = plain_clz(v);
    TEST_ASSERT_EQUAL_UINT(n, xgo_clz32(v));
    if (v != 0u) {
        TEST_ASSERT_EQUAL_UINT(n, xgo_clz32_nz(v));
        TEST_ASSERT_EQUAL_UINT(n & ~1u, xgo_clz32_even(v));
    }
}

/* mdeg -> BAM against the 64-bit formula for every |mdeg| up to 70,000
 * (the _narrow build's short path below 65,536 and its edge) and random
 * values of any size. */
static xgo_bam_t mdeg_to_bam_wide(int32_t mdeg)
{
    const int64_t frac = ((int64_t)mdeg * 1995919024 + ((int64_t)1 << 31)) >> 32;
    return (uint32_t)mdeg * 11930u + (uint32_t)(uint64_t)frac;
}

static void test_mdeg_to_bam_every_short_value(void)
{
    int32_t m;
    unsigned i;
    for (m = -70000; m <= 70000; ++m) {
        TEST_ASSERT_EQUAL_UINT32(mdeg_to_bam_wide(m), xgo_mdeg_to_bam(m));
    }
    for (i = 0; i < 100000u; ++i) {
        const int32_t v = (int32_t)(uint32_t)rnd64();
        TEST_ASSERT_EQUAL_UINT32(mdeg_to_bam_wide(v), xgo_mdeg_to_bam(v));
    }
    TEST_ASSERT_EQUAL_UINT32(mdeg_to_bam_wide(INT32_MIN), xgo_mdeg_to_bam(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT32(mdeg_to_bam_wide(INT32_MAX), xgo_mdeg_to_bam(INT32_MAX));
}

static void test_clz_forms(void)
{
    unsigned b, i;
    check_clz(0u);
    check_clz(0xFFFFFFFFu);
    for (b = 0; b < 32u; ++b) {
        const uint32_t p2 = (uint32_t)1 << b;
        check_clz(p2);
        check_clz(p2 - 1u);
        check_clz(p2 + 1u);
        check_clz(p2 | (p2 - 1u));
    }
    for (i = 0; i < 200000u; ++i) {
        check_clz((uint32_t)rnd64() >> (i % 32u));
    }
    /* the inline bit length (the leg IK's cut) is xgo_bit_length */
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_bit_length_inline(0u));
    for (b = 0; b < 64u; ++b) {
        const uint64_t p2 = (uint64_t)1 << b;
        TEST_ASSERT_EQUAL_UINT32(xgo_bit_length(p2), xgo_bit_length_inline(p2));
        TEST_ASSERT_EQUAL_UINT32(xgo_bit_length(p2 - 1u), xgo_bit_length_inline(p2 - 1u));
        TEST_ASSERT_EQUAL_UINT32(xgo_bit_length(p2 | (p2 - 1u)), xgo_bit_length_inline(p2 | (p2 - 1u)));
    }
    for (i = 0; i < 200000u; ++i) {
        const uint64_t v = rnd64() >> (i % 64u);
        TEST_ASSERT_EQUAL_UINT32(xgo_bit_length(v), xgo_bit_length_inline(v));
    }
}

static void test_isqrt_exact(void)
{
    uint32_t i;
    uint64_t s;
    check_isqrt32(0);
    check_isqrt32(1);
    check_isqrt32(0xFFFFFFFFu);
    TEST_ASSERT_EQUAL_UINT32(65535u, xgo_isqrt32(0xFFFFFFFFu));
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_isqrt64(0));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu, xgo_isqrt64(UINT64_MAX));
    for (i = 0; i < 300000; ++i) {
        check_isqrt32(i);
        check_isqrt32(rnd32());
    }
    /* around every perfect square up to 2^32 (sampled) and near 2^32 */
    for (i = 1; i < 65536; i += 7) {
        check_isqrt32(i * i);
        check_isqrt32(i * i - 1);
        check_isqrt32(i * i + 1);
    }
    for (s = 1; s <= 0xFFFFFFFFull; s = s * 3 + 1) {
        check_isqrt64(s * s);
        check_isqrt64(s * s - 1);
        check_isqrt64(s * s + 1);
    }
    check_isqrt64(0xFFFFFFFFull * 0xFFFFFFFFull);
    check_isqrt64(0xFFFFFFFFull * 0xFFFFFFFFull - 1);
    check_isqrt64(UINT64_MAX - 1);
    for (i = 0; i < 300000; ++i) {
        check_isqrt64(rnd64());
        check_isqrt64(rnd64() >> (rnd32() % 64));
    }
    report("xgo_isqrt32 / xgo_isqrt64", 0.0, "(floor, exact)");
}

static void test_q16_sqrt_against_libm(void)
{
    double max_err = 0;
    uint32_t i;
    TEST_ASSERT_EQUAL_INT32(0, xgo_q16_sqrt(0));
    TEST_ASSERT_EQUAL_INT32(0, xgo_q16_sqrt(-1));
    TEST_ASSERT_EQUAL_INT32(0, xgo_q16_sqrt(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(XGO_Q16_ONE, xgo_q16_sqrt(XGO_Q16_ONE));
    TEST_ASSERT_EQUAL_INT32(2 * XGO_Q16_ONE, xgo_q16_sqrt(4 * XGO_Q16_ONE));
    for (i = 0; i < 600000; ++i) {
        int32_t x;
        double ref, err;
        if (i < 200000) {
            x = (int32_t)i;
        } else if (i < 400000) {
            x = INT32_MAX - (int32_t)(i - 200000);
        } else {
            x = (int32_t)(rnd32() >> 1);
        }
        ref = sqrt((double)x / 65536.0) * 65536.0;
        err = fabs((double)xgo_q16_sqrt(x) - ref);
        if (err > max_err) {
            max_err = err;
        }
    }
    report("xgo_q16_sqrt", max_err, "LSB of Q16");
    TEST_ASSERT_TRUE(max_err <= 0.5 + 1e-6);
}

/* ------------------------------------------------------------ angles */

static double bam_wrap_diff(double a, double b)
{
    double d = fmod(a - b, 4294967296.0);
    if (d > 2147483648.0) {
        d -= 4294967296.0;
    } else if (d < -2147483648.0) {
        d += 4294967296.0;
    }
    return d;
}

static void test_angle_conversions(void)
{
    double max_err_bam = 0, max_err_mdeg = 0;
    int32_t m;
    uint32_t i;
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_mdeg_to_bam(0));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90, xgo_mdeg_to_bam(90000));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180, xgo_mdeg_to_bam(180000));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180, xgo_mdeg_to_bam(-180000));
    TEST_ASSERT_EQUAL_UINT32(0u - XGO_BAM_90, xgo_mdeg_to_bam(-90000));
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_mdeg_to_bam(360000));
    TEST_ASSERT_EQUAL_INT32(90000, xgo_bam_to_mdeg(XGO_BAM_90));
    TEST_ASSERT_EQUAL_INT32(-90000, xgo_bam_to_mdeg(0u - XGO_BAM_90));
    TEST_ASSERT_EQUAL_INT32(-180000, xgo_bam_to_mdeg(XGO_BAM_180));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, xgo_bam_signed(0x80000000u));
    TEST_ASSERT_EQUAL_INT32(-1, xgo_bam_signed(0xFFFFFFFFu));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, xgo_bam_signed(0x7FFFFFFFu));
    (void)xgo_mdeg_to_bam(INT32_MIN);
    (void)xgo_mdeg_to_bam(INT32_MAX);
    for (m = -1000000; m <= 1000000; m += 1) {
        double ref = (double)m * 4294967296.0 / 360000.0;
        double err = fabs(bam_wrap_diff((double)xgo_mdeg_to_bam(m), ref));
        if (err > max_err_bam && (m >= -360000 && m <= 360000)) {
            max_err_bam = err;
        }
        TEST_ASSERT_TRUE(err <= 0.75);
    }
    for (i = 0; i < 2000000; ++i) {
        uint32_t a = i < 1000000 ? i * 4295u : rnd32();
        double ref = (double)xgo_bam_signed(a) * 360000.0 / 4294967296.0;
        int32_t got = xgo_bam_to_mdeg(a);
        double err = fabs((double)got - ref);
        if (err > max_err_mdeg) {
            max_err_mdeg = err;
        }
        TEST_ASSERT_TRUE(got >= -180000 && got <= 180000);
    }
    {
        /* whole int32 domain against the exact value: one mdeg is
         * 2^27 / 11250 BAM, so mdeg * 2^27 (< 2^59) / 11250 is exact in
         * 64-bit integers (fractional part from the remainder) */
        double max_full = 0;
        uint32_t k;
        for (k = 0; k < 2000000; ++k) {
            int32_t mm = k < 1000 ? INT32_MIN + (int32_t)k
                         : k < 2000 ? INT32_MAX - (int32_t)(k - 1000)
                                    : (int32_t)rnd32();
            int64_t num = (int64_t)mm * ((int64_t)1 << 27);
            int64_t q = floor_div(num, 11250);
            double frac = (double)(num - q * 11250) / 11250.0; /* [0, 1) */
            double ref = (double)(uint32_t)(uint64_t)q + frac;
            double err = fabs(bam_wrap_diff((double)xgo_mdeg_to_bam(mm), ref));
            if (err > max_full) {
                max_full = err;
            }
        }
        report("xgo_mdeg_to_bam (any int32)", max_full, "LSB of BAM");
        TEST_ASSERT_TRUE(max_full <= 0.75);
    }
    report("xgo_mdeg_to_bam (|mdeg| <= 360000)", max_err_bam, "LSB of BAM");
    report("xgo_bam_to_mdeg", max_err_mdeg, "mdeg");
    TEST_ASSERT_TRUE(max_err_bam <= 0.5 + 1e-6);
    TEST_ASSERT_TRUE(max_err_mdeg <= 0.5 + 1e-6);
}

/* ------------------------------------------------------------ sin / cos */

static double max_sin_err, max_cos_err;

static void check_sincos(uint32_t a)
{
    xgo_q30_t s, c;
    double rad = (double)a * (2.0 * M_PI / 4294967296.0);
    double es, ec;
    xgo_sincos(a, &s, &c);
    es = fabs((double)s - sin(rad) * 1073741824.0);
    ec = fabs((double)c - cos(rad) * 1073741824.0);
    if (es > max_sin_err) {
        max_sin_err = es;
    }
    if (ec > max_cos_err) {
        max_cos_err = ec;
    }
    TEST_ASSERT_TRUE(s >= -XGO_Q30_ONE && s <= XGO_Q30_ONE);
    TEST_ASSERT_TRUE(c >= -XGO_Q30_ONE && c <= XGO_Q30_ONE);
}

/* The near-0 form gives xgo_sincos's values: every angle within 2^22 BAM
 * of 0 and a margin past either end (its own path and the fallback's
 * edge), and angles spread over the whole turn (the fallback). */
static void test_sincos_near0_is_sincos(void)
{
    int32_t d;
    uint32_t i;
    for (d = -(1 << 22) - 4096; d <= (1 << 22) + 4096; ++d) {
        xgo_q30_t s0, c0, s1, c1;
        xgo_sincos((xgo_bam_t)d, &s0, &c0);
        xgo_sincos_near0((xgo_bam_t)d, &s1, &c1);
        if (s0 != s1 || c0 != c1) {
            TEST_ASSERT_EQUAL_INT32_MESSAGE(s0, s1, "sin near 0");
            TEST_ASSERT_EQUAL_INT32_MESSAGE(c0, c1, "cos near 0");
        }
    }
    for (i = 0; i < (1u << 16); ++i) {
        const xgo_bam_t a = i * 65537u + 12345u;
        xgo_q30_t s0, c0, s1, c1;
        xgo_sincos(a, &s0, &c0);
        xgo_sincos_near0(a, &s1, &c1);
        TEST_ASSERT_EQUAL_INT32(s0, s1);
        TEST_ASSERT_EQUAL_INT32(c0, c1);
    }
}

/* The square's three-product form (the _narrow build's; the plain product
 * elsewhere) against the 64-bit product: the edges of its pieces and
 * random values of every length (its own draws: the others' stay). */
static void test_usquare_wide_is_the_product(void)
{
    static const uint32_t us[] = {0u, 1u, 0xFFFFu, 0x10000u, 0x10001u, 0x7FFFFFFFu, 0x80000000u, 0x80000001u,
                                  0xFFFEFFFFu, 0xFFFF0000u, 0xFFFFFFFFu, 0x0001FFFFu, 0x00017FFFu};
    uint64_t state = 0x5a5a1234ULL;
    size_t i;
    long n;
    for (i = 0; i < sizeof us / sizeof us[0]; ++i) {
        TEST_ASSERT_TRUE(xgo_usquare_wide(us[i]) == (uint64_t)us[i] * us[i]);
    }
    for (n = 0; n < 2000000; ++n) {
        const uint32_t u = (uint32_t)xgo_test_xorshift64(&state) >> (n & 31);
        if (xgo_usquare_wide(u) != (uint64_t)u * u) {
            TEST_ASSERT_EQUAL_UINT32(u, ~u); /* fails, naming u */
        }
    }
}

static void test_sincos_against_libm(void)
{
    uint32_t i, k;
    max_sin_err = max_cos_err = 0;
    /* 2^21 evenly spaced angles over the whole turn */
    for (i = 0; i < (1u << 21); ++i) {
        check_sincos(i << 11);
    }
    /* around every table node and quadrant boundary, where the correction
     * term switches side */
    for (k = 0; k < 512; ++k) {
        uint32_t node = k << 23;
        int32_t off;
        for (off = -3; off <= 3; ++off) {
            check_sincos(node + (uint32_t)off);
            check_sincos(node + (1u << 22) + (uint32_t)off);
        }
    }
    for (i = 0; i < 500000; ++i) {
        check_sincos(rnd32());
    }
    check_sincos(0xFFFFFFFFu);
    TEST_ASSERT_EQUAL_INT32(0, xgo_sin(0));
    TEST_ASSERT_EQUAL_INT32(XGO_Q30_ONE, xgo_cos(0));
    TEST_ASSERT_EQUAL_INT32(XGO_Q30_ONE, xgo_sin(XGO_BAM_90));
    TEST_ASSERT_EQUAL_INT32(-XGO_Q30_ONE, xgo_cos(XGO_BAM_180));
    TEST_ASSERT_EQUAL_INT32(0, xgo_sin(XGO_BAM_180));
    report("xgo_sin", max_sin_err, "LSB of Q30");
    report("xgo_cos", max_cos_err, "LSB of Q30");
    TEST_ASSERT_TRUE(max_sin_err <= 3.5);
    TEST_ASSERT_TRUE(max_cos_err <= 3.5);
}


/* xgo_sqrt64_near against the exact floor: equal below 2^32, within a few
 * units of it above (the leg IK's two roots; docs/fixed-point.md). */
static void check_sqrt_near(uint64_t x, uint32_t *worst)
{
    const uint32_t r = xgo_isqrt64(x), n = xgo_sqrt64_near(x);
    const uint32_t e = n > r ? n - r : r - n;
    if (x <= 0xFFFFFFFFu) {
        TEST_ASSERT_EQUAL_UINT32(r, n);
    }
    if (e > *worst) {
        *worst = e;
    }
}

static void test_sqrt64_near_within_units_of_the_floor(void)
{
    uint32_t worst = 0, i;
    uint64_t s;
    check_sqrt_near(0, &worst);
    check_sqrt_near(UINT64_MAX, &worst);
    check_sqrt_near((uint64_t)1 << 32, &worst);
    check_sqrt_near(((uint64_t)1 << 32) - 1u, &worst);
    for (s = 1; s <= 0xFFFFFFFFull; s = s * 3 + 1) {
        check_sqrt_near(s * s, &worst);
        check_sqrt_near(s * s - 1, &worst);
        check_sqrt_near(s * s + 1, &worst);
    }
    for (i = 0; i < 1000000; ++i) {
        check_sqrt_near(rnd64(), &worst);
        check_sqrt_near(rnd64() >> (rnd32() % 64), &worst);
    }
    report("xgo_sqrt64_near vs the exact floor", (double)worst, "units");
    TEST_ASSERT_TRUE(worst >= 1u); /* it is not the exact root: the test can tell */
    TEST_ASSERT_TRUE(worst <= 6u);
}

/* xgo_sqrt64_near's exact values (not only their distance from the
 * floor): 2 * 10^6 random x of every bit length and a high word at every
 * step of the table's chord, folded into one digest. The golden digest was
 * taken from the code before the chord lost its clamp to 65535 (3fcb945),
 * which never acted. */
#define SQRT64_NEAR_DIGEST 0xf36298ef851547deull

static void test_sqrt64_near_same_bits_as_before(void)
{
    uint64_t state = 0x9E3779B97F4A7C15ull, digest = 0;
    uint32_t k, m;
    for (k = 0; k < 2000000u; ++k) {
        /* one draw a statement (the order of calls in an expression is unspecified) */
        const uint64_t hi = xgo_test_xorshift64(&state);
        const uint64_t lo = xgo_test_xorshift64(&state);
        const unsigned s = xgo_test_xorshift64(&state) % 64u;
        digest = (digest ^ xgo_sqrt64_near(((hi << 32) | lo) >> s)) * 0x100000001B3ull;
    }
    for (m = 0x40000000u; m >= 0x40000000u; m += 0x200u) { /* up to the wrap past 2^32 */
        digest = (digest ^ xgo_sqrt64_near(((uint64_t)m << 32) | (m ^ 0x5A5A5A5Au))) * 0x100000001B3ull;
    }
    printf("xgo_sqrt64_near digest 0x%016llx\n", (unsigned long long)digest);
    TEST_ASSERT_TRUE(digest == SQRT64_NEAR_DIGEST);
}

/* ------------------------------------------------------------ atan2 */

#define BOUND_LEN30 52.0 /* xgo_atan2_len30: measured 44.8 LSB (docs/fixed-point.md) */

static double max_atan_err;

static double atan2_err(double y, double x, uint32_t got)
{
    double ref = (x == 0 && y == 0) ? 0.0 : atan2(y, x) * (4294967296.0 / (2.0 * M_PI));
    return fabs(bam_wrap_diff((double)got, ref));
}

static void check_atan2(int32_t y, int32_t x)
{
    double e = atan2_err((double)y, (double)x, xgo_atan2(y, x));
    if (e > max_atan_err) {
        max_atan_err = e;
    }
}

static void test_atan2_against_libm(void)
{
    int32_t x, y;
    size_t i, j;
    uint32_t k;
    static const double mags[] = {3, 17, 1000, 65536, 1e6, 3.3e7, 5e8, 1.07e9, 2.1e9};
    max_atan_err = 0;
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_atan2(0, 0));
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_atan2(0, 5));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90, xgo_atan2(5, 0));
    TEST_ASSERT_EQUAL_UINT32(0u - XGO_BAM_90, xgo_atan2(-5, 0));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180, xgo_atan2(0, -5));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90 / 2, xgo_atan2(INT32_MAX, INT32_MAX));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180 + XGO_BAM_90 / 2, xgo_atan2(INT32_MIN, INT32_MIN));
    /* every small pair: coarse inputs, the hardest case for precision */
    for (y = -128; y <= 128; ++y) {
        for (x = -128; x <= 128; ++x) {
            check_atan2(y, x);
        }
    }
    /* every extreme against every extreme */
    for (i = 0; i < N_EXTREMES; ++i) {
        for (j = 0; j < N_EXTREMES; ++j) {
            check_atan2(extremes32[i], extremes32[j]);
        }
    }
    /* rays: 2^16 directions at magnitudes from 3 to 2^31 */
    for (i = 0; i < sizeof mags / sizeof mags[0]; ++i) {
        for (k = 0; k < 65536; ++k) {
            double t = (double)k * (2.0 * M_PI / 65536.0) + 1e-4;
            double fx = mags[i] * cos(t), fy = mags[i] * sin(t);
            check_atan2((int32_t)fy, (int32_t)fx);
        }
    }
    for (k = 0; k < 1000000; ++k) {
        int32_t ry = (int32_t)rnd32() >> (rnd32() % 31);
        int32_t rx = (int32_t)rnd32() >> (rnd32() % 31);
        check_atan2(ry, rx);
    }
    report("xgo_atan2", max_atan_err, "LSB of BAM");
    TEST_ASSERT_TRUE(max_atan_err <= 32.0);
}

static void test_atan2_64_against_libm(void)
{
    double max_err = 0;
    uint32_t k;
    static const int64_t ext[] = {INT64_MIN, INT64_MIN + 1, -((int64_t)1 << 40), -5, -1, 0,
                                  1, 5, (int64_t)1 << 40, INT64_MAX - 1, INT64_MAX};
    size_t i, j;
    for (i = 0; i < sizeof ext / sizeof ext[0]; ++i) {
        for (j = 0; j < sizeof ext / sizeof ext[0]; ++j) {
            double e = atan2_err((double)ext[i], (double)ext[j], xgo_atan2_64(ext[i], ext[j]));
            if (e > max_err) {
                max_err = e;
            }
        }
    }
    for (k = 0; k < 300000; ++k) {
        int64_t y = (int64_t)rnd64() >> (rnd32() % 63);
        int64_t x = (int64_t)rnd64() >> (rnd32() % 63);
        double e = atan2_err((double)y, (double)x, xgo_atan2_64(y, x));
        if (e > max_err) {
            max_err = e;
        }
    }
    report("xgo_atan2_64", max_err, "LSB of BAM");
    TEST_ASSERT_TRUE(max_err <= 32.0);
}

/* ------------------------------------------------------------ asin / acos */


/* xgo_atan2_len30: vectors of length 2^29 .. 2^30 in every direction (the
 * leg IK's knee angle), against libm. */
static void test_atan2_len30_against_libm(void)
{
    double max_err = 0;
    uint32_t k;
    static const double lens[] = {536870912.0, 700000000.0, 900000000.0, 1073741823.0};
    size_t i;
    for (i = 0; i < sizeof lens / sizeof lens[0]; ++i) {
        for (k = 0; k < 262144; ++k) {
            double t = (double)k * (2.0 * M_PI / 262144.0) + 1e-5;
            int32_t x = (int32_t)(lens[i] * cos(t)), y = (int32_t)(lens[i] * sin(t));
            double e = atan2_err((double)y, (double)x, xgo_atan2_len30(y, x));
            max_err = e > max_err ? e : max_err;
        }
    }
    for (k = 0; k < 1000000; ++k) {
        double t = (double)rnd32() * (2.0 * M_PI / 4294967296.0);
        double r = 536870912.0 + (double)(rnd32() % 536870912u);
        int32_t x = (int32_t)(r * cos(t)), y = (int32_t)(r * sin(t));
        double e = atan2_err((double)y, (double)x, xgo_atan2_len30(y, x));
        max_err = e > max_err ? e : max_err;
    }
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_atan2_len30(0, 1 << 30));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90, xgo_atan2_len30(1 << 30, 0));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180, xgo_atan2_len30(0, -(1 << 30)));
    report("xgo_atan2_len30", max_err, "LSB of BAM");
    TEST_ASSERT_TRUE(max_err <= BOUND_LEN30);
}

static void test_asin_acos_against_libm(void)
{
    double max_as = 0, max_ac = 0;
    int64_t v;
    uint32_t k;
    for (k = 0; k < 1200000; ++k) {
        int32_t x;
        double xd, ea, ec;
        if (k < 400000) {
            x = (int32_t)(-XGO_Q30_ONE + (int64_t)k * 5369); /* whole range */
        } else if (k < 600000) {
            x = XGO_Q30_ONE - (int32_t)(k - 400000); /* last 2e5 LSB below +1 */
        } else if (k < 800000) {
            x = -XGO_Q30_ONE + (int32_t)(k - 600000);
        } else {
            x = (int32_t)(rnd32() % (2u * XGO_Q30_ONE + 1u)) - XGO_Q30_ONE;
        }
        xd = (double)x / 1073741824.0;
        ea = fabs(bam_wrap_diff((double)xgo_asin(x), asin(xd) * (4294967296.0 / (2.0 * M_PI))));
        ec = fabs(bam_wrap_diff((double)xgo_acos(x), acos(xd) * (4294967296.0 / (2.0 * M_PI))));
        if (ea > max_as) {
            max_as = ea;
        }
        if (ec > max_ac) {
            max_ac = ec;
        }
    }
    /* clamping outside [-1, 1] */
    for (v = INT32_MIN; v <= INT32_MAX; v += 0x01000000) {
        int32_t x = (int32_t)v;
        int32_t s = xgo_bam_signed(xgo_asin(x));
        int32_t c = xgo_bam_signed(xgo_acos(x));
        TEST_ASSERT_TRUE(s >= -(int32_t)XGO_BAM_90 && s <= (int32_t)XGO_BAM_90);
        TEST_ASSERT_TRUE(c >= 0 || xgo_acos(x) == XGO_BAM_180);
    }
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90, xgo_asin(INT32_MAX));
    TEST_ASSERT_EQUAL_UINT32(0u - XGO_BAM_90, xgo_asin(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_acos(INT32_MAX));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_180, xgo_acos(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT32(XGO_BAM_90, xgo_acos(0));
    report("xgo_asin", max_as, "LSB of BAM");
    report("xgo_acos", max_ac, "LSB of BAM");
    TEST_ASSERT_TRUE(max_as <= 32.0);
    TEST_ASSERT_TRUE(max_ac <= 32.0);
}

/* xgo_atan2_64 gives the same bits on every core: the 64-bit host's
 * rounding and the 32-bit cores' (the left-normalised top word, the _narrow
 * build) over 4 * 10^6 random pairs of every bit length and sign, the
 * extremes and the scaled pairs where the larger rounds up to 2^25, folded
 * into one digest. The golden digest was taken from the single form every
 * core ran before (the rounding by xgo_round_shr64). */
#define ATAN2_64_DIGEST 0x5c556f8d2e95209cull

static void test_atan2_64_same_bits_everywhere(void)
{
    static const int64_t ext[] = {INT64_MIN, INT64_MIN + 1, -((int64_t)1 << 40), -5, -1, 0,
                                  1, 5, (int64_t)1 << 40, INT64_MAX - 1, INT64_MAX,
                                  ((int64_t)1 << 57) - 1, (int64_t)1 << 32, ((int64_t)1 << 32) - 1};
    uint64_t state = 0x2545F4914F6CDD1Dull, digest = 0;
    size_t i, j;
    uint32_t k;
    for (i = 0; i < sizeof ext / sizeof ext[0]; ++i) {
        for (j = 0; j < sizeof ext / sizeof ext[0]; ++j) {
            digest = (digest ^ xgo_atan2_64(ext[i], ext[j])) * 0x100000001B3ull;
        }
    }
    for (k = 0; k < 4000000u; ++k) {
        /* one draw a statement: the order of two calls in one expression is
         * unspecified, and compilers differ (the digest must not) */
        const uint64_t ry = xgo_test_xorshift64(&state);
        const uint64_t sy = xgo_test_xorshift64(&state) % 63u;
        const uint64_t rx = xgo_test_xorshift64(&state);
        const uint64_t sx = xgo_test_xorshift64(&state) % 63u;
        const int64_t y = (int64_t)ry >> sy;
        int64_t x = (int64_t)rx >> sx;
        if ((k & 7u) == 0u) { /* the larger just below a rounding up to 2^25 at its length */
            const unsigned len = 33u + xgo_test_xorshift64(&state) % 30u;
            x = (((int64_t)1 << len) - 1 - (int64_t)(xgo_test_xorshift64(&state) % 1000u)) * ((k & 8u) ? -1 : 1);
        }
        digest = (digest ^ xgo_atan2_64(y, x)) * 0x100000001B3ull;
    }
    printf("xgo_atan2_64 digest 0x%016llx\n", (unsigned long long)digest);
    TEST_ASSERT_TRUE(digest == ATAN2_64_DIGEST);
}

/* xgo_sincos's exact values: 4 * 10^6 angles (random, and a sweep in
 * steps of 2^8 BAM through every table node's neighbourhood) folded into
 * one digest. The golden digest was taken from the code before the final
 * clamps to [-1, 1] went (3fcb945; they never acted: checked for every
 * position in a quadrant). */
#define SINCOS_DIGEST 0x6ef3586082735605ull

static void test_sincos_same_bits_as_before(void)
{
    uint64_t state = 0x5EEDC0DE5EEDC0DEull, digest = 0;
    uint32_t k;
    for (k = 0; k < 4000000u; ++k) {
        const uint32_t hi = xgo_test_xorshift64(&state);
        const uint32_t lo = xgo_test_xorshift64(&state);
        const xgo_bam_t a = (k & 1u) ? (hi << 16) ^ lo : (xgo_bam_t)(k << 8) + (hi & 0xFFu);
        xgo_q30_t s, c;
        xgo_sincos(a, &s, &c);
        digest = (digest ^ (uint32_t)s) * 0x100000001B3ull;
        digest = (digest ^ (uint32_t)c) * 0x100000001B3ull;
    }
    printf("xgo_sincos digest 0x%016llx\n", (unsigned long long)digest);
    TEST_ASSERT_TRUE(digest == SINCOS_DIGEST);
}

/* The inline bodies (fixed.h, XGO_FIXED_INLINE: the kinematics' on a
 * 64-bit host) give the out-of-line functions' values, the narrow
 * atan2_64 case (both below 2^32, handed to the function) included:
 * random arguments of every bit length and sign, the len30 domain's
 * vectors, random angles. */
static void test_inline_bodies_are_the_functions(void)
{
    uint64_t state = 0x0DDBA11CAFEF00Dull;
    uint32_t k;
    for (k = 0; k < 1000000u; ++k) {
        const uint64_t a = xgo_test_xorshift64(&state);
        const uint64_t b = xgo_test_xorshift64(&state);
        const uint64_t c = xgo_test_xorshift64(&state);
        const uint64_t d = xgo_test_xorshift64(&state);
        const unsigned sy = xgo_test_xorshift64(&state) % 64u;
        const unsigned sx = xgo_test_xorshift64(&state) % 64u;
        const int64_t y = (int64_t)((a << 32) | b) >> sy, x = (int64_t)((c << 32) | d) >> sx;
        const int32_t ly = (int32_t)(a & 0x7FFFFFFFu) - (1 << 30), lx = (int32_t)(c & 0x7FFFFFFFu) - (1 << 30);
        TEST_ASSERT_EQUAL_UINT32(xgo_sqrt64_near((uint64_t)x), xgo_sqrt64_near_inline((uint64_t)x));
        TEST_ASSERT_EQUAL_UINT32(xgo_atan2_64(y, x), xgo_atan2_64_inline(y, x));
        {
            xgo_q30_t s, c, si, ci;
            xgo_sincos((xgo_bam_t)b, &s, &c);
            xgo_sincos_inline((xgo_bam_t)b, &si, &ci);
            TEST_ASSERT_EQUAL_INT32(s, si);
            TEST_ASSERT_EQUAL_INT32(c, ci);
        }
        const uint64_t len2 = (uint64_t)((int64_t)ly * ly) + (uint64_t)((int64_t)lx * lx);
        if (len2 >= (1ull << 58) && len2 <= (1ull << 60)) { /* length in [2^29, 2^30] */
            TEST_ASSERT_EQUAL_UINT32(xgo_atan2_len30(ly, lx), xgo_atan2_len30_inline(ly, lx));
        }
    }
}

/* The sine alone from the inline body (no cosine asked: the gait's swing
 * and a periodic motion's sine on a 64-bit host) is xgo_sin's: random
 * angles and every angle around the four quadrant edges. */
static void test_inline_sine_alone_is_xgo_sin(void)
{
    uint64_t state = 0x51DE5A11ull;
    uint32_t k;
    for (k = 0; k < 2000000u; ++k) {
        const xgo_bam_t a = k < 400000u ? (k / 100000u << 30) + (k % 100000u) - 50000u
                                        : (xgo_bam_t)xgo_test_xorshift64(&state);
        xgo_q30_t si;
        xgo_sincos_inline(a, &si, 0);
        TEST_ASSERT_EQUAL_INT32(xgo_sin(a), si);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_saturating_add_sub_neg_abs);
    RUN_TEST(test_mul_q_exact_rounding_and_saturation);
    RUN_TEST(test_div_q_and_muldiv);
    RUN_TEST(test_udiv64_cap_is_the_capped_quotient);
    RUN_TEST(test_isqrt_exact);
    RUN_TEST(test_sqrt64_near_within_units_of_the_floor);
    RUN_TEST(test_q16_sqrt_against_libm);
    RUN_TEST(test_angle_conversions);
    RUN_TEST(test_sincos_against_libm);
    RUN_TEST(test_sincos_near0_is_sincos);
    RUN_TEST(test_usquare_wide_is_the_product);
    RUN_TEST(test_atan2_against_libm);
    RUN_TEST(test_atan2_64_against_libm);
    RUN_TEST(test_atan2_len30_against_libm);
    RUN_TEST(test_asin_acos_against_libm);
    RUN_TEST(test_clz_forms); /* last: the others' random draws as before */
    RUN_TEST(test_mdeg_to_bam_every_short_value);
    RUN_TEST(test_atan2_64_same_bits_everywhere);
    RUN_TEST(test_sqrt64_near_same_bits_as_before);
    RUN_TEST(test_inline_bodies_are_the_functions);
    RUN_TEST(test_inline_sine_alone_is_xgo_sin);
    RUN_TEST(test_sincos_same_bits_as_before);
    return UNITY_END();
}
