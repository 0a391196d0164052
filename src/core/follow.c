/*
 * follow.c - the body pose follows its target smoothly (follow.h).
 */
#include "follow.h"

#include "compiler.h" /* XGO_ALWAYS_INLINE */
#include "fixed.h"
#include "wide.h"     /* XGO_CORE_DIV64_NATIVE: a 64-bit host */

/* A 64-bit host tries the usual tick, every channel taking its step
 * straight to the target, on all six in one branchless pass, which GCC
 * -O3 makes vector compares (follow_direct); an MCU channel by channel. */
#define FOLLOW_ALL_FIRST XGO_CORE_DIV64_NATIVE

#define CHANNELS 6
#define Q8 256

/* Per-tick speed and acceleration bounds in 1/256 unit, per channel kind. */
#define SPEED_T ((int32_t)((int64_t)XGO_FOLLOW_SPEED_UM_S * Q8 / XGO_TICK_HZ))
#define ACCEL_T ((int32_t)((int64_t)XGO_FOLLOW_ACCEL_UM_S2 * Q8 / XGO_TICK_HZ / XGO_TICK_HZ))
#define SPEED_R ((int32_t)((int64_t)XGO_FOLLOW_SPEED_MDEG_S * Q8 / XGO_TICK_HZ))
#define ACCEL_R ((int32_t)((int64_t)XGO_FOLLOW_ACCEL_MDEG_S2 * Q8 / XGO_TICK_HZ / XGO_TICK_HZ))

static void to_array(const xgo_body_pose_t *p, int32_t v[CHANNELS])
{
    v[0] = p->x_um;
    v[1] = p->y_um;
    v[2] = p->z_um;
    v[3] = p->roll_mdeg;
    v[4] = p->pitch_mdeg;
    v[5] = p->yaw_mdeg;
}

/* (v + 128) >> 8 without the 64-bit sum (a library shift on an M0, six
 * times a tick): floor((v + 128) / 256) = floor(v / 256) + 1 exactly when
 * v's low byte is 128 or more. */
static int32_t round_q8(int32_t v)
{
    return (v >> 8) + ((v & (Q8 - 1)) >= Q8 / 2 ? 1 : 0);
}

void xgo_follow_pose(const xgo_follow_t *f, xgo_body_pose_t *out)
{
    out->x_um = round_q8(f->pos_q8[0]);
    out->y_um = round_q8(f->pos_q8[1]);
    out->z_um = round_q8(f->pos_q8[2]);
    out->roll_mdeg = round_q8(f->pos_q8[3]);
    out->pitch_mdeg = round_q8(f->pos_q8[4]);
    out->yaw_mdeg = round_q8(f->pos_q8[5]);
}

void xgo_follow_init(xgo_follow_t *f, const xgo_body_pose_t *pose)
{
    int32_t v[CHANNELS];
    unsigned c;
    to_array(pose, v);
    for (c = 0; c < CHANNELS; c++) {
        f->pos_q8[c] = v[c] * Q8;
        f->vel_q8[c] = 0;
    }
}

void xgo_follow_take(xgo_follow_t *f, const xgo_body_pose_t *pose)
{
    int32_t v[CHANNELS];
    unsigned c;
    to_array(pose, v);
    for (c = 0; c < CHANNELS; c++) {
        f->vel_q8[c] = v[c] * Q8 - f->pos_q8[c];
        f->pos_q8[c] = v[c] * Q8;
    }
}

void xgo_follow_shift_z(xgo_follow_t *f, int32_t dz_um)
{
    f->pos_q8[2] += dz_um * Q8;
}

/* One channel: take the step to the target if it is within the bounds
 * (then the output is the target), else accelerate toward it, never faster
 * than lets it stop there: the speed v with v^2 / 2a + v / 2 = |e| (a
 * discrete braking sequence v, v - a, ... covers that). */
static void channel_tick(int32_t *pos, int32_t *vel, int32_t target_q8, int32_t speed, int32_t accel)
{
    const int32_t e = target_q8 - *pos;
    const int32_t dv = e - *vel;
    if (e >= -speed && e <= speed && dv >= -accel && dv <= accel) {
        *vel = e;
        *pos = target_q8;
        return;
    }
    {
        const uint32_t ae = e < 0 ? 0u - (uint32_t)e : (uint32_t)e;
        int32_t brake = (int32_t)xgo_isqrt64((uint64_t)accel * (uint64_t)accel / 4u +
                                             2u * (uint64_t)accel * ae) - accel / 2;
        int32_t want, step;
        brake = brake > (int32_t)ae ? (int32_t)ae : brake;
        brake = brake > speed ? speed : brake;
        want = e < 0 ? -brake : brake;
        step = want - *vel;
        step = step > accel ? accel : (step < -accel ? -accel : step);
        *vel += step;
        *pos += *vel;
    }
}

