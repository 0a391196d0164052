/*
 * The Mini2's arm (--profile mini2): forward and inverse kinematics against a
 * double-precision reference written from the vendor library's own arm model
 * (arm_pos_update), the projection of unreachable points against a
 * brute-force search, then the board over the wire - identity, the library's
 * arm(), arm_polar(), claw() and servo_set_angle() bytes reaching their
 * point (within 2 mm as read back through read_motor's bytes, 1 mm by the
 * board's own account), servo slew, clamping counted, hold mode, reset, and
 * that 0x5D is the arm's servo on the Mini2 and the standing posture on the
 * Mini.
 */
#include <math.h>
#include <string.h>

#include "board_io.h"
#include "unity.h"
#include "arm.h"
#include "xgo/board.h"

static xgo_board_t board;
static const xgo_arm_geometry_t *g;

#define PI 3.14159265358979323846

void setUp(void)
{
    xgo_board_config_t cfg;
    xgo_board_default_config(&cfg);
    cfg.model = XGO_MODEL_MINI2;
    xgo_board_init(&board, &cfg);
    g = xgo_profile_mini2()->arm;
}

void tearDown(void)
{
}

/* ------------------------------------------------------------ reference */

/* The vendor library's arm model, written from its arm_pos_update(): links
 * of 60 mm (arm_init(60, 60)); servo 53 = th2 - 3, servo 52 = th3 - 11
 * (its offsets); alpha = 90 - th2 the upper arm's elevation, th2 + th3 the
 * forearm's angle below horizontal. s, e: servo angles in degrees. */
static void ref_fk(double s, double e, double *x, double *z)
{
    const double th2 = s + 3.0, th3 = e + 11.0;
    const double alpha = (90.0 - th2) * PI / 180.0, beta = (th2 + th3) * PI / 180.0;
    *x = 60.0 * cos(alpha) + 60.0 * cos(beta);
    *z = 60.0 * sin(alpha) - 60.0 * sin(beta);
}

/* The nearest point the limits allow, by brute force on a 0.5 degree grid. */
static double ref_nearest(double x, double z)
{
    double best = 1e9, s, e;
    for (s = -90.0; s <= 90.0; s += 0.5) {
        for (e = -50.0; e <= 83.0; e += 0.5) {
            double px, pz;
            ref_fk(s, e, &px, &pz);
            if (hypot(px - x, pz - z) < best) {
                best = hypot(px - x, pz - z);
            }
        }
    }
    return best;
}

/* The vendor library's conver2u8: int(255 / (hi - lo) * (v - lo)), clamped. */
static uint8_t lib_byte(double v, double lo, double hi)
{
    if (v >= hi) {
        return 255;
    }
    if (v <= lo) {
        return 0;
    }
    return (uint8_t)(int)(255.0 / (hi - lo) * (v - lo));
}

/* The library's servo_set_angle: int(map_val(angle, lo, hi, 1, 255)). */
static uint8_t servo_byte(double a, double lo, double hi)
{
    a = a < lo ? lo : (a > hi ? hi : a);
    return (uint8_t)(int)((a - lo) * 254.0 / (hi - lo) + 1.0);
}

/* A servo byte read back, as the middle of its step (the library reads the
 * start, b / 255 * (hi - lo) + lo; the middle is the better estimate). */
static double byte_mid(uint8_t b, double lo, double hi)
{
    return lo + (b + 0.5) * (hi - lo) / 255.0;
}

/* ------------------------------------------------------------ kinematics */

static void test_fk_matches_the_reference(void)
{
    int32_t s, e;
    for (s = -90000; s <= 90000; s += 1500) {
        for (e = -50000; e <= 83000; e += 1500) {
            const int32_t q[XGO_ARM_JOINT_COUNT] = {0, e, s};
            int32_t x, z;
            double rx, rz;
            xgo_arm_fk(g, q, &x, &z);
            ref_fk(s / 1000.0, e / 1000.0, &rx, &rz);
            TEST_ASSERT_DOUBLE_WITHIN(0.002, rx, x / 1000.0);
            TEST_ASSERT_DOUBLE_WITHIN(0.002, rz, z / 1000.0);
        }
    }
}

