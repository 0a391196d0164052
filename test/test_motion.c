/*
 * The board moves: registers -> modes, gait, body pose, actions, servos, IMU
 * and battery, on virtual time (ticks). Each test drives the board through
 * the register-write path of a host's frames (xgo_board_write) and checks
 * what a host would read back over the wire.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "actions.h" /* xgo_action_duration_ticks, xgo_action_next_in_cycle */
#include "board_unity.h"
#include "codec.h"
#include "gait.h"   /* XGO_GAIT_STOP_TICKS_MAX */
#include "heading.h" /* XGO_HEADING_RATE_MDEG_S */
#include "motion.h" /* XGO_JOINT_STEP_MAX_MDEG */
#include "motion_internal.h" /* xgo_motion_gait_command, xgo_motion_stroke */
#include "settle.h"          /* xgo_settle_active */
#include "unity.h"
#include "xgo/board.h"
#include "xgo/emulator.h"

static xgo_board_t board;

void setUp(void)
{
    xgo_board_init(&board, NULL);
}

void tearDown(void)
{
}

/* Writes, reads and ticks as a host would (test/support/board_unity.h). */
#define wr(addr, v) xgo_test_wr(&board, (addr), (v))
#define rd(addr) xgo_test_rd(&board, (addr))
#define rd_angle(addr) xgo_test_rd_float(&board, (addr)) /* read_roll/pitch/yaw's float */
#define ticks(n) xgo_test_ticks(&board, (n))

/* Vendor encoding of a value in [-limit, limit] (what xgolib sends). */
static uint8_t vendor_byte(double v, double limit)
{
    if (v >= limit) return 255;
    if (v <= -limit) return 0;
    return (uint8_t)(int)(255.0 / (2 * limit) * (v + limit));
}

/* The board seen through its observers (xgo/board.h). */
static int32_t joint(unsigned i)
{
    int32_t q[XGO_SERVO_COUNT];
    xgo_board_joints_mdeg(&board, q);
    return q[i];
}

static xgo_gait_status_t gait(void)
{
    xgo_gait_status_t g;
    xgo_board_gait(&board, &g);
    return g;
}

static int standing(void)
{
    return !gait().walking;
}

static int32_t produced_vx(void)
{
    int32_t cmd[3], produced[3];
    xgo_board_velocity(&board, cmd, produced);
    return produced[0];
}

/* ------------------------------------------------------------ modes */

static void test_mode_register_follows_the_group_written(void)
{
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_WHOLE_UNIT, rd(XGO_REG_MODE));
    wr(XGO_REG_LEG1_Z, 0x90);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_LEG, rd(XGO_REG_MODE));
    wr(XGO_REG_SERVO_SPEED, 0x40);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_SERVO, rd(XGO_REG_MODE));
    wr(XGO_REG_UNLOAD, 0x00);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_DEBUG, rd(XGO_REG_MODE));
    wr(XGO_REG_VX, 0x7F);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_WHOLE_UNIT, rd(XGO_REG_MODE));
    wr(XGO_REG_PERIOD_X, 0x00);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_WHOLE_UNIT, rd(XGO_REG_MODE));
}

static void test_dead_band_7f_and_80_both_mean_stop(void)
{
    TEST_ASSERT_EQUAL_INT32(0, xgo_signed_byte_to_value(0x7F, 250000));
    TEST_ASSERT_EQUAL_INT32(0, xgo_signed_byte_to_value(0x80, 250000));
    TEST_ASSERT_EQUAL_INT32(250000, xgo_signed_byte_to_value(0xFF, 250000));
    TEST_ASSERT_EQUAL_INT32(-250000, xgo_signed_byte_to_value(0x00, 250000));
    TEST_ASSERT_TRUE(xgo_signed_byte_to_value(0x81, 250000) > 0);
    TEST_ASSERT_TRUE(xgo_signed_byte_to_value(0x7E, 250000) < 0);

    wr(XGO_REG_VX, vendor_byte(20, 25));
    ticks(1000);
    TEST_ASSERT_FALSE(standing());
    wr(XGO_REG_VX, vendor_byte(0, 25)); /* stop() sends 0x7F */
    TEST_ASSERT_EQUAL_HEX8(0x7F, vendor_byte(0, 25));
    ticks(XGO_GAIT_STOP_TICKS_MAX);
    TEST_ASSERT_TRUE(standing());
    TEST_ASSERT_EQUAL_INT32(0, produced_vx());
}

/* ------------------------------------------------------------ whole unit */

