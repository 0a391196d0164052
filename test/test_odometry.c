/*
 * Where the robot is on the floor (leg odometry), the board's observer and
 * emulator-input API, and host-side writes (xgo_board_write), on virtual
 * time. Expected distances and radii are computed here from the documented
 * command scaling and velocity ramp, independently of the gait code.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "actions.h" /* xgo_action_duration_ticks */
#include "board_unity.h"
#include "codec.h"
#include "odometry.h"
#include "unity.h"
#include "xgo/board.h"
#include "xgo/emulator.h"

static xgo_board_t board;

#define ODOMETRY_DIGEST 0xedb058dau

void setUp(void)
{
    xgo_board_init(&board, NULL);
}

void tearDown(void)
{
}

/* Writes and ticks as a host would (test/support/board_unity.h). */
#define wr(addr, v) xgo_test_wr(&board, (addr), (v))
#define ticks(n) xgo_test_ticks(&board, (n))

static xgo_world_pose_t world(void)
{
    xgo_world_pose_t p;
    xgo_board_world_pose(&board, &p);
    return p;
}

/* The value a signed velocity register byte means (spec: 0x00..0xFF
 * linearly from -max to +max). */
static double byte_value(uint8_t b, double max)
{
    return -max + b * (2.0 * max) / 255.0;
}

/* Distance covered from standstill under a constant command v for t s,
 * with the documented ramp (acceleration a) at the start. */
static double ramped_distance(double v, double a, double t)
{
    const double t_ramp = v / a;
    return v * t - v * t_ramp / 2.0;
}

static void test_power_up_is_the_origin(void)
{
    const xgo_world_pose_t p = world();
    TEST_ASSERT_EQUAL_INT32(0, p.x_um);
    TEST_ASSERT_EQUAL_INT32(0, p.y_um);
    TEST_ASSERT_EQUAL_INT32(0, p.yaw_mdeg);
    TEST_ASSERT_EQUAL_HEX8(0x0F, xgo_board_contacts(&board));
}

static void test_five_seconds_of_full_speed_trot_covers_the_commanded_distance(void)
{
    const double v = 250.0; /* mm/s: vx 0xFF */
    const double expect = ramped_distance(v, 500.0, 5.0);
    xgo_world_pose_t p;
    wr(XGO_REG_VX, 0xFF);
    ticks(5 * XGO_TICK_HZ);
    p = world();
    TEST_ASSERT_DOUBLE_WITHIN(expect * 0.01, expect, p.x_um / 1000.0);
    TEST_ASSERT_INT32_WITHIN(1000, 0, p.y_um);
    TEST_ASSERT_INT32_WITHIN(100, 0, p.yaw_mdeg);
}

static void test_sideways_and_backward_walks_go_their_way(void)
{
    const double vy = 180.0, expect = ramped_distance(vy, 500.0, 5.0);
    xgo_world_pose_t p;
    wr(XGO_REG_VY, 0x00); /* full speed to the right: -y */
    ticks(5 * XGO_TICK_HZ);
    p = world();
    TEST_ASSERT_DOUBLE_WITHIN(expect * 0.01, -expect, p.y_um / 1000.0);
    TEST_ASSERT_INT32_WITHIN(1000, 0, p.x_um);
    xgo_board_init(&board, NULL);
    wr(XGO_REG_VX, 0x00);
    ticks(5 * XGO_TICK_HZ);
    TEST_ASSERT_DOUBLE_WITHIN(ramped_distance(250.0, 500.0, 5.0) * 0.01,
                              -ramped_distance(250.0, 500.0, 5.0), world().x_um / 1000.0);
}

/* One full turn at 100 deg/s: ramp up 0.4 s (20 deg), 3.2 s steady (320
 * deg), ramp down 0.4 s (20 deg) after the stop command. */
static void test_a_full_turn_returns_the_heading_to_start(void)
{
    xgo_world_pose_t p;
    int32_t yaw_min = 0, yaw_max = 0;
    unsigned i;
    wr(XGO_REG_VYAW, 0xFF);
    for (i = 0; i < 1800; i++) {
        ticks(1);
        p = world();
        yaw_min = p.yaw_mdeg < yaw_min ? p.yaw_mdeg : yaw_min;
        yaw_max = p.yaw_mdeg > yaw_max ? p.yaw_mdeg : yaw_max;
    }
    wr(XGO_REG_VYAW, 0x80);
    ticks(1500);
    p = world();
    TEST_ASSERT_INT32_WITHIN(1000, 0, p.yaw_mdeg);
    /* it did go round (counter-clockwise: through +180, wrapping) */
    TEST_ASSERT_GREATER_THAN_INT32(179000, yaw_max);
    TEST_ASSERT_LESS_THAN_INT32(-179000, yaw_min);
    /* turning in place: the body stays put */
    TEST_ASSERT_INT32_WITHIN(2000, 0, p.x_um);
    TEST_ASSERT_INT32_WITHIN(2000, 0, p.y_um);
}

