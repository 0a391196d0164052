/*
 * unity_internals.h - internals of xgo-board's own Unity-compatible test
 * harness (see README.md).  Tests include "unity.h" only; nothing here is
 * part of the supported API except what upstream Unity also exposes
 * (the Unity state struct, UnityTestFunction, the UNITY_* types).
 *
 * Written from scratch for this project; it mirrors the public API and the
 * console output of ThrowTheSwitch/Unity so that upstream Unity can be
 * dropped in via the CMake option XGO_UNITY_DIR.
 */
#ifndef XGO_UNITY_INTERNALS_H
#define XGO_UNITY_INTERNALS_H

#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ types */

typedef int8_t   UNITY_INT8;
typedef int16_t  UNITY_INT16;
typedef int32_t  UNITY_INT32;
typedef int64_t  UNITY_INT64;
typedef uint8_t  UNITY_UINT8;
typedef uint16_t UNITY_UINT16;
typedef uint32_t UNITY_UINT32;
typedef uint64_t UNITY_UINT64;

/* The widest integer the harness computes with (64-bit support is always on). */
typedef UNITY_INT64  UNITY_INT;
typedef UNITY_UINT64 UNITY_UINT;

typedef float  UNITY_FLOAT;
typedef double UNITY_DOUBLE;

typedef UNITY_UINT  UNITY_LINE_TYPE;
typedef UNITY_UINT  UNITY_COUNTER_TYPE;
typedef const void *UNITY_INTERNAL_PTR;

typedef void (*UnityTestFunction)(void);

/* Relative tolerance used by TEST_ASSERT_EQUAL_FLOAT / _DOUBLE. */
#ifndef UNITY_FLOAT_PRECISION
#define UNITY_FLOAT_PRECISION 0.00001f
#endif
#ifndef UNITY_DOUBLE_PRECISION
#define UNITY_DOUBLE_PRECISION 1e-12
#endif

/*
 * Display style of an integer assertion: the low nibble is the operand size
 * in bytes (1, 2, 4 or 8), the high bits say how it is compared and printed.
 */
#define UNITY_DISPLAY_RANGE_INT  0x10
#define UNITY_DISPLAY_RANGE_UINT 0x20
#define UNITY_DISPLAY_RANGE_HEX  0x40

typedef enum {
    UNITY_DISPLAY_STYLE_INT     = (int)sizeof(int) + UNITY_DISPLAY_RANGE_INT,
    UNITY_DISPLAY_STYLE_INT8    = 1 + UNITY_DISPLAY_RANGE_INT,
    UNITY_DISPLAY_STYLE_INT16   = 2 + UNITY_DISPLAY_RANGE_INT,
    UNITY_DISPLAY_STYLE_INT32   = 4 + UNITY_DISPLAY_RANGE_INT,
    UNITY_DISPLAY_STYLE_INT64   = 8 + UNITY_DISPLAY_RANGE_INT,

    UNITY_DISPLAY_STYLE_UINT    = (int)sizeof(unsigned int) + UNITY_DISPLAY_RANGE_UINT,
    UNITY_DISPLAY_STYLE_UINT8   = 1 + UNITY_DISPLAY_RANGE_UINT,
    UNITY_DISPLAY_STYLE_UINT16  = 2 + UNITY_DISPLAY_RANGE_UINT,
    UNITY_DISPLAY_STYLE_UINT32  = 4 + UNITY_DISPLAY_RANGE_UINT,
    UNITY_DISPLAY_STYLE_UINT64  = 8 + UNITY_DISPLAY_RANGE_UINT,

    UNITY_DISPLAY_STYLE_HEX8    = 1 + UNITY_DISPLAY_RANGE_HEX,
    UNITY_DISPLAY_STYLE_HEX16   = 2 + UNITY_DISPLAY_RANGE_HEX,
    UNITY_DISPLAY_STYLE_HEX32   = 4 + UNITY_DISPLAY_RANGE_HEX,
    UNITY_DISPLAY_STYLE_HEX64   = 8 + UNITY_DISPLAY_RANGE_HEX,

    UNITY_DISPLAY_STYLE_POINTER = (int)sizeof(void *) + UNITY_DISPLAY_RANGE_HEX
} UNITY_DISPLAY_STYLE_T;

