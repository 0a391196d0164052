/*
 * Emulated servos: rate-limited tracking of targets, limp joints, zero offsets.
 */
#include "servos.h"

#include <string.h>

#include "check.h"
#include "wide.h" /* XGO_CORE_NARROW_CPU */

/* joint: 0..2 (servo index % 3), the profile's joint ranges */
static int32_t clamp_joint(const xgo_servos_t *s, unsigned joint, int32_t mdeg)
{
    const xgo_range_t *r = &s->profile->joint_mdeg[joint];
    return mdeg < r->lo ? r->lo : (mdeg > r->hi ? r->hi : mdeg);
}

void xgo_servos_init(xgo_servos_t *s, const xgo_profile_t *profile,
                     const int32_t initial_mdeg[XGO_SERVO_COUNT])
{
    unsigned i;
    memset(s, 0, sizeof *s);
    s->profile = profile;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        s->angle_mdeg[i] = clamp_joint(s, i % XGO_JOINT_COUNT, initial_mdeg[i]);
        s->target_mdeg[i] = s->angle_mdeg[i];
    }
}

void xgo_servos_set_targets(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT])
{
    unsigned i, joint = 0;
    /* joint counts along (no i % 3: a library division per servo on an M0) */
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if ((s->unloaded & (1u << i)) == 0) {
            s->target_mdeg[i] = clamp_joint(s, joint, target_mdeg[i]);
        }
        joint = joint + 1u == XGO_JOINT_COUNT ? 0u : joint + 1u;
    }
}

/* One joint's step toward its target, at most max_step (>= 0). Both are
 * within the joint limits (|v| < 2^20), so no overflow. */
static int32_t step_toward(int32_t angle, int32_t target, int32_t max_step)
{
    const int32_t error = target - angle;
    return error > max_step ? angle + max_step : (error < -max_step ? angle - max_step : target);
}

void xgo_servos_tick(xgo_servos_t *s, int32_t max_step_mdeg)
{
    unsigned i;
    if (max_step_mdeg < 0) {
        max_step_mdeg = 0;
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if ((s->unloaded & (1u << i)) == 0) {
            s->angle_mdeg[i] = step_toward(s->angle_mdeg[i], s->target_mdeg[i], max_step_mdeg);
        }
    }
}

int xgo_servos_follow(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT], int32_t max_step_mdeg)
{
    const xgo_range_t *range = s->profile->joint_mdeg;
    unsigned leg, j, i = 0;
    int at = 1; /* every angle == target_mdeg: cleared on the rare branches only */
    if (max_step_mdeg < 0) {
        max_step_mdeg = 0;
    }
    if (s->unloaded == 0) {
#if XGO_CORE_NARROW_CPU
        /* every joint loaded (walking, actions): no per-joint mask test.
         * Here the flag below costs the loop more than the caller's compare
         * of the twelve angles (Cortex-M0 -Os): unknown, -1. */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            for (j = 0; j < XGO_JOINT_COUNT; j++, i++) {
                const int32_t t = target_mdeg[i] < range[j].lo   ? range[j].lo
                                  : target_mdeg[i] > range[j].hi ? range[j].hi
                                                                 : target_mdeg[i];
                s->target_mdeg[i] = t;
                s->angle_mdeg[i] = step_toward(s->angle_mdeg[i], t, max_step_mdeg);
            }
        }
        (void)at;
        return -1;
#else
        /* every joint loaded (walking, actions): no per-joint mask test. A
         * limited target is out of range and the angle within it, a step
         * short of the target leaves the angle elsewhere: either way the
         * angle differs from target_mdeg[i]; otherwise it is that value. */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            for (j = 0; j < XGO_JOINT_COUNT; j++, i++) {
                int32_t t = target_mdeg[i], error;
                if (t < range[j].lo) {
                    t = range[j].lo;
                    at = 0;
                } else if (t > range[j].hi) {
                    t = range[j].hi;
                    at = 0;
                }
                s->target_mdeg[i] = t;
                error = t - s->angle_mdeg[i];
                if (error > max_step_mdeg) {
                    s->angle_mdeg[i] += max_step_mdeg;
                    at = 0;
                } else if (error < -max_step_mdeg) {
                    s->angle_mdeg[i] -= max_step_mdeg;
                    at = 0;
                } else {
                    s->angle_mdeg[i] = t;
                }
            }
        }
        return at;
#endif
    }
    /* one pass instead of two; leg by joint, no i % 3 */
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        for (j = 0; j < XGO_JOINT_COUNT; j++, i++) {
            if ((s->unloaded & (1u << i)) == 0) {
                const int32_t t = target_mdeg[i] < range[j].lo   ? range[j].lo
                                  : target_mdeg[i] > range[j].hi ? range[j].hi
                                                                 : target_mdeg[i];
                s->target_mdeg[i] = t;
                s->angle_mdeg[i] = step_toward(s->angle_mdeg[i], t, max_step_mdeg);
            }
            at = at && s->angle_mdeg[i] == target_mdeg[i];
        }
    }
    return at;
}

void xgo_servos_unload(xgo_servos_t *s, uint16_t mask)
{
    unsigned i;
    s->unloaded = (uint16_t)((s->unloaded | mask) & XGO_SERVO_ALL_MASK);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if ((mask & (1u << i)) != 0) {
            s->target_mdeg[i] = s->angle_mdeg[i];
        }
    }
}

void xgo_servos_load(xgo_servos_t *s, uint16_t mask)
{
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if ((mask & s->unloaded & (1u << i)) != 0) {
            s->target_mdeg[i] = s->angle_mdeg[i];
        }
    }
    s->unloaded = (uint16_t)(s->unloaded & ~mask);
}

void xgo_servos_record_zero(xgo_servos_t *s)
{
    unsigned i;
    /* The raw position the servo has now becomes 0 deg: from here on the
     * board counts angles from it. */
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        /* A servo position is an angle: keep offsets in [-180, 180) deg so
         * repeated calibrations cannot grow them without bound. */
        int32_t offset = (s->zero_offset_mdeg[i] + s->angle_mdeg[i]) % 360000;
        if (offset >= 180000) {
            offset -= 360000;
        } else if (offset < -180000) {
            offset += 360000;
        }
        s->zero_offset_mdeg[i] = offset;
        s->angle_mdeg[i] = clamp_joint(s, i % XGO_JOINT_COUNT, 0);
        s->target_mdeg[i] = s->angle_mdeg[i];
    }
}

int32_t xgo_servos_raw(const xgo_servos_t *s, unsigned joint)
{
    XGO_ASSERT(joint < XGO_SERVO_COUNT);
    return joint < XGO_SERVO_COUNT ? s->angle_mdeg[joint] + s->zero_offset_mdeg[joint] : 0;
}
