/*
 * Deliberately failing self-test of the test harness (test/unity).
 *
 * Each fail_* test contains exactly one assertion that must fail (a couple
 * have a second one after it that must never be reached).  ctest runs this
 * binary twice (see test/CMakeLists.txt):
 *   - test_unity_harness_fail         WILL_FAIL: the exit code must be non-zero;
 *   - test_unity_harness_fail_output  PASS_REGULAR_EXPRESSION: the failure
 *     lines and the summary must read exactly as expected, and the
 *     bookkeeping check printed by main() must say "ok".
 *
 * To see the output: ./build/test/test_unity_harness_fail
 */
#include "unity.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

static unsigned setup_calls;
static unsigned teardown_calls;
static int reached_after_failure;      /* must stay 0 */
static int fail_in_setup_armed;
static int fail_in_teardown_armed;
static int body_ran_after_setup_failed; /* must stay 0 */

void setUp(void)
{
    setup_calls++;
    if (fail_in_setup_armed) {
        fail_in_setup_armed = 0;
        TEST_FAIL_MESSAGE("setUp failed");
    }
}

void tearDown(void)
{
    teardown_calls++;
    if (fail_in_teardown_armed) {
        fail_in_teardown_armed = 0;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, 1, "tearDown check");
    }
}

/* ---------------------------------------------------------------- numbers */

static void fail_equal_int(void)
{
    TEST_ASSERT_EQUAL_INT(5, 7);
    reached_after_failure = 1;
}

static void fail_equal_int_message(void)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(5, 7, "servo 3 angle");
}

static void fail_equal(void)
{
    TEST_ASSERT_EQUAL(-1, 1);
}

static void fail_equal_int8(void)
{
    TEST_ASSERT_EQUAL_INT8(-128, 127);
}

static void fail_equal_uint16(void)
{
    TEST_ASSERT_EQUAL_UINT16(65535u, 0x10000u); /* 0x10000 is 0 as uint16 */
}

static void fail_equal_int64(void)
{
    TEST_ASSERT_EQUAL_INT64(INT64_MIN, INT64_MAX);
}

static void fail_equal_uint64(void)
{
    TEST_ASSERT_EQUAL_UINT64(UINT64_MAX, 0u);
}

static void fail_equal_hex16(void)
{
    TEST_ASSERT_EQUAL_HEX16(0xBEEF, 0xBEEE);
}

static void fail_equal_hex32_message(void)
{
    TEST_ASSERT_EQUAL_HEX32_MESSAGE(0x1u, 0x10u, "status register");
}

static void fail_not_equal_int(void)
{
    TEST_ASSERT_NOT_EQUAL_INT(5, 5);
}

static void fail_greater_than(void)
{
    TEST_ASSERT_GREATER_THAN(5, 3);
}

static void fail_less_than(void)
{
    TEST_ASSERT_LESS_THAN_INT(5, 7);
}

static void fail_greater_or_equal(void)
{
    TEST_ASSERT_GREATER_OR_EQUAL(5, 4);
}

static void fail_less_or_equal_message(void)
{
    TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(5, 6, "queue depth");
}

static void fail_less_than_uint_is_unsigned(void)
{
    TEST_ASSERT_LESS_THAN_UINT(1u, 0xFFFFFFFFu); /* would pass if compared signed */
}

static void fail_int_within(void)
{
    TEST_ASSERT_INT_WITHIN(2, 100, 97);
}

static void fail_uint_within_message(void)
{
    TEST_ASSERT_UINT_WITHIN_MESSAGE(1u, 10u, 12u, "rpm");
}

static void fail_int32_within(void)
{
    TEST_ASSERT_INT32_WITHIN(5, INT32_MIN, INT32_MAX); /* distance overflows int32 */
}

static void fail_bits(void)
{
    TEST_ASSERT_BITS(0x0Fu, 0x05u, 0x04u);
}

/* ---------------------------------------------------------- floating point */

static void fail_double_within(void)
{
    TEST_ASSERT_DOUBLE_WITHIN(0.01, 1.5, 1.6);
}

static void fail_float_within_message(void)
{
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.1f, 0.25f, -0.5f, "pitch");
}

static void fail_equal_double(void)
{
    TEST_ASSERT_EQUAL_DOUBLE(2.5, 2.75);
}

