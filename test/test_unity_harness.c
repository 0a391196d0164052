/*
 * Self-test of the test harness (test/unity): every assertion macro in a
 * passing case, plus the bookkeeping around tests (setUp/tearDown around each
 * test, ignored tests counted as ignored, TEST_PASS ending a test early).
 * The deliberately failing counterpart is test_unity_harness_fail.c.
 *
 * Uses only the Unity API (and the Unity state struct fields upstream has
 * too), so it also builds against upstream Unity (XGO_UNITY_DIR).
 */
#include "unity.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

static unsigned setup_calls;
static unsigned teardown_calls;
static unsigned tests_started;      /* incremented by each test body that starts */
static int reached_after_ignore;    /* must stay 0 */
static int reached_after_pass;      /* must stay 0 */
static int ignore_in_setup;         /* makes setUp ignore the next test */
static int body_ran_after_setup_ignore; /* must stay 0 */

void setUp(void)
{
    setup_calls++;
    if (ignore_in_setup) {
        ignore_in_setup = 0;
        TEST_IGNORE_MESSAGE("ignored from setUp");
    }
}

void tearDown(void)
{
    teardown_calls++;
}

/* setUp has run exactly once more than tearDown whenever a test body runs. */
static void check_setup_before_body(void)
{
    tests_started++;
    TEST_ASSERT_EQUAL_UINT(teardown_calls + 1u, setup_calls);
}

static void test_booleans_and_pointers(void)
{
    int x = 3;
    int *p = &x;
    int *nothing = NULL;

    check_setup_before_body();
    TEST_ASSERT(x == 3);
    TEST_ASSERT_MESSAGE(x == 3, "x is three");
    TEST_ASSERT_TRUE(x > 0);
    TEST_ASSERT_TRUE_MESSAGE(x > 0, "positive");
    TEST_ASSERT_FALSE(x < 0);
    TEST_ASSERT_FALSE_MESSAGE(x < 0, "not negative");
    TEST_ASSERT_UNLESS(x == 4);
    TEST_ASSERT_UNLESS_MESSAGE(x == 4, "not four");
    TEST_ASSERT_NULL(nothing);
    TEST_ASSERT_NULL_MESSAGE(nothing, "null");
    TEST_ASSERT_NOT_NULL(p);
    TEST_ASSERT_NOT_NULL_MESSAGE(p, "not null");
    TEST_ASSERT_EQUAL_PTR(&x, p);
    TEST_ASSERT_EQUAL_PTR_MESSAGE(&x, p, "same pointer");
    TEST_ASSERT_NOT_EQUAL(1, x);
    TEST_ASSERT_NOT_EQUAL_MESSAGE(1, x, "differs");
}

static void test_equal_integers(void)
{
    check_setup_before_body();
    TEST_ASSERT_EQUAL(5, 2 + 3);
    TEST_ASSERT_EQUAL_MESSAGE(5, 2 + 3, "sum");
    TEST_ASSERT_EQUAL_INT(-7, -7);
    TEST_ASSERT_EQUAL_INT_MESSAGE(-7, -7, "int");
    TEST_ASSERT_EQUAL_INT8(-1, 255);              /* both are -1 as int8 */
    TEST_ASSERT_EQUAL_INT8_MESSAGE(-128, 128, "int8 wraps");
    TEST_ASSERT_EQUAL_INT16(-2, 0xFFFE);
    TEST_ASSERT_EQUAL_INT16_MESSAGE(INT16_MIN, INT16_MIN, "int16");
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, INT32_MIN);
    TEST_ASSERT_EQUAL_INT32_MESSAGE(-100000, -100000, "int32");
    TEST_ASSERT_EQUAL_INT64(INT64_MIN, INT64_MIN);
    TEST_ASSERT_EQUAL_INT64_MESSAGE((int64_t)1 << 40, (int64_t)1 << 40, "int64");
    TEST_ASSERT_EQUAL_UINT(7u, 7u);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(7u, 7u, "uint");
    TEST_ASSERT_EQUAL_UINT8(0x12, 0x312);         /* only the low byte counts */
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(255, -1, "uint8");
    TEST_ASSERT_EQUAL_UINT16(65535u, 65535u);
    TEST_ASSERT_EQUAL_UINT16_MESSAGE(1u, 0x10001u, "uint16");
    TEST_ASSERT_EQUAL_UINT32(UINT32_MAX, UINT32_MAX);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, 0u, "uint32");
    TEST_ASSERT_EQUAL_UINT64(UINT64_MAX, UINT64_MAX);
    TEST_ASSERT_EQUAL_UINT64_MESSAGE((uint64_t)1 << 63, (uint64_t)1 << 63, "uint64");
    TEST_ASSERT_EQUAL_HEX8(0xA5, 0xA5);
    TEST_ASSERT_EQUAL_HEX8_MESSAGE(0x5A, 0x5A, "hex8");
    TEST_ASSERT_EQUAL_HEX16(0xBEEF, 0xBEEF);
    TEST_ASSERT_EQUAL_HEX16_MESSAGE(0x1234, 0x1234, "hex16");
    TEST_ASSERT_EQUAL_HEX32(0xDEADBEEFu, 0xDEADBEEFu);
    TEST_ASSERT_EQUAL_HEX32_MESSAGE(0x0u, 0x0u, "hex32");
    TEST_ASSERT_EQUAL_HEX(0x55AAu, 0x55AAu);
    TEST_ASSERT_EQUAL_HEX64(0x0123456789ABCDEFu, 0x0123456789ABCDEFu);
}

