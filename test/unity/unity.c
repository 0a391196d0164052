/*
 * unity.c - xgo-board's own Unity-compatible test harness (see README.md).
 *
 * Written from scratch for this project; only the API and the console
 * output format follow ThrowTheSwitch/Unity.  No heap, one state struct.
 */
#include "unity.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Output hooks: override at compile time (e.g. for a target without stdio). */
#ifndef UNITY_OUTPUT_CHAR
#define UNITY_OUTPUT_CHAR(c) ((void)putchar(c))
#endif
#ifndef UNITY_OUTPUT_FLUSH
#define UNITY_OUTPUT_FLUSH() ((void)fflush(stdout))
#endif
#define UNITY_PRINT_EOL() UNITY_OUTPUT_CHAR('\n')

struct UNITY_STORAGE_T Unity;

/* Non-zero while RUN_TEST has an abort frame set up (Unity.AbortFrame valid). */
static int unity_in_test;

static const char unity_str_pass[]        = "PASS";
static const char unity_str_fail[]        = "FAIL";
static const char unity_str_ignore[]      = "IGNORE";
static const char unity_str_info[]        = "INFO";
static const char unity_str_expected[]    = " Expected ";
static const char unity_str_was[]         = " Was ";
static const char unity_str_element[]     = " Element ";
static const char unity_str_byte[]        = " Byte ";
static const char unity_str_memory[]      = " Memory Mismatch.";
static const char unity_str_delta[]       = " Values Not Within Delta ";
static const char unity_str_gt[]          = " to be greater than ";
static const char unity_str_lt[]          = " to be less than ";
static const char unity_str_or_equal[]    = "or equal to ";
static const char unity_str_not_equal[]   = " to be not equal to ";
static const char unity_str_pointless[]   = " You Asked Me To Compare Nothing, Which Was Pointless.";
static const char unity_str_null_exp[]    = " Expected pointer to be NULL";
static const char unity_str_null_act[]    = " Actual pointer was NULL";
static const char unity_str_null[]        = "NULL";
/* Between a failure's details and the assertion's message: upstream's
 * UNITY_FAILURE_DETAIL_SEPARATOR (":" since Unity 2.6.1), overridable the same
 * way. */
#ifndef UNITY_FAILURE_DETAIL_SEPARATOR
#define UNITY_FAILURE_DETAIL_SEPARATOR ":"
#endif
static const char unity_str_spacer[]      = UNITY_FAILURE_DETAIL_SEPARATOR;
static const char unity_str_character[]   = " Character ";
static const char unity_str_breaker[]     = "-----------------------";

/* ================================================================ printing */

static void unity_print_char(char c)
{
    if (c >= 32 && c <= 126) {
        UNITY_OUTPUT_CHAR(c);
    } else if (c == '\n') {
        UNITY_OUTPUT_CHAR('\\');
        UNITY_OUTPUT_CHAR('n');
    } else if (c == '\r') {
        UNITY_OUTPUT_CHAR('\\');
        UNITY_OUTPUT_CHAR('r');
    } else {
        UNITY_OUTPUT_CHAR('\\');
        UNITY_OUTPUT_CHAR('x');
        UnityPrintNumberHex((UNITY_UINT)(unsigned char)c, 2);
    }
}

void UnityPrint(const char *string)
{
    if (string == NULL) {
        return;
    }
    while (*string != '\0') {
        unity_print_char(*string++);
    }
}

void UnityPrintLen(const char *string, const UNITY_UINT32 length)
{
    UNITY_UINT32 i;

    if (string == NULL) {
        return;
    }
    for (i = 0; i < length && string[i] != '\0'; i++) {
        unity_print_char(string[i]);
    }
}

void UnityPrintNumberUnsigned(const UNITY_UINT number)
{
    char digits[24]; /* 2^64 has 20 decimal digits */
    int n = 0;
    UNITY_UINT rest = number;

    do {
        digits[n++] = (char)('0' + (int)(rest % 10u));
        rest /= 10u;
    } while (rest != 0u);
    while (n > 0) {
        UNITY_OUTPUT_CHAR(digits[--n]);
    }
}

