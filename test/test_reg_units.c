/*
 * Register bytes <-> physical values (xgo/reg_units.h): every byte of every
 * register with a unit against a double-precision reference written here
 * from the vendor's ranges (not from the core's tables), the nearest-byte
 * encoding, out-of-range refusals, "off" bytes and registers without a unit.
 */
#include <math.h>
#include <string.h>

#include "regfile.h" /* the register file itself, for the attitude view */
#include "unity.h"
#include "xgo/profile.h"
#include "xgo/reg_units.h"
#include "xgo/regs.h"

void setUp(void)
{
}

void tearDown(void)
{
}

/* The vendor library's map of [lo, hi] onto 0..255, decoded. */
static double ref_linear(double lo, double hi, unsigned b)
{
    return lo + (double)b * (hi - lo) / 255.0;
}

/* Signed registers: the same map over [-limit, limit], 0x7F and 0x80 both 0. */
static double ref_signed(double limit, unsigned b)
{
    return (b == 0x7Fu || b == 0x80u) ? 0.0 : ref_linear(-limit, limit, b);
}

typedef struct {
    uint8_t addr;
    xgo_unit_t unit;
    char kind;      /* 's' signed, 'l' linear, 'p' period, 'm' mark time, 'a' attitude, 'i' identity */
    double lo, hi;  /* Mini, vendor numbers (docs/geometry.md, vendor-client-facts) */
} ref_reg_t;

static const ref_reg_t k_mini[] = {
    {0x01, XGO_UNIT_PERCENT, 'i', 0, 255},
    {0x30, XGO_UNIT_UM_S, 's', -250000, 250000},
    {0x31, XGO_UNIT_UM_S, 's', -180000, 180000},
    {0x32, XGO_UNIT_MDEG_S, 's', -100000, 100000},
    {0x33, XGO_UNIT_UM, 's', -35000, 35000},
    {0x34, XGO_UNIT_UM, 's', -19500, 19500},
    {0x35, XGO_UNIT_UM, 'l', 75000, 120000},
    {0x36, XGO_UNIT_MDEG, 's', -20000, 20000},
    {0x37, XGO_UNIT_MDEG, 's', -22000, 22000},
    {0x38, XGO_UNIT_MDEG, 's', -16000, 16000},
    {0x39, XGO_UNIT_MS, 'p', 1500, 8000},
    {0x3A, XGO_UNIT_MS, 'p', 1500, 8000},
    {0x3B, XGO_UNIT_MS, 'p', 1500, 8000},
    {0x3C, XGO_UNIT_UM, 'm', 10000, 35000},
    {0x40, XGO_UNIT_UM, 's', -35000, 35000},
    {0x41, XGO_UNIT_UM, 's', -18000, 18000},
    {0x42, XGO_UNIT_UM, 'l', 75000, 115000},
    {0x4B, XGO_UNIT_UM, 'l', 75000, 115000},
    {0x50, XGO_UNIT_MDEG, 'l', -73000, 57000},
    {0x51, XGO_UNIT_MDEG, 'l', -66000, 93000},
    {0x52, XGO_UNIT_MDEG, 'l', -31000, 31000},
    {0x5B, XGO_UNIT_MDEG, 'l', -31000, 31000},
    {0x5C, XGO_UNIT_MDEG_S, 'l', 10000, 600000},
    {0x62, XGO_UNIT_MDEG, 'a', 0, 0},
    {0x64, XGO_UNIT_MDEG, 'a', 0, 0},
    {0x80, XGO_UNIT_MS, 'p', 1500, 8000},
    {0x82, XGO_UNIT_MS, 'p', 1500, 8000},
};

static double ref_value(const ref_reg_t *r, unsigned b)
{
    switch (r->kind) {
    case 's': return ref_signed(r->hi, b);
    case 'l': return ref_linear(r->lo, r->hi, b);
    case 'p': return b == 0 ? 0.0 : ref_linear(r->lo, r->hi, b);
    case 'm': return b == 0 ? 0.0 : ref_linear(r->lo, r->hi, b);
    case 'a': return ((double)b - 128.0) * 180000.0 / 128.0;
    default: return (double)b;
    }
}

static void test_every_byte_decodes_like_the_reference(void)
{
    size_t i;
    unsigned b;
    for (i = 0; i < sizeof k_mini / sizeof k_mini[0]; i++) {
        const ref_reg_t *r = &k_mini[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(r->unit, xgo_reg_unit(r->addr), xgo_reg_name(r->addr));
        for (b = 0; b < 256; b++) {
            int32_t v = 0x7FFFFFFF;
            TEST_ASSERT_TRUE(xgo_reg_byte_to_value(NULL, r->addr, (uint8_t)b, &v));
            /* the core rounds up to the next unit: within one um / mdeg / ms */
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1.0, ref_value(r, b), (double)v, xgo_reg_name(r->addr));
        }
    }
}

static void test_issue_examples(void)
{
    int32_t v;
    uint8_t b;
    TEST_ASSERT_TRUE(xgo_reg_byte_to_value(NULL, 0x30, 0xFF, &v));
    TEST_ASSERT_EQUAL_INT32(250000, v); /* vx 0xff = +25.0 cm/s */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x30, 125000, &b));
    /* 12.5 cm/s lies between 0xBF (12.45) and 0xC0 (12.65): 0xBF is nearer */
    TEST_ASSERT_EQUAL_HEX8(0xBF, b);
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x36, -10000, &b));
    TEST_ASSERT_EQUAL_HEX8(0x40, b); /* roll -10 deg: -9.96 (0x40) beats -10.12 (0x3F) */
}

