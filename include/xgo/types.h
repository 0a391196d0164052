/*
 * xgo/types.h - the value types of the core's API, one per concept: a point
 * (xgo_vec3_t), the body's pose (xgo_body_pose_t), a whole-robot pose of body
 * and feet (xgo_pose_t) and the robot's place on the floor
 * (xgo_world_pose_t). Every module and every observer uses these; there are
 * no other shapes for feet or poses.
 *
 * Units: lengths in int32 micrometres (_um), angles in int32 millidegrees
 * (_mdeg). Frames (docs/geometry.md): the machine frame has x forward, y
 * left, z up, its origin on the ground under the body centre of the standing
 * pose; each use says which frame its points are in.
 */
#ifndef XGO_TYPES_H
#define XGO_TYPES_H

#include <stdint.h>

#include "xgo/profile.h" /* XGO_LEG_COUNT */

#ifdef __cplusplus
extern "C" {
#endif

/* A point or a displacement. */
typedef struct xgo_vec3_s {
    int32_t x;
    int32_t y;
    int32_t z;
} xgo_vec3_t;

/* Body pose in the machine frame: the body centre's position (z is the
 * height of the hip axes above the ground) and its attitude, applied as
 * R = Rz(yaw) * Ry(pitch) * Rx(roll), right-hand rule about the machine axes
 * (roll + lifts the left side, pitch + lowers the nose, yaw + turns the nose
 * left). */
typedef struct xgo_body_pose_s {
    int32_t x_um;
    int32_t y_um;
    int32_t z_um;
    int32_t roll_mdeg;
    int32_t pitch_mdeg;
    int32_t yaw_mdeg;
} xgo_body_pose_t;

/* The body and the four feet (legs LF, RF, RH, LH), machine frame. Preset
 * actions use it as an offset from the standing pose and the stance feet
 * (all zero = standing; a foot's z + lifts it). */
typedef struct xgo_pose_s {
    xgo_body_pose_t body;
    xgo_vec3_t feet_um[XGO_LEG_COUNT];
} xgo_pose_t;

/* Where the robot is on the floor: origin where the body was at power-up,
 * x forward at power-up, y left, yaw counter-clockwise seen from above. */
typedef struct xgo_world_pose_s {
    int32_t x_um;
    int32_t y_um;
    int32_t yaw_mdeg; /* [-180000, 180000] */
} xgo_world_pose_t;

#ifdef __cplusplus
}
#endif

#endif /* XGO_TYPES_H */