/* Kasa's algebraic circle fit: minimise sum (x^2 + y^2 + D x + E y + F)^2. */
static double fit_circle_radius(const double *x, const double *y, int n, double *cx, double *cy)
{
    double s[3][4] = {{0}};
    int i, r, c, k;
    for (i = 0; i < n; i++) {
        const double row[3] = {x[i], y[i], 1.0};
        const double rhs = -(x[i] * x[i] + y[i] * y[i]);
        for (r = 0; r < 3; r++) {
            for (c = 0; c < 3; c++) {
                s[r][c] += row[r] * row[c];
            }
            s[r][3] += row[r] * rhs;
        }
    }
    for (k = 0; k < 3; k++) { /* Gauss-Jordan, the normal matrix is positive definite */
        for (r = 0; r < 3; r++) {
            if (r != k) {
                const double f = s[r][k] / s[k][k];
                for (c = k; c < 4; c++) {
                    s[r][c] -= f * s[k][c];
                }
            }
        }
    }
    {
        const double d = s[0][3] / s[0][0], e = s[1][3] / s[1][1], f = s[2][3] / s[2][2];
        *cx = -d / 2.0;
        *cy = -e / 2.0;
        return sqrt(*cx * *cx + *cy * *cy - f);
    }
}

static void test_an_arc_closes_into_a_circle_of_radius_v_over_omega(void)
{
    enum { SAMPLES = 400 };
    static double xs[SAMPLES], ys[SAMPLES];
    const uint8_t vb = 0xC0, wb = 0xC0;
    const double v = byte_value(vb, 250.0);                 /* mm/s */
    const double w = byte_value(wb, 100.0) * M_PI / 180.0;  /* rad/s */
    const double radius = v / w;
    const unsigned period_ticks = (unsigned)(2.0 * M_PI / w * XGO_TICK_HZ + 0.5);
    double cx, cy, r;
    xgo_world_pose_t start, end;
    int i;
    wr(XGO_REG_VX, vb);
    wr(XGO_REG_VYAW, wb);
    ticks(XGO_TICK_HZ); /* past the ramp */
    start = world();
    for (i = 0; i < SAMPLES; i++) {
        xgo_world_pose_t p;
        ticks(period_ticks / SAMPLES);
        p = world();
        xs[i] = p.x_um / 1000.0;
        ys[i] = p.y_um / 1000.0;
    }
    ticks(period_ticks - (period_ticks / SAMPLES) * SAMPLES);
    end = world();
    r = fit_circle_radius(xs, ys, SAMPLES, &cx, &cy);
    TEST_ASSERT_DOUBLE_WITHIN(radius * 0.02, radius, r);
    /* one period later the robot is back where it was, heading and all */
    TEST_ASSERT_DOUBLE_WITHIN(radius * 0.02, start.x_um / 1000.0, end.x_um / 1000.0);
    TEST_ASSERT_DOUBLE_WITHIN(radius * 0.02, start.y_um / 1000.0, end.y_um / 1000.0);
    TEST_ASSERT_INT32_WITHIN(2000, start.yaw_mdeg, end.yaw_mdeg);
    /* counter-clockwise: the centre is to the left of the start heading */
    TEST_ASSERT_TRUE(cy > 0.0);
}

static void assert_no_drift(const char *what)
{
    const xgo_world_pose_t p = world();
    TEST_ASSERT_INT32_WITHIN_MESSAGE(1000, 0, p.x_um, what);
    TEST_ASSERT_INT32_WITHIN_MESSAGE(1000, 0, p.y_um, what);
    /* 1 mm at the feet (about 130 mm from the centre) */
    TEST_ASSERT_INT32_WITHIN_MESSAGE(440, 0, p.yaw_mdeg, what);
}

static void test_standing_for_a_minute_does_not_move(void)
{
    ticks(60 * XGO_TICK_HZ);
    assert_no_drift("standing");
    TEST_ASSERT_EQUAL_INT32(0, world().x_um);
}

/* Body translation and attitude through their whole ranges and back, 30
 * times in a minute, at a rate the servos follow (writes that jump the pose
 * make the feet skid today: issue 9 eases such transitions). */
static void test_body_pose_changes_for_a_minute_drift_less_than_a_millimetre(void)
{
    static const uint8_t regs[] = {XGO_REG_BODY_X,    XGO_REG_BODY_Y,     XGO_REG_BODY_Z,
                                   XGO_REG_BODY_ROLL, XGO_REG_BODY_PITCH, XGO_REG_BODY_YAW};
    unsigned r;
    for (r = 0; r < sizeof regs; r++) {
        int k, v;
        xgo_board_init(&board, NULL);
        for (k = 0; k < 30; k++) {
            for (v = 0x80; v <= 0xFF; v++) {
                wr(regs[r], (uint8_t)v);
                ticks(2);
            }
            for (v = 0xFF; v >= 0x00; v--) {
                wr(regs[r], (uint8_t)v);
                ticks(2);
            }
            for (v = 0x00; v <= 0x80; v++) {
                wr(regs[r], (uint8_t)v);
                ticks(2);
            }
        }
        assert_no_drift(xgo_reg_name(regs[r]));
    }
}

/* The same registers written in one jump across their whole range, every
 * 0.4 s for a minute (the vendor library's attitude('r', 20) writes so): the
 * body follows smoothly (issue 9), the feet do not skid, the robot stays. */