/* One channel's tick and its output (xgo_follow_pose's rounding): a channel
 * resting on its target stays and outputs the target (round_q8 of
 * target * Q8 is the target), the common case; inline per channel, so each
 * field and bound is a constant. */
XGO_ALWAYS_INLINE void follow_channel(int32_t *pos, int32_t *vel, int32_t target, int32_t speed,
                                      int32_t accel, int32_t *out)
{
    if (*pos == target * Q8 && *vel == 0) {
        *out = target;
        return;
    }
    channel_tick(pos, vel, target * Q8, speed, accel);
    *out = round_q8(*pos);
}

#if FOLLOW_ALL_FIRST
/* channel_tick's first case for the six channels at once: when every one
 * is within its speed and acceleration bounds of its target (a channel
 * resting on its target is: e = dv = 0), each takes the step (vel = e, pos
 * = target * Q8) and outputs its target (round_q8 of target * Q8), returns
 * 1; else nothing is stored, returns 0. The same sums as channel_tick's,
 * modulo 2^32; the bounds per channel in arrays, so the loop is uniform. */
static int follow_direct(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out)
{
    static const int32_t speed[CHANNELS] = {SPEED_T, SPEED_T, SPEED_T, SPEED_R, SPEED_R, SPEED_R};
    static const int32_t accel[CHANNELS] = {ACCEL_T, ACCEL_T, ACCEL_T, ACCEL_R, ACCEL_R, ACCEL_R};
    int32_t t[CHANNELS], e[CHANNELS];
    uint32_t bad = 0;
    unsigned c;
    to_array(target, t);
    for (c = 0; c < CHANNELS; c++) {
        int32_t dv;
        e[c] = (int32_t)((uint32_t)t[c] * Q8 - (uint32_t)f->pos_q8[c]);
        dv = (int32_t)((uint32_t)e[c] - (uint32_t)f->vel_q8[c]);
        bad |= 0u - (uint32_t)((e[c] < -speed[c]) | (e[c] > speed[c]) | (dv < -accel[c]) | (dv > accel[c]));
    }
    if (bad != 0u) {
        return 0;
    }
    for (c = 0; c < CHANNELS; c++) {
        f->vel_q8[c] = e[c];
        f->pos_q8[c] = (int32_t)((uint32_t)t[c] * Q8);
    }
    *out = *target;
    return 1;
}
#endif

/* The six channels one by one. */
XGO_ALWAYS_INLINE void follow_each(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out)
{
    follow_channel(&f->pos_q8[0], &f->vel_q8[0], target->x_um, SPEED_T, ACCEL_T, &out->x_um);
    follow_channel(&f->pos_q8[1], &f->vel_q8[1], target->y_um, SPEED_T, ACCEL_T, &out->y_um);
    follow_channel(&f->pos_q8[2], &f->vel_q8[2], target->z_um, SPEED_T, ACCEL_T, &out->z_um);
    follow_channel(&f->pos_q8[3], &f->vel_q8[3], target->roll_mdeg, SPEED_R, ACCEL_R, &out->roll_mdeg);
    follow_channel(&f->pos_q8[4], &f->vel_q8[4], target->pitch_mdeg, SPEED_R, ACCEL_R, &out->pitch_mdeg);
    follow_channel(&f->pos_q8[5], &f->vel_q8[5], target->yaw_mdeg, SPEED_R, ACCEL_R, &out->yaw_mdeg);
}

#if FOLLOW_ALL_FIRST
/* A channel on its way (braking or speeding up) out of line: the usual
 * tick then saves no registers. */
static XGO_OWN_FRAME void follow_slow(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out)
{
    follow_each(f, target, out);
}

void xgo_follow_tick(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out)
{
    if (!follow_direct(f, target, out)) {
        follow_slow(f, target, out);
    }
}
#else
void xgo_follow_tick(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out)
{
    follow_each(f, target, out);
}
#endif

int xgo_follow_at(const xgo_follow_t *f, const xgo_body_pose_t *pose)
{
    int32_t t[CHANNELS];
    unsigned c;
    to_array(pose, t);
    for (c = 0; c < CHANNELS; c++) {
        if (f->pos_q8[c] != t[c] * Q8 || f->vel_q8[c] != 0) {
            return 0;
        }
    }
    return 1;
}
