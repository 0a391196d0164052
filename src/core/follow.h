/*
 * follow.h - the body pose follows its target along a smooth path at rates
 * the servos keep up with (issue 9, docs/motion.md "Transitions").
 *
 * A body register written in one jump (the vendor library's
 * attitude('r', 20) does that), a reset, the end of an action: the pose the
 * registers ask for jumps, and if the joint targets jumped with it the
 * rate-limited servos would lag and the planted feet skid. Instead each of
 * the six channels (x, y, z, roll, pitch, yaw) moves toward its target with
 * a bounded speed and a bounded acceleration, braking in time to stop on it
 * (a trapezoid velocity profile): translations 150 mm/s and 1.5 m/s^2,
 * attitude 120 deg/s and 1000 deg/s^2. A target that itself moves within
 * those bounds (periodic motions, self-levelling, a host sweeping a
 * register) is followed exactly once caught: the output equals the target.
 * The planted feet stay put whatever the body does (body IK keeps them
 * fixed in the machine frame), so only the joints' speed matters.
 *
 * Positions in 1/256 um or mdeg, velocities per tick. Per tick: compares
 * only, when following exactly; one 64-bit square root per channel on its
 * way. Checks: none (every input value is handled).
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_FOLLOW_H
#define XGO_FOLLOW_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_follow_t */
#include "xgo/config.h"      /* XGO_TICK_HZ */
#include "xgo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_FOLLOW_SPEED_UM_S 150000    /* translations */
#define XGO_FOLLOW_ACCEL_UM_S2 1500000
#define XGO_FOLLOW_SPEED_MDEG_S 120000  /* attitude */
#define XGO_FOLLOW_ACCEL_MDEG_S2 1000000

/* At rest at pose. */
void xgo_follow_init(xgo_follow_t *f, const xgo_body_pose_t *pose);

/* Someone else moved the body to pose this tick (an action's keyframes):
 * take it, with the velocity of the move since the last tick. */
void xgo_follow_take(xgo_follow_t *f, const xgo_body_pose_t *pose);

/* One tick toward target; writes the pose reached. */
void xgo_follow_tick(xgo_follow_t *f, const xgo_body_pose_t *target, xgo_body_pose_t *out);

/* 1 when at rest exactly at pose. */
int xgo_follow_at(const xgo_follow_t *f, const xgo_body_pose_t *pose);

/* The pose now (rounded to whole um / mdeg). */
void xgo_follow_pose(const xgo_follow_t *f, xgo_body_pose_t *out);

/* Move the pose by dz (um) without moving anything else (a new ground
 * level: the lowest foot becomes the ground). */
void xgo_follow_shift_z(xgo_follow_t *f, int32_t dz_um);

#ifdef __cplusplus
}
#endif

#endif /* XGO_FOLLOW_H */