static void test_body_registers_jumping_for_a_minute_drift_less_than_a_millimetre(void)
{
    static const uint8_t regs[] = {XGO_REG_BODY_X,    XGO_REG_BODY_Y,     XGO_REG_BODY_Z,
                                   XGO_REG_BODY_ROLL, XGO_REG_BODY_PITCH, XGO_REG_BODY_YAW};
    unsigned r, k;
    for (r = 0; r < sizeof regs; r++) {
        xgo_board_init(&board, NULL);
        for (k = 0; k < 150; k++) {
            wr(regs[r], (k & 1u) ? 0x00 : 0xFF);
            ticks(XGO_TICK_HZ * 2 / 5);
        }
        wr(regs[r], 0x80);
        ticks(XGO_TICK_HZ);
        assert_no_drift(xgo_reg_name(regs[r]));
    }
}

static void test_periodic_motions_and_self_levelling_do_not_move_the_robot(void)
{
    static const uint8_t regs[] = {XGO_REG_PERIOD_ROLL, XGO_REG_PERIOD_PITCH, XGO_REG_PERIOD_YAW,
                                   XGO_REG_PERIOD_X,    XGO_REG_PERIOD_Y,     XGO_REG_PERIOD_Z};
    unsigned r;
    for (r = 0; r < sizeof regs; r++) {
        xgo_board_init(&board, NULL);
        wr(regs[r], 1); /* fastest */
        ticks(60 * XGO_TICK_HZ);
        assert_no_drift(xgo_reg_name(regs[r]));
    }
    xgo_board_init(&board, NULL);
    xgo_board_set_ground_tilt(&board, 10000, -8000);
    wr(XGO_REG_IMU_MODE, 1);
    ticks(60 * XGO_TICK_HZ);
    assert_no_drift("self-levelling on a tilted ground");
}

/* Every action leaves the robot where it was (circle, 4, turns it round a
 * full turn on the spot: its heading ends where it started), except creep,
 * 3, which crawls straight ahead (issue 9). */
static void test_actions_keep_the_robot_in_place_except_creep(void)
{
    uint8_t id;
    for (id = 1; id <= XGO_ACTION_LAST; id++) {
        xgo_world_pose_t p;
        xgo_board_init(&board, NULL);
        wr(XGO_REG_ACTION, id);
        ticks(xgo_action_duration_ticks(id) + 10);
        if (id != XGO_ACTION_CREEP) {
            assert_no_drift(xgo_action_name(id));
            continue;
        }
        p = world();
        TEST_ASSERT_GREATER_THAN_INT32(100000, p.x_um);
        TEST_ASSERT_INT32_WITHIN(1000, 0, p.y_um);
        TEST_ASSERT_INT32_WITHIN(440, 0, p.yaw_mdeg);
    }
}

/* A reset at full speed: the pose is kept, not zeroed, and the robot does
 * not stop dead either: it coasts to rest over its planted feet at the
 * documented 2.5 m/s^2 and 1250 deg/s^2 (docs/motion.md, Transitions), i.e.
 * v^2 / 2a further on, while its feet come home without skidding. */
static void test_reset_does_not_teleport_the_robot(void)
{
    const double v = 250.0, w = byte_value(0xC0, 100.0); /* mm/s, deg/s */
    const double coast_mm = v * v / (2.0 * 2500.0), coast_deg = w * w / (2.0 * 1250.0);
    xgo_world_pose_t before, after;
    double yaw, dx, dy;
    wr(XGO_REG_VX, 0xFF);
    wr(XGO_REG_VYAW, 0xC0);
    ticks(2 * XGO_TICK_HZ);
    before = world();
    TEST_ASSERT_GREATER_THAN_INT32(100000, before.x_um);
    wr(XGO_REG_ACTION, XGO_ACTION_RESET);
    ticks(2 * XGO_TICK_HZ);
    after = world();
    yaw = before.yaw_mdeg / 1000.0 * M_PI / 180.0;
    dx = (after.x_um - before.x_um) / 1000.0;
    dy = (after.y_um - before.y_um) / 1000.0;
    TEST_ASSERT_DOUBLE_WITHIN(1.0, coast_mm, cos(yaw) * dx + sin(yaw) * dy); /* on along its heading */
    TEST_ASSERT_DOUBLE_WITHIN(1.0, 0.0, -sin(yaw) * dx + cos(yaw) * dy);
    TEST_ASSERT_DOUBLE_WITHIN(0.2, coast_deg, (after.yaw_mdeg - before.yaw_mdeg) / 1000.0);
}

/* Leg mode: moving all four planted feet 10 mm back pushes the body 10 mm
 * forward (nobody says which feet are down there: the lowest are). */
static void test_feet_pushed_back_in_leg_mode_move_the_body_forward(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const uint8_t target = xgo_foot_to_byte(p, XGO_AXIS_X, -10000);
    const double moved = -xgo_byte_to_foot(p, XGO_AXIS_X, target) / 1000.0;
    int v;
    unsigned leg;
    for (v = 0x80; v >= target; v--) { /* slowly, as a careful host would */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            wr((uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_X), (uint8_t)v);
        }
        ticks(10);
    }
    ticks(100);
    TEST_ASSERT_EQUAL_INT(XGO_MODE_LEG, xgo_board_mode(&board));
    TEST_ASSERT_EQUAL_HEX8(0x0F, xgo_board_contacts(&board));
    TEST_ASSERT_DOUBLE_WITHIN(0.2, moved, world().x_um / 1000.0);
}

/* ------------------------------------------------------------ observers */

