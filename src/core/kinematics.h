/*
 * kinematics.h - leg inverse/forward kinematics, body pose to foot
 * positions, and the byte encodings of the foot and servo registers; all in
 * integer arithmetic (fixed.h).
 *
 * Frames (spec section 3; docs/geometry.md has the drawings and the sign
 * conventions):
 *   machine frame  x forward, y left, z up; origin on the ground under the
 *                  body centre in the standing pose.
 *   body frame     the machine frame moved by the body pose: origin at the
 *                  centre of the four hip (abduction) axes.
 *   leg frame      one per leg: x forward, y left, z DOWN; origin at the
 *                  thigh (hip pitch) joint with the abduction at zero, i.e.
 *                  at (+-hip_x, +-(hip_y + abad_offset), 0) in the body frame.
 *
 * Joint angles (vendor servo convention, docs/geometry.md):
 *   x3 abduction: 0 = leg plane vertical; + moves the foot outward (away
 *                 from the body) on every leg.
 *   x2 hip pitch: 0 = thigh pointing straight down; + swings the thigh
 *                 backward (right-hand rotation about +y).
 *   x1 knee:      0 = shank at (about) a right angle to the thigh, foot
 *                 ahead of the knee; + opens (extends) the knee.
 *
 * Data flow for the gait: body pose + feet on the ground (machine frame) ->
 * xgo_body_ik -> feet in leg frames -> xgo_leg_ik -> joint angles ->
 * xgo_joints_to_bytes -> servo registers 0x50..0x5B. xgo_body_to_joints does
 * the first three steps for all four legs.
 *
 * Units: lengths in int32 micrometres (_um), angles in int32 millidegrees
 * (_mdeg). Every function accepts any input value: nothing overflows, and
 * unreachable foot targets are expected input (reported, not asserted).
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_KINEMATICS_H
#define XGO_KINEMATICS_H

#include <stdint.h>

#include "fixed.h"
#include "xgo/profile.h"
#include "xgo/types.h" /* xgo_vec3_t, xgo_body_pose_t */

#ifdef __cplusplus
extern "C" {
#endif

/* Leg IK results. */
#define XGO_IK_REACHED 0
#define XGO_IK_PROJECTED 1 /* target unreachable: angles reach the projection */

/* Foot position in the leg frame (um) -> joint angles q_mdeg[XGO_JOINT_*].
 *
 * Of the two solutions (foot below or above the thigh joint's level in the
 * leg plane) the lower one is used when it is within the limits, else the
 * upper one. Unreachable targets (outside the link lengths, closer to the
 * abduction axis than abad_offset_um, or needing a joint past its limit) are
 * projected (docs/geometry.md, "Unreachable targets"):
 *   1. the abduction that puts the target in the leg plane is clamped to the
 *      x3 limits and the target is projected orthogonally onto that plane
 *      (a target closer to the abduction axis than abad_offset_um uses the
 *      plane through its own direction);
 *   2. inside the leg plane the target is replaced by the nearest point of
 *      the region the knee and hip limits allow;
 *   3. if both solutions need a projection, the one landing nearer wins.
 * The result is always within the profile's joint limits. Targets farther
 * than about 1 m are first scaled toward the thigh joint (same direction).
 * Returns XGO_IK_REACHED or XGO_IK_PROJECTED. */
int xgo_leg_ik(const xgo_profile_t *p, xgo_leg_t leg, const xgo_vec3_t *foot_um,
               int32_t q_mdeg[XGO_JOINT_COUNT]);

/* xgo_leg_ik for the four legs (feet in their leg frames): the profile's
 * constants worked out once. Returns a bit mask of the legs whose target
 * was projected (bit n = leg index n); 0 when all reached. */
unsigned xgo_legs_ik(const xgo_profile_t *p, const xgo_vec3_t feet_leg_um[XGO_LEG_COUNT],
                     int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT]);

/* Joint angles -> foot position in the leg frame (um). Any angles (limits
 * are not applied). */