typedef enum {
    UNITY_GREATER_THAN     = 0x1,
    UNITY_SMALLER_THAN     = 0x2,
    UNITY_EQUAL_TO         = 0x4,
    UNITY_GREATER_OR_EQUAL = UNITY_GREATER_THAN | UNITY_EQUAL_TO,
    UNITY_SMALLER_OR_EQUAL = UNITY_SMALLER_THAN | UNITY_EQUAL_TO,
    UNITY_NOT_EQUAL        = 0x8
} UNITY_COMPARISON_T;

/* ------------------------------------------------------------------ state */

/* Same name and field names as upstream Unity, so tests that peek at the
 * counters (e.g. Unity.CurrentTestFailed in tearDown) work with both. */
struct UNITY_STORAGE_T {
    const char        *TestFile;
    const char        *CurrentTestName;
    UNITY_LINE_TYPE    CurrentTestLineNumber;
    UNITY_COUNTER_TYPE NumberOfTests;
    UNITY_COUNTER_TYPE TestFailures;
    UNITY_COUNTER_TYPE TestIgnores;
    UNITY_COUNTER_TYPE CurrentTestFailed;
    UNITY_COUNTER_TYPE CurrentTestIgnored;
    jmp_buf            AbortFrame;
};

extern struct UNITY_STORAGE_T Unity;

/* setjmp is used directly as the whole controlling expression (C99 7.13.1.1). */
#define TEST_PROTECT() (setjmp(Unity.AbortFrame) == 0)
#define TEST_ABORT()   longjmp(Unity.AbortFrame, 1)

/* ------------------------------------------------------------- functions */

void UnityBegin(const char *filename);
int  UnityEnd(void);
void UnityDefaultTestRun(UnityTestFunction func, const char *func_name, const int func_line_num);
void UnityConcludeTest(void);

void UnityPrint(const char *string);
void UnityPrintLen(const char *string, const UNITY_UINT32 length);
void UnityPrintNumber(const UNITY_INT number);
void UnityPrintNumberUnsigned(const UNITY_UINT number);
void UnityPrintNumberHex(const UNITY_UINT number, const char nibbles);
void UnityPrintFloat(const UNITY_DOUBLE number);

void UnityFail(const char *message, const UNITY_LINE_TYPE line);
void UnityIgnore(const char *message, const UNITY_LINE_TYPE line);
void UnityMessage(const char *message, const UNITY_LINE_TYPE line);

void UnityAssertEqualNumber(const UNITY_INT expected, const UNITY_INT actual,
                            const char *msg, const UNITY_LINE_TYPE line,
                            const UNITY_DISPLAY_STYLE_T style);
void UnityAssertGreaterOrLessOrEqualNumber(const UNITY_INT threshold, const UNITY_INT actual,
                                           const UNITY_COMPARISON_T compare,
                                           const char *msg, const UNITY_LINE_TYPE line,
                                           const UNITY_DISPLAY_STYLE_T style);
void UnityAssertNumbersWithin(const UNITY_UINT delta, const UNITY_INT expected,
                              const UNITY_INT actual, const char *msg,
                              const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style);
void UnityAssertBits(const UNITY_INT mask, const UNITY_INT expected, const UNITY_INT actual,
                     const char *msg, const UNITY_LINE_TYPE line);
void UnityAssertEqualIntArray(UNITY_INTERNAL_PTR expected, UNITY_INTERNAL_PTR actual,
                              const UNITY_UINT32 num_elements, const char *msg,
                              const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style);
void UnityAssertEachEqualNumber(const UNITY_INT expected, UNITY_INTERNAL_PTR actual,
                                const UNITY_UINT32 num_elements, const char *msg,
                                const UNITY_LINE_TYPE line, const UNITY_DISPLAY_STYLE_T style);
void UnityAssertEqualMemory(UNITY_INTERNAL_PTR expected, UNITY_INTERNAL_PTR actual,
                            const UNITY_UINT32 length, const UNITY_UINT32 num_elements,
                            const char *msg, const UNITY_LINE_TYPE line);
void UnityAssertEqualString(const char *expected, const char *actual,
                            const char *msg, const UNITY_LINE_TYPE line);
void UnityAssertEqualStringLen(const char *expected, const char *actual,
                               const UNITY_UINT32 length, const char *msg,
                               const UNITY_LINE_TYPE line);
void UnityAssertFloatsWithin(const UNITY_FLOAT delta, const UNITY_FLOAT expected,
                             const UNITY_FLOAT actual, const char *msg,
                             const UNITY_LINE_TYPE line);