static void test_observers_describe_the_standing_robot(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    xgo_vec3_t feet[XGO_LEG_COUNT];
    int32_t q[XGO_SERVO_COUNT], cmd[3], prod[3], rpy[3], lo, hi;
    xgo_body_pose_t pose;
    unsigned leg, j;
    ticks(10);
    TEST_ASSERT_EQUAL_UINT32(20, xgo_board_time_ms(&board));
    TEST_ASSERT_EQUAL_UINT8(XGO_MODE_WHOLE_UNIT, xgo_board_mode(&board));
    TEST_ASSERT_EQUAL_UINT8(0, xgo_board_action(&board));
    xgo_board_body_pose(&board, &pose);
    xgo_board_feet_um(&board, feet);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        /* under the thigh joints, on the ground the body stands above */
        TEST_ASSERT_INT32_WITHIN(50, xgo_leg_side_x((xgo_leg_t)leg) * p->hip_x_um, feet[leg].x);
        TEST_ASSERT_INT32_WITHIN(50, xgo_leg_side_y((xgo_leg_t)leg) * (p->hip_y_um + p->abad_offset_um),
                                 feet[leg].y);
        TEST_ASSERT_INT32_WITHIN(50, -pose.z_um, feet[leg].z);
    }
    xgo_board_joints_mdeg(&board, q);
    for (j = 0; j < XGO_SERVO_COUNT; j++) {
        xgo_board_joint_limits_mdeg(&board, j, &lo, &hi);
        TEST_ASSERT_EQUAL_INT32(p->joint_mdeg[j % 3].lo, lo);
        TEST_ASSERT_EQUAL_INT32(p->joint_mdeg[j % 3].hi, hi);
        TEST_ASSERT_TRUE(q[j] > lo && q[j] < hi);
    }
    xgo_board_velocity(&board, cmd, prod);
    TEST_ASSERT_EQUAL_INT32(0, cmd[0]);
    TEST_ASSERT_EQUAL_INT32(0, prod[0]);
    xgo_board_imu_mdeg(&board, rpy);
    TEST_ASSERT_EQUAL_INT32(0, rpy[0]);
    TEST_ASSERT_EQUAL_UINT8(100, xgo_board_battery_pct(&board));
}

static void test_velocity_observer_shows_command_and_ramp(void)
{
    int32_t cmd[3], prod[3];
    wr(XGO_REG_VX, 0xFF);
    ticks(50);
    xgo_board_velocity(&board, cmd, prod);
    TEST_ASSERT_EQUAL_INT32(250000, cmd[0]);
    TEST_ASSERT_EQUAL_INT32(50 * 1000, prod[0]); /* 1 mm/s per tick */
    ticks(XGO_TICK_HZ);
    xgo_board_velocity(&board, cmd, prod);
    TEST_ASSERT_EQUAL_INT32(250000, prod[0]);
}

static void test_trotting_feet_alternate_on_the_ground(void)
{
    unsigned i, two = 0;
    wr(XGO_REG_VX, 0xFF);
    for (i = 0; i < 1000; i++) {
        const uint8_t c = xgo_board_contacts(&board);
        ticks(1);
        if (c == 0x05 || c == 0x0A) { /* LF+RH or RF+LH: the trot's diagonals */
            two++;
        }
    }
    TEST_ASSERT_GREATER_THAN_UINT(800, two);
}

/* ------------------------------------------------------------ inputs */

static void test_battery_input_sets_the_charge(void)
{
    uint8_t v;
    xgo_board_set_battery(&board, 37);
    TEST_ASSERT_EQUAL_UINT8(37, xgo_board_battery_pct(&board));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, XGO_REG_BATTERY, 1, &v));
    TEST_ASSERT_EQUAL_UINT8(37, v);
    xgo_board_set_battery(&board, 250);
    TEST_ASSERT_EQUAL_UINT8(100, xgo_board_battery_pct(&board));
}

static void test_a_push_tips_the_imu_and_dies_away(void)
{
    int32_t rpy[3], peak = 0;
    unsigned i;
    int32_t tr, tp;
    xgo_board_push(&board, 8000, -5000);
    ticks(1);
    xgo_board_imu_mdeg(&board, rpy);
    TEST_ASSERT_INT32_WITHIN(500, 8000, rpy[0]);
    TEST_ASSERT_INT32_WITHIN(500, -5000, rpy[1]);
    for (i = 0; i < 100; i++) { /* it swings through zero to the other side */
        ticks(1);
        xgo_board_imu_mdeg(&board, rpy);
        peak = rpy[0] < peak ? rpy[0] : peak;
    }
    TEST_ASSERT_LESS_THAN_INT32(-1000, peak);
    ticks(XGO_TICK_HZ);
    xgo_board_imu_mdeg(&board, rpy);
    TEST_ASSERT_INT32_WITHIN(20, 0, rpy[0]);
    TEST_ASSERT_INT32_WITHIN(20, 0, rpy[1]);
    assert_no_drift("push");
    xgo_board_push(&board, 90000, -90000); /* clamped to 30 degrees */
    ticks(1);
    xgo_board_imu_mdeg(&board, rpy);
    TEST_ASSERT_INT32_WITHIN(1000, 30000, rpy[0]);
    TEST_ASSERT_INT32_WITHIN(1000, -30000, rpy[1]);
    xgo_board_ground_tilt(&board, &tr, &tp);
    TEST_ASSERT_EQUAL_INT32(0, tr);
}

