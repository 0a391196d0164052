/*
 * The motion core: modes, register decoding, body pose, and the hand-off to
 * gait, actions, kinematics, servos and sensors.
 */
#include "motion.h"

#include <string.h>

#include "check.h"
#include "codec.h"

#define PERIODIC_AXES 6 /* roll, pitch, yaw, x, y, z */

/* Self-stabilisation: each tick the correction moves by 1/STAB_GAIN_SHIFT^2
 * of the remaining IMU error (time constant 32 ticks = 64 ms at 500 Hz). */
#define STAB_GAIN_SHIFT 5

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static void reset_gait(xgo_motion_t *m)
{
    xgo_gait_init(&m->gait, m->stance_um);
}

/* The standing pose is what the body registers say at their initial values
 * (height 0x80 = 97.6 mm on the Mini), so power-up, actions and the gait all
 * stand at the same height. */
static void standing_pose(const xgo_profile_t *p, xgo_body_pose_t *pose)
{
    const xgo_reg_desc_t *z = xgo_reg_find(XGO_REG_BODY_Z);
    xgo_body_pose_stand(p, pose);
    pose->z_um = xgo_byte_to_range(&p->body_um[XGO_AXIS_Z], z->initial);
}

static void measure_feet(xgo_motion_t *m, int contact_known);

static void standing_joints(const xgo_motion_t *m, int32_t q[XGO_SERVO_COUNT])
{
    xgo_body_to_joints(m->profile, &m->stand, m->stance_um, (int32_t(*)[XGO_JOINT_COUNT])q);
}

void xgo_motion_init(xgo_motion_t *m, const xgo_profile_t *profile, uint8_t battery_pct)
{
    int32_t q[XGO_SERVO_COUNT];
    memset(m, 0, sizeof *m);
    m->profile = profile;
    m->mode = XGO_MODE_WHOLE_UNIT;
    m->group_mode = XGO_MODE_WHOLE_UNIT;
    xgo_stance_feet(profile, m->stance_um);
    reset_gait(m);
    xgo_action_init(&m->actions);
    standing_pose(profile, &m->stand);
    m->pose = m->stand;
    standing_joints(m, q);
    xgo_servos_init(&m->servos, profile, q);
    xgo_imu_init(&m->imu);
    xgo_battery_init(&m->battery, battery_pct);
    xgo_odometry_init(&m->odom);
    xgo_heading_init(&m->heading);
    xgo_inertial_init(&m->inertial);
    xgo_arm_init(&m->arm, profile->arm);
    m->contact = 0x0Fu;
    measure_feet(m, 1);
}

/* ------------------------------------------------------------ host writes */

static int any_written(xgo_regs_t *r, unsigned first, unsigned last)
{
    int any = 0;
    unsigned a;
    for (a = first; a <= last; a++) {
        any |= xgo_regs_take_written(r, (uint8_t)a);
    }
    return any;
}

static void stop_action(xgo_motion_t *m)
{
    xgo_action_stop(&m->actions);
    m->action_id = 0;
}

static void start_action(xgo_motion_t *m, uint8_t id)
{
    if (id == 0) {
        stop_action(m);
        return;
    }
    if (xgo_action_start(&m->actions, id)) {
        m->action_id = id;
        reset_gait(m); /* actions start from the stance */
    }
}

/* Motion registers back to their initial values (standing posture, 0x5D). */
static void clear_motion_registers(xgo_regs_t *r)
{
    unsigned a;
    for (a = XGO_REG_VX; a <= XGO_REG_MARK_TIME; a++) {
        const xgo_reg_desc_t *d = xgo_reg_find((uint8_t)a);
        xgo_regs_set(r, (uint8_t)a, d->initial);
    }
    for (a = XGO_REG_PERIOD_X; a <= XGO_REG_PERIOD_Z; a++) {
        xgo_regs_set(r, (uint8_t)a, 0);
    }
}

void xgo_motion_init_registers(const xgo_motion_t *m, xgo_regs_t *r)
{
    const uint8_t z = xgo_foot_to_byte(m->profile, XGO_AXIS_Z, m->stand.z_um);
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_regs_set(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Z), z);
    }
}