static void test_ik_reaches_every_point_the_limits_allow(void)
{
    int32_t s, e;
    for (s = -90000; s <= 90000; s += 1500) {
        for (e = -50000; e <= 83000; e += 1500) {
            int32_t q[XGO_ARM_JOINT_COUNT] = {0, 0, 0};
            double rx, rz, px, pz;
            ref_fk(s / 1000.0, e / 1000.0, &rx, &rz);
            TEST_ASSERT_EQUAL_INT(XGO_ARM_REACHED,
                                  xgo_arm_ik(g, (int32_t)lround(rx * 1000.0), (int32_t)lround(rz * 1000.0), q));
            TEST_ASSERT_TRUE(q[XGO_ARM_SHOULDER] >= -90000 && q[XGO_ARM_SHOULDER] <= 90000);
            TEST_ASSERT_TRUE(q[XGO_ARM_ELBOW] >= -50000 && q[XGO_ARM_ELBOW] <= 83000);
            ref_fk(q[XGO_ARM_SHOULDER] / 1000.0, q[XGO_ARM_ELBOW] / 1000.0, &px, &pz);
            TEST_ASSERT_DOUBLE_WITHIN(0.02, 0.0, hypot(px - rx, pz - rz));
        }
    }
}

static void test_rest_point_gives_the_rest_pose(void)
{
    int32_t q[XGO_ARM_JOINT_COUNT] = {0, 0, 0};
    double x, z;
    ref_fk(0, 0, &x, &z);
    TEST_ASSERT_EQUAL_INT(XGO_ARM_REACHED,
                          xgo_arm_ik(g, (int32_t)lround(x * 1000.0), (int32_t)lround(z * 1000.0), q));
    TEST_ASSERT_INT32_WITHIN(5, 0, q[XGO_ARM_SHOULDER]);
    TEST_ASSERT_INT32_WITHIN(5, 0, q[XGO_ARM_ELBOW]);
}

/* Too far, too close, behind, below: the nearest point within the limits. */
static void test_out_of_reach_lands_on_the_nearest_point(void)
{
    static const int32_t pts[][2] = {{200, 0},   {155, 155},  {-80, -95}, {0, -95},
                                     {50, -140}, {-150, 150}, {0, 200},   {120, -120},
                                     {155, -95}, {-80, 155},  {30, -80},  {130, 0},
                                     {-100, 0},  {-60, 60}};
    size_t i;
    for (i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        int32_t q[XGO_ARM_JOINT_COUNT] = {0, 0, 0};
        const double tx = pts[i][0], tz = pts[i][1];
        double px, pz;
        TEST_ASSERT_EQUAL_INT(XGO_ARM_PROJECTED, xgo_arm_ik(g, pts[i][0] * 1000, pts[i][1] * 1000, q));
        TEST_ASSERT_TRUE(q[XGO_ARM_SHOULDER] >= -90000 && q[XGO_ARM_SHOULDER] <= 90000);
        TEST_ASSERT_TRUE(q[XGO_ARM_ELBOW] >= -50000 && q[XGO_ARM_ELBOW] <= 83000);
        ref_fk(q[XGO_ARM_SHOULDER] / 1000.0, q[XGO_ARM_ELBOW] / 1000.0, &px, &pz);
        /* the grid's own resolution is about 0.5 mm */
        TEST_ASSERT_DOUBLE_WITHIN(0.8, ref_nearest(tx, tz), hypot(px - tx, pz - tz));
    }
}

static void test_polar_points(void)
{
    int32_t x, z;
    xgo_arm_polar_point(90000, 100000, &x, &z);
    TEST_ASSERT_EQUAL_INT32(100000, x);
    TEST_ASSERT_EQUAL_INT32(0, z);
    xgo_arm_polar_point(180000, 120000, &x, &z);
    TEST_ASSERT_EQUAL_INT32(0, x);
    TEST_ASSERT_EQUAL_INT32(120000, z);
    xgo_arm_polar_point(135000, 100000, &x, &z);
    TEST_ASSERT_INT32_WITHIN(1, 70711, x);
    TEST_ASSERT_INT32_WITHIN(1, 70711, z);
}

/* ------------------------------------------------------------ the board */

static uint8_t read1(uint8_t addr)
{
    uint8_t v = 0xEE;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, addr, 1, 0, &v));
    return v;
}

static uint32_t counter(xgo_diag_t which)
{
    uint32_t c[XGO_DIAG_COUNT];
    xgo_board_counters(&board, c);
    return c[which];
}