void UnityPrintNumber(const UNITY_INT number)
{
    UNITY_UINT magnitude = (UNITY_UINT)number;

    if (number < 0) {
        UNITY_OUTPUT_CHAR('-');
        magnitude = 0u - magnitude; /* well defined, also for INT64_MIN */
    }
    UnityPrintNumberUnsigned(magnitude);
}

void UnityPrintNumberHex(const UNITY_UINT number, const char nibbles)
{
    int n = nibbles;

    if (n > 16) {
        n = 16;
    }
    while (n > 0) {
        unsigned nibble;
        n--;
        nibble = (unsigned)(number >> (4 * n)) & 0xFu;
        UNITY_OUTPUT_CHAR((char)(nibble < 10u ? '0' + (int)nibble : 'A' + (int)nibble - 10));
    }
}

/* printf("%.9g"): what upstream Unity prints in double mode, the exponent
 * with at least two digits ("1e+10", "-2.5e-07"). */
void UnityPrintFloat(const UNITY_DOUBLE number)
{
    char buf[40];
    UNITY_DOUBLE value = number;

    if (value < 0.0) {
        UNITY_OUTPUT_CHAR('-');
        value = -value;
    }
    if (isnan(value)) {
        UnityPrint("nan");
        return;
    }
    if (isinf(value)) {
        UnityPrint("inf");
        return;
    }
    if (value == 0.0) {
        UNITY_OUTPUT_CHAR('0'); /* also -0.0, which "%.9g" would print as "-0" */
        return;
    }
    (void)snprintf(buf, sizeof buf, "%.9g", value);
    UnityPrint(buf);
}

static unsigned unity_style_size(const UNITY_DISPLAY_STYLE_T style)
{
    return (unsigned)style & 0xFu;
}

static int unity_style_is_signed(const UNITY_DISPLAY_STYLE_T style)
{
    return ((unsigned)style & UNITY_DISPLAY_RANGE_INT) != 0u;
}

static void unity_print_by_style(const UNITY_INT number, const UNITY_DISPLAY_STYLE_T style)
{
    if (((unsigned)style & UNITY_DISPLAY_RANGE_INT) != 0u) {
        UnityPrintNumber(number);
    } else if (((unsigned)style & UNITY_DISPLAY_RANGE_UINT) != 0u) {
        UnityPrintNumberUnsigned((UNITY_UINT)number);
    } else {
        UNITY_OUTPUT_CHAR('0');
        UNITY_OUTPUT_CHAR('x');
        UnityPrintNumberHex((UNITY_UINT)number, (char)(unity_style_size(style) * 2u));
    }
}

/* "FILE:LINE:TEST_NAME:" */
static void unity_result_begin(const UNITY_LINE_TYPE line)
{
    UnityPrint(Unity.TestFile);
    UNITY_OUTPUT_CHAR(':');
    UnityPrintNumberUnsigned(line);
    UNITY_OUTPUT_CHAR(':');
    UnityPrint(Unity.CurrentTestName);
    UNITY_OUTPUT_CHAR(':');
}

/* "FILE:LINE:TEST_NAME:FAIL:" - the details follow, each starting with a space. */
static void unity_fail_begin(const UNITY_LINE_TYPE line)
{
    unity_result_begin(line);
    UnityPrint(unity_str_fail);
    UNITY_OUTPUT_CHAR(':');
}

static void unity_add_message(const char *msg)
{
    if (msg != NULL) {
        UnityPrint(unity_str_spacer);
        UnityPrint(msg);
    }
}

/* ====================================================== test flow control */

/*
 * Called before evaluating a failing assertion's report.  If the current test
 * already failed or was ignored (e.g. a second failure in tearDown), nothing
 * more is reported and the function is left via longjmp.  Returns normally if
 * the failure should be reported.
 */