/* Action 255: every register back to its initial value, then 1 s of
 * standing (the player's reset action). */
static void reset_all(xgo_motion_t *m, xgo_regs_t *r)
{
    xgo_regs_restore_initial(r);
    xgo_motion_init_registers(m, r);
    xgo_servos_load(&m->servos, XGO_SERVO_ALL_MASK);
    m->perform = 0;
    m->perform_last = 0;
    m->calibration = 0;
    m->group_mode = XGO_MODE_WHOLE_UNIT;
    memset(m->periodic_phase, 0, sizeof m->periodic_phase);
    memset(m->stab_mdeg, 0, sizeof m->stab_mdeg);
    xgo_heading_init(&m->heading);
    xgo_arm_reset(&m->arm);
    start_action(m, XGO_ACTION_RESET);
}

static void apply_unload(xgo_motion_t *m, uint8_t v)
{
    xgo_unload_t u;
    uint16_t mask;
    if (!xgo_unload_decode(v, &u)) {
        XGO_ASSERT(!"the register file accepts only the unload set"); /* ruled out */
        return;
    }
    mask = u.leg == XGO_UNLOAD_ALL_LEGS ? XGO_SERVO_ALL_MASK : XGO_SERVO_LEG_MASK(u.leg);
    if (u.load) {
        xgo_servos_load(&m->servos, mask);
    } else {
        xgo_servos_unload(&m->servos, mask);
    }
}

static void capture_servo_commands(xgo_motion_t *m, xgo_regs_t *r, int entering)
{
    unsigned i;
    if (entering) {
        memcpy(m->servo_cmd_mdeg, m->servos.angle_mdeg, sizeof m->servo_cmd_mdeg);
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if (xgo_regs_take_written(r, (uint8_t)(XGO_REG_SERVO11 + i))) {
            m->servo_cmd_mdeg[i] = xgo_byte_to_joint(m->profile, (xgo_joint_t)(i % XGO_JOINT_COUNT),
                                                     xgo_regs_servo_command(r, i));
        }
    }
}

/* The mode groups of the spec's Mode column: the last group written wins.
 * Every flag is taken (no short-circuit), or a flag left behind would switch
 * the mode back one tick later. */
static void take_group_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    unsigned i;
    int servo = 0;
    int whole = any_written(r, XGO_REG_VX, XGO_REG_MOVE_MODE);
    whole |= any_written(r, XGO_REG_PERIOD_X, XGO_REG_PERIOD_Z);
    whole |= xgo_regs_take_written(r, XGO_REG_GAIT_TYPE);
    if (whole) {
        m->group_mode = XGO_MODE_WHOLE_UNIT;
    }
    if (any_written(r, XGO_REG_LEG1_X, XGO_REG_LEG4_Z)) {
        m->group_mode = XGO_MODE_LEG;
    }
    /* Servo group: peek, so capture_servo_commands sees which joints. */
    servo = xgo_regs_take_written(r, XGO_REG_SERVO_SPEED);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        servo |= xgo_regs_was_written(r, (uint8_t)(XGO_REG_SERVO11 + i));
    }
    if (servo) {
        capture_servo_commands(m, r, m->group_mode != XGO_MODE_SERVO);
        m->group_mode = XGO_MODE_SERVO;
    }
}

