/*
 * Bugs that shout, bad input that does not: with the core's checks on
 * (XGO_ASSERTS, the default of our builds) a caller's mistake reaches
 * xgo_assert_failed - here a hook of the test's own, which takes precedence
 * over the hosted default and jumps back - while any amount of bad input
 * from the wire is dropped and counted without a single failed check.
 */
#include <setjmp.h>
#include <string.h>

#include "board_io.h"
#include "servos.h"
#include "unity.h"
#include "xgo/board.h"

#if !XGO_ASSERT_ENABLED
#error "test_checks needs the core's checks (configure with -DXGO_ASSERTS=ON)"
#endif

static xgo_board_t board;
static jmp_buf g_back;
static unsigned g_failed;
static char g_expr[128];

void xgo_assert_failed(const char *file, int line, const char *expr)
{
    (void)file;
    (void)line;
    g_failed++;
    strncpy(g_expr, expr, sizeof g_expr - 1);
    longjmp(g_back, 1);
}

void setUp(void)
{
    xgo_board_init(&board, NULL);
    g_failed = 0;
    g_expr[0] = '\0';
}

void tearDown(void)
{
}

/* Runs one call that breaks a precondition; returns the failed check. */
#define EXPECT_CHECK(call, expr_text)                                                            \
    do {                                                                                         \
        g_failed = 0;                                                                            \
        if (setjmp(g_back) == 0) {                                                               \
            call;                                                                                \
        }                                                                                        \
        TEST_ASSERT_EQUAL_UINT_MESSAGE(1, g_failed, #call " went unnoticed");                    \
        TEST_ASSERT_EQUAL_STRING(expr_text, g_expr);                                             \
    } while (0)

static void test_caller_bugs_reach_the_hook(void)
{
    xgo_board_config_t cfg;
    xgo_board_t other;
    int32_t lo, hi;
    uint8_t out[4];
    EXPECT_CHECK(xgo_board_joint_limits_mdeg(&board, XGO_SERVO_COUNT, &lo, &hi),
                 "joint < XGO_SERVO_COUNT");
    EXPECT_CHECK(xgo_servos_raw(&board.motion.servos, 12), "joint < XGO_SERVO_COUNT");
    xgo_board_default_config(&cfg);
    cfg.battery_pct = 101;
    EXPECT_CHECK(xgo_board_init(&other, &cfg),
                 "cfg == NULL || (cfg->model <= XGO_MODEL_MINI2 && cfg->battery_pct <= 100)");
    EXPECT_CHECK(xgo_board_receive(&board, NULL, 3, 0), "bytes != NULL || n == 0");
    EXPECT_CHECK(xgo_board_write(&board, XGO_SOURCE_CLI, 0x30, NULL, 1), "data != NULL || n == 0");
    EXPECT_CHECK(xgo_board_transmit(&board, NULL, sizeof out), "out != NULL || max == 0");
}

/* Expected input never asserts: 20,000 random bytes, writes of every value
 * to every register, reads of every range, emulator inputs out of range. */
static void test_bad_input_is_counted_not_asserted(void)
{
    uint32_t state = 0x1234567u;
    uint8_t junk[256], out[XGO_FRAME_MAX_LEN];
    uint32_t c[XGO_DIAG_COUNT];
    unsigned i, a, v;
    if (setjmp(g_back) != 0) {
        TEST_FAIL_MESSAGE(g_expr);
    }
    for (i = 0; i < 20000u / sizeof junk; i++) {
        for (a = 0; a < sizeof junk; a++) {
            junk[a] = (uint8_t)xgo_test_xorshift32(&state);
        }
        xgo_board_receive(&board, junk, sizeof junk, i);
        xgo_board_tick(&board);
        (void)xgo_board_transmit(&board, out, sizeof out);
    }
    for (a = 0; a < XGO_REG_COUNT; a++) {
        for (v = 0; v < 256; v += 17) {
            const uint8_t b = (uint8_t)v;
            (void)xgo_board_write(&board, XGO_SOURCE_CLI, (uint8_t)a, &b, 1);
        }
        (void)xgo_board_read(&board, (uint8_t)a, 300, out); /* too long: refused */
        xgo_board_tick(&board);
    }
    xgo_board_counters(&board, c);
    TEST_ASSERT_TRUE(c[XGO_DIAG_REJECTED_VALUE] > 0 && c[XGO_DIAG_REJECTED_READ_ONLY] > 0);
    TEST_ASSERT_TRUE(c[XGO_DIAG_BYTES_DISCARDED] > 19000);
    TEST_ASSERT_EQUAL_UINT(0, g_failed);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_caller_bugs_reach_the_hook);
    RUN_TEST(test_bad_input_is_counted_not_asserted);
    return UNITY_END();
}