static void test_walking_forward_moves_stance_feet_backward(void)
{
    xgo_gait_status_t g;
    unsigned t, leg, seen = 0;
    wr(XGO_REG_VX, vendor_byte(15, 25));
    ticks(1000);
    for (t = 0; t < 200; t++) {
        int32_t before[4];
        for (leg = 0; leg < 4; leg++) {
            before[leg] = gait().feet_um[leg].x;
        }
        ticks(1);
        g = gait();
        for (leg = 0; leg < 4; leg++) {
            if ((g.contact >> leg & 1u) && g.feet_um[leg].z == 0 && before[leg] != g.feet_um[leg].x) {
                TEST_ASSERT_TRUE(g.feet_um[leg].x < before[leg]);
                seen++;
            }
        }
    }
    TEST_ASSERT_GREATER_THAN_UINT(100, seen);
    /* forward speed 15 (vendor units, cm/s) = 150 mm/s produced */
    TEST_ASSERT_INT32_WITHIN(15000, 150000, produced_vx());
}

/* Each foot's place on the floor: the world pose (odometry) carrying the
 * machine-frame foot (body pose + FK of the actual joints), x and y in mm. */
static void feet_on_floor(double out[XGO_LEG_COUNT][2])
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t pose;
    xgo_world_pose_t w;
    double yaw, c, s;
    unsigned leg;
    xgo_board_feet_um(&board, feet);
    xgo_board_body_pose(&board, &pose);
    xgo_board_world_pose(&board, &w);
    yaw = w.yaw_mdeg / 1000.0 * M_PI / 180.0;
    c = cos(yaw);
    s = sin(yaw);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) { /* level body: attitude 0 here */
        const double mx = (pose.x_um + feet[leg].x) / 1000.0, my = (pose.y_um + feet[leg].y) / 1000.0;
        out[leg][0] = w.x_um / 1000.0 + c * mx - s * my;
        out[leg][1] = w.y_um / 1000.0 + s * mx + c * my;
    }
}

/* Issue 9 part 4, measured with the board's own FK and odometry: trotting
 * at the vendor maxima (forward 250 mm/s, sideways 180 mm/s, turning 100
 * deg/s), a foot's speed over the floor in the tick it lifts off or touches
 * down is at most 20 mm/s (the swing used to leave and land at the body's
 * speed: 256 mm/s at 250 mm/s). */
static void test_trotting_feet_lift_and_land_at_the_speed_of_the_floor(void)
{
    static const uint8_t cmds[3][2] = {{XGO_REG_VX, 0xFF}, {XGO_REG_VY, 0x00}, {XGO_REG_VYAW, 0xFF}};
    unsigned k, t, leg, events = 0;
    for (k = 0; k < 3; k++) {
        double prev[XGO_LEG_COUNT][2], now[XGO_LEG_COUNT][2], worst = 0.0;
        uint8_t before;
        xgo_board_init(&board, NULL);
        wr(cmds[k][0], cmds[k][1]);
        ticks(XGO_TICK_HZ); /* past the ramp */
        feet_on_floor(prev);
        before = xgo_board_contacts(&board);
        for (t = 0; t < 2 * XGO_TICK_HZ; t++) {
            uint8_t after;
            ticks(1);
            feet_on_floor(now);
            after = xgo_board_contacts(&board);
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                if (((before ^ after) >> leg) & 1u) {
                    const double v = hypot(now[leg][0] - prev[leg][0], now[leg][1] - prev[leg][1]) * XGO_TICK_HZ;
                    worst = v > worst ? v : worst;
                    events++;
                }
            }
            memcpy(prev, now, sizeof prev);
            before = after;
        }
        TEST_ASSERT_TRUE_MESSAGE(worst <= 20.0, xgo_reg_name(cmds[k][0]));
    }
    TEST_ASSERT_GREATER_THAN_UINT(60, events);
}

static void test_turning_integrates_yaw(void)
{
    /* +50 deg/s for 4 s (after a 0.2 s ramp) -> about +190 deg, wrapped. */
    double yaw;
    wr(XGO_REG_VYAW, vendor_byte(50, 100));
    ticks(4 * XGO_TICK_HZ);
    yaw = rd_angle(XGO_REG_IMU_YAW);
    /* expected: 50 deg/s * (4 s - 0.1 s average ramp loss) = 195 -> -165 */
    TEST_ASSERT_DOUBLE_WITHIN(10.0, -165.0, yaw);
    wr(XGO_REG_VYAW, 0x80);
    ticks(XGO_GAIT_STOP_TICKS_MAX);
    TEST_ASSERT_TRUE(standing());
}

static void test_body_attitude_shows_on_the_imu(void)
{
    wr(XGO_REG_BODY_ROLL, vendor_byte(10, 20));
    wr(XGO_REG_BODY_PITCH, vendor_byte(-15, 22));
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(0.2, 10.0, rd_angle(XGO_REG_IMU_ROLL));
    TEST_ASSERT_DOUBLE_WITHIN(0.2, -15.0, rd_angle(XGO_REG_IMU_PITCH));
    /* one-byte view: 0x80 + 10 / (180/128) */
    TEST_ASSERT_UINT8_WITHIN(1, 0x80 + 7, rd(XGO_REG_IMU_ROLL));
}