static void test_not_equal_integers(void)
{
    check_setup_before_body();
    TEST_ASSERT_NOT_EQUAL_INT(1, 2);
    TEST_ASSERT_NOT_EQUAL_INT_MESSAGE(-1, 1, "int");
    TEST_ASSERT_NOT_EQUAL_INT8(0, 1);
    TEST_ASSERT_NOT_EQUAL_UINT(0u, 1u);
    TEST_ASSERT_NOT_EQUAL_UINT8_MESSAGE(0u, 1u, "uint8");
    TEST_ASSERT_NOT_EQUAL_HEX16(0x1234, 0x4321);
}

static void test_ordering(void)
{
    check_setup_before_body();
    /* GREATER_THAN(threshold, actual): actual > threshold */
    TEST_ASSERT_GREATER_THAN(5, 6);
    TEST_ASSERT_GREATER_THAN_MESSAGE(-5, 0, "gt");
    TEST_ASSERT_GREATER_THAN_INT(-10, -9);
    TEST_ASSERT_GREATER_THAN_INT_MESSAGE(0, 1, "gt int");
    TEST_ASSERT_GREATER_THAN_INT8(-128, 127);
    TEST_ASSERT_GREATER_THAN_INT16(-1, 0);
    TEST_ASSERT_GREATER_THAN_INT32(INT32_MIN, INT32_MAX);
    TEST_ASSERT_GREATER_THAN_INT64(INT64_MIN, 0);
    TEST_ASSERT_GREATER_THAN_UINT(5u, 6u);
    TEST_ASSERT_GREATER_THAN_UINT_MESSAGE(0u, 0xFFFFFFFFu, "gt uint");
    TEST_ASSERT_GREATER_THAN_UINT8(1u, 255u);
    TEST_ASSERT_GREATER_THAN_UINT16(1u, 65535u);
    TEST_ASSERT_GREATER_THAN_UINT32(0x7FFFFFFFu, 0x80000000u);
    TEST_ASSERT_GREATER_THAN_UINT64(0u, UINT64_MAX);
    TEST_ASSERT_GREATER_THAN_HEX8(0x7F, 0x80);
    TEST_ASSERT_GREATER_THAN_HEX64(0x7FFFFFFFFFFFFFFFu, 0x8000000000000000u);

    TEST_ASSERT_LESS_THAN(6, 5);
    TEST_ASSERT_LESS_THAN_MESSAGE(0, -5, "lt");
    TEST_ASSERT_LESS_THAN_INT(-9, -10);
    TEST_ASSERT_LESS_THAN_INT_MESSAGE(1, 0, "lt int");
    TEST_ASSERT_LESS_THAN_UINT(6u, 5u);
    TEST_ASSERT_LESS_THAN_UINT_MESSAGE(0xFFFFFFFFu, 0u, "lt uint");
    TEST_ASSERT_LESS_THAN_UINT8(255u, 1u);
    TEST_ASSERT_LESS_THAN_INT32(0, -1);

    TEST_ASSERT_GREATER_OR_EQUAL(5, 5);
    TEST_ASSERT_GREATER_OR_EQUAL(5, 6);
    TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(5, 5, "ge");
    TEST_ASSERT_GREATER_OR_EQUAL_INT(-3, -3);
    TEST_ASSERT_GREATER_OR_EQUAL_INT_MESSAGE(-3, 3, "ge int");
    TEST_ASSERT_GREATER_OR_EQUAL_UINT(3u, 3u);
    TEST_ASSERT_GREATER_OR_EQUAL_UINT_MESSAGE(3u, 4u, "ge uint");

    TEST_ASSERT_LESS_OR_EQUAL(5, 5);
    TEST_ASSERT_LESS_OR_EQUAL(5, 4);
    TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(5, 5, "le");
    TEST_ASSERT_LESS_OR_EQUAL_INT(3, -3);
    TEST_ASSERT_LESS_OR_EQUAL_INT_MESSAGE(3, 3, "le int");
    TEST_ASSERT_LESS_OR_EQUAL_UINT(3u, 3u);
    TEST_ASSERT_LESS_OR_EQUAL_UINT_MESSAGE(4u, 3u, "le uint");
}

