/*
 * motion_pose.c - what the whole-unit registers ask for: the body pose of
 * 0x33..0x38 with the periodic motions (0x39..0x3B, 0x80..0x82) and
 * self-stabilisation (0x61), and the gait command of 0x30..0x32, 0x09,
 * 0x3C, 0x3D (docs/motion.md).
 */

#include "codec.h"
#include "fixed.h"
#include "motion_internal.h"
#include "wide.h" /* XGO_CORE_DIV64_NATIVE: a 64-bit host (command_decoding) */
/* On a 64-bit host a periodic motion's sine inline (fixed.h's bodies: the
 * same code as xgo_sin, so the same value; one a tick); an MCU calls
 * xgo_sin (flash). */
#if XGO_CORE_DIV64_NATIVE
#define XGO_FIXED_BODIES
#define XGO_FIXED_INLINE
#include "fixed.h"
#endif

#define PERIODIC_AXES 6 /* roll, pitch, yaw, x, y, z */

/* Self-stabilisation: each tick the correction moves by 1/STAB_GAIN_SHIFT^2
 * of the remaining IMU error (time constant 32 ticks = 64 ms at 500 Hz). */
#define STAB_GAIN_SHIFT 5

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static int32_t abs32(int32_t v)
{
    return v < 0 ? -v : v;
}

/* ms * XGO_TICK_HZ / 1000: when the tick divides a second into whole ms
 * (500 Hz: 2 ms), the same as ms / (1000 / XGO_TICK_HZ), a shift or a
 * constant division where the general form is a library division on an
 * M0 (every tick with a periodic motion). */
#if 1000u % XGO_TICK_HZ == 0u
#define MS_TO_TICKS(ms) ((ms) / (1000u / XGO_TICK_HZ))
#else
#define MS_TO_TICKS(ms) ((ms) * XGO_TICK_HZ / 1000u)
#endif

/* The phase advance per tick of a periodic motion of period byte b (1..255). */
static uint32_t periodic_step(uint8_t period_byte)
{
    const uint32_t ticks = MS_TO_TICKS((uint32_t)xgo_period_byte_to_ms(period_byte));
    const uint32_t t = ticks < 2u ? 2u : ticks; /* 750..4000 ticks: never below 2 */
    /* One turn of phase per period: floor(2^32 / t) per tick, in 32 bits:
     * (2^32 - 1) / t, plus one when t divides 2^32 (a power of two). */
    return 0xFFFFFFFFu / t + ((t & (t - 1u)) == 0u ? 1u : 0u);
}

/* amplitude * sin(phase) rounded (xgo_mul_q(amplitude, sin, 30), whose
 * saturation never acts here: |result| <= amplitude + 1, a quarter of a
 * profile range), amplitude in the caller's unit. The shift by a constant
 * is inline on an M0, xgo_mul_q's by a variable q two library calls. */
static int32_t wave(xgo_bam_t phase, int32_t amplitude)
{
#if XGO_CORE_DIV64_NATIVE
    xgo_q30_t sin_phase;
    xgo_sincos_inline(phase, &sin_phase, 0);
#else
    const xgo_q30_t sin_phase = xgo_sin(phase);
#endif
    const int64_t p = xgo_mul_wide(amplitude, sin_phase);
    return (int32_t)((p + ((int64_t)1 << 29)) >> 30);
}

/* The body pose and the velocity command of 0x30..0x3C in their units,
 * decoded again only after they were written or reset (motion_writes.c
 * clears decoded.valid then): they change a few times a second at most. */
