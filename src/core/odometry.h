/*
 * odometry.h - where the robot is on the floor: position and heading
 * integrated from what the legs do.
 *
 * Each control tick the caller hands in the feet positions it has measured
 * (forward kinematics of the actual joint angles, put into the machine frame
 * with the body pose: x forward, y left, on the ground plane) and which feet
 * are on the ground. A foot on the ground does not move in the world, so
 * when planted feet move in the machine frame the body moved the other way:
 * the rigid motion (rotation + translation in the floor plane) that carries
 * this tick's planted feet onto their positions of the previous tick is the
 * body's own motion during the tick (a least-squares fit, 2-D Procrustes).
 * Feet that are planted at both ends of the tick take part; when fewer than
 * two are (the trot's support switch) the previous tick's motion is used for
 * that one tick. Standing still with unchanged feet adds exactly zero.
 *
 * World frame (docs/motion.md): origin = where the body was at power-up
 * (init), x forward at power-up, y left, yaw counter-clockwise seen from
 * above; nothing but xgo_odometry_init resets it (action 255 does not).
 *
 * Precision: positions accumulate in 1/256 um (int64), the heading as a
 * 32-bit binary angle, so neither drifts by rounding at low speeds.
 * Checks: none; every input value is handled (expected input).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_ODOMETRY_H
#define XGO_ODOMETRY_H

#include <stdint.h>

#include "fixed.h"
#include "xgo/board_state.h" /* xgo_odometry_t */
#include "xgo/config.h"      /* XGO_WITH_ODOMETRY */
#include "xgo/profile.h"
#include "xgo/types.h" /* xgo_vec3_t, xgo_world_pose_t */

#ifdef __cplusplus
extern "C" {
#endif

/* At the origin, heading 0, no previous feet. */
void xgo_odometry_init(xgo_odometry_t *o);

/* One tick: the feet in the machine frame (um; only x and y count); contact
 * bit leg set when that foot is on the ground. Without XGO_WITH_ODOMETRY
 * (xgo/config.h) it does nothing: the pose stays at the origin. */
#if XGO_WITH_ODOMETRY
void xgo_odometry_update(xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                         uint8_t contact);

/* Feet in the air need not be measured: the fit takes only feet planted at
 * both ends of the tick, and the others count only in the test that nothing
 * moved (every foot's x, y as last tick, no foot set down). So a caller may
 * measure only the feet in `measured` (every planted one among them) and:
 *   1. ask xgo_odometry_needs_all(o, feet_um, contact, measured); when it
 *      says 1, measure the other feet too and give those last tick's update
 *      left unmeasured (xgo_odometry_unmeasured) with xgo_odometry_set_prev;
 *   2. update with xgo_odometry_update_measured (the unmeasured feet's values
 *      are kept but never read unless given again by set_prev).
 * The result is that of xgo_odometry_update with every foot measured. */
int xgo_odometry_needs_all(const xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                           uint8_t contact, uint8_t measured);
static inline uint8_t xgo_odometry_unmeasured(const xgo_odometry_t *o)
{
    return o->prev_unmeasured;
}
void xgo_odometry_set_prev(xgo_odometry_t *o, unsigned leg, const xgo_vec3_t *foot_um);
void xgo_odometry_update_measured(xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                                  uint8_t contact, uint8_t measured);

/* bx ay - by ax as the fit computes it (a 32-bit form on a narrow core for
 * a small change of a small a): exposed for test_odometry, which checks it
 * against the 64-bit products. */
int64_t xgo_odometry_cross(int32_t bx, int32_t by, int32_t ax, int32_t ay);

/* The fit's turn of (dot, cross) as a signed binary angle: that of
 * xgo_atan2_64 (0 for cross == 0), with a 64-bit host's inline form for a
 * small turn; exposed for test_odometry, which checks the two agree. */
int32_t xgo_odometry_turn(int64_t cross, int64_t dot);
#else
static inline void xgo_odometry_update(xgo_odometry_t *o,
                                       const xgo_vec3_t feet_um[XGO_LEG_COUNT], uint8_t contact)
{
    (void)o, (void)feet_um, (void)contact;
}

static inline void xgo_odometry_update_measured(xgo_odometry_t *o,
                                                const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                                                uint8_t contact, uint8_t measured)
{
    (void)o, (void)feet_um, (void)contact, (void)measured;
}
#endif

void xgo_odometry_pose(const xgo_odometry_t *o, xgo_world_pose_t *out);

#ifdef __cplusplus
}
#endif

#endif /* XGO_ODOMETRY_H */
