/*
 * Turn to heading (0x3F) and its origin (0x06): the controller on its own,
 * then the board over the wire on virtual time - how long a turn takes, where
 * it ends, that it turns in place, and what ends it.
 */
#include <math.h>
#include <string.h>

#include "board_io.h"
#include "unity.h"
#include "xgo/board.h"
#include "heading.h"

static xgo_board_t board;

void setUp(void)
{
    xgo_board_init(&board, NULL);
}

void tearDown(void)
{
}

/* ------------------------------------------------------------ controller */

static void test_rate_follows_the_braking_profile(void)
{
    xgo_heading_t h;
    xgo_heading_init(&h);
    xgo_heading_start(&h, 90);
    TEST_ASSERT_EQUAL_INT32(60000, xgo_heading_tick(&h, 0, 0));       /* far: full rate */
    /* 1 degree to go: sqrt(2 * 200 deg/s^2 * 1 deg) = 20 deg/s */
    TEST_ASSERT_INT32_WITHIN(1, 20000, xgo_heading_tick(&h, 89000, 0));
    /* 0.3 degree: 10.95 deg/s; within 0.25 it brakes (below) */
    TEST_ASSERT_INT32_WITHIN(1, (int32_t)sqrt(2.0 * 200000.0 * 300.0), xgo_heading_tick(&h, 89700, 0));
    TEST_ASSERT_EQUAL_INT32(-60000, xgo_heading_tick(&h, 179000, 0)); /* past it: back */
    TEST_ASSERT_EQUAL_UINT8(0, xgo_heading_done(&h));
}

static void test_settles_then_reports_done(void)
{
    xgo_heading_t h;
    xgo_heading_init(&h);
    xgo_heading_start(&h, 10);
    TEST_ASSERT_EQUAL_INT32(0, xgo_heading_tick(&h, 9900, 8000)); /* within 0.25: brake */
    TEST_ASSERT_EQUAL_UINT8(0, xgo_heading_done(&h));              /* still moving */
    TEST_ASSERT_EQUAL_INT32(0, xgo_heading_tick(&h, 10300, 0));
    TEST_ASSERT_EQUAL_UINT8(1, xgo_heading_done(&h));
    /* stopped outside the tolerance (pushed): turns again */
    xgo_heading_start(&h, 10);
    (void)xgo_heading_tick(&h, 9900, 8000);
    TEST_ASSERT_EQUAL_INT32(0, xgo_heading_tick(&h, 12000, 0));
    TEST_ASSERT_TRUE(xgo_heading_tick(&h, 12000, 0) < 0);
}

static void test_takes_the_shorter_way_across_180(void)
{
    xgo_heading_t h;
    xgo_heading_init(&h);
    xgo_heading_set_origin(&h, 170000);
    xgo_heading_start(&h, 20); /* 190 = -170 */
    TEST_ASSERT_TRUE(xgo_heading_tick(&h, 170000, 0) > 0);
    TEST_ASSERT_EQUAL_INT32(-170000, h.target_mdeg);
    xgo_heading_start(&h, 32767); /* 91 turns and 7 degrees */
    TEST_ASSERT_EQUAL_INT32(177000, h.target_mdeg);
    xgo_heading_start(&h, -32768);
    TEST_ASSERT_EQUAL_INT32(162000, h.target_mdeg); /* -91 turns and -8 */
}

/* ------------------------------------------------------------ the board */

static uint8_t read1(uint8_t addr)
{
    uint8_t v = 0xEE;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, addr, 1, 0, &v));
    return v;
}

static double read_yaw_deg(void)
{
    uint8_t b[4];
    float f;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, 0x64, 4, 0, b));
    memcpy(&f, b, 4); /* little-endian host */
    return f;
}

static void move_to(int16_t deg)
{
    const uint8_t be[2] = {(uint8_t)((uint16_t)deg >> 8), (uint8_t)deg};
    xgo_test_write(&board, 0x3F, be, 2, 0);
}

/* Ticks until 0x3F reads 1, polled every 50 ms as the library does (0.1 s),
 * at most limit ticks. */
static uint32_t ticks_until_done(uint32_t limit)
{
    uint32_t t = 0;
    while (t < limit && read1(0x3F) == 0) {
        xgo_test_ticks(&board, 25);
        t += 25;
    }
    return t;
}

static double wrap_deg(double a)
{
    return fmod(fmod(a + 180.0, 360.0) + 360.0, 360.0) - 180.0;
}

