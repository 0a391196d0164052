/*
 * gait_governor.c - the gait's governor: how far the velocity may ramp, and
 * whether a gait switch fits, so that every planted foot still finishes its
 * stance inside its reach box (the contract in gait.h).
 *
 * A planted foot at offset off from its stance point, with r phase left
 * until its lift-off, travels s * r / (TICKS_PER_S * rate_max) more at the
 * capped cadence (s: its ground speed). The governor finds the largest step
 * from the produced velocity toward the ramp's proposal that keeps every
 * planted foot's end of stance inside [-reach, reach] (x: XGO_GAIT_REACH_X_UM;
 * y: gait_reach_y, set at touchdown). Under yaw the path is an arc: the
 * ground velocity is taken at the midpoint of the rest of the path, which is
 * its mean to second order and linear in (v, w) for a fixed midpoint, so one
 * division per limited component finds the step.
 */
#include "gait_internal.h"

#include "fixed.h"

/* End-of-stance bounds for one foot component: a foot at offset off (um)
 * from its stance point, moving at ground speed s (um/s) for r more phase
 * at the capped cadence, ends at off - s * r / k with k = TICKS_PER_S * rate_max.
 * It stays in [-reach, reach] (widened to include off, so that s = 0 always
 * fits) iff s * r lies in [lo, hi] computed here. */
static void end_bounds(int32_t off, int32_t reach, int64_t k, int64_t *lo, int64_t *hi)
{
    int32_t up = off > reach ? off : reach;
    int32_t down = -off > reach ? -off : reach;
    *lo = (int64_t)(off - up) * k;
    *hi = (int64_t)(off + down) * k;
}

/* Largest lambda (Q16, 0..65536) for which a + lambda * b keeps s * r in
 * [lo, hi]. When a itself is outside (rounding, or the arc's third-order
 * terms), only steps that do not make it worse are allowed (and *outside is
 * set). One division, only when the full step does not fit. */
static int32_t segment_limit(int32_t a, int32_t b, uint32_t r, int64_t lo, int64_t hi, int *outside)
{
    int64_t ar = (int64_t)a * r;
    int64_t er = (int64_t)(a + b) * r;
    int64_t room;
    int64_t span;
    if (ar > hi || ar < lo) {
        *outside = 1;
        return (ar > hi ? er <= ar : er >= ar) ? 65536 : 0;
    }
    if (er <= hi && er >= lo) {
        return 65536;
    }
    room = er > hi ? hi - ar : ar - lo;
    span = (er > hi ? er - ar : ar - er) >> 16;
    if (span <= 0) {
        return 0;
    }
    return (int32_t)xgo_udiv64_cap((uint64_t)room, (uint64_t)span, 65536u); /* room >= 0 */
}

/* Largest step lambda (Q16) from base towards prop that every stance foot
 * can absorb before its lift-off at the capped cadence; *outside is set when
 * base itself does not quite fit (then no step may make that foot worse). */
static int32_t governor_lambda(const xgo_gait_t *g, const gait_table_t *t, uint32_t phase,
                               const int32_t base[3], const int32_t prop[3], int *outside)
{
    int64_t k = (int64_t)TICKS_PER_S * t->rate_max;
    int32_t wb = yaw_q24(base[2]);
    int32_t wp = yaw_q24(prop[2]);
    int32_t lambda = 65536;
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t q[2];
        int32_t a[2], e[2];
        uint32_t r;
        if (g->swinging[leg]) {
            continue;
        }
        r = 0u - (phase - t->lift[leg]);
        gait_stance_midpoint(g, leg, base, wb, half_time_q16(t, r), q);
        gait_foot_velocity(base, wb, q[0], q[1], a);
        gait_foot_velocity(prop, wp, q[0], q[1], e);
        for (c = 0; c < 2; ++c) {
            int64_t lo, hi;
            int32_t l;
            end_bounds((g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c],
                       c == 0 ? XGO_GAIT_REACH_X_UM : g->reach_y_um[leg], k, &lo, &hi);
            l = segment_limit(a[c], e[c] - a[c], r, lo, hi, outside);
            if (l < lambda) {
                lambda = l;
            }
        }
    }
    return lambda;
}

void gait_governed_ramp(xgo_gait_t *g, const gait_table_t *t, const int32_t prop[3])
{
    int outside = 0;
    int32_t lambda;
    int c;
    if (prop[0] == g->v_ramp[0] && prop[1] == g->v_ramp[1] && prop[2] == g->v_ramp[2]) {
        return;
    }
    lambda = governor_lambda(g, t, g->phase, g->v_ramp, prop, &outside);
    if (lambda < 65536) {
        g->governed_ticks++;
    }
    if (outside) {
        g->outside_ticks++;
    }
    for (c = 0; c < 3; ++c) {
        g->v_ramp[c] += gait_scale_q16(prop[c] - g->v_ramp[c], lambda);
    }
}

/* Would the velocity v fit every planted foot under table n entered at
 * phase p (legs lifting at p excluded)? */
int gait_switch_fits(const xgo_gait_t *g, const gait_table_t *n, uint32_t p, uint32_t rate,
                     const int32_t v[3])
{
    int64_t k = (int64_t)TICKS_PER_S * n->rate_max;
    int32_t w = yaw_q24(v[2]);
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t q[2];
        int32_t f[2];
        uint32_t r = 0u - (p - n->lift[leg]);
        if (p - n->lift[leg] < rate) {
            continue; /* lifts now */
        }
        gait_stance_midpoint(g, leg, v, w, half_time_q16(n, r), q);
        gait_foot_velocity(v, w, q[0], q[1], f);
        for (c = 0; c < 2; ++c) {
            int64_t lo, hi;
            int64_t s = (int64_t)f[c] * r;
            end_bounds((g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c],
                       c == 0 ? XGO_GAIT_REACH_X_UM : g->reach_y_um[leg], k, &lo, &hi);
            if (s < lo || s > hi) {
                return 0;
            }
        }
    }
    return 1;
}
