/*
 * The twelve emulated servos (src/core/servos.c) on their own: rate-limited
 * tracking, joint limits, limp joints and reloading without a jump, zero
 * offsets recorded in calibration and kept within a turn. Expected angles are
 * computed here from the step and the limits.
 */
#include <stdlib.h>
#include <string.h>

#include "unity.h"
#include "xgo/profile.h"
#include "servos.h"

static xgo_servos_t s;
static const xgo_profile_t *p;

void setUp(void)
{
    static const int32_t zero[XGO_SERVO_COUNT] = {0};
    p = xgo_profile_mini();
    xgo_servos_init(&s, p, zero);
}

void tearDown(void)
{
}

static const xgo_range_t *limits(unsigned i)
{
    return &p->joint_mdeg[i % XGO_JOINT_COUNT];
}

static void test_init_clamps_to_the_joint_limits(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = i % 2 ? 1000000 : -1000000;
    }
    xgo_servos_init(&s, p, q);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(i % 2 ? limits(i)->hi : limits(i)->lo, s.angle_mdeg[i]);
        TEST_ASSERT_EQUAL_INT32(s.angle_mdeg[i], s.target_mdeg[i]);
        TEST_ASSERT_EQUAL_INT32(0, s.zero_offset_mdeg[i]);
    }
    TEST_ASSERT_EQUAL_HEX16(0, s.unloaded);
}

/* Each tick a joint moves by the step (or what is left), never past the
 * target; the number of ticks to arrive is ceil(distance / step). */
static void test_joints_move_at_most_one_step_per_tick_and_arrive_exactly(void)
{
    int32_t q[XGO_SERVO_COUNT];
    const int32_t step = 1200;
    unsigned i, t;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = (int32_t)(i * 4001) - 20000; /* -20.000 .. +24.011 deg, inside every range */
    }
    xgo_servos_set_targets(&s, q);
    for (t = 1; t <= 25; t++) {
        xgo_servos_tick(&s, step);
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            const int32_t dist = abs(q[i]);
            const int32_t moved = (int32_t)t * step < dist ? (int32_t)t * step : dist;
            TEST_ASSERT_EQUAL_INT32(q[i] < 0 ? -moved : moved, s.angle_mdeg[i]);
        }
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(q[i], s.angle_mdeg[i]);
    }
}

static void test_targets_beyond_the_limits_stop_at_the_limits(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = i < 6 ? INT32_MAX : INT32_MIN;
    }
    xgo_servos_set_targets(&s, q);
    for (i = 0; i < 1000; i++) {
        xgo_servos_tick(&s, 600000);
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(i < 6 ? limits(i)->hi : limits(i)->lo, s.angle_mdeg[i]);
    }
}

static void test_a_negative_step_holds_every_joint(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = 10000;
    }
    xgo_servos_set_targets(&s, q);
    xgo_servos_tick(&s, -5);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(0, s.angle_mdeg[i]);
    }
}

/* Unloaded joints are limp: they keep their angle whatever the targets; a
 * reloaded joint holds where it is (no jump back to an old target). */
static void test_limp_joints_ignore_targets_and_reload_without_a_jump(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = 5000;
    }
    xgo_servos_set_targets(&s, q);
    xgo_servos_tick(&s, 2000); /* every joint at 2000 */
    xgo_servos_unload(&s, XGO_SERVO_LEG_MASK(1));
    TEST_ASSERT_EQUAL_HEX16(0x0038, s.unloaded);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = -30000;
    }
    xgo_servos_set_targets(&s, q);
    xgo_servos_tick(&s, 1000);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(i / 3 == 1 ? 2000 : 1000, s.angle_mdeg[i]);
    }
    xgo_servos_load(&s, XGO_SERVO_ALL_MASK);
    TEST_ASSERT_EQUAL_HEX16(0, s.unloaded);
    xgo_servos_tick(&s, 1000);
    for (i = 3; i < 6; i++) {
        TEST_ASSERT_EQUAL_INT32(2000, s.angle_mdeg[i]); /* holds where it was */
    }
    xgo_servos_unload(&s, 0xF000u); /* bits beyond the twelve joints mean nothing */
    TEST_ASSERT_EQUAL_HEX16(0, s.unloaded);
}