static void test_within(void)
{
    check_setup_before_body();
    TEST_ASSERT_INT_WITHIN(2, 100, 98);
    TEST_ASSERT_INT_WITHIN(2, 100, 102);
    TEST_ASSERT_INT_WITHIN_MESSAGE(0, -5, -5, "int within");
    TEST_ASSERT_INT8_WITHIN(1, -128, -127);
    TEST_ASSERT_INT16_WITHIN(10, -30000, -29990);
    TEST_ASSERT_INT32_WITHIN(5, -1000, -996);
    TEST_ASSERT_INT32_WITHIN_MESSAGE(5, INT32_MAX, INT32_MAX - 5, "int32 within");
    TEST_ASSERT_INT64_WITHIN(1, INT64_MIN, INT64_MIN + 1);
    TEST_ASSERT_UINT_WITHIN(3u, 10u, 7u);
    TEST_ASSERT_UINT_WITHIN(3u, 10u, 13u);
    TEST_ASSERT_UINT_WITHIN_MESSAGE(0u, 10u, 10u, "uint within");
    TEST_ASSERT_UINT8_WITHIN(5u, 250u, 255u);
    TEST_ASSERT_UINT16_WITHIN(1u, 0u, 1u);
    TEST_ASSERT_UINT32_WITHIN(1u, 0xFFFFFFFFu, 0xFFFFFFFEu);
    TEST_ASSERT_UINT64_WITHIN(2u, UINT64_MAX, UINT64_MAX - 2u);
    TEST_ASSERT_HEX8_WITHIN(1u, 0x10u, 0x11u);
    TEST_ASSERT_HEX16_WITHIN(0x10u, 0x1000u, 0x0FF0u);
    TEST_ASSERT_HEX32_WITHIN(1u, 0x80000000u, 0x7FFFFFFFu);
    TEST_ASSERT_HEX_WITHIN(1u, 0x80000000u, 0x7FFFFFFFu);
}

static void test_bits(void)
{
    check_setup_before_body();
    TEST_ASSERT_BITS(0xF0u, 0x5Au, 0x53u);        /* high nibbles equal */
    TEST_ASSERT_BITS_MESSAGE(0x0Fu, 0xA3u, 0x13u, "low nibble");
    TEST_ASSERT_BITS_HIGH(0x81u, 0xC3u);
    TEST_ASSERT_BITS_LOW(0x3Cu, 0xC3u);
    TEST_ASSERT_BIT_HIGH(7, 0x80u);
    TEST_ASSERT_BIT_LOW(0, 0xFEu);
    TEST_ASSERT_BIT_HIGH_MESSAGE(31, 0x80000000u, "bit 31");
}

