/*
 * test_gait_arith.c - the gait's short-cut arithmetic (src/core/gait_internal.h)
 * against plain 64-bit arithmetic computed here, at the edges of the ranges
 * each short cut claims. The Cortex-M0 forms are the ones under test: this
 * file selects them on any host (XGO_WIDE_MUL_SPLIT, wide.h).
 */
#define XGO_WIDE_MUL_SPLIT 1

#include <stdint.h>

#include "unity.h"
#include "gait_internal.h"

void setUp(void) {}

void tearDown(void) {}

/* floor((a b + 2^(q-1)) / 2^q) with a 64-bit product, modulo 2^32 (as
 * mul_q wraps when the result does not fit). */
static int32_t reference_mul_q(int32_t a, int32_t b, unsigned q)
{
    int64_t p = (int64_t)a * b + ((int64_t)1 << (q - 1u));
    int64_t r = p >= 0 ? p / ((int64_t)1 << q) : -((-p + ((int64_t)1 << q) - 1) / ((int64_t)1 << q));
    uint32_t u = (uint32_t)(uint64_t)r;
    return u <= (uint32_t)INT32_MAX ? (int32_t)u : -(int32_t)(~u) - 1;
}

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s;
}

/* mul_q_u16 at the q this file's callers use (inline with a constant q, as
 * in gait.c). */
static int32_t short_mul(int32_t a, uint32_t b, unsigned q)
{
    switch (q) {
    case 1u: return mul_q_u16(a, b, 1u);
    case 8u: return mul_q_u16(a, b, 8u);
    case 16u: return mul_q_u16(a, b, 16u);
    case 17u: return mul_q_u16(a, b, 17u);
    case 30u: return mul_q_u16(a, b, 30u);
    default: return mul_q_u16(a, b, q);
    }
}

/* Every b edge, every a edge (the whole int32 range: where the result does
 * not fit, both wrap alike), ties and random values: same as the reference. */
static void test_mul_q_u16_matches_the_wide_product(void)
{
    static const uint32_t bs[] = { 0u, 1u, 2u, 0x7FFFu, 0x8000u, 0x8001u, 0xFFFEu, 0xFFFFu, 29491u, 39321u };
    static const unsigned qs[] = { 1u, 8u, 9u, 15u, 16u, 17u, 24u, 30u, 31u };
    static const int32_t edges[] = { INT32_MAX, INT32_MIN, INT32_MAX - 1, INT32_MIN + 1, 0, 1, -1,
                                     0x10000, -0x10000, 0xFFFF, -0xFFFF, 0x7FFF0000, -0x7FFF0000,
                                     (int32_t)0x8000FFFF, 0x7FFFFFFF - 0xFFFF };
    uint32_t seed = 12345u;
    unsigned checked = 0;
    size_t i, j, k;
    for (i = 0; i < sizeof qs / sizeof qs[0]; ++i) {
        const unsigned q = qs[i];
        for (j = 0; j < sizeof bs / sizeof bs[0]; ++j) {
            const uint32_t b = bs[j];
            /* a b just below, at and above a tie of the rounding */
            const int32_t tie = b == 0u ? 0 : (int32_t)(((int64_t)1 << (q - 1u)) / b);
            for (k = 0; k < sizeof edges / sizeof edges[0] + 3u + 3000u; ++k) {
                int32_t a;
                if (k < sizeof edges / sizeof edges[0]) {
                    a = edges[k];
                } else if (k < sizeof edges / sizeof edges[0] + 3u) {
                    a = tie - 1 + (int32_t)(k - sizeof edges / sizeof edges[0]);
                } else {
                    uint32_t r = lcg(&seed);
                    /* half of them small enough for the result to fit */
                    a = (k & 1u) ? (int32_t)r : (int32_t)r >> (lcg(&seed) >> 27);
                }
                TEST_ASSERT_EQUAL_INT32(reference_mul_q(a, (int32_t)b, q), short_mul(a, b, q));
                ++checked;
            }
        }
    }
    TEST_ASSERT_TRUE(checked > 200000u);
}

/* w x p's products: yaw rates and positions at the edges of the short form's
 * range, just outside it (the general product) and at random. */