/* One follow of s, checked against the two calls it stands for (on a copy):
 * the same angles and targets, and a result saying exactly whether every
 * angle is now q (on every core). Returns that result. */
static int follow_checked(const int32_t q[XGO_SERVO_COUNT], int32_t step)
{
    xgo_servos_t two = s;
    int at, all = 1;
    unsigned i;
    xgo_servos_set_targets(&two, q);
    xgo_servos_tick(&two, step);
    at = xgo_servos_follow(&s, q, step);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        all = all && s.angle_mdeg[i] == q[i];
    }
    TEST_ASSERT_EQUAL_INT(all, at);
    TEST_ASSERT_EQUAL_INT32_ARRAY(two.angle_mdeg, s.angle_mdeg, XGO_SERVO_COUNT);
    TEST_ASSERT_EQUAL_INT32_ARRAY(two.target_mdeg, s.target_mdeg, XGO_SERVO_COUNT);
    return at;
}

/* The control tick's one-pass form does what the two calls do, limp
 * joints, limits and negative steps included; what it returns says whether
 * every angle is now the target given. */
static void test_follow_is_set_targets_then_tick(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i, n, reached = 0;
    srand(12);
    for (n = 0; n < 6000; n++) {
        const int32_t step = (int32_t)(rand() % 4000) - 500;
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            q[i] = n % 3 == 0 ? s.angle_mdeg[i] + (int32_t)(rand() % 200) - 100
                              : (int32_t)(rand() % 400000) - 200000;
        }
        if (n % 50 == 0) {
            xgo_servos_unload(&s, (uint16_t)(rand() & 0xFFF));
            xgo_servos_load(&s, (uint16_t)(rand() & 0xFFF));
        }
        reached += follow_checked(q, step) == 1;
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            TEST_ASSERT_TRUE(s.angle_mdeg[i] >= limits(i)->lo && s.angle_mdeg[i] <= limits(i)->hi);
        }
    }
    TEST_ASSERT_NOT_EQUAL(0, s.unloaded); /* limp joints were part of it */
    TEST_ASSERT_TRUE(reached > 10u); /* some reached it */
}

/* With every joint loaded (walking) the follow takes a short path while
 * each target is in range and within a step: it still does what the two
 * calls do at the limits, next to them, far beyond them (any int32), for a
 * step of any size, and says exactly whether every joint arrived. */
static void test_follow_with_every_joint_loaded_is_set_targets_then_tick(void)
{
    static const int32_t far[] = {INT32_MIN, INT32_MAX, -(1 << 30), 1 << 30, 0};
    static const int32_t big[] = {INT32_MAX, (1 << 30) + 1, 1 << 30, (1 << 30) - 1, 0, -1};
    int32_t q[XGO_SERVO_COUNT];
    uint32_t seed = 99u;
    unsigned i, n, reached = 0, short_of = 0;
    for (n = 0; n < 20000; n++) {
        int32_t step;
        int at;
        seed = seed * 1103515245u + 12345u;
        step = n % 5 == 4 ? big[(seed >> 16) % 6u] : (int32_t)((seed >> 16) % 3000u);
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            seed = seed * 1103515245u + 12345u;
            q[i] = s.angle_mdeg[i] + (int32_t)((seed >> 16) % 2001u) - 1000; /* mostly within a step */
            if (n % 9 == 0 && (seed >> 8) % 12u == i) {
                const int32_t edge = (seed >> 12) % 2u ? limits(i)->lo : limits(i)->hi;
                q[i] = (seed >> 13) % 3u == 0 ? far[(seed >> 20) % 5u] : edge + (int32_t)((seed >> 20) % 3u) - 1;
            }
        }
        at = follow_checked(q, step);
        reached += at == 1;
        short_of += at == 0;
    }
    TEST_ASSERT_EQUAL_HEX16(0, s.unloaded);
    TEST_ASSERT_TRUE(reached > 2000u && short_of > 2000u); /* both ways, often */
}