static void unity_abort_if_done(void)
{
    if ((Unity.CurrentTestFailed != 0u || Unity.CurrentTestIgnored != 0u) && unity_in_test) {
        TEST_ABORT();
    }
}

/* Ends the current test as failed (the failure line has been printed). */
static void unity_fail_and_bail(void)
{
    Unity.CurrentTestFailed = 1u;
    if (unity_in_test) {
        UNITY_OUTPUT_FLUSH();
        TEST_ABORT();
    }
    /* An assertion outside RUN_TEST cannot abort anything: report it on its
     * own line, count it and carry on. */
    UNITY_PRINT_EOL();
    Unity.TestFailures++;
    Unity.CurrentTestFailed = 0u;
    UNITY_OUTPUT_FLUSH();
}

void UnityFail(const char *message, const UNITY_LINE_TYPE line)
{
    unity_abort_if_done();
    unity_result_begin(line);
    UnityPrint(unity_str_fail);
    unity_add_message(message); /* "FAIL:message", as upstream prints it */
    unity_fail_and_bail();
}

void UnityIgnore(const char *message, const UNITY_LINE_TYPE line)
{
    unity_abort_if_done();
    unity_result_begin(line);
    UnityPrint(unity_str_ignore);
    if (message != NULL) {
        UNITY_OUTPUT_CHAR(':');
        UNITY_OUTPUT_CHAR(' ');
        UnityPrint(message);
    }
    if (unity_in_test) {
        Unity.CurrentTestIgnored = 1u;
        UNITY_OUTPUT_FLUSH();
        TEST_ABORT();
    }
    UNITY_PRINT_EOL();
    Unity.TestIgnores++;
}

void UnityMessage(const char *message, const UNITY_LINE_TYPE line)
{
    unity_result_begin(line);
    UnityPrint(unity_str_info);
    if (message != NULL) {
        UNITY_OUTPUT_CHAR(':');
        UNITY_OUTPUT_CHAR(' ');
        UnityPrint(message);
    }
    UNITY_PRINT_EOL();
}

void UnityBegin(const char *filename)
{
    Unity.TestFile = filename;
    Unity.CurrentTestName = NULL;
    Unity.CurrentTestLineNumber = 0u;
    Unity.NumberOfTests = 0u;
    Unity.TestFailures = 0u;
    Unity.TestIgnores = 0u;
    Unity.CurrentTestFailed = 0u;
    Unity.CurrentTestIgnored = 0u;
    unity_in_test = 0;
}

void UnityConcludeTest(void)
{
    if (Unity.CurrentTestIgnored != 0u) {
        Unity.TestIgnores++;
    } else if (Unity.CurrentTestFailed == 0u) {
        unity_result_begin(Unity.CurrentTestLineNumber);
        UnityPrint(unity_str_pass);
    } else {
        Unity.TestFailures++;
    }
    Unity.CurrentTestFailed = 0u;
    Unity.CurrentTestIgnored = 0u;
    UNITY_PRINT_EOL();
    UNITY_OUTPUT_FLUSH();
}

void UnityDefaultTestRun(UnityTestFunction func, const char *func_name, const int func_line_num)
{
    Unity.CurrentTestName = func_name;
    Unity.CurrentTestLineNumber = (UNITY_LINE_TYPE)func_line_num;
    Unity.NumberOfTests++;
    unity_in_test = 1;
    if (TEST_PROTECT()) {
        setUp();
        func();
    }
    if (TEST_PROTECT()) {
        tearDown();
    }
    unity_in_test = 0;
    UnityConcludeTest();
}

int UnityEnd(void)
{
    UNITY_PRINT_EOL();
    UnityPrint(unity_str_breaker);
    UNITY_PRINT_EOL();
    UnityPrintNumberUnsigned(Unity.NumberOfTests);
    UnityPrint(" Tests ");
    UnityPrintNumberUnsigned(Unity.TestFailures);
    UnityPrint(" Failures ");
    UnityPrintNumberUnsigned(Unity.TestIgnores);
    UnityPrint(" Ignored ");
    UNITY_PRINT_EOL();
    UnityPrint(Unity.TestFailures == 0u ? "OK" : unity_str_fail);
    UNITY_PRINT_EOL();
    UNITY_OUTPUT_FLUSH();
    return (int)Unity.TestFailures;
}