static void test_body_height_changes_the_legs(void)
{
    const int32_t knee_before = joint(XGO_JOINT_KNEE);
    xgo_body_pose_t pose;
    wr(XGO_REG_BODY_Z, 0x00); /* lowest: 75 mm */
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_TRUE(joint(XGO_JOINT_KNEE) < knee_before - 10000); /* knee folds */
    xgo_board_body_pose(&board, &pose);
    TEST_ASSERT_INT32_WITHIN(1, 75000, pose.z_um);
}

static void test_periodic_roll_has_the_register_period(void)
{
    /* byte 255 -> 8 s; byte 1 -> ~1.5 s. Count zero crossings of roll. */
    double prev;
    unsigned t, crossings = 0;
    wr(XGO_REG_PERIOD_ROLL, 1);
    ticks(1);
    prev = rd_angle(XGO_REG_IMU_ROLL);
    for (t = 0; t < 15 * XGO_TICK_HZ; t++) {
        double now;
        ticks(1);
        now = rd_angle(XGO_REG_IMU_ROLL);
        if ((prev < 0) != (now < 0)) {
            crossings++;
        }
        prev = now;
    }
    /* period = 1.5 + 6.5/255 s = 1.5255 s: 15 s hold 9.8 periods, 2 crossings each */
    TEST_ASSERT_UINT_WITHIN(1, 20, crossings);
    wr(XGO_REG_PERIOD_ROLL, 0);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(0.01, 0.0, rd_angle(XGO_REG_IMU_ROLL));
}

static void test_self_stabilisation_levels_the_imu(void)
{
    xgo_board_set_ground_tilt(&board, 10000, -6000);
    ticks(10);
    TEST_ASSERT_DOUBLE_WITHIN(0.01, 10.0, rd_angle(XGO_REG_IMU_ROLL));
    TEST_ASSERT_DOUBLE_WITHIN(0.01, -6.0, rd_angle(XGO_REG_IMU_PITCH));
    wr(XGO_REG_IMU_MODE, 1);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 0.0, rd_angle(XGO_REG_IMU_ROLL));
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 0.0, rd_angle(XGO_REG_IMU_PITCH));
    wr(XGO_REG_IMU_MODE, 0);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(0.1, 10.0, rd_angle(XGO_REG_IMU_ROLL));
}

static void test_mark_time_steps_in_place(void)
{
    unsigned t;
    int32_t top = 0;
    wr(XGO_REG_MARK_TIME, 255); /* 35 mm */
    for (t = 0; t < 2 * XGO_TICK_HZ; t++) {
        ticks(1);
        if (gait().feet_um[0].z > top) {
            top = gait().feet_um[0].z;
        }
    }
    TEST_ASSERT_INT32_WITHIN(1000, 35000, top);
    TEST_ASSERT_EQUAL_INT32(0, produced_vx());
}

/* ------------------------------------------------------------ leg, servo, debug */

static void test_leg_mode_puts_the_foot_where_commanded(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    int32_t q[3];
    xgo_vec3_t foot;
    wr(XGO_REG_LEG2_X, 0xC0); /* leg 2 forward */
    wr(XGO_REG_LEG2_Z, 0x40);
    ticks(XGO_TICK_HZ);
    q[0] = joint(3);
    q[1] = joint(4);
    q[2] = joint(5);
    xgo_leg_fk(p, XGO_LEG_RF, q, &foot);
    TEST_ASSERT_INT32_WITHIN(100, xgo_byte_to_foot(p, XGO_AXIS_X, 0xC0), foot.x);
    TEST_ASSERT_INT32_WITHIN(100, 0, foot.y);
    TEST_ASSERT_INT32_WITHIN(100, xgo_byte_to_foot(p, XGO_AXIS_Z, 0x40), foot.z);
}

/* Issue 9 part 5: the foot registers start at the standing stance (z byte
 * 0x90 = 97.6 mm on the Mini, the standing height; 0x80 would be 95.1 mm by
 * the vendor's formula), at power-up and after a reset, so a host entering
 * leg mode from standing - here the vendor library's leg(1, [0, 0, 97.6])
 * - moves nothing: every joint, every foot and the world pose stay put. */