/* Debug group: unload/reload, calibration, set zero, Bluetooth name. */
static void take_debug_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    if (xgo_regs_take_written(r, XGO_REG_UNLOAD)) {
        apply_unload(m, xgo_regs_get(r, XGO_REG_UNLOAD));
        m->group_mode = XGO_MODE_DEBUG;
    }
    if (xgo_regs_take_written(r, XGO_REG_CALIBRATION)) {
        const uint8_t on = xgo_regs_get(r, XGO_REG_CALIBRATION);
        if (on && !m->calibration) {
            stop_action(m);
            xgo_servos_unload(&m->servos, XGO_SERVO_ALL_MASK);
        } else if (!on && m->calibration) {
            xgo_servos_load(&m->servos, XGO_SERVO_ALL_MASK);
            m->group_mode = XGO_MODE_WHOLE_UNIT;
        }
        m->calibration = on;
    }
    if (xgo_regs_take_written(r, XGO_REG_SET_ZERO)) {
        /* Only meaningful in calibration, where the joints are limp and
         * have been placed in the reference pose. */
        if (xgo_regs_get(r, XGO_REG_SET_ZERO) == 1 && m->calibration) {
            xgo_servos_record_zero(&m->servos);
            m->nv_changes++;
        }
        xgo_regs_set(r, XGO_REG_SET_ZERO, 0);
    }
    if (any_written(r, XGO_REG_BT_NAME, XGO_REG_BT_NAME + XGO_BT_NAME_LEN - 1u)) {
        m->nv_changes++;
    }
}

/* Standing posture, perform mode, actions; returns 1 for a reset (255). */
static int take_action_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    int reset = 0;
    /* (on the Mini2 0x5D is the arm's servo 52: no standing-posture register) */
    if (!r->arm && xgo_regs_take_written(r, XGO_REG_STAND)) {
        if (xgo_regs_get(r, XGO_REG_STAND) == 1) {
            stop_action(m);
            m->perform = 0;
            clear_motion_registers(r);
            m->group_mode = XGO_MODE_WHOLE_UNIT;
        }
        xgo_regs_set(r, XGO_REG_STAND, 0);
    }
    if (xgo_regs_take_written(r, XGO_REG_PERFORM)) {
        m->perform = xgo_regs_get(r, XGO_REG_PERFORM);
    }
    if (xgo_regs_take_written(r, XGO_REG_ACTION)) {
        const uint8_t id = xgo_regs_get(r, XGO_REG_ACTION);
        if (id == XGO_ACTION_RESET) {
            reset = 1;
        } else {
            start_action(m, id);
            m->group_mode = XGO_MODE_WHOLE_UNIT;
        }
    }
    if (m->perform && m->action_id == 0 && !m->calibration) {
        m->perform_last = xgo_action_next_in_cycle(m->perform_last);
        start_action(m, m->perform_last);
    }
    return reset;
}

/* Writes within one tick apply in this order (docs/motion.md); a reset
 * comes last so it wins. */
/* Turn to heading (0x3F) and its origin (0x06). Any other motion command
 * ends a turn in progress: velocities, an action, the standing posture, a
 * mode other than whole unit; a turn command in the same tick wins. */
static void take_heading_writes(xgo_motion_t *m, xgo_regs_t *r, int cancel)
{
    if (cancel || m->group_mode != XGO_MODE_WHOLE_UNIT || m->calibration) {
        xgo_heading_cancel(&m->heading);
    }
    if (xgo_regs_take_written(r, XGO_REG_SET_ORIGIN)) {
        if (xgo_regs_get(r, XGO_REG_SET_ORIGIN) == 1) {
            xgo_heading_set_origin(&m->heading, m->imu.yaw_mdeg);
        }
        xgo_regs_set(r, XGO_REG_SET_ORIGIN, 0);
    }
    if (xgo_regs_take_written(r, XGO_REG_TURN_TO)) {
        xgo_heading_start(&m->heading, xgo_regs_turn_to_deg(r));
        m->group_mode = XGO_MODE_WHOLE_UNIT;
    }
}

static int ends_a_turn(const xgo_regs_t *r)
{
    static const uint8_t regs[] = {XGO_REG_VX, XGO_REG_VY, XGO_REG_VYAW, XGO_REG_ACTION,
                                   XGO_REG_STAND};
    unsigned i;
    int any = 0;
    for (i = 0; i < sizeof regs; i++) {
        /* on the Mini2 0x5D is an arm servo, no motion command */
        any |= xgo_regs_was_written(r, regs[i]) && (regs[i] != XGO_REG_STAND || !r->arm);
    }
    return any;
}

static void handle_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    const int cancel = ends_a_turn(r);
    take_group_writes(m, r);
    take_debug_writes(m, r);
    if (take_action_writes(m, r)) {
        reset_all(m, r);
    }
    take_heading_writes(m, r, cancel);
}

