/*
 * Emulated servos: rate-limited tracking of targets, limp joints, zero offsets.
 */
#include "servos.h"

#include <string.h>

#include "check.h"
#include "compiler.h" /* XGO_ALWAYS_INLINE */
#include "wide.h"     /* XGO_CORE_DIV64_NATIVE: a 64-bit host */

/* A 64-bit host checks the twelve joints of xgo_servos_follow in one
 * branchless pass, which GCC -O3 turns into vector compares
 * (follow_all_fast); a 32-bit MCU one by one, stopping at the first that
 * fails (follow_fast). */
#define SERVOS_ALL_AT_ONCE XGO_CORE_DIV64_NATIVE

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

#if !SERVOS_ALL_AT_ONCE
/* The usual case of a loaded joint's follow (xgo_servos_follow): the target
 * t within the joint's range [lo, lo + span] and the angle within one step
 * of it. Then the target is t and the angle arrives: stored, returns 1;
 * otherwise nothing is stored, returns 0. Two unsigned compares decide it,
 * for lo <= hi = lo + span, span < 2^30 (the profile's ranges): t - lo (mod
 * 2^32) <= span is lo <= t <= hi for every int32 t (a t below lo wraps to
 * above hi - lo); and e + step <= 2 step (mod 2^32) is -step <= e <= step
 * for the error e = t - angle, both inside the range (|e| <= span), and
 * step <= 2^30 (the caller caps it: any larger step reaches every target in
 * range alike). */
XGO_ALWAYS_INLINE int follow_fast(int32_t *angle, int32_t *target, int32_t t, int32_t lo, uint32_t span,
                                  uint32_t step)
{
    if ((uint32_t)t - (uint32_t)lo <= span && (uint32_t)t - (uint32_t)*angle + step <= 2u * step) {
        *target = t;
        *angle = t;
        return 1;
    }
    return 0;
}
#else

/* The joints' ranges along the joints (joint i: range i % 3): one leg's,
 * copied along the legs, so the loops over the twelve joints are
 * uniform. */
XGO_ALWAYS_INLINE void ranges_along(const xgo_range_t *range, int32_t lo[XGO_SERVO_COUNT],
                                    int32_t hi[XGO_SERVO_COUNT])
{
    unsigned j;
    for (j = 0; j < XGO_JOINT_COUNT; j++) {
        lo[j] = range[j].lo;
        hi[j] = range[j].hi;
    }
    memcpy(&lo[3], lo, 3 * sizeof lo[0]);
    memcpy(&hi[3], hi, 3 * sizeof hi[0]);
    memcpy(&lo[6], lo, 6 * sizeof lo[0]);
    memcpy(&hi[6], hi, 6 * sizeof hi[0]);
}

/* follow_fast for all twelve joints in one branchless pass (the host's
 * form: GCC -O3 makes the loop vector compares): every joint passes, then
 * each angle and target is stored and it returns 1; else nothing is
 * stored, returns 0. The same tests as signed compares: lo <= t <= hi,
 * and -step <= e <= step for e = t - angle taken modulo 2^32 (it matters
 * only for a t in range, where it is exact); both for every joint, no
 * early exit. */
static int follow_all_fast(xgo_servos_t *s, const int32_t *t, const xgo_range_t *range, int32_t step)
{
    int32_t lo[XGO_SERVO_COUNT], hi[XGO_SERVO_COUNT];
    uint32_t bad = 0;
    unsigned i;
    ranges_along(range, lo, hi);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        const int32_t e = (int32_t)((uint32_t)t[i] - (uint32_t)s->angle_mdeg[i]);
        bad |= 0u - (uint32_t)((t[i] < lo[i]) | (t[i] > hi[i]) | (e > step) | (e < -step));
    }
    if (bad != 0u) {
        return 0;
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        s->target_mdeg[i] = t[i];
        s->angle_mdeg[i] = t[i];
    }
    return 1;
}

/* follow_loaded_from(s, range, t, step, 0) in one uniform pass (the ticks
 * where a joint is limited or short of its target): each target clamped
 * into its range, each angle a step toward it. */
static void follow_all_loaded(xgo_servos_t *s, const int32_t *t, const xgo_range_t *range, int32_t step)
{
    int32_t lo[XGO_SERVO_COUNT], hi[XGO_SERVO_COUNT];
    unsigned i;
    ranges_along(range, lo, hi);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        const int32_t c = t[i] < lo[i] ? lo[i] : (t[i] > hi[i] ? hi[i] : t[i]);
        s->target_mdeg[i] = c;
        s->angle_mdeg[i] = step_toward(s->angle_mdeg[i], c, step);
    }
}
#endif

/* The follow joint by joint (set_targets, then tick, in one pass; leg by
 * joint, no i % 3), limp joints included: returns 1 when every angle is
 * now target_mdeg. max_step_mdeg >= 0. */
