/*
 * motion_pose.c - what the whole-unit registers ask for: the body pose of
 * 0x33..0x38 with the periodic motions (0x39..0x3B, 0x80..0x82) and
 * self-stabilisation (0x61), and the gait command of 0x30..0x32, 0x09,
 * 0x3C, 0x3D (docs/motion.md).
 */
#include <string.h>

#include "codec.h"
#include "motion_internal.h"

#define PERIODIC_AXES 6 /* roll, pitch, yaw, x, y, z */

/* Self-stabilisation: each tick the correction moves by 1/STAB_GAIN_SHIFT^2
 * of the remaining IMU error (time constant 32 ticks = 64 ms at 500 Hz). */
#define STAB_GAIN_SHIFT 5

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

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
        /* what the IMU would read with the body at the pose asked for last
         * tick (the same once the body follows it): no wind-up while the
         * body is still on its way */
        const int32_t roll = m->imu.roll_mdeg - m->pose.roll_mdeg + m->pose_target.roll_mdeg;
        const int32_t pitch = m->imu.pitch_mdeg - m->pose.pitch_mdeg + m->pose_target.pitch_mdeg;
        m->stab_mdeg[0] -= roll >> STAB_GAIN_SHIFT;
        m->stab_mdeg[1] -= pitch >> STAB_GAIN_SHIFT;
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

void xgo_motion_gait_command(const xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd)
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
void xgo_motion_asked_pose(xgo_motion_t *m, const xgo_regs_t *r, xgo_body_pose_t *pose)
{
    body_pose_from_registers(m, r, pose);
    self_level(m, r, pose); /* sees last tick's target, m->pose_target */
}