/* ------------------------------------------------------------ whole unit */

static void advance_periodic(xgo_motion_t *m, unsigned axis, uint8_t period_byte)
{
    const uint32_t ticks = (uint32_t)xgo_period_byte_to_ms(period_byte) * XGO_TICK_HZ / 1000u;
    /* One turn of phase per period: 2^32 / ticks per tick. */
    m->periodic_phase[axis] += (xgo_bam_t)(((uint64_t)1 << 32) / (ticks == 0 ? 1u : ticks));
}

/* amplitude * sin(phase), amplitude in the caller's unit */
static int32_t wave(xgo_bam_t phase, int32_t amplitude)
{
    return xgo_mul_q(amplitude, xgo_sin(phase), 30);
}

/* The body pose the registers ask for: 0x33..0x38 (dead band at 0x7F/0x80),
 * each axis with a periodic motion (0x39..0x3B, 0x80..0x82) replaced by its
 * sinusoid. Advances the periodic phases. */
static void body_pose_from_registers(xgo_motion_t *m, const xgo_regs_t *r, xgo_body_pose_t *pose)
{
    const xgo_profile_t *p = m->profile;
    static const uint8_t period_reg[PERIODIC_AXES] = {XGO_REG_PERIOD_ROLL, XGO_REG_PERIOD_PITCH,
                                                      XGO_REG_PERIOD_YAW, XGO_REG_PERIOD_X,
                                                      XGO_REG_PERIOD_Y, XGO_REG_PERIOD_Z};
    int32_t v[PERIODIC_AXES];
    unsigned axis;

    v[0] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_ROLL), p->body_mdeg[0].hi);
    v[1] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_PITCH), p->body_mdeg[1].hi);
    v[2] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_YAW), p->body_mdeg[2].hi);
    v[3] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_X), p->body_um[0].hi);
    v[4] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_Y), p->body_um[1].hi);
    v[5] = xgo_byte_to_range(&p->body_um[2], xgo_regs_get(r, XGO_REG_BODY_Z));

    /* A periodic motion replaces the static value on its axis: a sinusoid
     * of half the axis' range around its middle (the spec's "half of the
     * position limit"), starting at the middle. */
    for (axis = 0; axis < PERIODIC_AXES; axis++) {
        const uint8_t b = xgo_regs_get(r, period_reg[axis]);
        const xgo_range_t *range = axis < 3 ? &p->body_mdeg[axis] : &p->body_um[axis - 3];
        if (b == 0) {
            m->periodic_phase[axis] = 0;
            continue;
        }
        advance_periodic(m, axis, b);
        v[axis] = (range->lo + range->hi) / 2 + wave(m->periodic_phase[axis], (range->hi - range->lo) / 4);
    }

    pose->roll_mdeg = v[0];
    pose->pitch_mdeg = v[1];
    pose->yaw_mdeg = v[2];
    pose->x_um = v[3];
    pose->y_um = v[4];
    pose->z_um = v[5];
}

/* Self-stabilisation (0x61 = 1) levels the body against the IMU: each tick
 * the roll and pitch correction moves by a share of the IMU's error (of the
 * last tick); off, the correction decays. It is added to the body pose,
 * whose roll and pitch stay within the profile's ranges. */
static void self_level(xgo_motion_t *m, const xgo_regs_t *r, xgo_body_pose_t *pose)
{
    const xgo_profile_t *p = m->profile;
    if (xgo_regs_get(r, XGO_REG_IMU_MODE) == 1) {
        m->stab_mdeg[0] -= m->imu.roll_mdeg >> STAB_GAIN_SHIFT;
        m->stab_mdeg[1] -= m->imu.pitch_mdeg >> STAB_GAIN_SHIFT;
    } else {
        m->stab_mdeg[0] -= m->stab_mdeg[0] >> STAB_GAIN_SHIFT;
        m->stab_mdeg[1] -= m->stab_mdeg[1] >> STAB_GAIN_SHIFT;
    }
    m->stab_mdeg[0] = clamp32(m->stab_mdeg[0], 2 * p->body_mdeg[0].lo, 2 * p->body_mdeg[0].hi);
    m->stab_mdeg[1] = clamp32(m->stab_mdeg[1], 2 * p->body_mdeg[1].lo, 2 * p->body_mdeg[1].hi);
    pose->roll_mdeg = clamp32(pose->roll_mdeg + m->stab_mdeg[0], p->body_mdeg[0].lo, p->body_mdeg[0].hi);
    pose->pitch_mdeg =
        clamp32(pose->pitch_mdeg + m->stab_mdeg[1], p->body_mdeg[1].lo, p->body_mdeg[1].hi);
}