static void fail_double_within_large(void)
{
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 1e10, -2.5e-7);
}

/* ---------------------------------------------------- booleans, pointers */

static void fail_assert(void)
{
    TEST_ASSERT(1 == 2);
}

static void fail_assert_true(void)
{
    TEST_ASSERT_TRUE(0);
}

static void fail_assert_false(void)
{
    TEST_ASSERT_FALSE(1);
}

static void fail_assert_true_message(void)
{
    TEST_ASSERT_TRUE_MESSAGE(0, "battery low");
}

static void fail_null(void)
{
    static int x;
    TEST_ASSERT_NULL(&x);
}

static void fail_not_null(void)
{
    TEST_ASSERT_NOT_NULL(NULL);
}

static void fail_not_equal(void)
{
    TEST_ASSERT_NOT_EQUAL(3, 3);
}

static void fail_test_fail(void)
{
    TEST_FAIL();
}

static void fail_test_fail_message(void)
{
    TEST_FAIL_MESSAGE("not wired up");
}

/* ------------------------------------------------ arrays, memory, strings */

static void fail_hex8_array(void)
{
    static const uint8_t expected[] = { 0x55, 0x00, 0x09, 0x55, 0xAA };
    static const uint8_t actual[]   = { 0x55, 0x00, 0x09, 0x56, 0xAA };
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expected, actual, sizeof expected);
}

static void fail_uint8_array_message(void)
{
    static const uint8_t expected[] = { 200, 1 };
    static const uint8_t actual[]   = { 201, 1 };
    TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(expected, actual, 2, "reply frame");
}

static void fail_int_array(void)
{
    static const int expected[] = { 1, -2, 3 };
    static const int actual[]   = { 1, 2, 3 };
    TEST_ASSERT_EQUAL_INT_ARRAY(expected, actual, 3);
}

static void fail_int_array_null_actual(void)
{
    static const int expected[] = { 1, 2, 3 };
    TEST_ASSERT_EQUAL_INT_ARRAY(expected, NULL, 3);
}

static void fail_array_pointless(void)
{
    static const int a[] = { 1 };
    TEST_ASSERT_EQUAL_INT_ARRAY(a, a, 0);
}

static void fail_each_equal(void)
{
    static const uint8_t actual[] = { 0, 0, 1 };
    TEST_ASSERT_EACH_EQUAL_UINT8(0, actual, 3);
}

static void fail_memory(void)
{
    static const uint8_t expected[] = { 1, 2, 3, 4 };
    static const uint8_t actual[]   = { 1, 2, 4, 4 };
    TEST_ASSERT_EQUAL_MEMORY(expected, actual, sizeof expected);
}

static void fail_memory_array(void)
{
    static const uint8_t expected[] = { 1, 2, 3, 4 };
    static const uint8_t actual[]   = { 1, 2, 0xF3, 4 };
    TEST_ASSERT_EQUAL_MEMORY_ARRAY(expected, actual, 2, 2);
}

static void fail_string(void)
{
    TEST_ASSERT_EQUAL_STRING("servo", "servO");
}

static void fail_string_null_actual(void)
{
    TEST_ASSERT_EQUAL_STRING("servo", NULL);
}

static void fail_string_escaped(void)
{
    TEST_ASSERT_EQUAL_STRING_MESSAGE("ok\n", "ok\r\001", "line ending");
}

static void fail_string_len(void)
{
    TEST_ASSERT_EQUAL_STRING_LEN("abcdef", "abcxyz", 4);
}

/* ---------------------------------------------------- control flow checks */

static void helper_that_fails(int value)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(42, value, "from a helper");
    reached_after_failure = 1;
}

static void fail_in_nested_function(void)
{
    helper_that_fails(41);
    reached_after_failure = 1;
}

static void fail_stops_at_first_failure(void)
{
    TEST_ASSERT_EQUAL_UINT(1u, 2u);
    TEST_ASSERT_EQUAL_UINT(3u, 4u); /* never evaluated: no second FAIL line */
    reached_after_failure = 1;
}

static void fail_in_setup(void)
{
    body_ran_after_setup_failed = 1; /* must not run: setUp failed */
}

