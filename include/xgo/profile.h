/*
 * xgo/profile.h - the robot models the board can drive (Mini, Lite, Mini2)
 * as data, and the one place where legs, joints, servos and registers are
 * numbered.
 *
 * A profile holds the link geometry the kinematics needs, the joint limits,
 * and the vendor library's byte ranges for the body-pose (0x33..0x38), foot
 * (0x40..0x4B) and servo (0x50..0x5B) registers. Every number and its source
 * is listed in docs/geometry.md.
 *
 * Numbering (vendor library, xgo_ros joints.yaml, the spec's register table):
 *
 *   leg index  leg no.  position      servos      foot regs    servo regs
 *   0 (LF)     1        left  front   11 12 13    0x40..0x42   0x50..0x52
 *   1 (RF)     2        right front   21 22 23    0x43..0x45   0x53..0x55
 *   2 (RH)     3        right hind    31 32 33    0x46..0x48   0x56..0x58
 *   3 (LH)     4        left  hind    41 42 43    0x49..0x4B   0x59..0x5B
 *
 *   joint index  servo  vendor name  joint
 *   0            x1     "lower"      knee
 *   1            x2     "middle"     hip pitch (thigh)
 *   2            x3     "upper"      hip roll (abduction)
 *
 * The Mini2's arm (docs/registers.md, "Mini2"): servo 51 the claw, 52 the
 * elbow, 53 the shoulder, read back at 0x5C, 0x5D, 0x5E (what the vendor
 * library's read_motor() takes as motors 13..15).
 *
 * Units: lengths in micrometres (_um), angles in millidegrees (_mdeg).
 * Checks: none fail; an unknown model code gives the Mini (documented).
 *
 * Portable: no OS calls, no heap, no globals (profiles are const data), no
 * floating point.
 */
#ifndef XGO_PROFILE_H
#define XGO_PROFILE_H

#include <stdint.h>

#include "xgo/config.h" /* XGO_WITH_LITE, XGO_WITH_MINI2 */