/* Where the claw is, from the servos as read over the wire (0x5D elbow,
 * 0x5E shoulder, read_motor's MOTOR_LIMIT ranges), in mm in the arm frame. */
static void claw_from_readback(double *x, double *z)
{
    uint8_t b[3];
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, 0x5C, 3, 0, b));
    ref_fk(byte_mid(b[2], -75, 90), byte_mid(b[1], -85, 50), x, z);
}

static void test_mini2_identity(void)
{
    uint8_t fw[10];
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, 0x07, 10, 0, fw));
    TEST_ASSERT_EQUAL_MEMORY("W-EMU-0.1", fw, 10);
    TEST_ASSERT_EQUAL_HEX8(0x03, read1(0x02));
    TEST_ASSERT_NOT_NULL(xgo_reg_find(0x5D));
    TEST_ASSERT_EQUAL_STRING("servo52", xgo_regs_find(&board.regs, 0x5D)->name);
    TEST_ASSERT_EQUAL_STRING("stand", xgo_reg_find(0x5D)->name); /* the Mini's */
}

/* arm(x, z) as the library sends it: the claw gets there within 2 mm, read
 * back as the library can; the board's own claw point is within 1 mm (the
 * commands' byte steps: about 0.9 mm in x, 1.0 mm in z, halved by decoding
 * to the step's middle). */
static void test_arm_xz_reaches_the_point(void)
{
    static const double pts[][2] = {{100, 0}, {90, 40}, {60, -60}, {0, 100}, {-40, 90},
                                    {100, -20}, {70, 70}, {50, 50}};
    size_t i;
    for (i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        xgo_board_arm_t arm;
        double x, z;
        xgo_test_write1(&board, 0x73, lib_byte(pts[i][0], -80, 155), 0);
        xgo_test_write1(&board, 0x74, lib_byte(pts[i][1], -95, 155), 0);
        xgo_test_ticks(&board, XGO_TICK_HZ);
        claw_from_readback(&x, &z);
        TEST_ASSERT_DOUBLE_WITHIN(2.0, 0.0, hypot(x - pts[i][0], z - pts[i][1]));
        TEST_ASSERT_EQUAL_INT(1, xgo_board_arm(&board, &arm));
        TEST_ASSERT_DOUBLE_WITHIN(1.0, 0.0,
                                  hypot((arm.claw_um.x - arm.shoulder_um.x) / 1000.0 - pts[i][0],
                                        (arm.claw_um.z - arm.shoulder_um.z) / 1000.0 - pts[i][1]));
        TEST_ASSERT_EQUAL_UINT8(0, arm.out_of_reach);
    }
    TEST_ASSERT_EQUAL_UINT32(0, counter(XGO_DIAG_REACH_CLAMPED));
}

static void test_arm_polar_reaches_the_point(void)
{
    static const double pts[][2] = {{90, 100}, {120, 100}, {70, 80}, {180, 100}, {150, 90},
                                    {210, 90}};
    size_t i;
    for (i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        const double t = pts[i][0] * PI / 180.0, wx = pts[i][1] * sin(t), wz = -pts[i][1] * cos(t);
        double x, z;
        xgo_test_write1(&board, 0x76, lib_byte(pts[i][0], 70, 270), 0);
        xgo_test_write1(&board, 0x77, lib_byte(pts[i][1], 80, 140), 0);
        xgo_test_ticks(&board, XGO_TICK_HZ);
        claw_from_readback(&x, &z);
        TEST_ASSERT_DOUBLE_WITHIN(2.0, 0.0, hypot(x - wx, z - wz));
    }
}

/* servo_set_angle(51..53, angle): the servo gets there and read_motor's
 * bytes (0x5C..0x5E, MOTOR_LIMIT) say so within a step. */