static void fail_in_teardown(void)
{
    /* The body passes; tearDown's assertion fails the test. */
}

static void fail_in_test_and_teardown(void)
{
    /* Only this failure is reported; tearDown's is swallowed. */
    TEST_FAIL_MESSAGE("first failure wins");
}

static void pass_between_failures(void)
{
    TEST_ASSERT_EQUAL_INT(1, 1); /* failure state was reset */
}

static void ignored_test(void)
{
    TEST_IGNORE_MESSAGE("fixture missing");
}

int main(void)
{
    unsigned expected_tests;
    const unsigned expected_ignored = 1u;
    const unsigned expected_passed = 1u;
    int ok;

    UNITY_BEGIN();
    RUN_TEST(fail_equal_int);
    RUN_TEST(fail_equal_int_message);
    RUN_TEST(fail_equal);
    RUN_TEST(fail_equal_int8);
    RUN_TEST(fail_equal_uint16);
    RUN_TEST(fail_equal_int64);
    RUN_TEST(fail_equal_uint64);
    RUN_TEST(fail_equal_hex16);
    RUN_TEST(fail_equal_hex32_message);
    RUN_TEST(fail_not_equal_int);
    RUN_TEST(fail_greater_than);
    RUN_TEST(fail_less_than);
    RUN_TEST(fail_greater_or_equal);
    RUN_TEST(fail_less_or_equal_message);
    RUN_TEST(fail_less_than_uint_is_unsigned);
    RUN_TEST(fail_int_within);
    RUN_TEST(fail_uint_within_message);
    RUN_TEST(fail_int32_within);
    RUN_TEST(fail_bits);
    RUN_TEST(fail_double_within);
    RUN_TEST(fail_float_within_message);
    RUN_TEST(fail_equal_double);
    RUN_TEST(fail_double_within_large);
    RUN_TEST(fail_assert);
    RUN_TEST(fail_assert_true);
    RUN_TEST(fail_assert_false);
    RUN_TEST(fail_assert_true_message);
    RUN_TEST(fail_null);
    RUN_TEST(fail_not_null);
    RUN_TEST(fail_not_equal);
    RUN_TEST(fail_test_fail);
    RUN_TEST(fail_test_fail_message);
    RUN_TEST(fail_hex8_array);
    RUN_TEST(fail_uint8_array_message);
    RUN_TEST(fail_int_array);
    RUN_TEST(fail_int_array_null_actual);
    RUN_TEST(fail_array_pointless);
    RUN_TEST(fail_each_equal);
    RUN_TEST(fail_memory);
    RUN_TEST(fail_memory_array);
    RUN_TEST(fail_string);
    RUN_TEST(fail_string_null_actual);
    RUN_TEST(fail_string_escaped);
    RUN_TEST(fail_string_len);
    RUN_TEST(fail_in_nested_function);
    RUN_TEST(fail_stops_at_first_failure);
    fail_in_setup_armed = 1;
    RUN_TEST(fail_in_setup);
    fail_in_teardown_armed = 1;
    RUN_TEST(fail_in_teardown);
    fail_in_teardown_armed = 1;
    RUN_TEST(fail_in_test_and_teardown);
    RUN_TEST(pass_between_failures);
    RUN_TEST(ignored_test);

    /* Bookkeeping, checked in plain C: every fail_* test failed exactly once,
     * nothing ran past a failed assertion, setUp/tearDown ran around every
     * test.  The ctest output check requires the "ok" line. */
    expected_tests = (unsigned)Unity.NumberOfTests;
    ok = expected_tests == 51u &&
         (unsigned)Unity.TestFailures == expected_tests - expected_ignored - expected_passed &&
         (unsigned)Unity.TestIgnores == expected_ignored &&
         setup_calls == expected_tests && teardown_calls == expected_tests &&
         !reached_after_failure && !body_ran_after_setup_failed &&
         !fail_in_setup_armed && !fail_in_teardown_armed;
    printf("harness self-check: %s (tests=%u failures=%u ignored=%u setUp=%u tearDown=%u)\n",
           ok ? "ok" : "FAILED", expected_tests, (unsigned)Unity.TestFailures,
           (unsigned)Unity.TestIgnores, setup_calls, teardown_calls);
    return UNITY_END();
}