static void gait_command_from_registers(const xgo_motion_t *m, const xgo_regs_t *r,
                                        xgo_gait_command_t *cmd)
{
    memset(cmd, 0, sizeof *cmd);
    cmd->vx_um_s = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VX), XGO_VX_MAX_UM_S);
    cmd->vy_um_s = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VY), XGO_VY_MAX_UM_S);
    cmd->vyaw_mdeg_s = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VYAW), XGO_VYAW_MAX_MDEG_S);
    cmd->mark_time_um = xgo_mark_time_byte_to_um(m->profile, xgo_regs_get(r, XGO_REG_MARK_TIME));
    cmd->type = xgo_regs_get(r, XGO_REG_GAIT_TYPE);
    cmd->pace = xgo_regs_get(r, XGO_REG_MOVE_MODE);
}

/* Feet and pose for a running action (255, the reset, stands for 1 s): the
 * action's offsets on the standing pose and the stance; a foot not lifted
 * is on the ground. */
static void action_pose(xgo_motion_t *m, xgo_body_pose_t *pose, xgo_vec3_t feet[XGO_LEG_COUNT])
{
    xgo_pose_t ap;
    unsigned leg;
    if (!xgo_action_tick(&m->actions, &ap)) {
        m->action_id = 0;
    }
    pose->x_um = m->stand.x_um + ap.body.x_um;
    pose->y_um = m->stand.y_um + ap.body.y_um;
    pose->z_um = m->stand.z_um + ap.body.z_um;
    pose->roll_mdeg = m->stand.roll_mdeg + ap.body.roll_mdeg;
    pose->pitch_mdeg = m->stand.pitch_mdeg + ap.body.pitch_mdeg;
    pose->yaw_mdeg = m->stand.yaw_mdeg + ap.body.yaw_mdeg;
    m->contact = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg].x = m->stance_um[leg].x + ap.feet_um[leg].x;
        feet[leg].y = m->stance_um[leg].y + ap.feet_um[leg].y;
        feet[leg].z = m->stance_um[leg].z + ap.feet_um[leg].z;
        if (ap.feet_um[leg].z <= 0) {
            m->contact |= (uint8_t)(1u << leg);
        }
    }
}

/* Body + leg IK, skipped when the pose and the feet are those of the last
 * solve: a robot standing still (the common case) then costs almost nothing,
 * which matters on a Cortex-M0 (docs/mcu.md). */
static void solve_joints(xgo_motion_t *m, const xgo_body_pose_t *pose,
                         const xgo_vec3_t feet[XGO_LEG_COUNT], int32_t q[XGO_SERVO_COUNT])
{
    if (!m->ik_cache.valid || memcmp(&m->ik_cache.pose, pose, sizeof *pose) != 0 ||
        memcmp(m->ik_cache.feet, feet, sizeof m->ik_cache.feet) != 0) {
        m->ik_cache.pose = *pose;
        memcpy(m->ik_cache.feet, feet, sizeof m->ik_cache.feet);
        unsigned leg;
        xgo_body_ik(m->profile, pose, feet, m->ik_cache.feet_leg);
        m->ik_cache.projected = 0;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (xgo_leg_ik(m->profile, (xgo_leg_t)leg, &m->ik_cache.feet_leg[leg],
                           &m->ik_cache.q_mdeg[XGO_JOINT_COUNT * leg]) != XGO_IK_REACHED) {
                m->ik_cache.projected |= (uint8_t)(1u << leg);
            }
        }
        m->ik_cache.valid = 1;
    }
    memcpy(q, m->ik_cache.q_mdeg, sizeof m->ik_cache.q_mdeg);
}