void UnityAssertDoublesWithin(const UNITY_DOUBLE delta, const UNITY_DOUBLE expected,
                              const UNITY_DOUBLE actual, const char *msg,
                              const UNITY_LINE_TYPE line);

/* ------------------------------------------------- assertion building blocks
 * UNITY_TEST_ASSERT_xxx(args..., line, message): what the public TEST_ASSERT_xxx
 * and TEST_ASSERT_xxx_MESSAGE macros in unity.h expand to. */

#define UNITY_LINE_(line) ((UNITY_LINE_TYPE)(line))

#define UNITY_TEST_FAIL(line, message)   UnityFail((message), UNITY_LINE_(line))
#define UNITY_TEST_IGNORE(line, message) UnityIgnore((message), UNITY_LINE_(line))

#define UNITY_TEST_ASSERT(condition, line, message) \
    do { if (condition) { } else { UNITY_TEST_FAIL((line), (message)); } } while (0)

#define UNITY_TEST_ASSERT_NULL(pointer, line, message) \
    UNITY_TEST_ASSERT(((pointer) == NULL), (line), (message))
#define UNITY_TEST_ASSERT_NOT_NULL(pointer, line, message) \
    UNITY_TEST_ASSERT(((pointer) != NULL), (line), (message))

/* Equality of integers: operands are first narrowed to the named width. */
#define UNITY_EQ_(e, a, cast, line, message, style) \
    UnityAssertEqualNumber((UNITY_INT)(cast)(e), (UNITY_INT)(cast)(a), (message), UNITY_LINE_(line), (style))