static void test_arrays(void)
{
    static const uint8_t frame[] = { 0x55, 0x00, 0x09, 0x01, 0xAA };
    uint8_t copy[sizeof frame];
    const int ints[] = { -1, 0, 1, 2147483647 };
    const int ints2[] = { -1, 0, 1, 2147483647 };
    const int8_t i8[] = { -128, 127 };
    const int16_t i16[] = { -32768, 32767 };
    const int32_t i32[] = { INT32_MIN, INT32_MAX };
    const int64_t i64[] = { INT64_MIN, INT64_MAX };
    const unsigned u[] = { 0u, 0xFFFFFFFFu };
    const uint16_t u16[] = { 0u, 0xFFFFu, 0x8000u };
    const uint32_t u32[] = { 0u, 0xFFFFFFFFu };
    const uint64_t u64[] = { 0u, UINT64_MAX };
    const uint16_t h16[] = { 0xBEEFu };
    const uint32_t h32[] = { 0xDEADBEEFu };
    const uint64_t h64[] = { 0x0123456789ABCDEFu };
    const uint8_t zeros[] = { 0, 0, 0 };
    const int sevens[] = { 7, 7, 7, 7 };
    size_t i;

    check_setup_before_body();
    for (i = 0; i < sizeof frame; i++) {
        copy[i] = frame[i];
    }
    TEST_ASSERT_EQUAL_HEX8_ARRAY(frame, copy, sizeof frame);
    TEST_ASSERT_EQUAL_HEX8_ARRAY_MESSAGE(frame, copy, sizeof frame, "frame");
    TEST_ASSERT_EQUAL_UINT8_ARRAY(frame, copy, sizeof frame);
    TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(frame, copy, 2, "prefix");
    TEST_ASSERT_EQUAL_INT_ARRAY(ints, ints2, 4);
    TEST_ASSERT_EQUAL_INT_ARRAY_MESSAGE(ints, ints2, 4, "ints");
    TEST_ASSERT_EQUAL_INT_ARRAY(ints, ints, 4);           /* same pointer */
    TEST_ASSERT_EQUAL_INT8_ARRAY(i8, i8, 2);
    TEST_ASSERT_EQUAL_INT16_ARRAY(i16, i16, 2);
    TEST_ASSERT_EQUAL_INT32_ARRAY(i32, i32, 2);
    TEST_ASSERT_EQUAL_INT64_ARRAY(i64, i64, 2);
    TEST_ASSERT_EQUAL_UINT_ARRAY(u, u, 2);
    TEST_ASSERT_EQUAL_UINT16_ARRAY(u16, u16, 3);
    TEST_ASSERT_EQUAL_UINT32_ARRAY(u32, u32, 2);
    TEST_ASSERT_EQUAL_UINT64_ARRAY(u64, u64, 2);
    TEST_ASSERT_EQUAL_HEX16_ARRAY(h16, h16, 1);
    TEST_ASSERT_EQUAL_HEX32_ARRAY(h32, h32, 1);
    TEST_ASSERT_EQUAL_HEX_ARRAY(h32, h32, 1);
    TEST_ASSERT_EQUAL_HEX64_ARRAY(h64, h64, 1);
    TEST_ASSERT_EACH_EQUAL_UINT8(0, zeros, 3);
    TEST_ASSERT_EACH_EQUAL_HEX8_MESSAGE(0x00, zeros, 3, "zeros");
    TEST_ASSERT_EACH_EQUAL_INT(7, sevens, 4);
}

static void test_memory_and_strings(void)
{
    struct pair { uint16_t a; uint16_t b; };
    const struct pair p1[2] = { { 1, 2 }, { 3, 4 } };
    const struct pair p2[2] = { { 1, 2 }, { 3, 4 } };
    char buf[8] = "servo";

    check_setup_before_body();
    TEST_ASSERT_EQUAL_MEMORY(&p1[0], &p2[0], sizeof p1[0]);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(p1, p2, sizeof p1, "pairs");
    TEST_ASSERT_EQUAL_MEMORY_ARRAY(p1, p2, sizeof p1[0], 2);
    TEST_ASSERT_EQUAL_MEMORY_ARRAY_MESSAGE(p1, p2, sizeof p1[0], 2, "pairs array");
    TEST_ASSERT_EQUAL_STRING("servo", buf);
    TEST_ASSERT_EQUAL_STRING_MESSAGE("servo", buf, "name");
    TEST_ASSERT_EQUAL_STRING(NULL, NULL);
    TEST_ASSERT_EQUAL_STRING_LEN("serial", buf, 3);        /* "ser" */
    TEST_ASSERT_EQUAL_STRING_LEN_MESSAGE("servomotor", buf, 5, "prefix");
    TEST_ASSERT_EQUAL_STRING_LEN("ab", "ab", 100);          /* stops at the NULs */
}

static void test_floating_point(void)
{
    volatile double third = 1.0 / 3.0;
    volatile float f = 0.1f;

    check_setup_before_body();
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.333333333, third);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.5, 10.0, 10.5, "edge of delta");
    TEST_ASSERT_DOUBLE_WITHIN(-0.5, 10.0, 9.5);              /* |delta| is used */
    TEST_ASSERT_EQUAL_DOUBLE(1.0 / 3.0, third);
    TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(0.0, 0.0, "zero");
    TEST_ASSERT_EQUAL_DOUBLE(-2.5e300, -2.5e300);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.1f, f);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.25f, 1.0f, 0.75f, "float");
    TEST_ASSERT_EQUAL_FLOAT(0.1f, f);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(3.0f, 3.0f, "float eq");
}

