/*
 * The accelerometer and gyroscope (IMU block 0x65) and the int16 attitude
 * views: the model against a double-precision reference of the same physics
 * (specific force R^T (a + g), body rates from Euler rates), then the board
 * over the wire - standing, tilted, walking, turning, pushed - and the views'
 * agreement with 0x62..0x64.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "board_unity.h"
#include "unity.h"
#include "xgo/board.h"
#include "xgo/emulator.h"
#include "inertial.h"

static xgo_board_t board;

void setUp(void)
{
    xgo_board_init(&board, NULL);
}

void tearDown(void)
{
}

#define DEG (3.14159265358979323846 / 180.0)

/* ------------------------------------------------------------ reference */

/* R^T (a + g z) for R = Rz(h) Ry(p) Rx(r); a in m/s^2, result in LSB. */
static void ref_specific_force(const double a[3], double h, double r, double p, double out[3])
{
    const double g = 9.80665, lsb = 16384.0 / g;
    const double v[3] = {a[0], a[1], a[2] + g};
    /* rows of R^T = columns of R */
    const double R[3][3] = {
        {cos(h) * cos(p), cos(h) * sin(p) * sin(r) - sin(h) * cos(r),
         cos(h) * sin(p) * cos(r) + sin(h) * sin(r)},
        {sin(h) * cos(p), sin(h) * sin(p) * sin(r) + cos(h) * cos(r),
         sin(h) * sin(p) * cos(r) - cos(h) * sin(r)},
        {-sin(p), cos(p) * sin(r), cos(p) * cos(r)},
    };
    unsigned i;
    for (i = 0; i < 3; i++) {
        out[i] = lsb * (R[0][i] * v[0] + R[1][i] * v[1] + R[2][i] * v[2]);
    }
}

/* Body rates (deg/s) from Euler rates for R = Rz(y) Ry(p) Rx(r). */
static void ref_body_rates(double r, double p, double dr, double dp, double dy, double w[3])
{
    w[0] = dr - dy * sin(p);
    w[1] = dp * cos(r) + dy * sin(r) * cos(p);
    w[2] = -dp * sin(r) + dy * cos(r) * cos(p);
}

/* ------------------------------------------------------------ the model */

static void run_still(xgo_inertial_t *s, int32_t r, int32_t p, int32_t y, xgo_bam_t h, int ticks)
{
    const int64_t pos[3] = {123456789, -98765, 97600 * 256};
    const int32_t att[3] = {r, p, y};
    int i;
    for (i = 0; i < ticks; i++) {
        xgo_inertial_tick(s, pos, h, att);
    }
}

static void test_at_rest_reads_gravity_in_the_body_frame(void)
{
    static const int32_t att[][2] = {{0, 0}, {10000, 0}, {0, 10000}, {-25000, 17000},
                                     {44000, -44000}, {90000, 0}, {0, -90000}};
    size_t k;
    for (k = 0; k < sizeof att / sizeof att[0]; k++) {
        xgo_inertial_t s;
        const double zero[3] = {0, 0, 0};
        double want[3];
        unsigned i;
        xgo_inertial_init(&s);
        run_still(&s, att[k][0], att[k][1], 5000, 0x12345678u, 60);
        ref_specific_force(zero, 0.0, att[k][0] / 1000.0 * DEG, att[k][1] / 1000.0 * DEG, want);
        for (i = 0; i < 3; i++) {
            TEST_ASSERT_INT_WITHIN(2, (int)lround(want[i]), s.accel[i]);
            TEST_ASSERT_EQUAL_INT16(0, s.gyro[i]);
        }
    }
}

/* A constant world acceleration (a parabola of positions) while the body is
 * tilted and headed anywhere: the reading matches R^T (a + g). */
static void test_constant_acceleration_is_turned_into_the_body_frame(void)
{
    const double a[3] = {1.2, -0.7, 0.4};          /* m/s^2 */
    const double h = 0.8, r = 6.0 * DEG, p = -9.0 * DEG;
    const int32_t att[3] = {6000, -9000, 45837};
    const double dt = 1.0 / XGO_TICK_HZ;
    xgo_inertial_t s;
    double want[3];
    unsigned i;
    int k;
    xgo_inertial_init(&s);
    for (k = 0; k < 200; k++) {
        int64_t pos[3];
        for (i = 0; i < 3; i++) {
            pos[i] = llround(0.5 * a[i] * (k * dt) * (k * dt) * 1e6 * 256.0);
        }
        xgo_inertial_tick(&s, pos, (xgo_bam_t)llround(h / (2.0 * 3.14159265358979323846) * 4294967296.0), att);
    }
    ref_specific_force(a, h, r, p, want);
    for (i = 0; i < 3; i++) {
        TEST_ASSERT_INT_WITHIN(3, (int)lround(want[i]), s.accel[i]);
    }
}