/* ------------------------------------------------------------ host writes */

#define MAX_EVENTS 8
static xgo_trace_event_t events[MAX_EVENTS];
static size_t n_events;

static void record(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    if (n_events < MAX_EVENTS) {
        events[n_events] = *ev;
        events[n_events].frame = NULL; /* valid only during the callback */
    }
    n_events++;
}

static void test_board_write_takes_the_register_write_path_with_its_source(void)
{
    static const uint8_t wire_write[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
    const uint8_t ff = 0xFF, five = 5;
    uint32_t counters[XGO_DIAG_COUNT];
    n_events = 0;
    xgo_board_set_trace(&board, record, NULL);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_VIEW, XGO_REG_VX, &ff, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY,
                          xgo_board_write(&board, XGO_SOURCE_VIEW, XGO_REG_BATTERY, &five, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_board_write(&board, XGO_SOURCE_VIEW, 0xFF, &ff, 2));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_board_write(&board, XGO_SOURCE_VIEW, 0x30, &ff, 0));
    xgo_board_receive(&board, wire_write, sizeof wire_write, 0);
    TEST_ASSERT_EQUAL_UINT(5, (unsigned)n_events);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_RX, events[0].kind);
    TEST_ASSERT_EQUAL_UINT8(XGO_SOURCE_VIEW, events[0].source);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_DROP, events[1].kind);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, events[1].reason);
    TEST_ASSERT_EQUAL_UINT8(XGO_SOURCE_VIEW, events[1].source);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, events[2].reason);
    TEST_ASSERT_EQUAL_UINT8(XGO_SOURCE_WIRE, events[4].source);
    xgo_board_counters(&board, counters);
    TEST_ASSERT_EQUAL_UINT32(1, counters[XGO_DIAG_FRAMES_OK]); /* the wire frame only */
    TEST_ASSERT_EQUAL_UINT32(1, counters[XGO_DIAG_REJECTED_READ_ONLY]);
    TEST_ASSERT_EQUAL_UINT32(2, counters[XGO_DIAG_BAD_RANGE]);
    /* the write acts like a host's: the robot walks */
    ticks(XGO_TICK_HZ);
    TEST_ASSERT_GREATER_THAN_INT32(50000, world().x_um);
}

/* The odometry's arithmetic is the same on every core: a random walk of the
 * feet (two to four planted, small steps and turns, inside and outside the
 * M0's 32-bit turn, turn_round in odometry.c) gives, step by step, the
 * digest the 64-bit products give (computed on x86-64; the _narrow build of
 * this suite runs the M0's forms). */
static void test_odometry_arithmetic_is_the_same_on_every_core(void)
{
    xgo_odometry_t o;
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_world_pose_t pose;
    uint32_t seed = 2024u, h = 2166136261u;
    unsigned k, leg;
    xgo_odometry_init(&o);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg].x = leg < 2u ? 75000 : -75000;
        feet[leg].y = (leg == 0u || leg == 3u) ? 53500 : -53500;
        feet[leg].z = 0;
    }
    for (k = 0; k < 200000; ++k) {
        uint8_t contact;
        seed = seed * 1664525u + 1013904223u;
        contact = (uint8_t)((seed >> 24) & 0x0Fu);
        contact = contact == 0 ? 0x05u : contact;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            seed = seed * 1664525u + 1013904223u;
            /* steps of up to +-0.5 mm, now and then +-8 mm (a far point) */
            feet[leg].x += (int32_t)(seed >> 22) - 512 + ((k % 97u) == 0u ? 8000 : 0);
            feet[leg].y += (int32_t)((seed >> 12) & 1023u) - 512;
            feet[leg].x = feet[leg].x > 600000 || feet[leg].x < -600000 ? 0 : feet[leg].x;
            feet[leg].y = feet[leg].y > 600000 || feet[leg].y < -600000 ? 0 : feet[leg].y;
        }
        xgo_odometry_update(&o, feet, contact);
        xgo_odometry_pose(&o, &pose);
        h = (h ^ (uint32_t)pose.x_um) * 16777619u;
        h = (h ^ (uint32_t)pose.y_um) * 16777619u;
        h = (h ^ (uint32_t)pose.yaw_mdeg) * 16777619u;
    }
    {
        char msg[48];
        snprintf(msg, sizeof msg, "odometry digest %08lx", (unsigned long)h);
        TEST_MESSAGE(msg);
    }
    TEST_ASSERT_EQUAL_HEX32(ODOMETRY_DIGEST, h);
}

/* The fit's cross product (xgo_odometry_cross: on a narrow core from the
 * change b - a when it and a are small; the _narrow build of this suite
 * takes that form) is the 64-bit one: at the form's edges (the change at
 * +-2^11, a at +-2^19, each just inside and outside) and for 2,000,000
 * random pairs, small changes and large. */