/* The every-joint-loaded follow decides joint by joint at the edges: a
 * target one inside or outside the range, an error one within or beyond
 * the step (the others resting, so only that joint decides), at angles at
 * and next to the limits, for steps of 0, 1, some and the cap. */
static void test_follow_with_every_joint_loaded_decides_at_the_edges(void)
{
    static const int32_t steps[] = {0, 1, 700, 1 << 30};
    unsigned i, a, e, k, reached = 0;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        const int32_t lo = limits(i)->lo, hi = limits(i)->hi;
        const int32_t at[] = {lo, lo + 1, lo / 2 + hi / 2, hi - 1, hi};
        for (a = 0; a < sizeof at / sizeof at[0]; a++) {
            for (k = 0; k < sizeof steps / sizeof steps[0]; k++) {
                const int32_t step = steps[k];
                const int32_t reach = step > 100000 ? 100000 : step; /* the cap: beyond any span */
                const int32_t t[] = {lo - 1, lo, hi, hi + 1, at[a] - reach - 1, at[a] - reach,
                                     at[a] + reach, at[a] + reach + 1};
                for (e = 0; e < sizeof t / sizeof t[0]; e++) {
                    int32_t q[XGO_SERVO_COUNT];
                    unsigned j;
                    for (j = 0; j < XGO_SERVO_COUNT; j++) {
                        q[j] = limits(j)->lo / 2 + limits(j)->hi / 2 + (int32_t)j;
                    }
                    q[i] = at[a];
                    xgo_servos_init(&s, p, q);
                    q[i] = t[e];
                    reached += follow_checked(q, step) == 1;
                }
            }
        }
    }
    TEST_ASSERT_TRUE(reached > 200u && reached < 1700u); /* both ways */
}

/* Set zero: the current angle joins the offset and reads 0 from then on
 * (clamped into the limits); offsets stay in [-180, 180) degrees. */
static void test_set_zero_moves_the_angle_into_the_offset_within_a_turn(void)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i, k;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q[i] = i % 2 ? limits(i)->hi : limits(i)->lo;
    }
    xgo_servos_init(&s, p, q);
    xgo_servos_record_zero(&s);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_EQUAL_INT32(q[i], s.zero_offset_mdeg[i]);
        TEST_ASSERT_EQUAL_INT32(0, s.angle_mdeg[i]);
        TEST_ASSERT_EQUAL_INT32(q[i], xgo_servos_raw(&s, i));
    }
    for (k = 0; k < 20; k++) { /* keep recording from the limit */
        xgo_servos_init(&s, p, q);
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            s.zero_offset_mdeg[i] = (int32_t)(k * 45000u) - 179000;
        }
        xgo_servos_record_zero(&s);
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            int32_t want = ((int32_t)(k * 45000u) - 179000 + q[i]) % 360000;
            want = want >= 180000 ? want - 360000 : (want < -180000 ? want + 360000 : want);
            TEST_ASSERT_EQUAL_INT32(want, s.zero_offset_mdeg[i]);
            TEST_ASSERT_TRUE(s.zero_offset_mdeg[i] >= -180000 && s.zero_offset_mdeg[i] < 180000);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_clamps_to_the_joint_limits);
    RUN_TEST(test_joints_move_at_most_one_step_per_tick_and_arrive_exactly);
    RUN_TEST(test_targets_beyond_the_limits_stop_at_the_limits);
    RUN_TEST(test_a_negative_step_holds_every_joint);
    RUN_TEST(test_limp_joints_ignore_targets_and_reload_without_a_jump);
    RUN_TEST(test_follow_is_set_targets_then_tick);
    RUN_TEST(test_follow_with_every_joint_loaded_is_set_targets_then_tick);
    RUN_TEST(test_follow_with_every_joint_loaded_decides_at_the_edges);
    RUN_TEST(test_set_zero_moves_the_angle_into_the_offset_within_a_turn);
    return UNITY_END();
}