/* Attitude changing at constant Euler rates: body rates as the reference. */
static void test_euler_rates_become_body_rates(void)
{
    static const double rates[][3] = {{30, 0, 0}, {0, -45, 0}, {0, 0, 90}, {12, 20, -60},
                                      {0, 0, -1500}};
    size_t k;
    for (k = 0; k < sizeof rates / sizeof rates[0]; k++) {
        const int64_t pos[3] = {0, 0, 0};
        xgo_inertial_t s;
        double w[3];
        int32_t att[3] = {0, 0, 0};
        double r = 0, p = 0;
        unsigned i;
        int t;
        xgo_inertial_init(&s);
        for (t = 0; t < 100; t++) {
            /* start tilted so the rates mix: roll 10, pitch 20 degrees */
            r = 10.0 + rates[k][0] * t / XGO_TICK_HZ;
            p = 20.0 + rates[k][1] * t / XGO_TICK_HZ;
            att[0] = (int32_t)lround(r * 1000.0);
            att[1] = (int32_t)lround(p * 1000.0);
            att[2] = (int32_t)lround(fmod(rates[k][2] * t / XGO_TICK_HZ + 540.0, 360.0) * 1000.0) - 180000;
            xgo_inertial_tick(&s, pos, 0, att);
        }
        ref_body_rates(r * DEG, p * DEG, rates[k][0], rates[k][1], rates[k][2], w);
        for (i = 0; i < 3; i++) {
            /* one mdeg of rounding per tick is 8.2 LSB at 500 Hz */
            TEST_ASSERT_INT_WITHIN(10, (int)lround(w[i] * 16.4), s.gyro[i]);
        }
    }
}

static void test_beyond_the_range_saturates(void)
{
    xgo_inertial_t s;
    int64_t pos[3] = {0, 0, 0};
    const int32_t att[3] = {0, 0, 0}, spin[3] = {0, 0, 179000};
    int t;
    xgo_inertial_init(&s);
    xgo_inertial_tick(&s, pos, 0, att);
    for (t = 0; t < 40; t++) {
        pos[0] += (int64_t)t << 32; /* violently faster every tick */
        xgo_inertial_tick(&s, pos, 0, t % 2 ? att : spin);
    }
    TEST_ASSERT_EQUAL_INT16(32767, s.accel[0]);
    TEST_ASSERT_TRUE(s.gyro[2] == 32767 || s.gyro[2] == -32768);
}

/* ------------------------------------------------------------ the board */

typedef struct {
    int16_t accel[3], gyro[3];
    float angle[3];
} block_t;

static block_t read_block(void)
{
    uint8_t b[24];
    block_t out;
    unsigned i;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, 0x65, 24, 0, b));
    for (i = 0; i < 3; i++) {
        out.accel[i] = (int16_t)(uint16_t)(b[2 * i] | b[2 * i + 1] << 8);
        out.gyro[i] = (int16_t)(uint16_t)(b[6 + 2 * i] | b[7 + 2 * i] << 8);
        memcpy(&out.angle[i], &b[12 + 4 * i], 4); /* little-endian host */
    }
    return out;
}

static float read_float(uint8_t addr)
{
    return xgo_test_rd_float(&board, addr);
}

static int16_t read_int16_be(uint8_t addr)
{
    uint8_t b[2];
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, addr, 2, 0, b));
    return (int16_t)(uint16_t)(b[0] << 8 | b[1]);
}

static void test_standing_reads_one_g_up(void)
{
    block_t blk;
    xgo_test_ticks(&board, 10);
    blk = read_block();
    TEST_ASSERT_EQUAL_INT16(0, blk.accel[0]);
    TEST_ASSERT_EQUAL_INT16(0, blk.accel[1]);
    TEST_ASSERT_EQUAL_INT16(16384, blk.accel[2]); /* the library: 16384 / 16384 * 9.8 */
    TEST_ASSERT_EQUAL_INT16(0, blk.gyro[2]);
}