static void test_cross_product_is_the_wide_one(void)
{
    static const int32_t a_edge[] = {0, 1, -1, 524287, -524288, 524288, -524289, 300000, -2147483647 - 1,
                                     2147483647};
    static const int32_t e_edge[] = {0, 1, -1, 2047, -2048, 2048, -2049, 7, 8191, -8192};
    uint32_t seed = 77u;
    unsigned i, j, k;
    for (i = 0; i < 10u * 10u * 10u * 10u; i++) {
        const int32_t ax = a_edge[i % 10u], ay = a_edge[(i / 10u) % 10u];
        const int32_t bx = (int32_t)((uint32_t)ax + (uint32_t)e_edge[(i / 100u) % 10u]);
        const int32_t by = (int32_t)((uint32_t)ay + (uint32_t)e_edge[i / 1000u]);
        TEST_ASSERT_TRUE(xgo_odometry_cross(bx, by, ax, ay) == (int64_t)bx * ay - (int64_t)by * ax);
    }
    for (k = 0; k < 2000000u; k++) {
        int32_t v[4];
        for (j = 0; j < 4u; j++) {
            seed = seed * 1664525u + 1013904223u;
            v[j] = (int32_t)seed >> (j < 2u ? 11u + (seed % 4u) : 19u - (k % 4u));
        }
        v[2] = (int32_t)((uint32_t)v[2] * (k % 3u == 0u ? 2u : 1u)); /* a beyond 2^19 now and then */
        {
            const int32_t ax = v[2], ay = v[3];
            const int32_t bx = (int32_t)((uint32_t)ax + (uint32_t)v[0]), by = (int32_t)((uint32_t)ay + (uint32_t)v[1]);
            if (xgo_odometry_cross(bx, by, ax, ay) != (int64_t)bx * ay - (int64_t)by * ax) {
                TEST_FAIL_MESSAGE("xgo_odometry_cross differs from the 64-bit cross product");
            }
        }
    }
}

/* The fit's turn (xgo_odometry_turn: on a 64-bit host a small turn's
 * atan2 inline) is xgo_atan2_64's, signed: at the inline form's edges (dot
 * at 2^32 and either side, |cross| at dot and either side, cross 0 and
 * INT64_MIN, either sign) and for 3,000,000 random pairs: any magnitudes,
 * and the fit's own (dot of 33 to 62 bits, cross a small part of it, the
 * ratio around the first table node's edge 1/64 too). */
static int32_t atan2_64_signed(int64_t cross, int64_t dot)
{
    return cross == 0 ? 0 : xgo_bam_signed(xgo_atan2_64(cross, dot));
}

static void test_turn_is_xgo_atan2_64s(void)
{
    static const int64_t dot_edge[] = {((int64_t)1 << 32) - 1, (int64_t)1 << 32, ((int64_t)1 << 32) + 1,
                                       ((int64_t)1 << 57) + 12345, INT64_MAX, 1, 0, -((int64_t)1 << 32),
                                       -((int64_t)1 << 40), INT64_MIN};
    uint64_t seed = 2026u;
    unsigned i, j, k;
    for (i = 0; i < 10u; i++) {
        const int64_t d = dot_edge[i];
        const int64_t mag = d < 0 ? (d == INT64_MIN ? INT64_MAX : -d) : d;
        const int64_t cross_edge[] = {0, 1, -1, mag, -mag, mag - 1, -(mag - 1), mag / 64, -(mag / 64),
                                      mag / 64 + 1, INT64_MIN, INT64_MAX};
        for (j = 0; j < sizeof cross_edge / sizeof cross_edge[0]; j++) {
            TEST_ASSERT_EQUAL_INT32(atan2_64_signed(cross_edge[j], d), xgo_odometry_turn(cross_edge[j], d));
            if (mag < INT64_MAX) {
                TEST_ASSERT_EQUAL_INT32(atan2_64_signed(cross_edge[j] == INT64_MIN ? 0 : cross_edge[j], mag + 1),
                                        xgo_odometry_turn(cross_edge[j] == INT64_MIN ? 0 : cross_edge[j], mag + 1));
            }
        }
    }
    for (k = 0; k < 3000000u; k++) {
        int64_t dot, cross;
        uint64_t r[2];
        for (j = 0; j < 2u; j++) {
            seed = seed * 6364136223846793005u + 1442695040888963407u;
            r[j] = seed;
        }
        switch (k % 4u) {
        case 0u: /* any magnitudes and signs */
            dot = (int64_t)r[0] >> (r[1] % 63u);
            cross = (int64_t)r[1] >> ((r[0] >> 7) % 63u);
            break;
        case 1u: /* the fit's: dot of 33 to 62 bits, a small turn */
            dot = (int64_t)((r[0] >> 2) >> (r[1] % 30u)) | ((int64_t)1 << 32);
            cross = ((int64_t)r[1] >> 1) >> (63u - 33u + (r[0] % 30u));
            break;
        case 2u: /* the ratio around 1/64, the first node's edge */
            dot = (int64_t)((r[0] >> 2) >> (r[1] % 30u)) | ((int64_t)1 << 32);
            cross = dot / 64 + (int64_t)(r[1] % 2001u) - 1000;
            cross = (r[1] >> 40) & 1u ? -cross : cross;
            break;
        default: /* |cross| around dot (the octant's other edge) */
            dot = (int64_t)((r[0] >> 2) >> (r[1] % 30u)) | ((int64_t)1 << 32);
            cross = dot + (int64_t)(r[1] % 2001u) - 1000;
            cross = (r[1] >> 40) & 1u ? -cross : cross;
            break;
        }
        if (xgo_odometry_turn(cross, dot) != atan2_64_signed(cross, dot)) {
            TEST_FAIL_MESSAGE("xgo_odometry_turn differs from xgo_atan2_64");
        }
    }
}