/* ============================================================= assertions */

void UnityAssertEqualNumber(const UNITY_INT expected, const UNITY_INT actual,
                            const char *msg, const UNITY_LINE_TYPE line,
                            const UNITY_DISPLAY_STYLE_T style)
{
    if (expected == actual) {
        return;
    }
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_expected);
    unity_print_by_style(expected, style);
    UnityPrint(unity_str_was);
    unity_print_by_style(actual, style);
    unity_add_message(msg);
    unity_fail_and_bail();
}

void UnityAssertGreaterOrLessOrEqualNumber(const UNITY_INT threshold, const UNITY_INT actual,
                                           const UNITY_COMPARISON_T compare,
                                           const char *msg, const UNITY_LINE_TYPE line,
                                           const UNITY_DISPLAY_STYLE_T style)
{
    int greater; /* actual > threshold */
    int ok;

    if (unity_style_is_signed(style)) {
        greater = actual > threshold;
    } else {
        greater = (UNITY_UINT)actual > (UNITY_UINT)threshold;
    }
    if (actual == threshold) {
        ok = (compare & UNITY_EQUAL_TO) != 0;
    } else if (compare == UNITY_NOT_EQUAL) {
        ok = 1;
    } else if (greater) {
        ok = (compare & UNITY_GREATER_THAN) != 0;
    } else {
        ok = (compare & UNITY_SMALLER_THAN) != 0;
    }
    if (ok) {
        return;
    }
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_expected);
    unity_print_by_style(actual, style);
    if ((compare & UNITY_GREATER_THAN) != 0) {
        UnityPrint(unity_str_gt);
    }
    if ((compare & UNITY_SMALLER_THAN) != 0) {
        UnityPrint(unity_str_lt);
    }
    if ((compare & UNITY_EQUAL_TO) != 0) {
        UnityPrint(unity_str_or_equal);
    }
    if (compare == UNITY_NOT_EQUAL) {
        UnityPrint(unity_str_not_equal);
    }
    unity_print_by_style(threshold, style);
    unity_add_message(msg);
    unity_fail_and_bail();
}

void UnityAssertNumbersWithin(const UNITY_UINT delta, const UNITY_INT expected,
                              const UNITY_INT actual, const char *msg,
                              const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style)
{
    UNITY_UINT distance;
    int actual_above;

    if (unity_style_is_signed(style)) {
        actual_above = actual > expected;
    } else {
        actual_above = (UNITY_UINT)actual > (UNITY_UINT)expected;
    }
    /* Unsigned subtraction: exact even when the signed difference overflows. */
    distance = actual_above ? (UNITY_UINT)actual - (UNITY_UINT)expected
                            : (UNITY_UINT)expected - (UNITY_UINT)actual;
    if (distance <= delta) {
        return;
    }
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_delta);
    unity_print_by_style((UNITY_INT)delta, style);
    UnityPrint(unity_str_expected);
    unity_print_by_style(expected, style);
    UnityPrint(unity_str_was);
    unity_print_by_style(actual, style);
    unity_add_message(msg);
    unity_fail_and_bail();
}

static void unity_print_mask(const UNITY_UINT mask, const UNITY_UINT number)
{
    int bits = (mask >> 32) != 0u ? 64 : 32;

    while (bits > 0) {
        UNITY_UINT bit;
        bits--;
        bit = (UNITY_UINT)1 << bits;
        if ((mask & bit) == 0u) {
            UNITY_OUTPUT_CHAR('X');
        } else {
            UNITY_OUTPUT_CHAR((number & bit) != 0u ? '1' : '0');
        }
    }
}