/* On a slope (left side up 12 degrees, nose up 5): gravity tips into y and
 * x, and the block's angles are 0x62..0x64 to the bit. */
static void test_tilt_shows_in_the_accelerometer_and_the_views_agree(void)
{
    block_t blk;
    xgo_board_set_ground_tilt(&board, 12000, -5000);
    xgo_test_ticks(&board, 100);
    blk = read_block();
    TEST_ASSERT_INT_WITHIN(3, (int)lround(16384.0 * sin(5.0 * DEG)), blk.accel[0]);
    TEST_ASSERT_INT_WITHIN(3, (int)lround(16384.0 * cos(5.0 * DEG) * sin(12.0 * DEG)), blk.accel[1]);
    TEST_ASSERT_INT_WITHIN(3, (int)lround(16384.0 * cos(5.0 * DEG) * cos(12.0 * DEG)), blk.accel[2]);
    TEST_ASSERT_EQUAL_FLOAT(read_float(0x62), blk.angle[0]);
    TEST_ASSERT_EQUAL_FLOAT(read_float(0x63), blk.angle[1]);
    TEST_ASSERT_EQUAL_FLOAT(read_float(0x64), blk.angle[2]);
    TEST_ASSERT_EQUAL_INT16(1200, read_int16_be(0x66));
    TEST_ASSERT_EQUAL_INT16(-500, read_int16_be(0x67));
}

/* Starting to walk forward at full speed: the gait ramps at 0.5 m/s^2, which
 * the accelerometer sees along x (835 LSB); at cruise it reads 0 again. */
static void test_walking_off_accelerates_forward(void)
{
    long sum = 0;
    int t, lo = 99999, hi = -99999;
    xgo_test_write1(&board, 0x30, 0xFF, 0);
    for (t = 0; t < 400; t++) {
        xgo_board_tick(&board);
        if (t >= 20 && t < 220) {
            sum += board.motion.inertial.accel[0];
        }
        if (t >= 350) {
            const int16_t z = board.motion.inertial.accel[2];
            lo = z < lo ? z : lo;
            hi = z > hi ? z : hi;
        }
    }
    TEST_ASSERT_INT_WITHIN(120, 835, (int)(sum / 200));
    TEST_ASSERT_INT_WITHIN(200, 0, read_block().accel[0]);
    TEST_ASSERT_INT_WITHIN(50, 16384, lo);
    TEST_ASSERT_INT_WITHIN(50, 16384, hi);
}

/* Turning left at vyaw 0xC0 (50.6 deg/s): gyro z = rate * 16.4, and it agrees
 * with how fast 0x64 changes; the int16 yaw equals read_yaw's float. */