static void test_mul_w_q24_matches_the_wide_product(void)
{
    static const int32_t ws[] = { 0, 1, -1, 0xFFFF, -0xFFFF, 0x10000, -0x10000, (1 << 26) - 1, -(1 << 26) + 1,
                                  -(1 << 26), 1 << 26, 58600000, -58600000, INT32_MAX, INT32_MIN };
    static const int32_t ps[] = { 0, 1, -1, 0xFFFF, -0xFFFF, 0x10000, -0x10000, (1 << 20) - 1, -(1 << 20) + 1,
                                  -(1 << 20), 1 << 20, 75000, -53500, INT32_MAX, INT32_MIN };
    uint32_t seed = 777u;
    size_t i, j;
    int k;
    for (i = 0; i < sizeof ws / sizeof ws[0]; ++i) {
        for (j = 0; j < sizeof ps / sizeof ps[0]; ++j) {
            TEST_ASSERT_EQUAL_INT32(reference_mul_q(ws[i], ps[j], 24u), mul_w_q24(ws[i], ps[j]));
        }
    }
    for (k = 0; k < 200000; ++k) {
        const int32_t w = (int32_t)lcg(&seed) >> (5 + (k & 3));  /* around |w| < 2^26 */
        const int32_t p = (int32_t)lcg(&seed) >> (10 + (k & 3)); /* around |p| < 2^20 */
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(w, p, 24u), mul_w_q24(w, p));
    }
}

/* A velocity as a tick's step: the pieces' form (|v| < 2^20) and the
 * product beyond, against the rounded wide product: the edges, every v
 * near 0 and random values of every length. */
static void test_ums_to_q8_tick_matches_the_wide_product(void)
{
    static const int32_t vs[] = { (1 << 20) - 1, -(1 << 20), 1 << 20, -(1 << 20) - 1, INT32_MAX, INT32_MIN,
                                  1000000, -1000000, 0x7FFFF, -0x80000 };
    uint32_t seed = 4242u;
    size_t i;
    int32_t v;
    int k;
    for (i = 0; i < sizeof vs / sizeof vs[0]; ++i) {
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(vs[i], K_UMS_TO_Q8_TICK_Q31, 31u), ums_to_q8_tick(vs[i]));
    }
    for (v = -70000; v <= 70000; ++v) {
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(v, K_UMS_TO_Q8_TICK_Q31, 31u), ums_to_q8_tick(v));
    }
    for (k = 0; k < 400000; ++k) {
        v = (int32_t)lcg(&seed) >> (k & 15);
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(v, K_UMS_TO_Q8_TICK_Q31, 31u), ums_to_q8_tick(v));
    }
}

/* The swing basis' product over its whole range: a in [0, 2^26], |b| <
 * 2^30, the edges and random pairs. */
static void test_mul_q26_unit_matches_the_wide_product(void)
{
    static const int32_t as[] = { 0, 1, 8191, 8192, (1 << 25), (1 << 26) - 1, 1 << 26 };
    static const int32_t bs[] = { 0, 1, -1, 8191, -8192, (1 << 30) - 1, -(1 << 30) + 1, -(1 << 30), 10 << 26,
                                  -(9 << 26), 3 << 26 };
    uint32_t seed = 2626u;
    size_t i, j;
    int k;
    for (i = 0; i < sizeof as / sizeof as[0]; ++i) {
        for (j = 0; j < sizeof bs / sizeof bs[0]; ++j) {
            TEST_ASSERT_EQUAL_INT32(reference_mul_q(as[i], bs[j], 26u), mul_q26_unit(as[i], bs[j]));
        }
    }
    for (k = 0; k < 1000000; ++k) {
        const int32_t a = (int32_t)(lcg(&seed) % ((1u << 26) + 1u)) >> (k & 7);
        const int32_t b = (int32_t)lcg(&seed) >> (2 + (k & 7));
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(a, b, 26u), mul_q26_unit(a, b));
    }
}

/* A weight times a span: the pieces where both fit (|w| < 2^27, |b| <
 * 2^29), mul_q beyond; the edges either side and random pairs. */