static int whole_unit_targets(xgo_motion_t *m, const xgo_regs_t *r, int32_t q[XGO_SERVO_COUNT],
                              int32_t *yaw_rate_mdeg_s)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t pose;
    int walking = 0;
    unsigned leg;

    *yaw_rate_mdeg_s = 0;
    if (m->action_id != 0) {
        action_pose(m, &pose, feet);
    } else {
        xgo_gait_command_t cmd;
        gait_command_from_registers(m, r, &cmd);
        if (xgo_heading_active(&m->heading)) {
            /* turning in place: the heading controller owns the yaw rate */
            cmd.vx_um_s = cmd.vy_um_s = cmd.mark_time_um = 0;
            cmd.vyaw_mdeg_s = xgo_heading_tick(&m->heading, m->imu.yaw_mdeg, m->gait.vyaw_mdeg_s);
        }
        xgo_gait_tick(&m->gait, &cmd);
        m->contact = 0;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            m->contact |= (uint8_t)(m->gait.contact[leg] << leg);
            feet[leg] = m->gait.foot_um[leg];
        }
        body_pose_from_registers(m, r, &pose);
        self_level(m, r, &pose);
        walking = !xgo_gait_is_standing(&m->gait);
        *yaw_rate_mdeg_s = m->gait.vyaw_mdeg_s;
    }
    m->pose = pose;
    solve_joints(m, &pose, feet, q);
    return walking || m->action_id != 0;
}

/* ------------------------------------------------------------ other modes */

static void leg_targets(xgo_motion_t *m, const xgo_regs_t *r, int32_t q[XGO_SERVO_COUNT])
{
    const xgo_profile_t *p = m->profile;
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_vec3_t foot;
        foot.x = xgo_signed_byte_to_value(xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_X)),
                                          p->foot_um[XGO_AXIS_X].hi);
        foot.y = xgo_signed_byte_to_value(xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Y)),
                                          p->foot_um[XGO_AXIS_Y].hi);
        foot.z = xgo_byte_to_foot(p, XGO_AXIS_Z, xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Z)));
        xgo_leg_ik(p, (xgo_leg_t)leg, &foot, &q[XGO_JOINT_COUNT * leg]);
    }
    m->pose = m->stand;
}

static int32_t servo_mode_step(const xgo_regs_t *r)
{
    const int32_t per_s = xgo_servo_speed_byte_to_mdeg_s(xgo_regs_servo_speed(r));
    const int32_t step = per_s / (int32_t)XGO_TICK_HZ;
    return step < 1 ? 1 : step;
}

/* ------------------------------------------------------------ measurement */

/* Where the feet are (FK of the joints as they are, not as commanded) and,
 * from the planted ones, how far the body moved on the floor. Outside the
 * gait and the actions nobody says which feet are down: those within 1 mm
 * of the lowest are. */
static void measure_feet(xgo_motion_t *m, int contact_known)
{
    xgo_vec3_t machine[XGO_LEG_COUNT];
    int32_t low = INT32_MAX;
    unsigned leg;
    if (contact_known && m->ik_cache.valid && m->ik_cache.projected == 0 &&
        memcmp(m->servos.angle_mdeg, m->ik_cache.q_mdeg, sizeof m->ik_cache.q_mdeg) == 0) {
        /* The joints are where this tick's IK put them and every foot was
         * reachable: the feet are where they were asked to be (FK of these
         * angles agrees within the IK's 2.4 um), so spare the FK. */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            xgo_leg_to_body(m->profile, (xgo_leg_t)leg, &m->ik_cache.feet_leg[leg],
                            &m->feet_body_um[leg]);
            machine[leg] = m->ik_cache.feet[leg];
        }
    } else {
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            xgo_vec3_t foot_leg;
            xgo_leg_fk(m->profile, (xgo_leg_t)leg, &m->servos.angle_mdeg[XGO_JOINT_COUNT * leg],
                       &foot_leg);
            xgo_leg_to_body(m->profile, (xgo_leg_t)leg, &foot_leg, &m->feet_body_um[leg]);
        }
        xgo_body_to_machine(&m->pose, m->feet_body_um, machine);
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        low = machine[leg].z < low ? machine[leg].z : low;
    }
    if (!contact_known) {
        m->contact = 0;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (machine[leg].z <= low + 1000) {
                m->contact |= (uint8_t)(1u << leg);
            }
        }
    }
    xgo_odometry_update(&m->odom, machine, m->contact);
}