static void test_leg_mode_entered_from_standing_keeps_the_stance(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const uint8_t stand_z = xgo_foot_to_byte(p, XGO_AXIS_Z, 97589);
    int32_t before[XGO_SERVO_COUNT], after[XGO_SERVO_COUNT];
    xgo_world_pose_t w;
    unsigned leg;
    TEST_ASSERT_EQUAL_HEX8(0x90, stand_z);
    TEST_ASSERT_INT32_WITHIN(50, 95100, xgo_byte_to_foot(p, XGO_AXIS_Z, 0x80));
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        TEST_ASSERT_EQUAL_HEX8(0x90, rd((uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Z)));
        TEST_ASSERT_EQUAL_HEX8(0x80, rd((uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_X)));
    }
    xgo_board_joints_mdeg(&board, before);
    wr(XGO_REG_LEG1_X, vendor_byte(0, 35));
    wr(XGO_REG_LEG1_Y, vendor_byte(0, 18));
    wr(XGO_REG_LEG1_Z, stand_z);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_LEG, rd(XGO_REG_MODE));
    xgo_board_joints_mdeg(&board, after);
    TEST_ASSERT_EQUAL_INT32_ARRAY(before, after, XGO_SERVO_COUNT);
    xgo_board_world_pose(&board, &w);
    TEST_ASSERT_EQUAL_INT32(0, w.x_um);
    TEST_ASSERT_EQUAL_INT32(0, w.y_um);
    /* a reset puts them back to the stance too */
    wr(XGO_REG_LEG2_Z, 0x20);
    wr(XGO_REG_ACTION, XGO_ACTION_RESET);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0x90, rd(XGO_REG_LEG2_Z));
    /* the Lite's stance height (85.1 mm) is its range's middle: 0x80 */
    {
        xgo_board_config_t cfg;
        xgo_board_default_config(&cfg);
        cfg.model = XGO_MODEL_LITE;
        xgo_board_init(&board, &cfg);
        TEST_ASSERT_EQUAL_HEX8(0x80, rd(XGO_REG_LEG4_Z));
    }
}

static void test_servo_mode_reads_back_commanded_angles_at_register_speed(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const uint8_t cmd = 0x30;
    const int32_t start = joint(0);
    const int32_t goal = xgo_byte_to_joint(p, XGO_JOINT_KNEE, cmd);
    unsigned t = 0;
    wr(XGO_REG_SERVO_SPEED, 0); /* slowest: 10 deg/s = 20 mdeg per tick */
    wr(XGO_REG_SERVO11, cmd);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_SERVO, rd(XGO_REG_MODE));
    TEST_ASSERT_INT32_WITHIN(40, 20, abs(joint(0) - start));
    while (joint(0) != goal && t < 20 * XGO_TICK_HZ) {
        ticks(1);
        t++;
    }
    TEST_ASSERT_EQUAL_INT32(goal, joint(0));
    TEST_ASSERT_EQUAL_HEX8(cmd, rd(XGO_REG_SERVO11));
    /* other joints kept their angles */
    TEST_ASSERT_UINT8_WITHIN(1, 0xBB, rd(XGO_REG_SERVO12));
}

/* Issue 9 part 6: the vendor library's servo read polls 0x50..0x5B while it
 * moves a joint. A read that arrives between the write and the next tick -
 * in the same receive call - gives where the joint is, and every later poll
 * too: the readings go from +60 to -40 degrees at the servo speed, never
 * showing the commanded byte ahead of the joint. */
static void test_joint_registers_read_the_joints_even_right_after_a_write(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const uint8_t up = xgo_joint_to_byte(p, XGO_JOINT_HIP, 60000);
    const uint8_t down = xgo_joint_to_byte(p, XGO_JOINT_HIP, -40000);
    uint8_t frames[2 * XGO_FRAME_MAX_LEN], reply[16], prev;
    size_t n;
    unsigned poll;
    wr(XGO_REG_SERVO_SPEED, 0xFF); /* 600 deg/s */
    wr(XGO_REG_SERVO12, up);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_HEX8(up, rd(XGO_REG_SERVO12));
    n = xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_SERVO12, &down, 1, frames, sizeof frames);
    {
        const uint8_t one = 1;
        n += xgo_frame_encode(XGO_TYPE_READ, XGO_REG_SERVO12, &one, 1, frames + n, sizeof frames - n);
    }
    xgo_board_receive(&board, frames, n, 0);
    TEST_ASSERT_EQUAL_UINT(9, xgo_board_transmit(&board, reply, sizeof reply));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_check_reply(reply, 9, XGO_REG_SERVO12, 1));
    TEST_ASSERT_EQUAL_HEX8(up, reply[5]); /* not the command: the joint has not moved yet */
    prev = up;
    for (poll = 0; poll < 25; poll++) { /* 50 Hz for half a second */
        uint8_t now;
        ticks(XGO_TICK_HZ / 50);
        now = rd(XGO_REG_SERVO12);
        TEST_ASSERT_EQUAL_HEX8(xgo_joint_to_byte(p, XGO_JOINT_HIP, joint(1)), now);
        TEST_ASSERT_TRUE(now <= prev); /* on its way down, never back up */
        /* 20 ms at 600 deg/s is 12 degrees: about 19 bytes of the 159-degree range */
        TEST_ASSERT_UINT8_WITHIN(20, prev, now);
        prev = now;
    }
    TEST_ASSERT_EQUAL_HEX8(down, prev);
}

