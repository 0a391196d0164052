/*
 * inertial.h - the accelerometer and gyroscope behind the IMU block
 * (register 0x65): what an MPU-6050-class sensor fixed to the body would read.
 *
 * Axes: the body's, x forward, y left, z up (docs/motion.md).
 *
 * Accelerometer: specific force, f = R^T (a + g z_up), where R is the body's
 * attitude (R = Rz(yaw) Ry(pitch) Rx(roll), the IMU's roll and pitch, the
 * heading of the odometry) and a the body centre's acceleration in the world:
 * the second difference, tick to tick, of its position (leg odometry for the
 * floor plane - walking, turning, skidding - plus the body pose's own shift
 * and height: actions, body registers, periodic motions). A standing, level
 * robot reads (0, 0, +1 g); nose down (positive pitch) gives x < 0, left
 * side up (positive roll) gives y > 0. 1 g = 16384 LSB (+-2 g range),
 * g = 9.80665 m/s^2.
 *
 * Gyroscope: the body's angular rate from the rate of change of the IMU's
 * roll, pitch and yaw (the Euler rates turned into body rates), so it agrees
 * with 0x62..0x64 as they change: turning left gives z > 0. 16.4 LSB = 1
 * deg/s (+-2000 deg/s range).
 *
 * Both pass a first-order low-pass of time constant 4 ticks (8 ms at 500 Hz,
 * about 20 Hz: a sensor's digital low-pass filter) and saturate at int16.
 *
 * Checks: none; every input value is handled (expected input).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_INERTIAL_H
#define XGO_INERTIAL_H

#include <stdint.h>
#include <string.h>

#include "fixed.h"
#include "xgo/board_state.h" /* xgo_inertial_t */
#include "kinematics.h" /* xgo_body_pose_t */
#include "odometry.h"
#include "xgo/config.h" /* XGO_WITH_INERTIAL */

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_ACCEL_LSB_PER_G 16384
#define XGO_GYRO_LSB_PER_10_DEG_S 164 /* 16.4 LSB per deg/s */
#define XGO_GRAVITY_UM_S2 9806650
#define XGO_INERTIAL_FILTER_SHIFT 2   /* low-pass: 1/4 of the gap per tick */

#if XGO_WITH_INERTIAL
/* A level body at rest: accel (0, 0, 16384), gyro 0. */
void xgo_inertial_init(xgo_inertial_t *s);

/* One tick. body_q8: the body centre's position in the world (x, y, z in
 * 1/256 um); heading: the body's yaw in that world frame; att_mdeg: the
 * IMU's roll, pitch, yaw. The first ticks after init see no motion. */
void xgo_inertial_tick(xgo_inertial_t *s, const int64_t body_q8[3], xgo_bam_t heading,
                       const int32_t att_mdeg[3]);
/* The same with the heading as its sine and cosine (Q30), as
 * xgo_inertial_body_position gives them. */
void xgo_inertial_tick_sc(xgo_inertial_t *s, const int64_t body_q8[3], const xgo_q30_t heading_sc[2],
                          const int32_t att_mdeg[3]);

/* Where the body centre is in the odometry's world: the machine frame's
 * position and heading plus the body pose's shift (x, y turned by the
 * heading; z the height) and yaw; the body's heading as its sine and
 * cosine (Q30; with no body yaw those of the machine's heading, computed
 * once for both). */
void xgo_inertial_body_position(const xgo_odometry_t *o, const xgo_body_pose_t *pose,
                                int64_t body_q8[3], xgo_q30_t heading_sc[2]);

/* One tick of the board's model: xgo_inertial_body_position, then
 * xgo_inertial_tick_sc with what it gave. */
void xgo_inertial_tick_body(xgo_inertial_t *s, const xgo_odometry_t *o, const xgo_body_pose_t *pose,
                            const int32_t att_mdeg[3]);

/* (a c + 2^29) >> 30 for a Q30 factor c: the model's product for its
 * large factors (exposed for test_inertial). */
int32_t xgo_inertial_mul_q30(int32_t a, xgo_q30_t c);

/* Before a tick: sin and cos (Q30) of a roll (axis 0) or pitch (axis 1) of
 * mdeg, exactly xgo_sincos(xgo_mdeg_to_bam(mdeg)), known elsewhere (the body
 * IK's rotation of the same pose): kept for that tick when its attitude
 * angle on the axis is mdeg and the kept trig is for another angle, so the
 * tick does not work them out again. */
static inline void xgo_inertial_known_trig(xgo_inertial_t *s, unsigned axis, int32_t att_mdeg,
                                           int32_t mdeg, xgo_q30_t sin_q30, xgo_q30_t cos_q30)
{
    if (mdeg == att_mdeg && s->trig_mdeg[axis] != mdeg) {
        s->trig_mdeg[axis] = mdeg;
        s->trig_q30[axis][0] = sin_q30;
        s->trig_q30[axis][1] = cos_q30;
    }
}

#else /* XGO_WITH_INERTIAL == 0 (xgo/config.h): accelerometer and gyroscope read 0 */
static inline void xgo_inertial_init(xgo_inertial_t *s)
{
    memset(s, 0, sizeof *s);
}

static inline void xgo_inertial_tick(xgo_inertial_t *s, const int64_t body_q8[3],
                                     xgo_bam_t heading, const int32_t att_mdeg[3])
{
    (void)s, (void)body_q8, (void)heading, (void)att_mdeg;
}

static inline void xgo_inertial_tick_sc(xgo_inertial_t *s, const int64_t body_q8[3],
                                        const xgo_q30_t heading_sc[2], const int32_t att_mdeg[3])
{
    (void)s, (void)body_q8, (void)heading_sc, (void)att_mdeg;
}

static inline void xgo_inertial_tick_body(xgo_inertial_t *s, const xgo_odometry_t *o,
                                          const xgo_body_pose_t *pose, const int32_t att_mdeg[3])
{
    (void)s, (void)o, (void)pose, (void)att_mdeg;
}

static inline void xgo_inertial_body_position(const xgo_odometry_t *o,
                                              const xgo_body_pose_t *pose, int64_t body_q8[3],
                                              xgo_q30_t heading_sc[2])
{
    (void)o, (void)pose;
    body_q8[0] = body_q8[1] = body_q8[2] = 0;
    heading_sc[0] = heading_sc[1] = 0;
}
#endif

#ifdef __cplusplus
}
#endif

#endif /* XGO_INERTIAL_H */
