/*
 * motion_writes.c - the host's writes, taken once per tick (docs/motion.md
 * "Modes"): which mode group was written last, debug and calibration,
 * standing posture, perform mode, actions, reset, turn to heading.
 */
#include <string.h>

#include "check.h"
#include "codec.h"
#include "motion_internal.h"

static int any_written(xgo_regs_t *r, unsigned first, unsigned last)
{
    return xgo_regs_take_written_range(r, (uint8_t)first, (uint8_t)last);
}

static void stop_action(xgo_motion_t *m)
{
    xgo_action_stop(&m->actions);
    m->action_id = 0;
}

/* An action starts from the stance and the standing pose: from anywhere
 * else the board first brings the robot there (a lead-in: feet home, body
 * eased), the player holding its keyframes meanwhile (xgo_action_hold);
 * the same ticks of 0x3E either way. */
static void start_action(xgo_motion_t *m, uint8_t id)
{
    if (id == 0) {
        stop_action(m);
        return;
    }
    if (xgo_action_start(&m->actions, id)) {
        m->action_id = id;
        xgo_motion_begin_settle(m, m->mode);
        xgo_action_hold(&m->actions);
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
    m->decoded.valid = 0;
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
        m->servo_written = 0;
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if (xgo_regs_take_written(r, (uint8_t)(XGO_REG_SERVO11 + i))) {
            m->servo_cmd_mdeg[i] = xgo_byte_to_joint(m->profile, (xgo_joint_t)(i % XGO_JOINT_COUNT),
                                                     xgo_regs_servo_command(r, i));
            m->servo_written = (uint16_t)(m->servo_written | (1u << i));
        }
    }
}

/* The mode groups of the spec's Mode column: the last group written wins.
 * Every flag is taken (no short-circuit), or a flag left behind would switch
 * the mode back one tick later. */
static void take_group_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    int servo = 0;
    int whole = any_written(r, XGO_REG_VX, XGO_REG_MOVE_MODE);
    whole |= any_written(r, XGO_REG_PERIOD_X, XGO_REG_PERIOD_Z);
    whole |= xgo_regs_take_written(r, XGO_REG_GAIT_TYPE);
    if (whole) {
        m->group_mode = XGO_MODE_WHOLE_UNIT;
        m->decoded.valid = 0; /* motion_pose.c decodes 0x30..0x3C again */
    }
    if (any_written(r, XGO_REG_LEG1_X, XGO_REG_LEG4_Z)) {
        m->group_mode = XGO_MODE_LEG;
    }
    /* Servo group: peek, so capture_servo_commands sees which joints. */
    servo = xgo_regs_take_written(r, XGO_REG_SERVO_SPEED);
    servo |= xgo_regs_was_written_range(r, XGO_REG_SERVO11,
                                        (uint8_t)(XGO_REG_SERVO11 + XGO_SERVO_COUNT - 1u));
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

/* Perform mode: the next action of the cycle once the last one ended. Out
 * of line (an MCU's -Os keeps it so anyway): what a start needs is not
 * saved on the tick's usual path, which only calls it. */
static XGO_OWN_FRAME void next_performance(xgo_motion_t *m)
{
    if (m->perform && m->action_id == 0 && !m->calibration) {
        m->perform_last = xgo_action_next_in_cycle(m->perform_last);
        start_action(m, m->perform_last);
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
            m->decoded.valid = 0;
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
    next_performance(m);
    return reset;
}

/* Writes within one tick apply in this order (docs/motion.md); a reset
 * comes last so it wins. */
/* Turn to heading (0x3F) and its origin (0x06). Any other motion command
 * ends a turn in progress: velocities, an action, the standing posture, a
 * mode other than whole unit; a turn command in the same tick wins. */
static void end_turn_outside_whole_unit(xgo_motion_t *m, int cancel)
{
    if (cancel || m->group_mode != XGO_MODE_WHOLE_UNIT || m->calibration) {
        xgo_heading_cancel(&m->heading);
    }
}

static void take_heading_writes(xgo_motion_t *m, xgo_regs_t *r, int cancel)
{
    end_turn_outside_whole_unit(m, cancel);
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

/* Something was written: every kind of write in turn. Out of line: the
 * usual tick (nothing written) then saves none of the registers it needs. */
static XGO_OWN_FRAME void take_all_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    const int cancel = ends_a_turn(r);
    take_group_writes(m, r);
    take_debug_writes(m, r);
    if (take_action_writes(m, r)) {
        reset_all(m, r);
    }
    take_heading_writes(m, r, cancel);
}

XGO_OWN_FRAME void xgo_motion_take_writes(xgo_motion_t *m, xgo_regs_t *r)
{
    if (!xgo_regs_take_any_written(r)) {
        /* Nothing written since the last pass, which took every flag this
         * file looks at: only what depends on the state alone (about 600
         * instructions a tick less, x86 and M0 alike). */
        next_performance(m);
        end_turn_outside_whole_unit(m, 0);
        return;
    }
    take_all_writes(m, r);
}
