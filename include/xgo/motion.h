/*
 * xgo/motion.h - the motion core: registers in, twelve servo targets out,
 * once per control tick.
 *
 * Data flow per tick (docs/motion.md):
 *   host writes (xgo_regs_take_written) -> mode + commands
 *   whole-unit: velocity -> gait -> feet; body registers + periodic motions
 *               + self-stabilisation -> body pose; or a preset action's pose
 *   leg mode:   foot registers -> feet in the leg frames
 *   servo mode: servo registers -> joint angles
 *   -> body IK -> leg IK -> joint targets -> emulated servos (rate limited)
 *   -> registers: mode 0x00, battery 0x01, joints 0x50..0x5B, action 0x3E,
 *      attitude 0x62..0x64
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_MOTION_H
#define XGO_MOTION_H

#include <stdint.h>

#include "xgo/config.h"
#include "xgo/profile.h"
#include "xgo/actions.h"
#include "xgo/gait.h"
#include "xgo/heading.h"
#include "xgo/inertial.h"
#include "xgo/kinematics.h"
#include "xgo/odometry.h"
#include "xgo/regs.h"
#include "xgo/sensors.h"
#include "xgo/servos.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Values of the mode register 0x00. */
typedef enum xgo_mode_e {
    XGO_MODE_WHOLE_UNIT = 0x00, /* gait, body pose, periodic motions */
    XGO_MODE_LEG = 0x01,        /* feet follow 0x40..0x4B */
    XGO_MODE_SERVO = 0x02,      /* joints follow 0x50..0x5B at the speed of 0x5C */
    XGO_MODE_DEBUG = 0x03,      /* after a write to 0x20: joints hold, some may be limp */
    XGO_MODE_ACTION = 0x04,     /* a preset action (0x3E) is running */
    XGO_MODE_CALIBRATION = 0x05 /* 0x04 = 1: all joints limp, 0x21 records zeros */
} xgo_mode_t;

/* Joint speed outside servo mode: the bound on how far any joint moves in one
 * tick (600 deg/s; 1200 mdeg at 500 Hz). */
#define XGO_JOINT_STEP_MAX_MDEG ((int32_t)(600000u / XGO_TICK_HZ))

typedef struct xgo_motion_s {
    const xgo_profile_t *profile;
    uint8_t mode;             /* xgo_mode_t */
    uint8_t group_mode;       /* the mode the last group write selected */
    uint8_t perform;          /* 0x03 = 1: cycle actions */
    uint8_t perform_last;     /* the action perform mode started last */
    uint8_t calibration;
    uint8_t action_id;        /* running preset action (incl. 255 reset), 0 none */
    xgo_gait_t gait;
    xgo_action_player_t actions;
    xgo_servos_t servos;
    xgo_imu_t imu;
    xgo_battery_t battery;
    xgo_vec3_t stance_um[XGO_LEG_COUNT];
    xgo_body_pose_t pose;     /* body pose used this tick (machine frame) */
    xgo_body_pose_t stand;    /* the standing pose (initial body registers) */
    int32_t servo_cmd_mdeg[XGO_SERVO_COUNT]; /* servo-mode commands */
    xgo_bam_t periodic_phase[6]; /* roll, pitch, yaw, x, y, z */
    int32_t stab_mdeg[2];     /* self-stabilisation roll, pitch correction */
    uint32_t nv_changes;      /* counts changes of non-volatile data */
    uint8_t contact;          /* bit leg: foot on the ground this tick */
    xgo_vec3_t feet_body_um[XGO_LEG_COUNT]; /* measured: FK of the actual joints,
                                               body frame (z up) */
    xgo_odometry_t odom;      /* world pose from the planted feet */
    xgo_heading_t heading;    /* turn to heading (0x3F) and its origin (0x06) */
    xgo_inertial_t inertial;  /* accelerometer and gyroscope (0x65) */
    struct {                  /* last body + leg IK solve (skipped when unchanged) */
        xgo_body_pose_t pose;
        xgo_vec3_t feet[XGO_LEG_COUNT];     /* machine frame, as asked */
        xgo_vec3_t feet_leg[XGO_LEG_COUNT]; /* the same in the leg frames */
        int32_t q_mdeg[XGO_SERVO_COUNT];
        uint8_t projected;                  /* bit leg: target was unreachable */
        uint8_t valid;
    } ik_cache;
} xgo_motion_t;

void xgo_motion_init(xgo_motion_t *m, const xgo_profile_t *profile, uint8_t battery_pct);

/* One control tick: consume host writes in regs, move, publish state to regs. */
void xgo_motion_tick(xgo_motion_t *m, xgo_regs_t *regs);

/* Write the board's state into the registers (mode, battery, joints, action,
 * attitude); xgo_motion_tick ends with it, the board calls it at init too so
 * the joints read where they are from power-up. */
void xgo_motion_publish(const xgo_motion_t *m, xgo_regs_t *r);

#ifdef __cplusplus
}
#endif

#endif /* XGO_MOTION_H */