static void test_message_is_not_a_failure(void)
{
    check_setup_before_body();
    TEST_MESSAGE("informational line, the test still passes");
}

static void test_pass_ends_test_early(void)
{
    check_setup_before_body();
    TEST_PASS();
    reached_after_pass = 1; /* must not run */
}

static void test_pass_message_ends_test_early(void)
{
    check_setup_before_body();
    TEST_PASS_MESSAGE("passed early");
    reached_after_pass = 1; /* must not run */
}

static void test_ignore(void)
{
    check_setup_before_body();
    TEST_IGNORE();
    reached_after_ignore = 1; /* must not run */
}

static void test_ignore_message(void)
{
    check_setup_before_body();
    TEST_IGNORE_MESSAGE("not implemented on this board revision");
    reached_after_ignore = 1; /* must not run */
}

static void test_ignored_by_setup(void)
{
    body_ran_after_setup_ignore = 1; /* must not run: setUp ignored the test */
}

static void arm_ignore_in_setup(void)
{
    ignore_in_setup = 1;
}

#define EXPECTED_TESTS_BEFORE_COUNTERS 16u
#define EXPECTED_IGNORED 3u

/* Runs last: the harness's own bookkeeping, checked with the harness. */
static void test_counters(void)
{
    TEST_ASSERT_EQUAL_UINT(EXPECTED_TESTS_BEFORE_COUNTERS + 1u, Unity.NumberOfTests);
    TEST_ASSERT_EQUAL_UINT(0u, Unity.TestFailures);
    TEST_ASSERT_EQUAL_UINT(EXPECTED_IGNORED, Unity.TestIgnores);
    TEST_ASSERT_EQUAL_UINT(0u, Unity.CurrentTestFailed);
    TEST_ASSERT_EQUAL_UINT(0u, Unity.CurrentTestIgnored);
    /* setUp ran for every test so far including this one, tearDown for all
     * but this one. */
    TEST_ASSERT_EQUAL_UINT(EXPECTED_TESTS_BEFORE_COUNTERS + 1u, setup_calls);
    TEST_ASSERT_EQUAL_UINT(EXPECTED_TESTS_BEFORE_COUNTERS, teardown_calls);
    /* every body except test_ignored_by_setup started */
    TEST_ASSERT_EQUAL_UINT(EXPECTED_TESTS_BEFORE_COUNTERS - 1u, tests_started);
    TEST_ASSERT_FALSE(reached_after_ignore);
    TEST_ASSERT_FALSE(reached_after_pass);
    TEST_ASSERT_FALSE(body_ran_after_setup_ignore);
}

int main(void)
{
    int failures;

    UNITY_BEGIN();
    RUN_TEST(test_booleans_and_pointers);
    RUN_TEST(test_equal_integers);
    RUN_TEST(test_not_equal_integers);
    RUN_TEST(test_ordering);
    RUN_TEST(test_within);
    RUN_TEST(test_bits);
    RUN_TEST(test_arrays);
    RUN_TEST(test_memory_and_strings);
    RUN_TEST(test_floating_point);
    RUN_TEST(test_message_is_not_a_failure);
    RUN_TEST(test_pass_ends_test_early);
    RUN_TEST(test_pass_message_ends_test_early);
    RUN_TEST(test_ignore);
    RUN_TEST(test_ignore_message);
    arm_ignore_in_setup();
    RUN_TEST(test_ignored_by_setup);
    RUN_TEST(test_booleans_and_pointers, 1234); /* explicit line number form */
    RUN_TEST(test_counters);
    failures = UNITY_END();

    /* Cross-check without the harness, in case its own reporting is broken. */
    if (Unity.NumberOfTests != EXPECTED_TESTS_BEFORE_COUNTERS + 1u ||
        Unity.TestIgnores != EXPECTED_IGNORED ||
        setup_calls != EXPECTED_TESTS_BEFORE_COUNTERS + 1u ||
        teardown_calls != EXPECTED_TESTS_BEFORE_COUNTERS + 1u ||
        reached_after_ignore || reached_after_pass || body_ran_after_setup_ignore) {
        printf("harness self-check FAILED: tests=%u ignored=%u setUp=%u tearDown=%u\n",
               (unsigned)Unity.NumberOfTests, (unsigned)Unity.TestIgnores,
               setup_calls, teardown_calls);
        return failures + 1;
    }
    return failures;
}