static void test_unloaded_leg_holds_and_ignores_commands(void)
{
    int32_t held[3];
    unsigned i;
    wr(XGO_REG_UNLOAD, 0x12); /* unload leg 2 */
    ticks(1);
    for (i = 0; i < 3; i++) {
        held[i] = joint(3 + i);
    }
    wr(XGO_REG_BODY_Z, 0x00);
    wr(XGO_REG_SERVO21, 0x00);
    ticks(XGO_TICK_HZ);
    for (i = 0; i < 3; i++) {
        TEST_ASSERT_EQUAL_INT32(held[i], joint(3 + i));
    }
    TEST_ASSERT_TRUE(joint(0) != 0 || joint(1) != 0); /* others still move */
    wr(XGO_REG_UNLOAD, 0x22); /* reload leg 2 */
    ticks(1);
    wr(XGO_REG_SERVO21, 0x00);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_INT32(xgo_profile_mini()->joint_mdeg[0].lo, joint(3));
}

static void test_calibration_records_zero_offsets(void)
{
    uint32_t before = xgo_board_nv_changes(&board);
    xgo_board_nv_t nv;
    int32_t standing_hip = joint(1);
    wr(XGO_REG_SET_ZERO, 1); /* outside calibration: ignored */
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_SET_ZERO));
    TEST_ASSERT_EQUAL_UINT32(before, xgo_board_nv_changes(&board));
    wr(XGO_REG_CALIBRATION, 1);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_CALIBRATION, rd(XGO_REG_MODE));
    wr(XGO_REG_SET_ZERO, 1);
    TEST_ASSERT_EQUAL_HEX8(1, rd(XGO_REG_SET_ZERO));
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_SET_ZERO)); /* auto-clear */
    TEST_ASSERT_EQUAL_UINT32(before + 1, xgo_board_nv_changes(&board));
    xgo_board_get_nv(&board, &nv);
    TEST_ASSERT_EQUAL_INT32(standing_hip, nv.zero_offset_mdeg[1]);
    wr(XGO_REG_CALIBRATION, 0);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_WHOLE_UNIT, rd(XGO_REG_MODE));
}

static void test_repeated_calibration_keeps_offsets_storable(void)
{
    xgo_board_nv_t nv;
    unsigned k, i;
    for (k = 0; k < 12; k++) {
        wr(XGO_REG_CALIBRATION, 1);
        wr(XGO_REG_SET_ZERO, 1);
        ticks(1);
        wr(XGO_REG_CALIBRATION, 0);
        ticks(XGO_TICK_HZ); /* the joints walk back to the standing pose */
    }
    xgo_board_get_nv(&board, &nv);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_TRUE(nv.zero_offset_mdeg[i] >= -180000 && nv.zero_offset_mdeg[i] < 180000);
    }
    TEST_ASSERT_TRUE(xgo_board_set_nv(&board, &nv)); /* what the board saves, it loads */
}

static void test_writes_of_several_groups_in_one_tick_keep_the_last_group(void)
{
    /* xgolib's pace(), gait_type() and motor() can land within one tick. */
    const uint8_t cmd = 0xA2;
    unsigned t;
    ticks(100);
    wr(XGO_REG_MOVE_MODE, 0);
    wr(XGO_REG_GAIT_TYPE, 0);
    wr(XGO_REG_SERVO11, cmd);
    for (t = 0; t < XGO_TICK_HZ; t++) {
        ticks(1);
        TEST_ASSERT_EQUAL_HEX8(XGO_MODE_SERVO, rd(XGO_REG_MODE));
    }
    TEST_ASSERT_EQUAL_HEX8(cmd, rd(XGO_REG_SERVO11));
}

static void test_nv_data_round_trip_and_validation(void)
{
    xgo_board_nv_t nv, back;
    memset(&nv, 0, sizeof nv);
    memcpy(nv.bt_name, "Rex", 3);
    nv.zero_offset_mdeg[5] = -1234;
    TEST_ASSERT_TRUE(xgo_board_set_nv(&board, &nv));
    xgo_board_get_nv(&board, &back);
    TEST_ASSERT_EQUAL_MEMORY(nv.bt_name, back.bt_name, sizeof nv.bt_name);
    TEST_ASSERT_EQUAL_INT32_ARRAY(nv.zero_offset_mdeg, back.zero_offset_mdeg, XGO_SERVO_COUNT);
    nv.bt_name[1] = (char)0xE7;
    TEST_ASSERT_FALSE(xgo_board_set_nv(&board, &nv));
    memset(nv.bt_name, 0, sizeof nv.bt_name);
    TEST_ASSERT_FALSE(xgo_board_set_nv(&board, &nv));
    memcpy(nv.bt_name, "A", 1);
    nv.zero_offset_mdeg[0] = 400000;
    TEST_ASSERT_FALSE(xgo_board_set_nv(&board, &nv));
    xgo_board_get_nv(&board, &back);
    TEST_ASSERT_EQUAL_MEMORY("Rex", back.bt_name, 3);
}