static void decode_now(xgo_motion_t *m, const xgo_regs_t *r)
{
    static const uint8_t period_reg[PERIODIC_AXES] = {XGO_REG_PERIOD_ROLL, XGO_REG_PERIOD_PITCH,
                                                      XGO_REG_PERIOD_YAW, XGO_REG_PERIOD_X,
                                                      XGO_REG_PERIOD_Y, XGO_REG_PERIOD_Z};
    const xgo_profile_t *p = m->profile;
    int32_t *v = m->decoded.body;
    unsigned axis;
    m->decoded.valid = 1;
    v[0] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_ROLL), p->body_mdeg[0].hi);
    v[1] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_PITCH), p->body_mdeg[1].hi);
    v[2] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_YAW), p->body_mdeg[2].hi);
    v[3] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_X), p->body_um[0].hi);
    v[4] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_BODY_Y), p->body_um[1].hi);
    v[5] = xgo_byte_to_range(&p->body_um[2], xgo_regs_get(r, XGO_REG_BODY_Z));
    m->decoded.velocity[0] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VX), XGO_VX_MAX_UM_S);
    m->decoded.velocity[1] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VY), XGO_VY_MAX_UM_S);
    m->decoded.velocity[2] = xgo_signed_byte_to_value(xgo_regs_get(r, XGO_REG_VYAW), XGO_VYAW_MAX_MDEG_S);
    m->decoded.mark_time_um = xgo_mark_time_byte_to_um(p, xgo_regs_get(r, XGO_REG_MARK_TIME));
    /* The periodic motions (0x39..0x3B, 0x80..0x82: their writes clear
     * valid too): an axis with one keeps its phase step where its static
     * value was (unused while the motion runs), not worked out every tick
     * (a library division on an M0). */
    m->decoded.periodic = 0;
    for (axis = 0; axis < PERIODIC_AXES; axis++) {
        const uint8_t b = xgo_regs_get(r, period_reg[axis]);
        if (b != 0) {
            m->decoded.periodic = (uint8_t)(m->decoded.periodic | (1u << axis));
            v[axis] = (int32_t)periodic_step(b);
        } else {
            /* an axis without a motion starts the next one from phase 0:
             * cleared here, not every tick (the pose is asked for in every
             * tick that decodes, motion.c, and only a decoding changes
             * which axes move) */
            m->periodic_phase[axis] = 0;
        }
    }
}

/* decode_now when needed: the test inline, twice a tick, the decoding out
 * of line. */
XGO_ALWAYS_INLINE void decode_registers(xgo_motion_t *m, const xgo_regs_t *r)
{
    if (!m->decoded.valid) {
        decode_now(m, r);
    }
}

/* A periodic motion on one axis (pose_axis): the sinusoid around the
 * range's middle, its phase advanced by the step decode_registers kept. */
static void periodic_axis(xgo_motion_t *m, unsigned axis, const xgo_range_t *range, int32_t *v,
                          int32_t *mid, int32_t *amp)
{
    m->periodic_phase[axis] += (uint32_t)m->decoded.body[axis];
    *mid = (range->lo + range->hi) / 2;
    *amp = (range->hi - range->lo) / 4;
    *v = *mid + wave(m->periodic_phase[axis], *amp);
}

/* The pose of the registers now; base: the same with each periodic
 * channel at its middle; spread: those channels' amplitudes, 0 elsewhere.
 * A periodic motion replaces the static value on its axis: a sinusoid of
 * half the axis' range around its middle (the spec's "half of the position
 * limit"), starting at the middle. (Field by field: no memcpy/memset calls,
 * every tick.) */
/* One axis of the pose of the registers (body_pose_from_registers): its
 * static value, or its periodic motion. Inline, once per axis: each axis's
 * fields are then constant offsets (no arrays copied into the poses). */
XGO_ALWAYS_INLINE void pose_axis(xgo_motion_t *m, unsigned axis, const xgo_range_t *range, int32_t *v,
                                 int32_t *mid, int32_t *amp)
{
    if (((m->decoded.periodic >> axis) & 1u) == 0) {
        *v = *mid = m->decoded.body[axis];
        *amp = 0;
        return;
    }
    periodic_axis(m, axis, range, v, mid, amp);
}