void UnityAssertBits(const UNITY_INT mask, const UNITY_INT expected, const UNITY_INT actual,
                     const char *msg, const UNITY_LINE_TYPE line)
{
    const UNITY_UINT m = (UNITY_UINT)mask;

    if ((m & (UNITY_UINT)expected) == (m & (UNITY_UINT)actual)) {
        return;
    }
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_expected);
    unity_print_mask(m, (UNITY_UINT)expected);
    UnityPrint(unity_str_was);
    unity_print_mask(m, (UNITY_UINT)actual);
    unity_add_message(msg);
    unity_fail_and_bail();
}

static void unity_fail_pointless(const char *msg, const UNITY_LINE_TYPE line)
{
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_pointless);
    unity_add_message(msg);
    unity_fail_and_bail();
}

/* Fails (and does not return) if exactly one of the two pointers is NULL.
 * Returns non-zero if both are the same pointer (nothing left to compare). */
static int unity_check_array_pointers(UNITY_INTERNAL_PTR expected, UNITY_INTERNAL_PTR actual,
                                      const char *msg, const UNITY_LINE_TYPE line)
{
    if (expected == actual) {
        return 1;
    }
    if (expected != NULL && actual != NULL) {
        return 0;
    }
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(expected == NULL ? unity_str_null_exp : unity_str_null_act);
    unity_add_message(msg);
    unity_fail_and_bail();
    return 1; /* only reached outside RUN_TEST */
}

/* Element `index` of an integer array of the given style, widened to UNITY_INT
 * (sign-extended for signed styles, zero-extended otherwise). */
static UNITY_INT unity_read_element(UNITY_INTERNAL_PTR array, const UNITY_UINT32 index,
                                    const UNITY_DISPLAY_STYLE_T style)
{
    const unsigned size = unity_style_size(style);
    const unsigned char *p = (const unsigned char *)array + (size_t)index * size;
    const int is_signed = unity_style_is_signed(style);

    switch (size) {
    case 1: {
        UNITY_UINT8 u;
        memcpy(&u, p, sizeof u);
        return is_signed ? (UNITY_INT)(UNITY_INT8)u : (UNITY_INT)u;
    }
    case 2: {
        UNITY_UINT16 u;
        memcpy(&u, p, sizeof u);
        return is_signed ? (UNITY_INT)(UNITY_INT16)u : (UNITY_INT)u;
    }
    case 4: {
        UNITY_UINT32 u;
        memcpy(&u, p, sizeof u);
        return is_signed ? (UNITY_INT)(UNITY_INT32)u : (UNITY_INT)u;
    }
    default: {
        UNITY_UINT64 u;
        memcpy(&u, p, sizeof u);
        return (UNITY_INT)u;
    }
    }
}

static void unity_fail_element(const UNITY_UINT32 index, const UNITY_INT expected,
                               const UNITY_INT actual, const char *msg,
                               const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style)
{
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_element);
    UnityPrintNumberUnsigned(index);
    UnityPrint(unity_str_expected);
    unity_print_by_style(expected, style);
    UnityPrint(unity_str_was);
    unity_print_by_style(actual, style);
    unity_add_message(msg);
    unity_fail_and_bail();
}

void UnityAssertEqualIntArray(UNITY_INTERNAL_PTR expected, UNITY_INTERNAL_PTR actual,
                              const UNITY_UINT32 num_elements, const char *msg,
                              const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style)
{
    UNITY_UINT32 i;

    if (num_elements == 0u) {
        unity_fail_pointless(msg, line);
        return;
    }
    if (unity_check_array_pointers(expected, actual, msg, line)) {
        return;
    }
    for (i = 0; i < num_elements; i++) {
        const UNITY_INT e = unity_read_element(expected, i, style);
        const UNITY_INT a = unity_read_element(actual, i, style);
        if (e != a) {
            unity_fail_element(i, e, a, msg, line, style);
            return;
        }
    }
}

