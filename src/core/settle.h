/*
 * settle.h - bring the feet home: from wherever they are (mid-stride, in
 * an action's pose, where leg or servo mode left them) to the stance, without
 * a planted foot ever sliding (issue 9, docs/motion.md "Transitions").
 *
 * The feet are points in the machine frame of the standing body (x forward,
 * y left, z up, z = 0 on the ground), like the gait's. A foot is planted
 * (z = 0, or flagged so) or in the air. Settling is a sequence of moves:
 *   1. every foot in the air flies to its stance point and lands;
 *   2. the planted feet that are not at their stance point step there, one
 *      diagonal pair at a time (LF + RH, then RF + LH; a pair is what the
 *      trot lifts together), the other pair staying put.
 * A move lifts its feet on a smooth arc (smootherstep across, a bump up)
 * and lasts 120 ms + 4 ms per mm of the longest way (at most 0.6 s), so a
 * foot moves at most ~1.9x its mean speed and the joints follow. A planted
 * foot within XGO_SETTLE_HOME_UM of its stance point is taken as home (put
 * there: a slide of at most that much).
 *
 * A body that was walking does not stop dead: it keeps going over its
 * planted feet, slowing down at XGO_SETTLE_DECEL_UM_S2 and
 * XGO_SETTLE_YAW_DECEL_MDEG_S2 (a planted foot moves by -(v + w x p) dt in
 * the machine frame, as in the gait), typically while the feet in the air
 * come down: 0.1 s from 250 mm/s, a 0.25 g deceleration.
 * The body's pose is not this module's business: the caller eases it (its
 * planted feet stay fixed in the machine frame whatever it does, by body
 * IK).
 * Checks: none; every input value is handled (expected input).
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_SETTLE_H
#define XGO_SETTLE_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_settle_t */
#include "xgo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_SETTLE_HOME_UM 20          /* closer than this is home */
#define XGO_SETTLE_MOVE_BASE_TICKS 60u /* 120 ms */
#define XGO_SETTLE_MOVE_MAX_TICKS 300u /* 600 ms */
#define XGO_SETTLE_DECEL_UM_S2 2500000     /* 2.5 m/s^2 */
#define XGO_SETTLE_YAW_DECEL_MDEG_S2 1250000 /* 1250 deg/s^2 */

/* Start settling feet (machine frame) with these on the ground (bit leg;
 * a planted foot keeps its z until it steps). When every foot is
 * already home (within XGO_SETTLE_HOME_UM) nothing is left to do: not
 * active. */
void xgo_settle_start(xgo_settle_t *s, const xgo_vec3_t feet[XGO_LEG_COUNT], uint8_t contact,
                      const xgo_vec3_t stance[XGO_LEG_COUNT]);

/* The body was moving at v (vx, vy in um/s, yaw rate in mdeg/s, as the gait
 * publishes it): it slows down to rest over its planted feet. Call right
 * after xgo_settle_start. */
void xgo_settle_coast(xgo_settle_t *s, const int32_t v[3]);

/* The body's velocity this tick (vx, vy um/s, yaw rate mdeg/s): 0 once it
 * has come to rest. */
void xgo_settle_velocity(const xgo_settle_t *s, int32_t v[3]);

/* 1 while feet are still on their way (xgo_settle_tick moves them). */
static inline int xgo_settle_active(const xgo_settle_t *s) /* inline: several times a tick */
{
    return s->active != 0;
}

/* One tick toward the stance: writes the feet and which are on the ground.
 * Returns 1 while still settling; 0 when every foot is home (feet = stance,
 * all on the ground) - also when it was not active. */
int xgo_settle_tick(xgo_settle_t *s, const xgo_vec3_t stance[XGO_LEG_COUNT],
                    xgo_vec3_t feet[XGO_LEG_COUNT], uint8_t *contact);

#ifdef __cplusplus
}
#endif

#endif /* XGO_SETTLE_H */