/* The byte chosen is the nearest by the reference, for a sweep of values. */
static void test_encoding_picks_the_nearest_byte(void)
{
    size_t i;
    for (i = 0; i < sizeof k_mini / sizeof k_mini[0]; i++) {
        const ref_reg_t *r = &k_mini[i];
        int32_t lo, hi, v;
        TEST_ASSERT_TRUE(xgo_reg_value_range(NULL, r->addr, &lo, &hi));
        for (v = lo; v <= hi; v += (hi - lo) / 997 + 1) {
            uint8_t b = 0;
            unsigned k;
            double err;
            TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, r->addr, v, &b));
            err = fabs(ref_value(r, b) - v);
            for (k = (r->kind == 'p' || r->kind == 'm') ? 1u : 0u; k < 256; k++) {
                /* none nearer by more than the core's rounding (1 unit each) */
                TEST_ASSERT_TRUE_MESSAGE(fabs(ref_value(r, k) - v) + 2.0 >= err,
                                         xgo_reg_name(r->addr));
            }
        }
    }
}

static void test_out_of_range_values_are_refused(void)
{
    uint8_t b = 0x55;
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x30, 250001, &b));
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x30, -250001, &b));
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x50, 57001, &b));
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x35, 74999, &b));
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x39, 1000, &b));
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x39, 8001, &b));
    TEST_ASSERT_EQUAL_HEX8(0x55, b); /* untouched */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x30, 250000, &b));
    TEST_ASSERT_EQUAL_HEX8(0xFF, b);
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x30, -250000, &b));
    TEST_ASSERT_EQUAL_HEX8(0x00, b);
}

static void test_zero_and_off(void)
{
    uint8_t b = 0;
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x30, 0, &b));
    TEST_ASSERT_EQUAL_HEX8(0x80, b); /* the tie 0x7F / 0x80 goes to 0x80 */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x39, 0, &b));
    TEST_ASSERT_EQUAL_HEX8(0x00, b); /* period off */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x39, 1500, &b));
    TEST_ASSERT_EQUAL_HEX8(0x01, b); /* the shortest period is byte 1 */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OK, xgo_reg_value_to_byte(NULL, 0x3C, 0, &b));
    TEST_ASSERT_EQUAL_HEX8(0x00, b); /* mark time off */
    TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_OUT_OF_RANGE, xgo_reg_value_to_byte(NULL, 0x3C, 5000, &b));
}

static void test_registers_without_unit(void)
{
    static const uint8_t none[] = {0x00, 0x02, 0x03, 0x07, 0x09, 0x13, 0x20, 0x21, 0x3D,
                                   0x3E, 0x5D, 0x61, 0x90, 0xC4, 0xD0, 0xFF};
    size_t i;
    for (i = 0; i < sizeof none; i++) {
        int32_t v = 12345;
        uint8_t b = 0x55;
        TEST_ASSERT_EQUAL_INT(XGO_UNIT_NONE, xgo_reg_unit(none[i]));
        TEST_ASSERT_FALSE(xgo_reg_byte_to_value(NULL, none[i], 0x10, &v));
        TEST_ASSERT_EQUAL_INT32(12345, v);
        TEST_ASSERT_EQUAL_INT(XGO_REG_VALUE_NO_UNIT, xgo_reg_value_to_byte(NULL, none[i], 0, &b));
        TEST_ASSERT_EQUAL_HEX8(0x55, b);
    }
}

/* The Lite's ranges differ: the profile is honoured. */
static void test_lite_profile_ranges(void)
{
    int32_t lo, hi, v;
    const xgo_profile_t *lite = xgo_profile_lite();
    TEST_ASSERT_TRUE(xgo_reg_value_range(lite, 0x50, &lo, &hi));
    TEST_ASSERT_EQUAL_INT32(-70000, lo);
    TEST_ASSERT_EQUAL_INT32(50000, hi);
    TEST_ASSERT_TRUE(xgo_reg_byte_to_value(lite, 0x37, 0xFF, &v));
    TEST_ASSERT_EQUAL_INT32(10000, v); /* Lite pitch +-10 deg */
    TEST_ASSERT_TRUE(xgo_reg_value_range(lite, 0x3C, &lo, &hi));
    TEST_ASSERT_EQUAL_INT32(25000, hi);
}

/* Attitude: the decoding is the exact inverse of the one-byte view. */
static void test_attitude_matches_register_view(void)
{
    xgo_regs_t r;
    unsigned b;
    xgo_regs_init(&r, "T", 0);
    for (b = 0; b < 256; b++) {
        int32_t mdeg;
        uint8_t got;
        TEST_ASSERT_TRUE(xgo_reg_byte_to_value(NULL, 0x62, (uint8_t)b, &mdeg));
        xgo_regs_set_attitude(&r, mdeg, 0, 0);
        TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&r, 0x62, 1, &got));
        TEST_ASSERT_EQUAL_HEX8(b, got);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_byte_decodes_like_the_reference);
    RUN_TEST(test_issue_examples);
    RUN_TEST(test_encoding_picks_the_nearest_byte);
    RUN_TEST(test_out_of_range_values_are_refused);
    RUN_TEST(test_zero_and_off);
    RUN_TEST(test_registers_without_unit);
    RUN_TEST(test_lite_profile_ranges);
    RUN_TEST(test_attitude_matches_register_view);
    return UNITY_END();
}