static void test_bluetooth_rename_counts_as_nv_change(void)
{
    const uint32_t before = xgo_board_nv_changes(&board);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                          xgo_board_write(&board, XGO_SOURCE_CLI, 0x13, (const uint8_t *)"Rex", 3));
    ticks(1);
    TEST_ASSERT_EQUAL_UINT32(before + 1, xgo_board_nv_changes(&board));
}

static void test_standing_posture_stops_and_clears_motion(void)
{
    wr(XGO_REG_VX, 0xFF);
    wr(XGO_REG_BODY_ROLL, 0xFF);
    ticks(500);
    wr(XGO_REG_STAND, 1);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_STAND));
    TEST_ASSERT_EQUAL_HEX8(0x80, rd(XGO_REG_VX));
    TEST_ASSERT_EQUAL_HEX8(0x80, rd(XGO_REG_BODY_ROLL));
    ticks(XGO_GAIT_STOP_TICKS_MAX);
    TEST_ASSERT_TRUE(standing());
}

/* ------------------------------------------------------------ actions */

static void test_action_reads_back_for_its_duration_then_zero(void)
{
    const uint32_t n = xgo_action_duration_ticks(XGO_ACTION_SIT);
    TEST_ASSERT_EQUAL_UINT32(5u * XGO_TICK_HZ, n);
    wr(XGO_REG_ACTION, XGO_ACTION_SIT);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(XGO_ACTION_SIT, rd(XGO_REG_ACTION));
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_ACTION, rd(XGO_REG_MODE));
    ticks(n - 2);
    TEST_ASSERT_EQUAL_HEX8(XGO_ACTION_SIT, rd(XGO_REG_ACTION));
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_ACTION));
    TEST_ASSERT_EQUAL_HEX8(XGO_MODE_WHOLE_UNIT, rd(XGO_REG_MODE));
}

static void test_actions_move_the_body_and_end_standing(void)
{
    int32_t stand[XGO_SERVO_COUNT];
    unsigned i, moved = 0;
    xgo_board_joints_mdeg(&board, stand);
    wr(XGO_REG_ACTION, XGO_ACTION_LIE_DOWN);
    ticks(xgo_action_duration_ticks(XGO_ACTION_LIE_DOWN) / 2);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        moved += abs(joint(i) - stand[i]) > 5000;
    }
    TEST_ASSERT_GREATER_THAN_UINT(0, moved);
    ticks(xgo_action_duration_ticks(XGO_ACTION_LIE_DOWN));
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        TEST_ASSERT_INT32_WITHIN(1, stand[i], joint(i));
    }
}

static void test_reset_restores_the_initial_table(void)
{
    static const uint8_t touched[] = {0x09, 0x30, 0x31, 0x32, 0x33, 0x36, 0x39, 0x3C, 0x3D, 0x61, 0x80};
    uint8_t initial[256];
    unsigned i;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x00, 0x80, initial));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x80, 0x80, initial + 0x80));
    for (i = 0; i < sizeof touched; i++) {
        wr(touched[i], 1);
    }
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                          xgo_board_write(&board, XGO_SOURCE_CLI, 0x13, (const uint8_t *)"Rex", 3));
    ticks(300);
    wr(XGO_REG_ACTION, 255);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(255, rd(XGO_REG_ACTION));
    for (i = 0; i < sizeof touched; i++) {
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(initial[touched[i]], rd(touched[i]), xgo_reg_name(touched[i]));
    }
    TEST_ASSERT_EQUAL_HEX8('R', rd(0x13)); /* the name is non-volatile */
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_ACTION));
    TEST_ASSERT_TRUE(standing());
}

static void test_perform_mode_cycles_actions(void)
{
    wr(XGO_REG_PERFORM, 1);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(xgo_action_next_in_cycle(0), rd(XGO_REG_ACTION));
    ticks(xgo_action_duration_ticks(xgo_action_next_in_cycle(0)));
    TEST_ASSERT_EQUAL_HEX8(xgo_action_next_in_cycle(xgo_action_next_in_cycle(0)), rd(XGO_REG_ACTION));
    wr(XGO_REG_PERFORM, 0);
    ticks(11 * XGO_TICK_HZ);
    TEST_ASSERT_EQUAL_HEX8(0, rd(XGO_REG_ACTION));
}

/* ------------------------------------------------------------ battery, identity */

