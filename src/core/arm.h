/*
 * arm.h - the Mini2's arm and claw (private to the core): kinematics of the
 * planar two-link arm, its servos, and its registers.
 *
 * Kinematics (geometry and angle conventions in xgo/profile.h,
 * xgo_arm_geometry_t; docs/geometry.md, "Arm"): with s, e the shoulder's and
 * the elbow's geometric angles (servo angle minus its zero), the claw point
 * in the arm frame (origin on the shoulder axis, x forward, z up) is
 *
 *   P = L1 (sin s, cos s) + L2 (cos b, -sin b),  b = s + e
 *
 * (the vendor library's arm_pos_update). The inverse takes the solution with
 * the elbow bent up when it is within the joint limits, else the other; a
 * point out of reach (too far, or past a limit) is replaced by the nearest
 * of the points the limits allow that it tries (both joints clamped; a joint
 * at a limit with the other aimed at the target) - XGO_ARM_PROJECTED.
 *
 * Checks: none - every input is expected (out-of-reach points are projected,
 * any angle is accepted by the FK).
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_CORE_ARM_H
#define XGO_CORE_ARM_H

#include <stdint.h>
#include <string.h>

#include "regfile.h"
#include "xgo/board_state.h" /* xgo_arm_t */
#include "xgo/config.h"      /* XGO_WITH_MINI2 */
#include "xgo/profile.h"
#include "xgo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#if XGO_WITH_MINI2
#define XGO_ARM_REACHED 0
#define XGO_ARM_PROJECTED 1

/* Claw point (um, arm frame) of joint angles q (mdeg, by xgo_arm_joint_t;
 * the claw's own angle is not used). Any angles. */
void xgo_arm_fk(const xgo_arm_geometry_t *g, const int32_t q_mdeg[XGO_ARM_JOINT_COUNT],
                int32_t *x_um, int32_t *z_um);

/* The elbow axis and the claw point (um, arm frame) of joint angles q. */
void xgo_arm_points(const xgo_arm_geometry_t *g, const int32_t q_mdeg[XGO_ARM_JOINT_COUNT],
                    int32_t *elbow_x, int32_t *elbow_z, int32_t *claw_x, int32_t *claw_z);

/* Elbow and shoulder (q[XGO_ARM_ELBOW], q[XGO_ARM_SHOULDER]) that put the
 * claw point at (x, z); the claw entry is left alone. Returns
 * XGO_ARM_REACHED, or XGO_ARM_PROJECTED with the angles of the nearest
 * point found (always within the limits). Any input. */
int xgo_arm_ik(const xgo_arm_geometry_t *g, int32_t x_um, int32_t z_um,
               int32_t q_mdeg[XGO_ARM_JOINT_COUNT]);

/* The polar command (0x76 theta from straight down, 0x77 r) as a point. */
void xgo_arm_polar_point(int32_t theta_mdeg, int32_t r_um, int32_t *x_um, int32_t *z_um);

/* At rest: every servo at 0 (upper arm about upright, forearm about level,
 * claw half closed), targets the same. geo may be NULL (then nothing ever
 * moves). */
void xgo_arm_init(xgo_arm_t *a, const xgo_arm_geometry_t *geo);

/* Action 255: back to rest. */
void xgo_arm_reset(xgo_arm_t *a);

/* One control tick: the host's arm writes (0x71..0x77, 0x5D, 0x5E), the
 * hold mode (0x72 = 1: the commanded point stays put in the machine frame
 * while the body moves, as far as the arm reaches - x, z and pitch, the
 * arm being planar), then the servos move toward their targets at the speed
 * of 0x75. pose: the body pose this tick; stand: the standing pose. */
void xgo_arm_tick(xgo_arm_t *a, xgo_regs_t *r, const xgo_body_pose_t *pose,
                  const xgo_body_pose_t *stand);

/* Where the arm servos are, into the registers the library reads them from:
 * 0x5C claw, 0x5D elbow, 0x5E shoulder (read_motor's bytes: read_mdeg). */
void xgo_arm_publish(const xgo_arm_t *a, xgo_regs_t *r);
#else /* XGO_WITH_MINI2 == 0: no model has an arm; the board's calls do nothing */
static inline void xgo_arm_init(xgo_arm_t *a, const xgo_arm_geometry_t *geo)
{
    (void)geo;
    memset(a, 0, sizeof *a);
}

static inline void xgo_arm_reset(xgo_arm_t *a)
{
    (void)a;
}

static inline void xgo_arm_tick(xgo_arm_t *a, xgo_regs_t *r, const xgo_body_pose_t *pose,
                                const xgo_body_pose_t *stand)
{
    (void)a, (void)r, (void)pose, (void)stand;
}

static inline void xgo_arm_publish(const xgo_arm_t *a, xgo_regs_t *r)
{
    (void)a, (void)r;
}

static inline void xgo_arm_points(const xgo_arm_geometry_t *g,
                                  const int32_t q_mdeg[XGO_ARM_JOINT_COUNT], int32_t *elbow_x,
                                  int32_t *elbow_z, int32_t *claw_x, int32_t *claw_z)
{
    (void)g, (void)q_mdeg;
    *elbow_x = *elbow_z = *claw_x = *claw_z = 0;
}
#endif

#ifdef __cplusplus
}
#endif

#endif /* XGO_CORE_ARM_H */