static void test_turning_shows_in_the_gyro(void)
{
    block_t blk;
    float y0, y1;
    xgo_test_write1(&board, 0x32, 0xC0, 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    blk = read_block();
    TEST_ASSERT_INT_WITHIN(10, (int)lround((-100.0 + 192.0 * 200.0 / 255.0) * 16.4), blk.gyro[2]);
    TEST_ASSERT_INT_WITHIN(3, 0, blk.gyro[0]);
    y0 = read_float(0x64);
    xgo_test_ticks(&board, XGO_TICK_HZ / 5);
    y1 = read_float(0x64);
    TEST_ASSERT_DOUBLE_WITHIN(0.6, blk.gyro[2] / 16.4 / 5.0, y1 - y0);
    TEST_ASSERT_INT_WITHIN(1, (int)lround(y1 * 100.0), read_int16_be(0x68));
}

/* A shove: the body tips and rings back. The tip itself is one tick (the
 * push model's), a spike in the gyro; the ringing after it is smooth,
 * and the gyro's integral over it is the change of the IMU's pitch (the
 * filter's lag of about 4 ticks allowed for). */
static void test_a_push_shows_in_the_gyro(void)
{
    int32_t rpy[3], pitch[80];
    double integral = 0;
    int t, peak = 0;
    xgo_test_ticks(&board, 10);
    xgo_board_push(&board, 0, 15000);
    for (t = 0; t < 80; t++) {
        xgo_board_tick(&board);
        xgo_board_imu_mdeg(&board, rpy);
        pitch[t] = rpy[1];
        if (t >= 20) {
            integral += board.motion.inertial.gyro[1] / 16.4 / XGO_TICK_HZ;
        }
        if (abs(board.motion.inertial.gyro[1]) > peak) {
            peak = abs(board.motion.inertial.gyro[1]);
        }
    }
    TEST_ASSERT_TRUE(peak > 16400); /* the tip: over 1000 deg/s */
    TEST_ASSERT_TRUE(pitch[79] - pitch[19] < -3000); /* it did swing back */
    TEST_ASSERT_DOUBLE_WITHIN(0.5, (pitch[75] - pitch[15]) / 1000.0, integral);
}

#if XGO_WITH_INERTIAL
static uint32_t lcg_next(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s;
}

/* The board's tick (xgo_inertial_tick_body: one function, inline on a
 * 64-bit host) is xgo_inertial_body_position, then xgo_inertial_tick_sc:
 * the same state after every tick of random walks, with and without a
 * body yaw. */
static void test_tick_body_is_position_then_tick(void)
{
    uint32_t seed = 5u;
    xgo_inertial_t a, b;
    xgo_odometry_t o;
    xgo_body_pose_t pose;
    unsigned k;
    xgo_inertial_init(&a);
    xgo_inertial_init(&b);
    xgo_odometry_init(&o);
    memset(&pose, 0, sizeof pose);
    for (k = 0; k < 100000; ++k) {
        int64_t body[3];
        xgo_q30_t sc[2];
        int32_t att[3];
        o.yaw += lcg_next(&seed) >> 10;
        xgo_sincos(o.yaw, &o.yaw_sc[0], &o.yaw_sc[1]);
        o.x_q8 += (int32_t)lcg_next(&seed) >> 12;
        o.y_q8 -= (int32_t)lcg_next(&seed) >> 12;
        pose.x_um = (int32_t)lcg_next(&seed) >> (k % 24u + 8u);
        pose.y_um = (int32_t)lcg_next(&seed) >> (k % 24u + 8u);
        pose.z_um = 90000 + (int32_t)(lcg_next(&seed) % 20000u);
        pose.yaw_mdeg = (k / 1000u) % 2u ? (int32_t)(lcg_next(&seed) % 40001u) - 20000 : 0;
        att[0] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        att[1] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        att[2] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        xgo_inertial_tick_body(&a, &o, &pose, att);
        xgo_inertial_body_position(&o, &pose, body, sc);
        xgo_inertial_tick_sc(&b, body, sc, att);
        if (memcmp(&a, &b, sizeof a) != 0) {
            TEST_FAIL_MESSAGE("xgo_inertial_tick_body differs from position + tick_sc");
        }
    }
}

/* The body's position in the world: the odometry's point plus the body
 * shift turned by the heading, * 256 / 2^30 rounded - against 64-bit
 * products computed here, for shifts inside the M0's 32-bit form (the
 * _narrow build of this suite takes it) and beyond it, every heading. */
static void test_body_position_is_the_rounded_turn(void)
{
    uint32_t seed = 99u;
    unsigned k;
    for (k = 0; k < 400000; ++k) {
        xgo_odometry_t o;
        xgo_body_pose_t pose;
        int64_t body[3], want0, want1;
        xgo_q30_t sc[2];
        memset(&o, 0, sizeof o);
        memset(&pose, 0, sizeof pose);
        o.yaw_sc[0] = (int32_t)(lcg_next(&seed) % 2147483649u) - (1 << 30);
        o.yaw_sc[1] = (int32_t)(lcg_next(&seed) % 2147483649u) - (1 << 30);
        o.x_q8 = (int64_t)(int32_t)lcg_next(&seed) * 1000;
        o.y_q8 = -(int64_t)(int32_t)lcg_next(&seed) * 777;
        pose.x_um = (int32_t)lcg_next(&seed) >> (k % 32u);
        pose.y_um = (int32_t)lcg_next(&seed) >> ((k / 32u) % 32u);
        pose.z_um = 97600;
        if (k % 4u == 0u) { /* near the 32-bit form's edges */
            pose.x_um = (int32_t)(lcg_next(&seed) % 3u) - 1 + ((k & 4u) ? (1 << 19) : -(1 << 19));
        }
        xgo_inertial_body_position(&o, &pose, body, sc);
        want0 = o.x_q8 + (((int64_t)o.yaw_sc[1] * pose.x_um - (int64_t)o.yaw_sc[0] * pose.y_um +
                           (1 << 21)) >> 22);
        want1 = o.y_q8 + (((int64_t)o.yaw_sc[0] * pose.x_um + (int64_t)o.yaw_sc[1] * pose.y_um +
                           (1 << 21)) >> 22);
        if (body[0] != want0 || body[1] != want1) {
            TEST_FAIL_MESSAGE("body position differs from the 64-bit turn");
        }
        TEST_ASSERT_TRUE(body[2] == (int64_t)97600 * 256);
    }
}

/* The model's product for large factors (xgo_inertial_mul_q30: 8-bit
 * pieces of c on a narrow core for |a| < 2^23, the _narrow build of this
 * suite takes them) is the rounded 64-bit product, at the form's edges and
 * for 2,000,000 random factors. */
static void test_large_products_are_the_rounded_wide_product(void)
{
    static const int32_t edge_a[] = {0, 1, -1, 4194304, -4194304, 8388607, -8388608, 8388608,
                                     -8388609, 2147483647, -2147483647 - 1, 1048575, -1048576};
    static const int32_t edge_c[] = {0, 1, -1, 1073741824, -1073741824, 1073741823, -1073741823,
                                     16777216, -16777216, 16777215, -16777217, 255, -256};
    uint32_t seed = 4242u;
    unsigned i, j, k;
    for (i = 0; i < sizeof edge_a / sizeof edge_a[0]; i++) {
        for (j = 0; j < sizeof edge_c / sizeof edge_c[0]; j++) {
            const int64_t want = ((int64_t)edge_a[i] * edge_c[j] + (1 << 29)) >> 30;
            TEST_ASSERT_TRUE(xgo_inertial_mul_q30(edge_a[i], edge_c[j]) == (int32_t)want);
        }
    }
    for (k = 0; k < 2000000; ++k) {
        const int32_t a = (int32_t)lcg_next(&seed) >> (k % 12u);
        const int32_t c = (int32_t)(lcg_next(&seed) % 2147483649u) - (1 << 30);
        const int64_t want = ((int64_t)a * c + (1 << 29)) >> 30;
        if (xgo_inertial_mul_q30(a, c) != (int32_t)want) {
            TEST_FAIL_MESSAGE("xgo_inertial_mul_q30 differs from the rounded 64-bit product");
        }
    }
}

/* The motion core hands the IMU model the roll's and the pitch's sin and
 * cos from the body IK's rotation of a pose without yaw (motion.c,
 * inertial_tick): those entries must be xgo_sincos's values exactly, for
 * every angle (0 included: sincos_mdeg's shortcut there). */
static void test_rotation_without_yaw_holds_the_sines(void)
{
    uint32_t seed = 7u;
    unsigned k;
    for (k = 0; k < 200000; ++k) {
        xgo_body_pose_t pose;
        xgo_q30_t rot[XGO_ROT_COUNT], sr, cr, sp, cp;
        memset(&pose, 0, sizeof pose);
        pose.roll_mdeg = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        pose.pitch_mdeg = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        if (k % 8u == 0u) {
            pose.roll_mdeg = 0;
        } else if (k % 8u == 1u) {
            pose.pitch_mdeg = 0;
        }
        xgo_body_rotation(&pose, rot);
        xgo_sincos(xgo_mdeg_to_bam(pose.roll_mdeg), &sr, &cr);
        xgo_sincos(xgo_mdeg_to_bam(pose.pitch_mdeg), &sp, &cp);
        if (-rot[XGO_ROT(1, 2)] != sr || rot[XGO_ROT(1, 1)] != cr || -rot[XGO_ROT(2, 0)] != sp ||
            rot[XGO_ROT(0, 0)] != cp) {
            TEST_FAIL_MESSAGE("the rotation's entries are not the sines and cosines");
        }
    }
}

/* ------------------------------------------------------------ exactness */

/* The model as inertial.h states it, every product the rounded 64-bit one
 * and no shortcut: the reference the tick's fast paths (the narrow cores'
 * pieces, 1 g's products as shifts, the 32-bit clamp) must equal bit for
 * bit. */
typedef struct ref_inertial_s {
    int64_t pos[2][3];
    int32_t att[3], acc_q8[3], gyro_q8[3];
    int history;
} ref_inertial_t;

static int32_t ref_mul(int64_t a, int32_t c)
{
    return (int32_t)((a * c + (1 << 29)) >> 30);
}

static int64_t ref_clamp(int64_t v, int64_t lim)
{
    return v > lim ? lim : (v < -lim ? -lim : v);
}

static int16_t ref_lsb(int32_t q8)
{
    const int32_t v = (q8 >= 0 ? q8 + 128 : q8 - 127) >> 8; /* inertial.c's rounding */
    return (int16_t)(v > 32767 ? 32767 : (v < -32768 ? -32768 : v));
}

static void ref_filter(int32_t state[3], const int32_t in[3], int16_t out[3])
{
    unsigned i;
    for (i = 0; i < 3; i++) {
        state[i] += (in[i] - state[i]) >> XGO_INERTIAL_FILTER_SHIFT;
        out[i] = ref_lsb(state[i]);
    }
}

static void ref_tick(ref_inertial_t *r, const int64_t body[3], const xgo_q30_t hsc[2],
                     const int32_t att[3], int16_t accel[3], int16_t gyro[3])
{
    const int64_t accel_q16 = ((int64_t)XGO_TICK_HZ * XGO_TICK_HZ * XGO_ACCEL_LSB_PER_G * 65536 +
                               XGO_GRAVITY_UM_S2 / 2) / XGO_GRAVITY_UM_S2;
    const int64_t gyro_q16 = ((int64_t)XGO_TICK_HZ * XGO_GYRO_LSB_PER_10_DEG_S * 256 * 65536 + 5000) /
                             10000;
    int32_t a[3], d[3], f[3], w[3], hx, hy, hz, x1, z1, yaw_cp;
    xgo_q30_t sr, cr, sp, cp;
    unsigned i;
    if (r->history == 0) {
        memcpy(r->pos[0], body, sizeof r->pos[0]);
        memcpy(r->att, att, sizeof r->att);
    }
    if (r->history < 2) {
        memcpy(r->pos[1], r->pos[0], sizeof r->pos[1]);
        r->history++;
    }
    for (i = 0; i < 3; i++) {
        const int64_t d2 = ref_clamp(body[i] - 2 * r->pos[0][i] + r->pos[1][i], 1 << 20);
        a[i] = (int32_t)((d2 * accel_q16 + 32768) >> 16);
        d[i] = xgo_wrap_mdeg(att[i] - r->att[i]);
        r->pos[1][i] = r->pos[0][i];
        r->pos[0][i] = body[i];
        r->att[i] = att[i];
    }
    xgo_sincos(xgo_mdeg_to_bam(att[0]), &sr, &cr);
    xgo_sincos(xgo_mdeg_to_bam(att[1]), &sp, &cp);
    hx = ref_mul(a[0], hsc[1]) + ref_mul(a[1], hsc[0]);
    hy = ref_mul(a[1], hsc[1]) - ref_mul(a[0], hsc[0]);
    hz = a[2] + XGO_ACCEL_LSB_PER_G * 256;
    x1 = ref_mul(hx, cp) - ref_mul(hz, sp);
    z1 = ref_mul(hx, sp) + ref_mul(hz, cp);
    f[0] = x1;
    f[1] = ref_mul(hy, cr) + ref_mul(z1, sr);
    f[2] = ref_mul(z1, cr) - ref_mul(hy, sr);
    yaw_cp = ref_mul(d[2], cp);
    w[0] = d[0] - ref_mul(d[2], sp);
    w[1] = ref_mul(d[1], cr) + ref_mul(yaw_cp, sr);
    w[2] = ref_mul(yaw_cp, cr) - ref_mul(d[1], sr);
    for (i = 0; i < 3; i++) {
        w[i] = (int32_t)((ref_clamp(w[i], 1 << 18) * gyro_q16 + 32768) >> 16);
    }
    ref_filter(r->acc_q8, f, accel);
    ref_filter(r->gyro_q8, w, gyro);
}

/* A change of v drawn at one of several sizes, so each path's range and
 * its edges are met: none, a few units, up to 2^14 (the rates' 16-bit
 * pieces), up to 2^20 (the 10-bit pieces), beyond. */
static int32_t ref_step(uint32_t *seed)
{
    const uint32_t r = lcg_next(seed);
    const int32_t v = (int32_t)lcg_next(seed);
    switch (r % 8u) {
    case 0:
    case 1:
        return 0;
    case 2:
        return v >> 26;
    case 3:
        return v >> 17;
    case 4:
        return (v >> 31) + ((r & 16u) ? (1 << 14) : -(1 << 14)); /* an edge */
    case 5:
        return v >> 11;
    case 6:
        return v >> 8;
    default:
        return v >> 2;
    }
}

/* 2,000,000 ticks of random motion - held still, walking-sized and wild
 * steps of position and attitude, constant and changing height, every
 * heading - give the accelerometer and gyroscope the reference's values
 * exactly, and the filters its states. */
static void test_tick_equals_the_wide_product_model(void)
{
    uint32_t seed = 2718u;
    unsigned run, k;
    for (run = 0; run < 2000; ++run) {
        xgo_inertial_t s;
        ref_inertial_t r;
        int64_t body[3] = {0, 0, 97600 * 256};
        int64_t vel[3] = {0, 0, 0};
        int32_t att[3], rate[3];
        memset(&r, 0, sizeof r);
        r.acc_q8[2] = XGO_ACCEL_LSB_PER_G * 256;
        xgo_inertial_init(&s);
        att[0] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        att[1] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        att[2] = (int32_t)(lcg_next(&seed) % 360000u) - 180000;
        rate[0] = ref_step(&seed);
        rate[1] = ref_step(&seed);
        rate[2] = ref_step(&seed);
        for (k = 0; k < 1000; ++k) {
            const xgo_bam_t h = lcg_next(&seed);
            xgo_q30_t hsc[2];
            int16_t accel[3], gyro[3];
            unsigned i;
            if (k % 50u == 0u) { /* a new motion: held (zeros) or walking-sized or wild */
                for (i = 0; i < 3; i++) {
                    vel[i] = (int64_t)ref_step(&seed) * ((run & 1u) ? 1 : 64);
                    rate[i] = ref_step(&seed);
                }
            }
            for (i = 0; i < 3; i++) {
                body[i] += vel[i] + ((k % 7u == 0u) ? ref_step(&seed) : 0);
                att[i] = xgo_wrap_mdeg(att[i] + rate[i] + ((k % 5u == 0u) ? ref_step(&seed) : 0));
            }
            xgo_sincos(h, &hsc[0], &hsc[1]);
            if (k % 3u == 0u) { /* a heading's sine and cosine as odometry keeps them, or any Q30 */
                hsc[0] = (int32_t)(lcg_next(&seed) % 2147483649u) - (1 << 30);
            }
            xgo_inertial_tick_sc(&s, body, hsc, att);
            ref_tick(&r, body, hsc, att, accel, gyro);
            if (memcmp(accel, s.accel, sizeof accel) != 0 || memcmp(gyro, s.gyro, sizeof gyro) != 0 ||
                memcmp(r.acc_q8, s.accel_q8, sizeof r.acc_q8) != 0 ||
                memcmp(r.gyro_q8, s.gyro_q8, sizeof r.gyro_q8) != 0) {
                TEST_FAIL_MESSAGE("the inertial tick differs from the wide-product model");
            }
        }
    }
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_at_rest_reads_gravity_in_the_body_frame);
    RUN_TEST(test_constant_acceleration_is_turned_into_the_body_frame);
    RUN_TEST(test_euler_rates_become_body_rates);
    RUN_TEST(test_beyond_the_range_saturates);
    RUN_TEST(test_standing_reads_one_g_up);
    RUN_TEST(test_tilt_shows_in_the_accelerometer_and_the_views_agree);
    RUN_TEST(test_walking_off_accelerates_forward);
    RUN_TEST(test_turning_shows_in_the_gyro);
    RUN_TEST(test_a_push_shows_in_the_gyro);
#if XGO_WITH_INERTIAL
    RUN_TEST(test_body_position_is_the_rounded_turn);
    RUN_TEST(test_tick_body_is_position_then_tick);
    RUN_TEST(test_rotation_without_yaw_holds_the_sines);
    RUN_TEST(test_large_products_are_the_rounded_wide_product);
    RUN_TEST(test_tick_equals_the_wide_product_model);
#endif
    return UNITY_END();
}