static void test_battery_drains_faster_while_walking(void)
{
    xgo_board_t idle;
    uint8_t idle_pct;
    unsigned t;
    xgo_board_init(&idle, NULL);
    wr(XGO_REG_VX, 0xFF);
    for (t = 0; t < 3u * 60u * XGO_TICK_HZ; t++) { /* 3 minutes */
        xgo_board_tick(&board);
        xgo_board_tick(&idle);
    }
    /* 3 min: idle 2.5 % (100 % / 120 min), walking 5 % (100 % / 60 min) */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&idle, XGO_REG_BATTERY, 1, &idle_pct));
    TEST_ASSERT_EQUAL_UINT8(98, idle_pct);
    TEST_ASSERT_EQUAL_UINT8(95, rd(XGO_REG_BATTERY));
}

static void test_lite_profile_version_and_ranges(void)
{
    xgo_board_config_t cfg;
    xgo_board_default_config(&cfg);
    cfg.model = XGO_MODEL_LITE;
    xgo_board_init(&board, &cfg);
    ticks(1);
    TEST_ASSERT_EQUAL_HEX8(0x01, rd(XGO_REG_VERSION));
    wr(XGO_REG_BODY_PITCH, 0xFF);
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(0.2, 10.0, rd_angle(XGO_REG_IMU_PITCH)); /* Lite pitch limit 10 deg */
}

/* ------------------------------------------------------------ robustness */

static uint32_t rng_state = 0x9E3779B9u;
static uint32_t rng(void)
{
    return xgo_test_xorshift32(&rng_state);
}

static void test_random_commands_never_jump_joints_or_break_limits(void)
{
    static const uint8_t regs[] = {0x09, 0x20, 0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37, 0x38,
                                   0x39, 0x3A, 0x3B, 0x3C, 0x3D, 0x3E, 0x40, 0x42, 0x45, 0x4B, 0x50,
                                   0x55, 0x5B, 0x5C, 0x5D, 0x61, 0x80, 0x81, 0x82, 0x03, 0x04};
    const xgo_profile_t *p = xgo_profile_mini();
    int32_t prev[XGO_SERVO_COUNT], now[XGO_SERVO_COUNT];
    unsigned t, i;
    xgo_board_joints_mdeg(&board, prev);
    for (t = 0; t < 200000; t++) {
        if (rng() % 50 == 0) {
            const uint8_t addr = regs[rng() % sizeof regs];
            const uint8_t v = (uint8_t)rng();
            (void)xgo_board_write(&board, XGO_SOURCE_CLI, addr, &v, 1); /* invalid ones are rejected */
        }
        ticks(1);
        xgo_board_joints_mdeg(&board, now);
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            const int32_t a = now[i];
            TEST_ASSERT_LESS_OR_EQUAL_INT32(XGO_JOINT_STEP_MAX_MDEG, abs(a - prev[i]));
            TEST_ASSERT_TRUE(a >= p->joint_mdeg[i % 3].lo && a <= p->joint_mdeg[i % 3].hi);
            prev[i] = a;
        }
    }
}

/* The stroke the reach checks (motion.c, update_stroke) is always that of
 * the command of the tick: its key the command's (a turn to a heading at
 * its highest rate) and the stroke xgo_motion_stroke's for the key, under
 * random changes of each field, one at a time and together. The host
 * compares the key's four words at once (same_stroke_command): a change
 * that compare missed would leave a stale key here. */
static void test_stroke_follows_every_command_change(void)
{
    static const uint8_t regs[] = {XGO_REG_VX, XGO_REG_VY, XGO_REG_VYAW, XGO_REG_MARK_TIME, XGO_REG_MOVE_MODE,
                                   XGO_REG_GAIT_TYPE, XGO_REG_TURN_TO};
    static xgo_motion_t copy;
    unsigned t, n, checked = 0;
    for (t = 0; t < 20000; t++) {
        const unsigned changes = rng() % 8 == 0 ? 1u + rng() % 3u : 0u;
        for (n = 0; n < changes; n++) {
            const uint8_t addr = regs[rng() % sizeof regs];
            /* near the dead band and the extremes as often as anywhere */
            const uint8_t v = (uint8_t)(rng() % 2 ? rng() : 0x7Eu + rng() % 5u);
            (void)xgo_board_write(&board, XGO_SOURCE_CLI, addr, &v, 1);
        }
        ticks(1);
        if (board.motion.mode == XGO_MODE_WHOLE_UNIT && board.motion.action_id == 0) {
            const xgo_motion_t *m = &board.motion;
            xgo_gait_command_t cmd;
            xgo_vec3_t stroke[XGO_LEG_COUNT];
            int walks;
            copy = *m; /* the decode may fill its cache: on a copy */
            xgo_motion_gait_command(&copy, &board.regs, &cmd);
            if (xgo_heading_active(&m->heading)) {
                cmd.vx_um_s = cmd.vy_um_s = cmd.mark_time_um = 0;
                cmd.vyaw_mdeg_s = XGO_HEADING_RATE_MDEG_S;
            }
            TEST_ASSERT_EQUAL_INT32(cmd.vx_um_s, m->stroke_key[0]);
            TEST_ASSERT_EQUAL_INT32(cmd.vy_um_s, m->stroke_key[1]);
            TEST_ASSERT_EQUAL_INT32(cmd.vyaw_mdeg_s, m->stroke_key[2]);
            TEST_ASSERT_EQUAL_INT32(cmd.mark_time_um, m->stroke_key[3]);
            TEST_ASSERT_EQUAL_INT32(cmd.type | (cmd.pace << 8), m->stroke_key[4]);
            copy.stroke_margin_um = m->stroke_key[5]; /* the margin it was worked out with */
            walks = xgo_motion_stroke(&copy, &cmd, stroke);
            TEST_ASSERT_EQUAL_UINT8((uint8_t)walks, m->stroke_walks);
            if (walks) { /* a command that does not walk leaves the stroke as it was */
                TEST_ASSERT_EQUAL_MEMORY(stroke, m->stroke, sizeof stroke);
            }
            checked++;
        }
    }
    TEST_ASSERT_GREATER_THAN_UINT(10000u, checked);
}