static void test_servo_angles_read_back(void)
{
    static const double claw = 30.0, elbow = -20.0, shoulder = 45.0;
    uint8_t b[3];
    xgo_test_write1(&board, 0x71, servo_byte(claw, -65, 65), 0);
    xgo_test_write1(&board, 0x5D, servo_byte(elbow, -50, 83), 0);
    xgo_test_write1(&board, 0x5E, servo_byte(shoulder, -90, 90), 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(&board, 0x5C, 3, 0, b));
    TEST_ASSERT_DOUBLE_WITHIN(0.8, claw, byte_mid(b[0], -65, 65));
    TEST_ASSERT_DOUBLE_WITHIN(0.8, elbow, byte_mid(b[1], -85, 50));
    TEST_ASSERT_DOUBLE_WITHIN(0.8, shoulder, byte_mid(b[2], -75, 90));
    TEST_ASSERT_EQUAL_HEX8(0x00, read1(0x00)); /* the legs stay in whole-unit mode */
    /* beyond read_motor's range the read-back saturates: elbow 70 reads 50 */
    xgo_test_write1(&board, 0x5D, servo_byte(70.0, -50, 83), 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_HEX8(0xFF, read1(0x5D));
}

/* The servos move at the speed of 0x75 (10..600 deg/s, like 0x5C). */
static void test_slew_follows_the_arm_speed(void)
{
    xgo_board_arm_t a0, a1;
    int t;
    int32_t max_step = 0;
    xgo_test_write1(&board, 0x75, 0, 0);    /* 10 deg/s: 20 mdeg a tick */
    xgo_test_write1(&board, 0x5E, 255, 0);  /* shoulder to 90 degrees */
    (void)xgo_board_arm(&board, &a0);
    for (t = 0; t < 100; t++) {
        xgo_board_tick(&board);
        (void)xgo_board_arm(&board, &a1);
        if (a1.joints_mdeg[XGO_ARM_SHOULDER] - a0.joints_mdeg[XGO_ARM_SHOULDER] > max_step) {
            max_step = a1.joints_mdeg[XGO_ARM_SHOULDER] - a0.joints_mdeg[XGO_ARM_SHOULDER];
        }
        a0 = a1;
    }
    TEST_ASSERT_EQUAL_INT32(20, max_step);
    TEST_ASSERT_EQUAL_INT32(2000, a1.joints_mdeg[XGO_ARM_SHOULDER]);
    xgo_test_write1(&board, 0x75, 255, 0); /* 600 deg/s: the rest in 0.15 s */
    xgo_test_ticks(&board, 75);
    (void)xgo_board_arm(&board, &a1);
    TEST_ASSERT_EQUAL_INT32(90000, a1.joints_mdeg[XGO_ARM_SHOULDER]);
}

static void test_out_of_reach_is_clamped_and_counted(void)
{
    xgo_board_arm_t arm;
    xgo_test_write1(&board, 0x73, 255, 0); /* x 155, z 155: 219 mm away, the arm reaches 120 */
    xgo_test_write1(&board, 0x74, 255, 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    /* counted every tick the arm holds a clamped point (reach_clamped) */
    TEST_ASSERT_EQUAL_UINT32(XGO_TICK_HZ, counter(XGO_DIAG_REACH_CLAMPED));
    (void)xgo_board_arm(&board, &arm);
    TEST_ASSERT_EQUAL_UINT8(1, arm.out_of_reach);
    TEST_ASSERT_TRUE(arm.joints_mdeg[XGO_ARM_SHOULDER] <= 90000);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_UINT32(2 * XGO_TICK_HZ, counter(XGO_DIAG_REACH_CLAMPED));
    /* a point it reaches: the count stops */
    xgo_test_write1(&board, 0x73, lib_byte(60, -80, 155), 0);
    xgo_test_write1(&board, 0x74, lib_byte(-60, -95, 155), 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    (void)xgo_board_arm(&board, &arm);
    TEST_ASSERT_EQUAL_UINT8(0, arm.out_of_reach);
    TEST_ASSERT_EQUAL_UINT32(2 * XGO_TICK_HZ, counter(XGO_DIAG_REACH_CLAMPED));
}

/* 0x72 = 1: the claw stays where it was in the machine frame while the body
 * pitches and lowers (x, z and pitch are the arm's to compensate). */
static void claw_in_machine_frame(double *x, double *z)
{
    xgo_board_arm_t arm;
    xgo_body_pose_t pose;
    double p;
    (void)xgo_board_arm(&board, &arm);
    xgo_board_body_pose(&board, &pose);
    p = pose.pitch_mdeg / 1000.0 * PI / 180.0;
    *x = pose.x_um / 1000.0 + arm.claw_um.x / 1000.0 * cos(p) + arm.claw_um.z / 1000.0 * sin(p);
    *z = pose.z_um / 1000.0 - arm.claw_um.x / 1000.0 * sin(p) + arm.claw_um.z / 1000.0 * cos(p);
}

static void test_hold_mode_keeps_the_claw_still(void)
{
    double x0, z0, x1, z1;
    xgo_test_write1(&board, 0x72, 1, 0);
    xgo_test_write1(&board, 0x73, lib_byte(80, -80, 155), 0);
    xgo_test_write1(&board, 0x74, lib_byte(10, -95, 155), 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    claw_in_machine_frame(&x0, &z0);
    xgo_test_write1(&board, 0x37, 0xE0, 0); /* nose down about 15 degrees */
    xgo_test_write1(&board, 0x35, 0x40, 0); /* and lower */
    xgo_test_ticks(&board, 2 * XGO_TICK_HZ);
    claw_in_machine_frame(&x1, &z1);
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 0.0, hypot(x1 - x0, z1 - z0));
    /* without it the claw rides with the body */
    xgo_test_write1(&board, 0x72, 0, 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    claw_in_machine_frame(&x1, &z1);
    TEST_ASSERT_TRUE(hypot(x1 - x0, z1 - z0) > 10.0);
}

static void test_reset_returns_the_arm_to_rest(void)
{
    xgo_board_arm_t arm;
    xgo_test_write1(&board, 0x5E, 200, 0);
    xgo_test_write1(&board, 0x71, 10, 0);
    xgo_test_ticks(&board, XGO_TICK_HZ);
    xgo_test_write1(&board, 0x3E, 255, 0);
    xgo_test_ticks(&board, 2 * XGO_TICK_HZ);
    (void)xgo_board_arm(&board, &arm);
    TEST_ASSERT_EQUAL_INT32(0, arm.joints_mdeg[XGO_ARM_SHOULDER]);
    TEST_ASSERT_EQUAL_INT32(0, arm.joints_mdeg[XGO_ARM_ELBOW]);
    TEST_ASSERT_EQUAL_INT32(0, arm.joints_mdeg[XGO_ARM_CLAW]);
}

/* 0x5C: written, the servo speed of the legs' servo mode; read, the claw. */
static void test_0x5c_reads_the_claw_and_keeps_the_servo_speed(void)
{
    xgo_test_write1(&board, 0x5C, 200, 0);
    xgo_test_ticks(&board, 2);
    TEST_ASSERT_EQUAL_HEX8(200, xgo_regs_servo_speed(&board.regs));
    TEST_ASSERT_EQUAL_HEX8(127, read1(0x5C)); /* the claw at rest (0 degrees) */
    TEST_ASSERT_EQUAL_HEX8(0x02, read1(0x00)); /* servo mode, as on the Mini */
}

/* The same bytes on the Mini: 0x5D = 1 is the standing posture, the arm's
 * registers are ignored and counted, and no arm is reported. */
static void test_the_mini_has_no_arm(void)
{
    xgo_board_arm_t arm;
    xgo_board_init(&board, NULL);
    TEST_ASSERT_EQUAL_INT(0, xgo_board_arm(&board, &arm));
    xgo_test_write1(&board, 0x30, 0xC0, 0);
    xgo_test_write1(&board, 0x5D, 1, 0);
    xgo_test_ticks(&board, 1);
    TEST_ASSERT_EQUAL_HEX8(0x80, read1(0x30)); /* the posture reset the velocity */
    xgo_test_write1(&board, 0x73, 0x40, 0);
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_IGNORED_UNMAPPED));
    TEST_ASSERT_EQUAL_HEX8(0x00, read1(0x73));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_fk_matches_the_reference);
    RUN_TEST(test_ik_reaches_every_point_the_limits_allow);
    RUN_TEST(test_rest_point_gives_the_rest_pose);
    RUN_TEST(test_out_of_reach_lands_on_the_nearest_point);
    RUN_TEST(test_polar_points);
    RUN_TEST(test_mini2_identity);
    RUN_TEST(test_arm_xz_reaches_the_point);
    RUN_TEST(test_arm_polar_reaches_the_point);
    RUN_TEST(test_servo_angles_read_back);
    RUN_TEST(test_slew_follows_the_arm_speed);
    RUN_TEST(test_out_of_reach_is_clamped_and_counted);
    RUN_TEST(test_hold_mode_keeps_the_claw_still);
    RUN_TEST(test_reset_returns_the_arm_to_rest);
    RUN_TEST(test_0x5c_reads_the_claw_and_keeps_the_servo_speed);
    RUN_TEST(test_the_mini_has_no_arm);
    return UNITY_END();
}