void UnityAssertEachEqualNumber(const UNITY_INT expected, UNITY_INTERNAL_PTR actual,
                                const UNITY_UINT32 num_elements, const char *msg,
                                const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style)
{
    UNITY_UINT32 i;

    if (num_elements == 0u) {
        unity_fail_pointless(msg, line);
        return;
    }
    if (actual == NULL) {
        unity_abort_if_done();
        unity_fail_begin(line);
        UnityPrint(unity_str_null_act);
        unity_add_message(msg);
        unity_fail_and_bail();
        return;
    }
    for (i = 0; i < num_elements; i++) {
        const UNITY_INT a = unity_read_element(actual, i, style);
        if (a != expected) {
            unity_fail_element(i, expected, a, msg, line, style);
            return;
        }
    }
}

void UnityAssertEqualMemory(UNITY_INTERNAL_PTR expected, UNITY_INTERNAL_PTR actual,
                            const UNITY_UINT32 length, const UNITY_UINT32 num_elements,
                            const char *msg, const UNITY_LINE_TYPE line)
{
    const unsigned char *e = (const unsigned char *)expected;
    const unsigned char *a = (const unsigned char *)actual;
    UNITY_UINT32 element;
    UNITY_UINT32 byte;

    if (length == 0u || num_elements == 0u) {
        unity_fail_pointless(msg, line);
        return;
    }
    if (unity_check_array_pointers(expected, actual, msg, line)) {
        return;
    }
    for (element = 0; element < num_elements; element++) {
        for (byte = 0; byte < length; byte++, e++, a++) {
            if (*e == *a) {
                continue;
            }
            unity_abort_if_done();
            unity_fail_begin(line);
            UnityPrint(unity_str_memory);
            if (num_elements > 1u) {
                UnityPrint(unity_str_element);
                UnityPrintNumberUnsigned(element);
            }
            UnityPrint(unity_str_byte);
            UnityPrintNumberUnsigned(byte);
            UnityPrint(unity_str_expected);
            unity_print_by_style((UNITY_INT)*e, UNITY_DISPLAY_STYLE_HEX8);
            UnityPrint(unity_str_was);
            unity_print_by_style((UNITY_INT)*a, UNITY_DISPLAY_STYLE_HEX8);
            unity_add_message(msg);
            unity_fail_and_bail();
            return;
        }
    }
}

static void unity_print_quoted(const char *s, const UNITY_UINT32 length, const int limited)
{
    if (s == NULL) {
        UnityPrint(unity_str_null);
        return;
    }
    UNITY_OUTPUT_CHAR('\'');
    if (limited) {
        UnityPrintLen(s, length);
    } else {
        UnityPrint(s);
    }
    UNITY_OUTPUT_CHAR('\'');
}

/* Index of the first character where two non-NULL strings differ within
 * the first length characters (limited) or anywhere. */
static UNITY_UINT32 unity_first_difference(const char *expected, const char *actual,
                                           const UNITY_UINT32 length, const int limited)
{
    UNITY_UINT32 i = 0;
    while ((!limited || i < length) && (expected[i] != '\0' || actual[i] != '\0') &&
           expected[i] == actual[i]) {
        i++;
    }
    return i;
}

/* " Character 4 Expected 'o' Was 'O'": where two strings part, as upstream
 * reports it (only when neither is NULL). */
static void unity_print_string_difference(const char *expected, const char *actual,
                                          const UNITY_UINT32 length, const int limited)
{
    UNITY_UINT32 at;
    if (expected == NULL || actual == NULL) {
        return;
    }
    at = unity_first_difference(expected, actual, length, limited);
    UnityPrint(unity_str_character);
    UnityPrintNumberUnsigned(at);
    UnityPrint(unity_str_expected);
    UNITY_OUTPUT_CHAR('\'');
    unity_print_char(expected[at]);
    UNITY_OUTPUT_CHAR('\'');
    UnityPrint(unity_str_was);
    UNITY_OUTPUT_CHAR('\'');
    unity_print_char(actual[at]);
    UNITY_OUTPUT_CHAR('\'');
}