void xgo_leg_fk(const xgo_profile_t *p, xgo_leg_t leg, const int32_t q_mdeg[XGO_JOINT_COUNT],
                xgo_vec3_t *foot_um);

/* The body pose's rotation R = Rz(yaw) Ry(pitch) Rx(roll) in Q30, row
 * major: R(row, col) is rot[XGO_ROT(row, col)]. It depends on the three
 * angles only; a caller that keeps it (the motion's IK cache) spares the
 * three sines and cosines when it maps the same pose again. */
#define XGO_ROT_COUNT 9
#define XGO_ROT(row, col) (3 * (row) + (col))
void xgo_body_rotation(const xgo_body_pose_t *pose, xgo_q30_t rot[XGO_ROT_COUNT]);
/* The same for pose when rot holds the rotation of last (a pose of the
 * previous solve): with no yaw in either and the same roll (a trot with a
 * periodic pitch) the roll's sine and cosine are taken from rot, exactly
 * as xgo_body_rotation(pose) would compute them. */
void xgo_body_rotation_next(const xgo_body_pose_t *last, const xgo_body_pose_t *pose,
                            xgo_q30_t rot[XGO_ROT_COUNT]);

/* Body IK: feet in the machine frame (on the ground or anywhere) and the
 * body pose -> each foot in its leg frame. Coordinates saturate at +-2147 m.
 * feet_leg_um may be feet_machine_um (each foot is read before written). */
void xgo_body_ik(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                 const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                 xgo_vec3_t feet_leg_um[XGO_LEG_COUNT]);
/* The same with rot = xgo_body_rotation(pose) already worked out. */
void xgo_body_ik_rotated(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                         const xgo_q30_t rot[XGO_ROT_COUNT],
                         const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                         xgo_vec3_t feet_leg_um[XGO_LEG_COUNT]);

/* The inverse direction, for measuring where the feet are (odometry, the
 * live view): a foot in its leg frame -> the body frame (origin at the body
 * centre, body axes, z up); the four feet in the body frame -> the machine
 * frame under the body pose. Coordinates saturate at +-2147 m. */
void xgo_leg_to_body(const xgo_profile_t *p, xgo_leg_t leg, const xgo_vec3_t *foot_leg_um,
                     xgo_vec3_t *foot_body_um);
void xgo_body_to_machine(const xgo_body_pose_t *pose, const xgo_vec3_t body_um[XGO_LEG_COUNT],
                         xgo_vec3_t machine_um[XGO_LEG_COUNT]);
void xgo_body_to_machine_rotated(const xgo_body_pose_t *pose, const xgo_q30_t rot[XGO_ROT_COUNT],
                                 const xgo_vec3_t body_um[XGO_LEG_COUNT],
                                 xgo_vec3_t machine_um[XGO_LEG_COUNT]);
/* The same for the legs in the mask legs (bit n: leg n) only, for the
 * feet measured (odometry: the planted ones); each other leg gets the body
 * centre's position, as xgo_body_to_machine_rotated gives a foot at (0, 0,
 * 0), and its body_um is not read. */
void xgo_body_to_machine_legs(const xgo_body_pose_t *pose, const xgo_q30_t rot[XGO_ROT_COUNT], unsigned legs,
                              const xgo_vec3_t body_um[XGO_LEG_COUNT], xgo_vec3_t machine_um[XGO_LEG_COUNT]);

/* Body IK then leg IK for all four legs. Returns a bit mask of the legs
 * whose target was projected (bit n = leg index n); 0 when all reached. */
unsigned xgo_body_to_joints(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                            const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                            int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT]);

/* The nominal stance: each foot on the ground right under its thigh joint,
 * (+-hip_x, +-(hip_y + abad_offset), 0) in the machine frame. */
void xgo_stance_feet(const xgo_profile_t *p, xgo_vec3_t feet_machine_um[XGO_LEG_COUNT]);

/* Standing pose: no shift, no rotation, z = stand_height_um. */
void xgo_body_pose_stand(const xgo_profile_t *p, xgo_body_pose_t *pose);

#ifdef __cplusplus
}
#endif

#endif /* XGO_KINEMATICS_H */