/* The contacts the motion core takes from the gait (motion.c,
 * gait_contact_bits: on a 64-bit host one multiply of the four bytes) are
 * its four bytes as bits, leg i bit i, every walking tick under random
 * velocity, mark time and gait type changes. */
static void test_contacts_are_the_gaits(void)
{
    static const uint8_t regs[] = {XGO_REG_VX, XGO_REG_VY, XGO_REG_VYAW, XGO_REG_MARK_TIME, XGO_REG_GAIT_TYPE};
    unsigned t, leg, checked = 0;
    for (t = 0; t < 20000; t++) {
        if (rng() % 16 == 0) {
            const uint8_t v = (uint8_t)rng();
            (void)xgo_board_write(&board, XGO_SOURCE_CLI, regs[rng() % sizeof regs], &v, 1);
        }
        ticks(1);
        if (board.motion.mode == XGO_MODE_WHOLE_UNIT && board.motion.action_id == 0 &&
            !xgo_settle_active(&board.motion.settle)) {
            unsigned want = 0;
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                want |= (unsigned)(board.motion.gait.contact[leg] != 0) << leg;
            }
            TEST_ASSERT_EQUAL_HEX8(want, board.motion.contact);
            checked++;
        }
    }
    TEST_ASSERT_GREATER_THAN_UINT(10000u, checked);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mode_register_follows_the_group_written);
    RUN_TEST(test_dead_band_7f_and_80_both_mean_stop);
    RUN_TEST(test_walking_forward_moves_stance_feet_backward);
    RUN_TEST(test_trotting_feet_lift_and_land_at_the_speed_of_the_floor);
    RUN_TEST(test_turning_integrates_yaw);
    RUN_TEST(test_body_attitude_shows_on_the_imu);
    RUN_TEST(test_body_height_changes_the_legs);
    RUN_TEST(test_periodic_roll_has_the_register_period);
    RUN_TEST(test_self_stabilisation_levels_the_imu);
    RUN_TEST(test_mark_time_steps_in_place);
    RUN_TEST(test_leg_mode_puts_the_foot_where_commanded);
    RUN_TEST(test_leg_mode_entered_from_standing_keeps_the_stance);
    RUN_TEST(test_servo_mode_reads_back_commanded_angles_at_register_speed);
    RUN_TEST(test_joint_registers_read_the_joints_even_right_after_a_write);
    RUN_TEST(test_unloaded_leg_holds_and_ignores_commands);
    RUN_TEST(test_calibration_records_zero_offsets);
    RUN_TEST(test_repeated_calibration_keeps_offsets_storable);
    RUN_TEST(test_writes_of_several_groups_in_one_tick_keep_the_last_group);
    RUN_TEST(test_nv_data_round_trip_and_validation);
    RUN_TEST(test_bluetooth_rename_counts_as_nv_change);
    RUN_TEST(test_standing_posture_stops_and_clears_motion);
    RUN_TEST(test_action_reads_back_for_its_duration_then_zero);
    RUN_TEST(test_actions_move_the_body_and_end_standing);
    RUN_TEST(test_reset_restores_the_initial_table);
    RUN_TEST(test_perform_mode_cycles_actions);
    RUN_TEST(test_battery_drains_faster_while_walking);
    RUN_TEST(test_lite_profile_version_and_ranges);
    RUN_TEST(test_random_commands_never_jump_joints_or_break_limits);
    RUN_TEST(test_stroke_follows_every_command_change);
    RUN_TEST(test_contacts_are_the_gaits);
    return UNITY_END();
}