static void body_pose_from_registers(xgo_motion_t *m, const xgo_regs_t *r, xgo_body_pose_t *pose,
                                     xgo_body_pose_t *base, xgo_body_pose_t *spread)
{
    const xgo_profile_t *p = m->profile;
    decode_registers(m, r);
    pose_axis(m, 0, &p->body_mdeg[0], &pose->roll_mdeg, &base->roll_mdeg, &spread->roll_mdeg);
    pose_axis(m, 1, &p->body_mdeg[1], &pose->pitch_mdeg, &base->pitch_mdeg, &spread->pitch_mdeg);
    pose_axis(m, 2, &p->body_mdeg[2], &pose->yaw_mdeg, &base->yaw_mdeg, &spread->yaw_mdeg);
    pose_axis(m, 3, &p->body_um[0], &pose->x_um, &base->x_um, &spread->x_um);
    pose_axis(m, 4, &p->body_um[1], &pose->y_um, &base->y_um, &spread->y_um);
    pose_axis(m, 5, &p->body_um[2], &pose->z_um, &base->z_um, &spread->z_um);
}

/* Self-stabilisation (0x61 = 1) levels the body against the IMU: each tick
 * the roll and pitch correction moves by a share of the IMU's error (of the
 * last tick); off, the correction decays. It is added to the body pose,
 * whose roll and pitch stay within the profile's ranges. */