static void test_move_to_90_turns_in_place_within_the_turn_time(void)
{
    xgo_world_pose_t w;
    uint32_t ticks;
    move_to(90);
    TEST_ASSERT_EQUAL_HEX8(0, read1(0x3F));
    ticks = ticks_until_done(5 * XGO_TICK_HZ);
    /* 60 deg/s with 250 deg/s^2 up and 200 deg/s^2 down: about 1.9 s */
    TEST_ASSERT_TRUE_MESSAGE(ticks <= 11u * XGO_TICK_HZ / 5u, "90 degrees took over 2.2 s");
    TEST_ASSERT_TRUE_MESSAGE(ticks >= 3u * XGO_TICK_HZ / 2u, "90 degrees in under 1.5 s");
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 90.0, read_yaw_deg());
    xgo_test_ticks(&board, XGO_TICK_HZ); /* the gait stops: nothing more turns */
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 90.0, read_yaw_deg());
    TEST_ASSERT_EQUAL_HEX8(0x80, read1(0x40)); /* the second byte was no foot command */
    TEST_ASSERT_EQUAL_HEX8(0x00, read1(0x00)); /* whole unit */
    xgo_board_world_pose(&board, &w);
    TEST_ASSERT_INT32_WITHIN(5000, 0, w.x_um); /* in place */
    TEST_ASSERT_INT32_WITHIN(5000, 0, w.y_um);
}

static void test_heading_is_relative_to_the_origin(void)
{
    double origin;
    xgo_test_write1(&board, 0x32, 0xC0, 0); /* turn left a while */
    xgo_test_ticks(&board, XGO_TICK_HZ);
    xgo_test_write1(&board, 0x32, 0x80, 0);
    xgo_test_ticks(&board, 2 * XGO_TICK_HZ);
    origin = read_yaw_deg();
    TEST_ASSERT_TRUE(origin > 20.0);
    xgo_test_write1(&board, 0x06, 1, 0);
    xgo_test_ticks(&board, 1);
    TEST_ASSERT_EQUAL_HEX8(0, read1(0x06)); /* acts, then clears */
    move_to(-135);
    TEST_ASSERT_TRUE(ticks_until_done(6 * XGO_TICK_HZ) < 6u * XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 0.0, wrap_deg(read_yaw_deg() - (origin - 135.0)));
}

static void test_half_turns_both_ways_end_there(void)
{
    move_to(180);
    TEST_ASSERT_TRUE(ticks_until_done(6 * XGO_TICK_HZ) < 6u * XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 0.0, wrap_deg(read_yaw_deg() - 180.0));
    move_to(-90);
    TEST_ASSERT_TRUE(ticks_until_done(6 * XGO_TICK_HZ) < 6u * XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(1.0, -90.0, read_yaw_deg());
}

static void test_another_motion_command_ends_the_turn(void)
{
    double y0, y1;
    move_to(170);
    xgo_test_ticks(&board, XGO_TICK_HZ / 2);
    xgo_test_write1(&board, 0x30, 0x80, 0); /* stop(): the host takes over */
    xgo_test_ticks(&board, 1);
    TEST_ASSERT_EQUAL_HEX8(1, read1(0x3F));
    xgo_test_ticks(&board, XGO_TICK_HZ);
    y0 = read_yaw_deg();
    xgo_test_ticks(&board, XGO_TICK_HZ / 2);
    y1 = read_yaw_deg();
    TEST_ASSERT_DOUBLE_WITHIN(0.01, y0, y1); /* not turning any more */
    TEST_ASSERT_TRUE(y0 < 100.0);
}

static void test_reset_returns_the_origin_to_power_up(void)
{
    xgo_test_write1(&board, 0x32, 0xC0, 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    xgo_test_write1(&board, 0x32, 0x80, 0);
    xgo_test_write1(&board, 0x06, 1, 0);
    xgo_test_ticks(&board, 2 * XGO_TICK_HZ);
    xgo_test_write1(&board, 0x3E, 255, 0);
    xgo_test_ticks(&board, 2 * XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_INT32(0, board.motion.heading.origin_mdeg);
    TEST_ASSERT_EQUAL_HEX8(1, read1(0x3F));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_rate_follows_the_braking_profile);
    RUN_TEST(test_settles_then_reports_done);
    RUN_TEST(test_takes_the_shorter_way_across_180);
    RUN_TEST(test_move_to_90_turns_in_place_within_the_turn_time);
    RUN_TEST(test_heading_is_relative_to_the_origin);
    RUN_TEST(test_half_turns_both_ways_end_there);
    RUN_TEST(test_another_motion_command_ends_the_turn);
    RUN_TEST(test_reset_returns_the_origin_to_power_up);
    return UNITY_END();
}