static void test_mul_q26_weight_matches_the_wide_product(void)
{
    static const int32_t ws[] = { 0, 1, -1, 8191, -8192, 1 << 26, -(1 << 26), (1 << 27) - 1, -(1 << 27),
                                  1 << 27, -(1 << 27) - 1, INT32_MAX, INT32_MIN };
    static const int32_t bs[] = { 0, 1, -1, 8191, -8192, (1 << 29) - 1, -(1 << 29), 1 << 29, -(1 << 29) - 1,
                                  51200000, -51200000, INT32_MAX, INT32_MIN };
    uint32_t seed = 2727u;
    size_t i, j;
    int k;
    for (i = 0; i < sizeof ws / sizeof ws[0]; ++i) {
        for (j = 0; j < sizeof bs / sizeof bs[0]; ++j) {
            TEST_ASSERT_EQUAL_INT32(reference_mul_q(ws[i], bs[j], 26u), mul_q26_weight(ws[i], bs[j]));
        }
    }
    for (k = 0; k < 1000000; ++k) {
        const int32_t w = (int32_t)lcg(&seed) >> (3 + (k & 7));
        const int32_t b = (int32_t)lcg(&seed) >> (1 + ((k >> 3) & 7));
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(w, b, 26u), mul_q26_weight(w, b));
    }
}

/* A sine's square: every value near 0 and both ends, random ones between. */
static void test_square_q30_matches_the_wide_product(void)
{
    uint32_t seed = 3030u;
    int32_t s;
    int k;
    for (s = -100000; s <= 100000; ++s) {
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(s, s, 30u), square_q30(s));
        TEST_ASSERT_EQUAL_INT32(reference_mul_q((1 << 30) - s - 100000, (1 << 30) - s - 100000, 30u),
                                square_q30((1 << 30) - s - 100000));
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(-(1 << 30) + s + 100000, -(1 << 30) + s + 100000, 30u),
                                square_q30(-(1 << 30) + s + 100000));
    }
    for (k = 0; k < 1000000; ++k) {
        s = (int32_t)lcg(&seed) >> (1 + (k & 15));
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(s, s, 30u), square_q30(s));
    }
}

/* The yaw widening: every yaw rate up to the reference, and beyond it (the
 * share saturates), against the division gait.h states. */