static void self_level(xgo_motion_t *m, const xgo_regs_t *r)
{
    const xgo_profile_t *p = m->profile;
    if (xgo_regs_at(r, XGO_REG_IMU_MODE) == 1) { /* constant slots: loads, no calls */
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
}

/* The correction on two poses (the pose asked and its base), whose roll
 * and pitch stay within the ranges; the ranges read once. */
static void level(const xgo_motion_t *m, xgo_body_pose_t *pose, xgo_body_pose_t *base)
{
    const xgo_range_t *roll = &m->profile->body_mdeg[0], *pitch = &m->profile->body_mdeg[1];
    const int32_t sr = m->stab_mdeg[0], sp = m->stab_mdeg[1];
    pose->roll_mdeg = clamp32(pose->roll_mdeg + sr, roll->lo, roll->hi);
    pose->pitch_mdeg = clamp32(pose->pitch_mdeg + sp, pitch->lo, pitch->hi);
    base->roll_mdeg = clamp32(base->roll_mdeg + sr, roll->lo, roll->hi);
    base->pitch_mdeg = clamp32(base->pitch_mdeg + sp, pitch->lo, pitch->hi);
}

/* The gait command of the decoded registers. */
XGO_ALWAYS_INLINE void command_now(const xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd)
{
    /* field by field, no memset call (every tick; padding is never read) */
    cmd->step_height_um = 0;
    cmd->vx_um_s = m->decoded.velocity[0];
    cmd->vy_um_s = m->decoded.velocity[1];
    cmd->vyaw_mdeg_s = m->decoded.velocity[2];
    cmd->mark_time_um = m->decoded.mark_time_um;
    cmd->type = xgo_regs_at(r, XGO_REG_GAIT_TYPE); /* constant slots: loads, no calls */
    cmd->pace = xgo_regs_at(r, XGO_REG_MOVE_MODE);
}

#if XGO_CORE_DIV64_NATIVE
/* The first command after a write: decoded first. Out of line on a host:
 * the usual command then saves no registers (an MCU keeps one copy of
 * command_now). */
static XGO_OWN_FRAME void command_decoding(xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd)
{
    decode_now(m, r);
    command_now(m, r, cmd);
}
#endif

void xgo_motion_gait_command(xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd)
{
#if XGO_CORE_DIV64_NATIVE
    if (!m->decoded.valid) {
        command_decoding(m, r, cmd);
        return;
    }
#else
    decode_registers(m, r);
#endif
    command_now(m, r, cmd);
}

/* Feet and pose for a running action (255, the reset, stands for 1 s): the
 * action's offsets on the standing pose and the stance; a foot not lifted
 * is on the ground. */
XGO_OWN_FRAME void xgo_motion_asked_pose(xgo_motion_t *m, const xgo_regs_t *r,
                                               xgo_body_pose_t *pose, xgo_body_pose_t *base,
                                               xgo_body_pose_t *spread)
{
    body_pose_from_registers(m, r, pose, base, spread);
    self_level(m, r); /* sees last tick's target, m->pose_target */
    level(m, pose, base);
}

/* mdeg/s x um -> um/s: pi / 180000, Q32 (74961.3) */
#define K_YAW_Q32 74961

/* How far each planted foot runs from its stance point either way while
 * the gait follows cmd: half its travel during a stance, (v + w x p) *
 * T_stance / 2 at the nominal cadence, capped at the stride budget (the gait
 * raises the cadence beyond it), plus an eighth for the velocity's
 * transients and the margin learnt while walking (stroke_margin_um), at
 * most the reach box. 0 for a command that stands. */
int xgo_motion_stroke(const xgo_motion_t *m, const xgo_gait_command_t *cmd,
                      xgo_vec3_t stroke[XGO_LEG_COUNT])
{
    const uint8_t type = cmd->mark_time_um > 0 ? (uint8_t)XGO_GAIT_TROT : cmd->type;
    const int32_t half_ms = (int32_t)(xgo_gait_duty_pct(type) * xgo_gait_period_ms(type, cmd->pace) / 200u);
    /* under yaw the stance path is an arc, not the chord checked: a little more */
    const int32_t yaw_extra = (int32_t)((uint32_t)abs32(cmd->vyaw_mdeg_s) / 10u); /* 10 mm at 100 deg/s */
    int32_t most = 0, cap_q15;
    unsigned leg;
    if (cmd->vx_um_s == 0 && cmd->vy_um_s == 0 && cmd->vyaw_mdeg_s == 0) {
        return 0;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        const int64_t wy = ((int64_t)cmd->vyaw_mdeg_s * m->stance_um[leg].y * K_YAW_Q32) >> 32;
        const int64_t wx = ((int64_t)cmd->vyaw_mdeg_s * m->stance_um[leg].x * K_YAW_Q32) >> 32;
        /* um/s * ms / 1000, as * 1049 / 2^20 */
        stroke[leg].x = (int32_t)(((cmd->vx_um_s - wy) * half_ms * 1049) >> 20);
        stroke[leg].y = (int32_t)(((cmd->vy_um_s + wx) * half_ms * 1049) >> 20);
        stroke[leg].z = 0;
        most = abs32(stroke[leg].x) > most ? abs32(stroke[leg].x) : most;
        most = abs32(stroke[leg].y) > most ? abs32(stroke[leg].y) : most;
    }
    /* the cap as a factor: one 32-bit division */
    cap_q15 = most > XGO_GAIT_HALF_STRIDE_X_UM ? ((int32_t)XGO_GAIT_HALF_STRIDE_X_UM << 15) / most : 1 << 15;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        stroke[leg].x = (int32_t)(((int64_t)stroke[leg].x * cap_q15) >> 15);
        stroke[leg].y = (int32_t)(((int64_t)stroke[leg].y * cap_q15) >> 15);
        {   /* longer by an eighth and the margin, along the stroke */
            const int32_t len = (int32_t)xgo_isqrt32((uint32_t)(stroke[leg].x * stroke[leg].x) +
                                                     (uint32_t)(stroke[leg].y * stroke[leg].y));
            const int32_t to = len + len / 8 + m->stroke_margin_um + yaw_extra;
            if (len > 0) {
                stroke[leg].x = stroke[leg].x * (to / 8) / (len / 8 + 1); /* < 2^31, 32-bit */
                stroke[leg].y = stroke[leg].y * (to / 8) / (len / 8 + 1);
            }
        }
        stroke[leg].x = clamp32(stroke[leg].x, -XGO_GAIT_REACH_X_UM, XGO_GAIT_REACH_X_UM);
        stroke[leg].y = clamp32(stroke[leg].y, -XGO_GAIT_REACH_X_UM, XGO_GAIT_REACH_X_UM);
    }
    return 1;
}