XGO_ALWAYS_INLINE int follow_each(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT],
                                  int32_t max_step_mdeg)
{
    const xgo_range_t *range = s->profile->joint_mdeg;
    unsigned leg, j, i = 0;
    int at = 1; /* with joints unloaded: every angle so far == target_mdeg */
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

#if SERVOS_ALL_AT_ONCE
/* The rare follows out of line (a joint limp; or limited or short of its
 * target, then the result is 0, see below): the usual one then saves no
 * registers. */
static XGO_OWN_FRAME int follow_slow(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT],
                                     int32_t max_step_mdeg)
{
    if (s->unloaded == 0) {
        follow_all_loaded(s, target_mdeg, s->profile->joint_mdeg, max_step_mdeg);
        return 0;
    }
    return follow_each(s, target_mdeg, max_step_mdeg);
}

int xgo_servos_follow(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT], int32_t max_step_mdeg)
{
    if (max_step_mdeg < 0) {
        max_step_mdeg = 0;
    }
    if (max_step_mdeg > (1 << 30)) {
        max_step_mdeg = 1 << 30; /* beyond any joint's span: the same steps (follow_all_fast) */
    }
    /* every joint loaded (walking, actions) and each reaching a target in
     * range (a steady walk: all of them, every tick): three vectors */
    if (s->unloaded == 0 && follow_all_fast(s, target_mdeg, s->profile->joint_mdeg, max_step_mdeg)) {
        return 1;
    }
    return follow_slow(s, target_mdeg, max_step_mdeg);
}
#else
/* Every joint loaded, from leg `from` on: each target clamped into its
 * range, each angle a step toward it (the general step, without the limp
 * joints' test). */
XGO_ALWAYS_INLINE void follow_loaded_from(xgo_servos_t *s, const xgo_range_t *range,
                                          const int32_t target_mdeg[XGO_SERVO_COUNT], int32_t max_step_mdeg,
                                          unsigned from)
{
    unsigned leg, j, i;
    for (leg = from; leg < XGO_LEG_COUNT; leg++) {
        for (j = 0, i = leg * XGO_JOINT_COUNT; j < XGO_JOINT_COUNT; j++, i++) {
            const int32_t t = target_mdeg[i] < range[j].lo   ? range[j].lo
                              : target_mdeg[i] > range[j].hi ? range[j].hi
                                                             : target_mdeg[i];
            s->target_mdeg[i] = t;
            s->angle_mdeg[i] = step_toward(s->angle_mdeg[i], t, max_step_mdeg);
        }
    }
}

int xgo_servos_follow(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT], int32_t max_step_mdeg)
{
    const xgo_range_t *range = s->profile->joint_mdeg;
    unsigned i;
    if (max_step_mdeg < 0) {
        max_step_mdeg = 0;
    }
    if (max_step_mdeg > (1 << 30)) {
        max_step_mdeg = 1 << 30; /* beyond any joint's span: the same steps (follow_fast) */
    }
    if (s->unloaded == 0) {
        /* every joint loaded (walking, actions): no per-joint mask test, and
         * while each joint reaches a target in range (a steady walk: all of
         * them, every tick) two compares a joint (follow_fast), the ranges
         * read once */
        const uint32_t step = (uint32_t)max_step_mdeg;
        const int32_t lo0 = range[0].lo, lo1 = range[1].lo, lo2 = range[2].lo;
        const uint32_t span0 = (uint32_t)range[0].hi - (uint32_t)lo0;
        const uint32_t span1 = (uint32_t)range[1].hi - (uint32_t)lo1;
        const uint32_t span2 = (uint32_t)range[2].hi - (uint32_t)lo2;
        /* follow_fast's bounds hold: every profile's joint ranges have lo <
         * hi and a span below 2^23 (codec.h's XGO_RANGE_SPAN_LIMIT; checked
         * by test_profile, not every tick) */
        for (i = 0; i < XGO_SERVO_COUNT; i += XGO_JOINT_COUNT) {
            if (!follow_fast(&s->angle_mdeg[i], &s->target_mdeg[i], target_mdeg[i], lo0, span0, step) ||
                !follow_fast(&s->angle_mdeg[i + 1u], &s->target_mdeg[i + 1u], target_mdeg[i + 1u], lo1,
                             span1, step) ||
                !follow_fast(&s->angle_mdeg[i + 2u], &s->target_mdeg[i + 2u], target_mdeg[i + 2u], lo2,
                             span2, step)) {
                break;
            }
        }
        if (i == XGO_SERVO_COUNT) {
            return 1; /* every angle is its target as given */
        }
        /* a joint limited or short of its target, so the result is 0 (a
         * limited target is out of range and the angle within it, a
         * step short leaves the angle elsewhere): the rest of this leg
         * and the next ones the general way (on the joints of this leg
         * follow_fast did, the general step does the same again) */
        follow_loaded_from(s, range, target_mdeg, max_step_mdeg, i / XGO_JOINT_COUNT);
        return 0;
    }
    return follow_each(s, target_mdeg, max_step_mdeg);
}
#endif

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