/* Feet in the air need not be measured (odometry.h): an odometry given
 * only the planted feet (and some others), garbage for the rest, that
 * measures them when xgo_odometry_needs_all asks (and last tick's through
 * xgo_odometry_set_prev), keeps the state of one given every foot - over
 * random contacts (none, one, up to four) and ticks where nothing moves,
 * only the feet in the air move or a foot is set down. */
static void test_feet_in_the_air_measured_only_when_needed(void)
{
    xgo_odometry_t ref, lazy;
    xgo_vec3_t feet[XGO_LEG_COUNT], prev[XGO_LEG_COUNT];
    uint32_t seed = 77u;
    unsigned k, leg, asked = 0, skipped = 0;
    xgo_odometry_init(&ref);
    xgo_odometry_init(&lazy);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg].x = leg < 2u ? 75000 : -75000;
        feet[leg].y = (leg == 0u || leg == 3u) ? 53500 : -53500;
        feet[leg].z = 0;
    }
    memcpy(prev, feet, sizeof prev);
    for (k = 0; k < 300000; ++k) {
        xgo_vec3_t given[XGO_LEG_COUNT];
        uint8_t contact, measured;
        unsigned kind;
        seed = seed * 1664525u + 1013904223u;
        kind = (seed >> 28) & 3u; /* 0: nothing moves, 1: only the air, else all */
        contact = (uint8_t)((seed >> 20) & 0x0Fu);
        if ((seed >> 16) & 1u) {
            contact = (uint8_t)(contact | ref.prev_contact); /* keep feet down more often */
        }
        measured = (uint8_t)(contact | ((seed >> 8) & (seed >> 12) & 0x0Fu));
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            seed = seed * 1664525u + 1013904223u;
            if (kind == 0u || (kind == 1u && ((contact >> leg) & 1u) != 0)) {
                continue;
            }
            if ((seed & 7u) != 0u) {
                feet[leg].x += (int32_t)(seed >> 22) - 512;
                feet[leg].y += (int32_t)((seed >> 12) & 1023u) - 512;
            }
            feet[leg].z = (int32_t)(seed & 255u); /* z never counts */
        }
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            given[leg] = feet[leg];
            if (((measured >> leg) & 1u) == 0) {
                seed = seed * 1664525u + 1013904223u;
                given[leg].x = (int32_t)(seed >> 8); /* not measured: anything */
                given[leg].y = (seed & 1u) ? prev[leg].y : -(int32_t)(seed >> 9);
            }
        }
        if ((measured != 0x0Fu || xgo_odometry_unmeasured(&lazy) != 0) &&
            xgo_odometry_needs_all(&lazy, given, contact, measured)) {
            memcpy(given, feet, sizeof given);
            measured = 0x0Fu;
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                if (((xgo_odometry_unmeasured(&lazy) >> leg) & 1u) != 0) {
                    xgo_odometry_set_prev(&lazy, leg, &prev[leg]);
                }
            }
            asked++;
        } else if (measured != 0x0Fu) {
            skipped++;
        }
        xgo_odometry_update(&ref, feet, contact);
        xgo_odometry_update_measured(&lazy, given, contact, measured);
        memcpy(prev, feet, sizeof prev);
        if (ref.x_q8 != lazy.x_q8 || ref.y_q8 != lazy.y_q8 || ref.yaw != lazy.yaw ||
            ref.last_d_q8[0] != lazy.last_d_q8[0] || ref.last_d_q8[1] != lazy.last_d_q8[1] ||
            ref.last_dyaw != lazy.last_dyaw || ref.extrapolated_ticks != lazy.extrapolated_ticks ||
            ref.prev_contact != lazy.prev_contact || ref.have_prev != lazy.have_prev) {
            TEST_FAIL_MESSAGE("the odometry with feet in the air unmeasured differs");
        }
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (((lazy.prev_unmeasured >> leg) & 1u) == 0 &&
                (ref.prev_um[leg].x != lazy.prev_um[leg].x || ref.prev_um[leg].y != lazy.prev_um[leg].y)) {
                TEST_FAIL_MESSAGE("a measured foot differs");
            }
        }
    }
    TEST_ASSERT_GREATER_THAN_UINT(1000u, asked);   /* both paths taken */
    TEST_ASSERT_GREATER_THAN_UINT(10000u, skipped);
}

static uint32_t fnv32(uint32_t h, uint32_t v)
{
    unsigned i;
    for (i = 0; i < 4u; i++) {
        h = (h ^ ((v >> (8u * i)) & 0xFFu)) * 16777619u;
    }
    return h;
}

/* What the board's sensing half keeps, tick by tick, as it walks, turns,
 * shifts and yaws its body, bobs, stands, runs an action and takes leg
 * and servo commands: the odometry's state, the accelerometer and
 * gyroscope model's, the measured contacts and the IMU's angles, hashed
 * every tick. The digest is the one the code gave before its host forms
 * (measure_feet's walking case first, inertial.c's one-frame tick,
 * odometry's whole-array copy; computed at 3fcb945), and the _narrow
 * build of this suite takes the MCU's forms: fast path and plain path
 * give the same state at every tick. */