#ifdef __cplusplus
extern "C" {
#endif

typedef enum xgo_leg_e {
    XGO_LEG_LF = 0, /* leg 1, left front  */
    XGO_LEG_RF = 1, /* leg 2, right front */
    XGO_LEG_RH = 2, /* leg 3, right hind  */
    XGO_LEG_LH = 3, /* leg 4, left hind   */
    XGO_LEG_COUNT = 4
} xgo_leg_t;

typedef enum xgo_joint_e {
    XGO_JOINT_KNEE = 0, /* servo x1 */
    XGO_JOINT_HIP = 1,  /* servo x2, hip pitch */
    XGO_JOINT_ABAD = 2, /* servo x3, hip roll (abduction) */
    XGO_JOINT_COUNT = 3
} xgo_joint_t;

typedef enum xgo_arm_joint_e {
    XGO_ARM_CLAW = 0,     /* servo 51 */
    XGO_ARM_ELBOW = 1,    /* servo 52 */
    XGO_ARM_SHOULDER = 2, /* servo 53 */
    XGO_ARM_JOINT_COUNT = 3
} xgo_arm_joint_t;

typedef enum xgo_axis_e { XGO_AXIS_X = 0, XGO_AXIS_Y = 1, XGO_AXIS_Z = 2, XGO_AXIS_COUNT = 3 } xgo_axis_t;

/* Joints in all: index = 3 * leg + joint, register order 0x50..0x5B. */
#define XGO_SERVO_COUNT (XGO_LEG_COUNT * XGO_JOINT_COUNT)

/* Register of a foot coordinate (leg frame) and of a servo position. */
#define XGO_FOOT_REG(leg, axis) (0x40u + 3u * (unsigned)(leg) + (unsigned)(axis))
#define XGO_SERVO_REG(leg, joint) (0x50u + 3u * (unsigned)(leg) + (unsigned)(joint))
/* Servo id as the vendor names it: 11..43. */
#define XGO_SERVO_ID(leg, joint) (10u * ((unsigned)(leg) + 1u) + (unsigned)(joint) + 1u)

/* The Mini's leg links (every built-in profile's: profile.c, sources in
 * docs/geometry.md); the leg IK keeps its constants of these worked out. */
#define XGO_MINI_THIGH_UM 59900
#define XGO_MINI_SHANK_UM 75995
#define XGO_MINI_KNEE_OFFSET_MDEG 754

/* +1 for the front legs, -1 for the hind legs. Inline: the leg IK asks
 * every leg every tick, and a call cost more than the test. */
static inline int xgo_leg_side_x(xgo_leg_t leg)
{
    return (leg == XGO_LEG_LF || leg == XGO_LEG_RF) ? 1 : -1;
}

/* +1 for the left legs, -1 for the right legs. */
static inline int xgo_leg_side_y(xgo_leg_t leg)
{
    return (leg == XGO_LEG_LF || leg == XGO_LEG_LH) ? 1 : -1;
}

/* An inclusive value range [lo, hi], lo < hi, in the unit of its field. */
typedef struct xgo_range_s {
    int32_t lo;
    int32_t hi;
} xgo_range_t;

/* The Mini2's arm: a planar two-link arm on the back, in the body's x-z
 * plane, and a claw (docs/geometry.md, "Arm", has the sources: the vendor
 * library's own arm model, arm_init() and arm_pos_update()). Arm frame:
 * origin on the shoulder axis, x forward, z up (body axes). Joint angles
 * are servo angles, as the registers carry them; a joint's geometric angle
 * is its servo angle minus zero_mdeg: shoulder 0 = upper arm straight up,
 * + tilts it forward; elbow 0 = forearm at right angles to the upper arm,
 * + turns it down; claw -65 deg = open .. +65 deg = closed. */
typedef struct xgo_arm_geometry_s {
    int32_t shoulder_x_um; /* shoulder axis in the body frame (y = 0) */
    int32_t shoulder_z_um;
    int32_t upper_um;      /* shoulder axis to elbow axis */
    int32_t fore_um;       /* elbow axis to the claw point */
    /* servo angle at the joint's geometric zero, by xgo_arm_joint_t */
    int32_t zero_mdeg[XGO_ARM_JOINT_COUNT];
    /* Joint limits and the written servo bytes: 1..255 over these
     * (servo_set_angle's table), by xgo_arm_joint_t. */
    xgo_range_t joint_mdeg[XGO_ARM_JOINT_COUNT];
    /* The read-back bytes (0x5C..0x5E): 0..255 over these (read_motor's
     * MOTOR_LIMIT[3..5]); angles beyond them read as the end. */
    xgo_range_t read_mdeg[XGO_ARM_JOINT_COUNT];
    /* Command registers (vendor ARM_LIMIT): 0x73 x, 0x74 z (arm frame),
     * 0x76 theta (from straight down, 90 = forward, 180 = up), 0x77 r. */
    xgo_range_t x_um;
    xgo_range_t z_um;
    xgo_range_t theta_mdeg;
    xgo_range_t r_um;
} xgo_arm_geometry_t;

typedef struct xgo_profile_s {
    const char *name; /* "mini", "lite", "mini2" */

    /* Leg geometry (docs/geometry.md, "Leg model"). */
    int32_t thigh_um;        /* L1: hip pitch axis to knee axis */
    int32_t shank_um;        /* L2: knee axis to foot contact point */
    int32_t knee_offset_mdeg; /* angle of the shank line past the servo's
                                 90-degree mark at x1 = 0 (foot pad offset) */
    int32_t abad_offset_um;  /* d: abduction axis to the leg plane */

    /* Body: abduction axes at (+-hip_x, +-hip_y, 0) from the body centre. */
    int32_t hip_x_um;
    int32_t hip_y_um;
    int32_t length_um;       /* overall outline (informational) */
    int32_t width_um;
    int32_t stand_height_um; /* hip axes above the ground when standing */

    /* Joint limits = the byte range of the servo registers, by joint index. */
    xgo_range_t joint_mdeg[XGO_JOINT_COUNT];
    /* Foot registers 0x40..: x, y, z in the leg frame. */
    xgo_range_t foot_um[XGO_AXIS_COUNT];
    /* Body registers 0x33..0x35 (translation; z is the height) and
     * 0x36..0x38 (roll, pitch, yaw). */
    xgo_range_t body_um[XGO_AXIS_COUNT];
    xgo_range_t body_mdeg[XGO_AXIS_COUNT];
    /* Mark time 0x3C: step height of bytes 1..255 (vendor MARK_TIME_LIMIT). */
    xgo_range_t mark_time_um;
    /* The arm, NULL for a model without one (Mini, Lite). */
    const xgo_arm_geometry_t *arm;
} xgo_profile_t;

#define XGO_PROFILE_MINI 0u /* same codes as xgo_model_t */
#define XGO_PROFILE_LITE 1u
#define XGO_PROFILE_MINI2 2u

/* The Lite's and the Mini2's exist only where they are built in
 * (XGO_WITH_LITE, XGO_WITH_MINI2: xgo/config.h). */
const xgo_profile_t *xgo_profile_mini(void);
#if XGO_WITH_LITE
const xgo_profile_t *xgo_profile_lite(void);
#endif
#if XGO_WITH_MINI2
const xgo_profile_t *xgo_profile_mini2(void);
#endif

/* 1 if the model code's profile is built into this core. */
int xgo_profile_built_in(unsigned model);

/* Profile for a model code (0 Mini, 1 Lite, 2 Mini2); unknown codes and
 * models not built in give the Mini, the default. Never NULL. */
const xgo_profile_t *xgo_profile_get(unsigned model);

#ifdef __cplusplus
}
#endif

#endif /* XGO_PROFILE_H */