/* ------------------------------------------------------------ publish */

void xgo_motion_publish(const xgo_motion_t *m, xgo_regs_t *r)
{
    uint8_t joints[XGO_SERVO_COUNT];
    unsigned i;
    xgo_joints_to_bytes(m->profile, (const int32_t(*)[XGO_JOINT_COUNT])m->servos.angle_mdeg, joints);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        xgo_regs_set(r, (uint8_t)(XGO_REG_SERVO11 + i), joints[i]);
    }
    xgo_regs_set(r, XGO_REG_MODE, m->mode);
    xgo_regs_set(r, XGO_REG_BATTERY, xgo_battery_percent(&m->battery));
    xgo_regs_set(r, XGO_REG_ACTION, m->action_id);
    xgo_regs_set(r, XGO_REG_PERFORM, m->perform);
    xgo_regs_set_attitude(r, m->imu.roll_mdeg, m->imu.pitch_mdeg, m->imu.yaw_mdeg);
    xgo_regs_set_inertial(r, m->inertial.accel, m->inertial.gyro);
    xgo_regs_set(r, XGO_REG_TURN_TO, xgo_heading_done(&m->heading));
    xgo_arm_publish(&m->arm, r);
}

/* The accelerometer and gyroscope see the body where the odometry and the
 * body pose put it, with the attitude the IMU reports. */
static void inertial_tick(xgo_motion_t *m)
{
    const int32_t att[3] = {m->imu.roll_mdeg, m->imu.pitch_mdeg, m->imu.yaw_mdeg};
    int64_t body_q8[3];
    xgo_bam_t heading;
    xgo_inertial_body_position(&m->odom, &m->pose, body_q8, &heading);
    xgo_inertial_tick(&m->inertial, body_q8, heading, att);
}

void xgo_motion_tick(xgo_motion_t *m, xgo_regs_t *r)
{
    int32_t q[XGO_SERVO_COUNT];
    int32_t step = XGO_JOINT_STEP_MAX_MDEG;
    int32_t yaw_rate = 0;
    int busy = 0;

    handle_writes(m, r);
    m->mode = m->action_id != 0 ? XGO_MODE_ACTION
              : m->calibration  ? XGO_MODE_CALIBRATION
                                : m->group_mode;
    switch (m->mode) {
    case XGO_MODE_WHOLE_UNIT:
    case XGO_MODE_ACTION:
        busy = whole_unit_targets(m, r, q, &yaw_rate);
        break;
    case XGO_MODE_LEG:
        leg_targets(m, r, q);
        break;
    case XGO_MODE_SERVO:
        memcpy(q, m->servo_cmd_mdeg, sizeof q);
        step = servo_mode_step(r);
        m->pose = m->stand;
        break;
    default: /* debug, calibration: hold */
        memcpy(q, m->servos.angle_mdeg, sizeof q);
        break;
    }
    xgo_servos_set_targets(&m->servos, q);
    xgo_servos_tick(&m->servos, step);
    measure_feet(m, m->mode == XGO_MODE_WHOLE_UNIT || m->mode == XGO_MODE_ACTION);
    xgo_imu_tick(&m->imu, m->pose.roll_mdeg, m->pose.pitch_mdeg, m->pose.yaw_mdeg, yaw_rate);
    inertial_tick(m);
    xgo_arm_tick(&m->arm, r, &m->pose, &m->stand);
    xgo_battery_tick(&m->battery, busy);
    if (m->mode == XGO_MODE_ACTION && m->action_id == 0) {
        m->mode = m->group_mode;
    }
    xgo_motion_publish(m, r);
}