#define UNITY_TEST_ASSERT_EQUAL_INT(e, a, line, message) \
    UnityAssertEqualNumber((UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_INT)
#define UNITY_TEST_ASSERT_EQUAL_INT8(e, a, line, message)   UNITY_EQ_(e, a, UNITY_INT8,   line, message, UNITY_DISPLAY_STYLE_INT8)
#define UNITY_TEST_ASSERT_EQUAL_INT16(e, a, line, message)  UNITY_EQ_(e, a, UNITY_INT16,  line, message, UNITY_DISPLAY_STYLE_INT16)
#define UNITY_TEST_ASSERT_EQUAL_INT32(e, a, line, message)  UNITY_EQ_(e, a, UNITY_INT32,  line, message, UNITY_DISPLAY_STYLE_INT32)
#define UNITY_TEST_ASSERT_EQUAL_INT64(e, a, line, message)  UNITY_EQ_(e, a, UNITY_INT64,  line, message, UNITY_DISPLAY_STYLE_INT64)
#define UNITY_TEST_ASSERT_EQUAL_UINT(e, a, line, message) \
    UnityAssertEqualNumber((UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_UINT)
#define UNITY_TEST_ASSERT_EQUAL_UINT8(e, a, line, message)  UNITY_EQ_(e, a, UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_UINT8)
#define UNITY_TEST_ASSERT_EQUAL_UINT16(e, a, line, message) UNITY_EQ_(e, a, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_UINT16)
#define UNITY_TEST_ASSERT_EQUAL_UINT32(e, a, line, message) UNITY_EQ_(e, a, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_UINT32)
#define UNITY_TEST_ASSERT_EQUAL_UINT64(e, a, line, message) UNITY_EQ_(e, a, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_UINT64)
#define UNITY_TEST_ASSERT_EQUAL_HEX8(e, a, line, message)   UNITY_EQ_(e, a, UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_HEX8)
#define UNITY_TEST_ASSERT_EQUAL_HEX16(e, a, line, message)  UNITY_EQ_(e, a, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_HEX16)
#define UNITY_TEST_ASSERT_EQUAL_HEX32(e, a, line, message)  UNITY_EQ_(e, a, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_HEX32)
#define UNITY_TEST_ASSERT_EQUAL_HEX64(e, a, line, message)  UNITY_EQ_(e, a, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_HEX64)
#define UNITY_TEST_ASSERT_EQUAL_PTR(e, a, line, message) \
    UnityAssertEqualNumber((UNITY_INT)(uintptr_t)(e), (UNITY_INT)(uintptr_t)(a), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_POINTER)

/* Ordering (threshold first, like upstream: GREATER_THAN(t, a) passes if a > t). */
#define UNITY_CMP_(t, a, cast, cmp, line, message, style) \
    UnityAssertGreaterOrLessOrEqualNumber((UNITY_INT)(cast)(t), (UNITY_INT)(cast)(a), (cmp), (message), UNITY_LINE_(line), (style))
#define UNITY_TEST_COMPARE_INT(t, a, cmp, line, message) \
    UnityAssertGreaterOrLessOrEqualNumber((UNITY_INT)(t), (UNITY_INT)(a), (cmp), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_INT)
#define UNITY_TEST_COMPARE_INT8(t, a, cmp, line, message)   UNITY_CMP_(t, a, UNITY_INT8,   cmp, line, message, UNITY_DISPLAY_STYLE_INT8)
#define UNITY_TEST_COMPARE_INT16(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_INT16,  cmp, line, message, UNITY_DISPLAY_STYLE_INT16)
#define UNITY_TEST_COMPARE_INT32(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_INT32,  cmp, line, message, UNITY_DISPLAY_STYLE_INT32)
#define UNITY_TEST_COMPARE_INT64(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_INT64,  cmp, line, message, UNITY_DISPLAY_STYLE_INT64)
#define UNITY_TEST_COMPARE_UINT(t, a, cmp, line, message) \
    UnityAssertGreaterOrLessOrEqualNumber((UNITY_INT)(t), (UNITY_INT)(a), (cmp), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_UINT)
#define UNITY_TEST_COMPARE_UINT8(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_UINT8,  cmp, line, message, UNITY_DISPLAY_STYLE_UINT8)
#define UNITY_TEST_COMPARE_UINT16(t, a, cmp, line, message) UNITY_CMP_(t, a, UNITY_UINT16, cmp, line, message, UNITY_DISPLAY_STYLE_UINT16)
#define UNITY_TEST_COMPARE_UINT32(t, a, cmp, line, message) UNITY_CMP_(t, a, UNITY_UINT32, cmp, line, message, UNITY_DISPLAY_STYLE_UINT32)
#define UNITY_TEST_COMPARE_UINT64(t, a, cmp, line, message) UNITY_CMP_(t, a, UNITY_UINT64, cmp, line, message, UNITY_DISPLAY_STYLE_UINT64)
#define UNITY_TEST_COMPARE_HEX8(t, a, cmp, line, message)   UNITY_CMP_(t, a, UNITY_UINT8,  cmp, line, message, UNITY_DISPLAY_STYLE_HEX8)
#define UNITY_TEST_COMPARE_HEX16(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_UINT16, cmp, line, message, UNITY_DISPLAY_STYLE_HEX16)
#define UNITY_TEST_COMPARE_HEX32(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_UINT32, cmp, line, message, UNITY_DISPLAY_STYLE_HEX32)
#define UNITY_TEST_COMPARE_HEX64(t, a, cmp, line, message)  UNITY_CMP_(t, a, UNITY_UINT64, cmp, line, message, UNITY_DISPLAY_STYLE_HEX64)

/* Integer ranges: |actual - expected| <= delta. */
#define UNITY_WITHIN_(d, e, a, dcast, cast, line, message, style) \
    UnityAssertNumbersWithin((UNITY_UINT)(dcast)(d), (UNITY_INT)(cast)(e), (UNITY_INT)(cast)(a), (message), UNITY_LINE_(line), (style))
#define UNITY_TEST_ASSERT_INT_WITHIN(d, e, a, line, message) \
    UnityAssertNumbersWithin((UNITY_UINT)(d), (UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_INT)
#define UNITY_TEST_ASSERT_INT8_WITHIN(d, e, a, line, message)   UNITY_WITHIN_(d, e, a, UNITY_UINT8,  UNITY_INT8,   line, message, UNITY_DISPLAY_STYLE_INT8)
#define UNITY_TEST_ASSERT_INT16_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT16, UNITY_INT16,  line, message, UNITY_DISPLAY_STYLE_INT16)
#define UNITY_TEST_ASSERT_INT32_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT32, UNITY_INT32,  line, message, UNITY_DISPLAY_STYLE_INT32)
#define UNITY_TEST_ASSERT_INT64_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT64, UNITY_INT64,  line, message, UNITY_DISPLAY_STYLE_INT64)
#define UNITY_TEST_ASSERT_UINT_WITHIN(d, e, a, line, message) \
    UnityAssertNumbersWithin((UNITY_UINT)(d), (UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_LINE_(line), UNITY_DISPLAY_STYLE_UINT)
#define UNITY_TEST_ASSERT_UINT8_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT8,  UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_UINT8)
#define UNITY_TEST_ASSERT_UINT16_WITHIN(d, e, a, line, message) UNITY_WITHIN_(d, e, a, UNITY_UINT16, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_UINT16)
#define UNITY_TEST_ASSERT_UINT32_WITHIN(d, e, a, line, message) UNITY_WITHIN_(d, e, a, UNITY_UINT32, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_UINT32)
#define UNITY_TEST_ASSERT_UINT64_WITHIN(d, e, a, line, message) UNITY_WITHIN_(d, e, a, UNITY_UINT64, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_UINT64)
#define UNITY_TEST_ASSERT_HEX8_WITHIN(d, e, a, line, message)   UNITY_WITHIN_(d, e, a, UNITY_UINT8,  UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_HEX8)
#define UNITY_TEST_ASSERT_HEX16_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT16, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_HEX16)
#define UNITY_TEST_ASSERT_HEX32_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT32, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_HEX32)
#define UNITY_TEST_ASSERT_HEX64_WITHIN(d, e, a, line, message)  UNITY_WITHIN_(d, e, a, UNITY_UINT64, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_HEX64)

/* Bit masks. */
#define UNITY_TEST_ASSERT_BITS(mask, e, a, line, message) \
    UnityAssertBits((UNITY_INT)(mask), (UNITY_INT)(e), (UNITY_INT)(a), (message), UNITY_LINE_(line))

/* Arrays of integers, compared element by element. */
#define UNITY_ARR_(e, a, n, line, message, style) \
    UnityAssertEqualIntArray((UNITY_INTERNAL_PTR)(e), (UNITY_INTERNAL_PTR)(a), (UNITY_UINT32)(n), (message), UNITY_LINE_(line), (style))
#define UNITY_TEST_ASSERT_EQUAL_INT_ARRAY(e, a, n, line, message)    UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_INT)
#define UNITY_TEST_ASSERT_EQUAL_INT8_ARRAY(e, a, n, line, message)   UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_INT8)
#define UNITY_TEST_ASSERT_EQUAL_INT16_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_INT16)
#define UNITY_TEST_ASSERT_EQUAL_INT32_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_INT32)
#define UNITY_TEST_ASSERT_EQUAL_INT64_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_INT64)
#define UNITY_TEST_ASSERT_EQUAL_UINT_ARRAY(e, a, n, line, message)   UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_UINT)
#define UNITY_TEST_ASSERT_EQUAL_UINT8_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_UINT8)
#define UNITY_TEST_ASSERT_EQUAL_UINT16_ARRAY(e, a, n, line, message) UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_UINT16)
#define UNITY_TEST_ASSERT_EQUAL_UINT32_ARRAY(e, a, n, line, message) UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_UINT32)
#define UNITY_TEST_ASSERT_EQUAL_UINT64_ARRAY(e, a, n, line, message) UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_UINT64)
#define UNITY_TEST_ASSERT_EQUAL_HEX8_ARRAY(e, a, n, line, message)   UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_HEX8)
#define UNITY_TEST_ASSERT_EQUAL_HEX16_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_HEX16)
#define UNITY_TEST_ASSERT_EQUAL_HEX32_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_HEX32)
#define UNITY_TEST_ASSERT_EQUAL_HEX64_ARRAY(e, a, n, line, message)  UNITY_ARR_(e, a, n, line, message, UNITY_DISPLAY_STYLE_HEX64)

/* Every element of an array equal to one value. */
#define UNITY_EACH_(e, a, n, cast, line, message, style) \
    UnityAssertEachEqualNumber((UNITY_INT)(cast)(e), (UNITY_INTERNAL_PTR)(a), (UNITY_UINT32)(n), (message), UNITY_LINE_(line), (style))
#define UNITY_TEST_ASSERT_EACH_EQUAL_INT(e, a, n, line, message)    UNITY_EACH_(e, a, n, int,          line, message, UNITY_DISPLAY_STYLE_INT)
#define UNITY_TEST_ASSERT_EACH_EQUAL_INT8(e, a, n, line, message)   UNITY_EACH_(e, a, n, UNITY_INT8,   line, message, UNITY_DISPLAY_STYLE_INT8)
#define UNITY_TEST_ASSERT_EACH_EQUAL_INT16(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_INT16,  line, message, UNITY_DISPLAY_STYLE_INT16)
#define UNITY_TEST_ASSERT_EACH_EQUAL_INT32(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_INT32,  line, message, UNITY_DISPLAY_STYLE_INT32)
#define UNITY_TEST_ASSERT_EACH_EQUAL_INT64(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_INT64,  line, message, UNITY_DISPLAY_STYLE_INT64)
#define UNITY_TEST_ASSERT_EACH_EQUAL_UINT(e, a, n, line, message)   UNITY_EACH_(e, a, n, unsigned int, line, message, UNITY_DISPLAY_STYLE_UINT)
#define UNITY_TEST_ASSERT_EACH_EQUAL_UINT8(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_UINT8)
#define UNITY_TEST_ASSERT_EACH_EQUAL_UINT16(e, a, n, line, message) UNITY_EACH_(e, a, n, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_UINT16)
#define UNITY_TEST_ASSERT_EACH_EQUAL_UINT32(e, a, n, line, message) UNITY_EACH_(e, a, n, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_UINT32)
#define UNITY_TEST_ASSERT_EACH_EQUAL_UINT64(e, a, n, line, message) UNITY_EACH_(e, a, n, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_UINT64)
#define UNITY_TEST_ASSERT_EACH_EQUAL_HEX8(e, a, n, line, message)   UNITY_EACH_(e, a, n, UNITY_UINT8,  line, message, UNITY_DISPLAY_STYLE_HEX8)
#define UNITY_TEST_ASSERT_EACH_EQUAL_HEX16(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_UINT16, line, message, UNITY_DISPLAY_STYLE_HEX16)
#define UNITY_TEST_ASSERT_EACH_EQUAL_HEX32(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_UINT32, line, message, UNITY_DISPLAY_STYLE_HEX32)
#define UNITY_TEST_ASSERT_EACH_EQUAL_HEX64(e, a, n, line, message)  UNITY_EACH_(e, a, n, UNITY_UINT64, line, message, UNITY_DISPLAY_STYLE_HEX64)

/* Raw memory and strings. */
#define UNITY_TEST_ASSERT_EQUAL_MEMORY(e, a, len, line, message) \
    UnityAssertEqualMemory((UNITY_INTERNAL_PTR)(e), (UNITY_INTERNAL_PTR)(a), (UNITY_UINT32)(len), 1u, (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_EQUAL_MEMORY_ARRAY(e, a, len, n, line, message) \
    UnityAssertEqualMemory((UNITY_INTERNAL_PTR)(e), (UNITY_INTERNAL_PTR)(a), (UNITY_UINT32)(len), (UNITY_UINT32)(n), (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_EQUAL_STRING(e, a, line, message) \
    UnityAssertEqualString((const char *)(e), (const char *)(a), (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_EQUAL_STRING_LEN(e, a, len, line, message) \
    UnityAssertEqualStringLen((const char *)(e), (const char *)(a), (UNITY_UINT32)(len), (message), UNITY_LINE_(line))

/* Floating point (tests only; the core never uses it). */
#define UNITY_TEST_ASSERT_FLOAT_WITHIN(d, e, a, line, message) \
    UnityAssertFloatsWithin((UNITY_FLOAT)(d), (UNITY_FLOAT)(e), (UNITY_FLOAT)(a), (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_EQUAL_FLOAT(e, a, line, message) \
    UnityAssertFloatsWithin((UNITY_FLOAT)(e) * (UNITY_FLOAT)UNITY_FLOAT_PRECISION, (UNITY_FLOAT)(e), (UNITY_FLOAT)(a), (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_DOUBLE_WITHIN(d, e, a, line, message) \
    UnityAssertDoublesWithin((UNITY_DOUBLE)(d), (UNITY_DOUBLE)(e), (UNITY_DOUBLE)(a), (message), UNITY_LINE_(line))
#define UNITY_TEST_ASSERT_EQUAL_DOUBLE(e, a, line, message) \
    UnityAssertDoublesWithin((UNITY_DOUBLE)(e) * (UNITY_DOUBLE)UNITY_DOUBLE_PRECISION, (UNITY_DOUBLE)(e), (UNITY_DOUBLE)(a), (message), UNITY_LINE_(line))

#ifdef __cplusplus
}
#endif

#endif /* XGO_UNITY_INTERNALS_H */
