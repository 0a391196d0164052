/*
 * The emulated IMU and battery (src/core/sensors.c) on their own, on virtual
 * time: yaw integrated exactly and wrapped, roll and pitch = body + ground
 * tilt (clamped to 45 degrees), a shove ringing down as a damped 3 Hz
 * oscillation (compared with the continuous solution computed here), and the
 * battery's drain rates and whole-percent reading.
 */
#include <math.h>
#include <stdlib.h>

#include "unity.h"
#include "xgo/config.h"
#include "sensors.h"
#include "fixed.h" /* xgo_wrap_mdeg, xgo_sat32: the reference below */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static xgo_imu_t imu;

void setUp(void)
{
    xgo_imu_init(&imu);
}

void tearDown(void)
{
}

static void imu_ticks(unsigned n, int32_t roll, int32_t pitch, int32_t yaw, int32_t rate)
{
    while (n-- > 0) {
        xgo_imu_tick(&imu, roll, pitch, yaw, rate);
    }
}

/* 90 deg/s for 1 s is 90 degrees exactly; 200 deg/s for 1 s wraps to -160;
 * the body's own yaw adds; reset zeroes the integral. */
static void test_yaw_integrates_the_rate_exactly_and_wraps(void)
{
    imu_ticks(XGO_TICK_HZ, 0, 0, 0, 90000);
    TEST_ASSERT_EQUAL_INT32(90000, imu.yaw_mdeg);
    imu_ticks(XGO_TICK_HZ, 0, 0, 0, -90000);
    TEST_ASSERT_EQUAL_INT32(0, imu.yaw_mdeg);
    imu_ticks(XGO_TICK_HZ, 0, 0, 0, 200000);
    TEST_ASSERT_EQUAL_INT32(-160000, imu.yaw_mdeg);
    imu_ticks(1, 0, 0, 5000, 0);
    TEST_ASSERT_EQUAL_INT32(-155000, imu.yaw_mdeg);
    imu_ticks(3u * XGO_TICK_HZ, 0, 0, 0, -1); /* 1 mdeg/s: sub-mdeg steps are kept */
    TEST_ASSERT_EQUAL_INT32(-160003, imu.yaw_mdeg);
    xgo_imu_reset_yaw(&imu);
    imu_ticks(1, 0, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(0, imu.yaw_mdeg);
    imu_ticks(XGO_TICK_HZ, 0, 0, 0, 5000000); /* 5000 deg/s: the 64-bit path */
    TEST_ASSERT_EQUAL_INT32(-40000, imu.yaw_mdeg); /* 5000 = 14 turns - 40 */
}

static void test_roll_and_pitch_are_body_plus_ground_tilt(void)
{
    xgo_imu_set_ground_tilt(&imu, 10000, -6000);
    imu_ticks(1, 2500, 1000, 0, 0);
    TEST_ASSERT_EQUAL_INT32(12500, imu.roll_mdeg);
    TEST_ASSERT_EQUAL_INT32(-5000, imu.pitch_mdeg);
    xgo_imu_set_ground_tilt(&imu, 90000, -46000); /* steeper than 45: not ground */
    TEST_ASSERT_EQUAL_INT32(45000, imu.ground_roll_mdeg);
    TEST_ASSERT_EQUAL_INT32(-45000, imu.ground_pitch_mdeg);
    imu_ticks(1, 170000, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(-145000, imu.roll_mdeg); /* 215 degrees wrapped */
}

/* A 10 degree shove: the reading follows the damped oscillation
 * x(t) = A e^(-z w t) (cos(wd t) + z w / wd sin(wd t)) of a 3 Hz spring with
 * damping ratio 0.35 to within 2 % of the tip (measured 1.6 %, the Euler
 * step's phase lag), stays below 1 % of it from 0.65 s on and is 0 at 1.5 s. */
static void test_a_shove_rings_down_like_the_damped_spring(void)
{
    const double w = 2.0 * M_PI * 3.0, z = 0.35, wd = w * sqrt(1.0 - z * z);
    double worst = 0.0;
    unsigned t;
    xgo_imu_push(&imu, 10000, 0);
    for (t = 1; t <= XGO_TICK_HZ; t++) {
        const double s = (double)t / XGO_TICK_HZ;
        const double ref = 10000.0 * exp(-z * w * s) * (cos(wd * s) + z * w / wd * sin(wd * s));
        imu_ticks(1, 0, 0, 0, 0);
        if (fabs(imu.roll_mdeg - ref) > worst) {
            worst = fabs(imu.roll_mdeg - ref);
        }
        if (t >= XGO_TICK_HZ * 65u / 100u) {
            TEST_ASSERT_TRUE(abs(imu.roll_mdeg) < 100);
        }
        TEST_ASSERT_EQUAL_INT32(0, imu.pitch_mdeg);
    }
    TEST_ASSERT_TRUE(worst < 200.0);
    imu_ticks(XGO_TICK_HZ / 2u, 0, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(0, imu.roll_mdeg); /* settled within 1.5 s */
    xgo_imu_push(&imu, 0, -90000);              /* clamped to 30 degrees */
    imu_ticks(1, 0, 0, 0, 0);
    TEST_ASSERT_INT32_WITHIN(100, -30000, imu.pitch_mdeg);
}

/* Idle 100 % lasts 120 min, walking 60 min; the register shows whole
 * percent rounded up, so a full battery reads 100 until 1 % has gone. */
static void test_battery_drains_at_the_documented_rates(void)
{
    const uint32_t idle_ticks_per_pct = (1000000u + XGO_BATTERY_IDLE_UPCT_PER_TICK - 1u) /
                                        XGO_BATTERY_IDLE_UPCT_PER_TICK;
    xgo_battery_t b;
    uint32_t t;
    TEST_ASSERT_EQUAL_UINT32(28, XGO_BATTERY_IDLE_UPCT_PER_TICK); /* 1e8 / 3.6e6 = 27.8 */
    TEST_ASSERT_EQUAL_UINT32(56, XGO_BATTERY_WALK_UPCT_PER_TICK); /* 1e8 / 1.8e6 = 55.6 */
    xgo_battery_init(&b, 100);
    for (t = 1; t < idle_ticks_per_pct; t++) {
        xgo_battery_tick(&b, 0);
    }
    TEST_ASSERT_EQUAL_UINT8(100, xgo_battery_percent(&b));
    xgo_battery_tick(&b, 0);
    TEST_ASSERT_EQUAL_UINT8(99, xgo_battery_percent(&b));
    xgo_battery_init(&b, 1);
    for (t = 0; t < 1000000u / XGO_BATTERY_WALK_UPCT_PER_TICK; t++) {
        xgo_battery_tick(&b, 1);
    }
    TEST_ASSERT_EQUAL_UINT8(1, xgo_battery_percent(&b)); /* 16 upct left */
    xgo_battery_tick(&b, 1);
    TEST_ASSERT_EQUAL_UINT8(0, xgo_battery_percent(&b));
    xgo_battery_tick(&b, 1);
    TEST_ASSERT_EQUAL_UINT32(0, b.charge_upct); /* empty stays empty */
}

/* xgo_battery_is_percent(b, p) holds exactly for p == xgo_battery_percent(b)
 * (beyond full, which never happens, for no p): every byte against charges
 * at and around each percent's edges, the empty and full ends. */
static void test_is_percent_is_the_percent_and_nothing_else(void)
{
    static const int32_t around[] = {-2, -1, 0, 1, 2, 499999, 500000};
    xgo_battery_t b;
    uint32_t pct;
    unsigned k, byte;
    for (pct = 0; pct <= 101u; pct++) {
        for (k = 0; k < sizeof around / sizeof around[0]; k++) {
            const int64_t c = (int64_t)pct * 1000000 + around[k];
            if (c < 0) {
                continue;
            }
            b.charge_upct = (uint32_t)c;
            for (byte = 0; byte < 256u; byte++) {
                TEST_ASSERT_EQUAL_INT(c <= 100000000 && byte == xgo_battery_percent(&b),
                                      xgo_battery_is_percent(&b, (uint8_t)byte));
            }
        }
    }
    b.charge_upct = 0xFFFFFFFFu;
    for (byte = 0; byte < 256u; byte++) {
        TEST_ASSERT_FALSE(xgo_battery_is_percent(&b, (uint8_t)byte));
    }
}

/* Each angle is the sum of its parts clamped to int32 and wrapped into
 * [-180000, 180000) (sensors.c sums them in 32 bits when they fit): at the
 * wrap's edges, at int32's (where the 32-bit sum overflows) and for
 * 200,000 random angles (half of them within two turns), with the
 * ground's tilt and the integrated yaw. */
static void test_attitude_is_the_clamped_sum_wrapped(void)
{
    static const int32_t edge[] = {0, 1, -1, 179999, 180000, -180000, -180001, 359999, -360000,
                                   2147483647, -2147483647 - 1, 2147483647 - 44999, -2147483647 + 44999,
                                   1073741824, -1073741824};
    static const int32_t tilt[] = {0, 45000, -45000, 1};
    uint32_t seed = 31u;
    unsigned i, j, k;
    for (k = 0; k < 200000u + 4u * 15u * 15u; ++k) {
        int32_t roll, pitch, yaw, rate;
        int64_t acc;
        if (k < 4u * 15u * 15u) {
            i = k % 15u;
            j = (k / 15u) % 15u;
            roll = edge[i];
            pitch = edge[j];
            yaw = edge[(i + j) % 15u];
            rate = (int32_t)(k / 225u) * 60000000 - 90000000;
#if XGO_WITH_EMULATOR_INPUTS
            xgo_imu_set_ground_tilt(&imu, tilt[k / 225u], tilt[(k / 225u + 1u) % 4u]);
#endif
        } else {
            /* every other draw within two turns: the sums a turn out of
             * the range, which a 64-bit host wraps inline */
            const unsigned near = k & 1u;
            seed = seed * 1664525u + 1013904223u;
            roll = near ? (int32_t)(seed % 1440001u) - 720000 : (int32_t)seed >> (seed % 16u);
            seed = seed * 1664525u + 1013904223u;
            pitch = near ? (int32_t)(seed % 1440001u) - 720000 : (int32_t)seed >> (seed % 16u);
            seed = seed * 1664525u + 1013904223u;
            yaw = near ? (int32_t)(seed % 1440001u) - 720000 : (int32_t)seed >> (seed % 16u);
            seed = seed * 1664525u + 1013904223u;
            rate = (int32_t)seed >> 4;
#if XGO_WITH_EMULATOR_INPUTS
            xgo_imu_set_ground_tilt(&imu, (int32_t)(seed % 90001u) - 45000, (int32_t)(seed % 80001u) - 40000);
#endif
        }
        imu_ticks(1, roll, pitch, yaw, rate);
        acc = imu.yaw_acc / (int32_t)XGO_TICK_HZ;
#if XGO_WITH_EMULATOR_INPUTS
        TEST_ASSERT_EQUAL_INT32(xgo_wrap_mdeg(xgo_sat32((int64_t)roll + imu.ground_roll_mdeg)), imu.roll_mdeg);
        TEST_ASSERT_EQUAL_INT32(xgo_wrap_mdeg(xgo_sat32((int64_t)pitch + imu.ground_pitch_mdeg)), imu.pitch_mdeg);
#else
        (void)tilt;
        TEST_ASSERT_EQUAL_INT32(xgo_wrap_mdeg(roll), imu.roll_mdeg);
        TEST_ASSERT_EQUAL_INT32(xgo_wrap_mdeg(pitch), imu.pitch_mdeg);
#endif
        TEST_ASSERT_EQUAL_INT32(xgo_wrap_mdeg(xgo_sat32(acc + yaw)), imu.yaw_mdeg);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_yaw_integrates_the_rate_exactly_and_wraps);
    RUN_TEST(test_is_percent_is_the_percent_and_nothing_else);
    RUN_TEST(test_roll_and_pitch_are_body_plus_ground_tilt);
    RUN_TEST(test_attitude_is_the_clamped_sum_wrapped);
    RUN_TEST(test_a_shove_rings_down_like_the_damped_spring);
    RUN_TEST(test_battery_drains_at_the_documented_rates);
    return UNITY_END();
}