#define SENSING_DIGEST 0x1c35f65fu
static void test_sensing_state_over_a_session_is_the_plain_paths(void)
{
    static const struct {
        uint8_t reg, value;
        uint16_t ticks;
    } script[] = {
        {XGO_REG_VX, 0xE0, 0},          {XGO_REG_VYAW, 0xA0, 0},       {XGO_REG_BODY_ROLL, 0xA0, 0},
        {XGO_REG_BODY_Z, 0x60, 0},      {XGO_REG_PERIOD_PITCH, 0x40, 1500},
        {XGO_REG_VX, 0x80, 0},          {XGO_REG_VY, 0x20, 0},         {XGO_REG_BODY_YAW, 0x90, 800},
        {XGO_REG_VY, 0x80, 0},          {XGO_REG_VYAW, 0x80, 0},       {XGO_REG_PERIOD_PITCH, 0x00, 500},
        {XGO_REG_PERIOD_Z, 0x30, 0},    {XGO_REG_VX, 0x30, 600},       {XGO_REG_VX, 0x80, 0},
        {XGO_REG_PERIOD_Z, 0x00, 0},    {XGO_REG_BODY_YAW, 0x80, 300}, {XGO_REG_ACTION, 0x0B, 1500},
        {XGO_FOOT_REG(0, XGO_AXIS_X), 0x60, 200}, {XGO_FOOT_REG(1, XGO_AXIS_Z), 0xA0, 200},
        {XGO_REG_SERVO12, 0x90, 300},   {XGO_REG_ACTION, 0xFF, 600},
    };
    const xgo_motion_t *m = &board.motion;
    uint32_t h = 2166136261u;
    unsigned i, k, j;
    for (i = 0; i < sizeof script / sizeof script[0]; i++) {
        wr(script[i].reg, script[i].value);
        for (k = 0; k < script[i].ticks; k++) {
            ticks(1);
            h = fnv32(h, (uint32_t)m->odom.x_q8);
            h = fnv32(h, (uint32_t)(m->odom.x_q8 >> 32));
            h = fnv32(h, (uint32_t)m->odom.y_q8);
            h = fnv32(h, (uint32_t)(m->odom.y_q8 >> 32));
            h = fnv32(h, m->odom.yaw);
            h = fnv32(h, (uint32_t)m->odom.last_d_q8[0]);
            h = fnv32(h, (uint32_t)m->odom.last_d_q8[1]);
            h = fnv32(h, (uint32_t)m->odom.last_dyaw);
            h = fnv32(h, m->odom.extrapolated_ticks);
            h = fnv32(h, (uint32_t)m->odom.prev_contact << 8 | m->odom.prev_unmeasured);
            for (j = 0; j < 3u; j++) {
                h = fnv32(h, (uint32_t)m->inertial.accel_q8[j]);
                h = fnv32(h, (uint32_t)m->inertial.gyro_q8[j]);
            }
            h = fnv32(h, (uint32_t)m->contact << 8 | m->feet_as_solved);
            h = fnv32(h, (uint32_t)m->imu.roll_mdeg);
            h = fnv32(h, (uint32_t)m->imu.pitch_mdeg);
            h = fnv32(h, (uint32_t)m->imu.yaw_mdeg);
        }
    }
    {
        char msg[48];
        snprintf(msg, sizeof msg, "sensing digest %08lx", (unsigned long)h);
        TEST_MESSAGE(msg);
    }
    TEST_ASSERT_EQUAL_HEX32(SENSING_DIGEST, h);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_power_up_is_the_origin);
    RUN_TEST(test_five_seconds_of_full_speed_trot_covers_the_commanded_distance);
    RUN_TEST(test_sideways_and_backward_walks_go_their_way);
    RUN_TEST(test_a_full_turn_returns_the_heading_to_start);
    RUN_TEST(test_an_arc_closes_into_a_circle_of_radius_v_over_omega);
    RUN_TEST(test_standing_for_a_minute_does_not_move);
    RUN_TEST(test_body_pose_changes_for_a_minute_drift_less_than_a_millimetre);
    RUN_TEST(test_body_registers_jumping_for_a_minute_drift_less_than_a_millimetre);
    RUN_TEST(test_periodic_motions_and_self_levelling_do_not_move_the_robot);
    RUN_TEST(test_actions_keep_the_robot_in_place_except_creep);
    RUN_TEST(test_reset_does_not_teleport_the_robot);
    RUN_TEST(test_feet_pushed_back_in_leg_mode_move_the_body_forward);
    RUN_TEST(test_observers_describe_the_standing_robot);
    RUN_TEST(test_velocity_observer_shows_command_and_ramp);
    RUN_TEST(test_trotting_feet_alternate_on_the_ground);
    RUN_TEST(test_battery_input_sets_the_charge);
    RUN_TEST(test_a_push_tips_the_imu_and_dies_away);
    RUN_TEST(test_board_write_takes_the_register_write_path_with_its_source);
    RUN_TEST(test_odometry_arithmetic_is_the_same_on_every_core);
    RUN_TEST(test_cross_product_is_the_wide_one);
    RUN_TEST(test_turn_is_xgo_atan2_64s);
    RUN_TEST(test_feet_in_the_air_measured_only_when_needed);
    RUN_TEST(test_sensing_state_over_a_session_is_the_plain_paths);
    return UNITY_END();
}