static void unity_fail_strings(const char *expected, const char *actual,
                               const UNITY_UINT32 length, const int limited,
                               const char *msg, const UNITY_LINE_TYPE line)
{
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_expected);
    unity_print_quoted(expected, length, limited);
    UnityPrint(unity_str_was);
    unity_print_quoted(actual, length, limited);
    unity_print_string_difference(expected, actual, length, limited);
    unity_add_message(msg);
    unity_fail_and_bail();
}

void UnityAssertEqualString(const char *expected, const char *actual,
                            const char *msg, const UNITY_LINE_TYPE line)
{
    if (expected == actual) {
        return;
    }
    if (expected != NULL && actual != NULL && strcmp(expected, actual) == 0) {
        return;
    }
    unity_fail_strings(expected, actual, 0u, 0, msg, line);
}

void UnityAssertEqualStringLen(const char *expected, const char *actual,
                               const UNITY_UINT32 length, const char *msg,
                               const UNITY_LINE_TYPE line)
{
    if (expected == actual) {
        return;
    }
    if (expected != NULL && actual != NULL && strncmp(expected, actual, length) == 0) {
        return;
    }
    unity_fail_strings(expected, actual, length, 1, msg, line);
}

/* |actual - expected| <= |delta|; two NaNs, or two infinities of the same
 * sign, count as equal (as in upstream Unity). */
static int unity_doubles_within(UNITY_DOUBLE delta, const UNITY_DOUBLE expected,
                                const UNITY_DOUBLE actual)
{
    UNITY_DOUBLE diff;

    if (isinf(expected) && isinf(actual) && ((expected < 0.0) == (actual < 0.0))) {
        return 1;
    }
    if (isnan(expected) && isnan(actual)) {
        return 1;
    }
    diff = actual - expected;
    if (diff < 0.0) {
        diff = -diff;
    }
    if (delta < 0.0) {
        delta = -delta;
    }
    return !(isnan(diff) || isinf(diff) || diff > delta);
}

static int unity_floats_within(UNITY_FLOAT delta, const UNITY_FLOAT expected,
                               const UNITY_FLOAT actual)
{
    UNITY_FLOAT diff;

    if (isinf(expected) && isinf(actual) && ((expected < 0.0f) == (actual < 0.0f))) {
        return 1;
    }
    if (isnan(expected) && isnan(actual)) {
        return 1;
    }
    diff = actual - expected;
    if (diff < 0.0f) {
        diff = -diff;
    }
    if (delta < 0.0f) {
        delta = -delta;
    }
    return !(isnan(diff) || isinf(diff) || diff > delta);
}

static void unity_fail_floats(const UNITY_DOUBLE expected, const UNITY_DOUBLE actual,
                              const char *msg, const UNITY_LINE_TYPE line)
{
    unity_abort_if_done();
    unity_fail_begin(line);
    UnityPrint(unity_str_expected);
    UnityPrintFloat(expected);
    UnityPrint(unity_str_was);
    UnityPrintFloat(actual);
    unity_add_message(msg);
    unity_fail_and_bail();
}

void UnityAssertFloatsWithin(const UNITY_FLOAT delta, const UNITY_FLOAT expected,
                             const UNITY_FLOAT actual, const char *msg,
                             const UNITY_LINE_TYPE line)
{
    if (!unity_floats_within(delta, expected, actual)) {
        unity_fail_floats((UNITY_DOUBLE)expected, (UNITY_DOUBLE)actual, msg, line);
    }
}

void UnityAssertDoublesWithin(const UNITY_DOUBLE delta, const UNITY_DOUBLE expected,
                              const UNITY_DOUBLE actual, const char *msg,
                              const UNITY_LINE_TYPE line)
{
    if (!unity_doubles_within(delta, expected, actual)) {
        unity_fail_floats(expected, actual, msg, line);
    }
}