static void test_yaw_widening_is_the_exact_division(void)
{
    int32_t w;
    for (w = -XGO_GAIT_YAW_REF_MDEG_S - 1000; w <= XGO_GAIT_YAW_REF_MDEG_S + 1000; ++w) {
        int64_t yaw = w < 0 ? -(int64_t)w : w;
        int64_t expect = (yaw > XGO_GAIT_YAW_REF_MDEG_S ? XGO_GAIT_YAW_REF_MDEG_S : yaw) *
                         XGO_GAIT_YAW_REACH_Y_UM / XGO_GAIT_YAW_REF_MDEG_S;
        TEST_ASSERT_EQUAL_UINT32((uint32_t)expect, gait_yaw_widening_um(w));
    }
    TEST_ASSERT_EQUAL_UINT32(XGO_GAIT_YAW_REACH_Y_UM, gait_yaw_widening_um(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT32(XGO_GAIT_YAW_REACH_Y_UM, gait_yaw_widening_um(INT32_MAX));
}

/* The velocity scaling by a Q16 factor (cadence cap, governor): random
 * values of every magnitude and the edges, against the 64-bit product and
 * C's division. */
static void test_scale_q16_is_the_truncated_wide_product(void)
{
    static const int32_t edges[] = {INT32_MIN + 1, -65537, -65536, -65535, -1, 0, 1,
                                    65535, 65536, 65537, INT32_MAX};
    uint32_t seed = 7u;
    unsigned k, e;
    for (k = 0; k < 400000; ++k) {
        const int32_t v = (int32_t)lcg(&seed) >> (k % 31u);
        const int32_t lambda = (int32_t)(lcg(&seed) % 65537u);
        TEST_ASSERT_EQUAL_INT32((int32_t)(((int64_t)v * lambda) / 65536), gait_scale_q16(v, lambda));
    }
    for (e = 0; e < sizeof edges / sizeof edges[0]; ++e) {
        int32_t lambda;
        for (lambda = 0; lambda <= 65536; ++lambda) {
            TEST_ASSERT_EQUAL_INT32((int32_t)(((int64_t)edges[e] * lambda) / 65536),
                                    gait_scale_q16(edges[e], lambda));
        }
    }
}

/* yaw_q24's split constant: every edge and random rates of every size,
 * against the full rounded product (mod 2^32, as mul_q). */
static void test_yaw_q24_is_the_rounded_product(void)
{
    static const int32_t edges[] = {INT32_MIN, INT32_MIN + 1, -200001, -200000, -65537, -65536, -1,
                                    0, 1, 65535, 65536, 200000, 200001, INT32_MAX};
    uint32_t seed = 5u;
    unsigned k, e;
    for (e = 0; e < sizeof edges / sizeof edges[0]; ++e) {
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(edges[e], K_MDEG_TO_RAD_Q24_Q16, 16u), yaw_q24(edges[e]));
    }
    for (k = 0; k < 1000000; ++k) {
        const int32_t w = (int32_t)lcg(&seed) >> (k % 32u);
        TEST_ASSERT_EQUAL_INT32(reference_mul_q(w, K_MDEG_TO_RAD_Q24_Q16, 16u), yaw_q24(w));
    }
}

/* The transient rule's 32-bit settlement (gait_quick_fit) never settles a
 * case where s r > TICKS_PER_S d rate, and settles most of the far ones:
 * random values of every magnitude, the guards' edges and near misses. */
static void test_quick_fit_only_settles_fitting_feet(void)
{
    static const uint32_t s_edge[] = {0u, 1u, (1u << 20) - 1u, 1u << 20, 0xFFFFFFFFu};
    static const uint32_t d_edge[] = {1u, (1u << 17) - 1u, 1u << 17, 0xFFFFFFFFu};
    static const uint32_t rate_edge[] = {0u, (1u << 20) - 1u, 1u << 20, (64u << 20) - 1u, 64u << 20,
                                         0xFFFFFFFFu};
    uint32_t seed = 11u;
    unsigned k, a, b, c, settled = 0;
    for (k = 0; k < 2000000; ++k) {
        const uint32_t s = lcg(&seed) >> (k % 32u);
        const uint32_t r = lcg(&seed);
        const uint32_t d = lcg(&seed) >> (12u + k % 20u);
        const uint32_t rate = lcg(&seed) >> (4u + k % 8u);
        const int fits = (uint64_t)s * r <= (uint64_t)TICKS_PER_S * d * rate;
        if (gait_quick_fit(s, r, d, rate)) {
            TEST_ASSERT_TRUE(fits);
            settled++;
        }
    }
    TEST_ASSERT_TRUE(settled > 100000u);
    for (a = 0; a < sizeof s_edge / sizeof s_edge[0]; ++a) {
        for (b = 0; b < sizeof d_edge / sizeof d_edge[0]; ++b) {
            for (c = 0; c < sizeof rate_edge / sizeof rate_edge[0]; ++c) {
                const uint32_t r[] = {0u, (1u << 20) - 1u, 1u << 20, 0xFFFFFFFFu};
                unsigned i;
                for (i = 0; i < 4u; ++i) {
                    if (gait_quick_fit(s_edge[a], r[i], d_edge[b], rate_edge[c])) {
                        TEST_ASSERT_TRUE((uint64_t)s_edge[a] * r[i] <=
                                         (uint64_t)TICKS_PER_S * d_edge[b] * rate_edge[c]);
                    }
                }
            }
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mul_q_u16_matches_the_wide_product);
    RUN_TEST(test_mul_w_q24_matches_the_wide_product);
    RUN_TEST(test_ums_to_q8_tick_matches_the_wide_product);
    RUN_TEST(test_mul_q26_unit_matches_the_wide_product);
    RUN_TEST(test_mul_q26_weight_matches_the_wide_product);
    RUN_TEST(test_square_q30_matches_the_wide_product);
    RUN_TEST(test_yaw_widening_is_the_exact_division);
    RUN_TEST(test_scale_q16_is_the_truncated_wide_product);
    RUN_TEST(test_quick_fit_only_settles_fitting_feet);
    RUN_TEST(test_yaw_q24_is_the_rounded_product);
    return UNITY_END();
}
