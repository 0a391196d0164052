/*
 * motion.h - the motion core: registers in, twelve servo targets out,
 * once per control tick (private to the core; the board drives it).
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
 * Checks: register values are expected input (the register file has
 * validated every write); a value the file should have refused is a bug
 * (XGO_ASSERT).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_MOTION_H
#define XGO_MOTION_H

#include <stdint.h>

#include "actions.h"
#include "arm.h"
#include "gait.h"
#include "heading.h"
#include "inertial.h"
#include "kinematics.h"
#include "odometry.h"
#include "regfile.h"
#include "sensors.h"
#include "servos.h"
#include "xgo/board_state.h" /* xgo_motion_t */
#include "xgo/config.h"
#include "xgo/profile.h"
#include "xgo/regs.h" /* xgo_mode_t */

#ifdef __cplusplus
extern "C" {
#endif

/* Joint speed outside servo mode: the bound on how far any joint moves in one
 * tick (600 deg/s; 1200 mdeg at 500 Hz). */
#define XGO_JOINT_STEP_MAX_MDEG ((int32_t)(600000u / XGO_TICK_HZ))

void xgo_motion_init(xgo_motion_t *m, const xgo_profile_t *profile, uint8_t battery_pct);

/* The registers whose initial value depends on the profile: the foot z
 * registers start at the standing height (Mini 0x90 = 97.6 mm; the table's
 * 0x80 is 95.1 mm by the vendor's formula), so leg mode entered from
 * standing keeps the stance (docs/motion.md). The board calls it at init;
 * action 255 restores them with the rest. */
void xgo_motion_init_registers(const xgo_motion_t *m, xgo_regs_t *r);

/* One control tick: consume host writes in regs, move, publish state to regs. */
void xgo_motion_tick(xgo_motion_t *m, xgo_regs_t *regs);

/* Write the board's state into the registers (mode, battery,
 * action, perform, turn to); xgo_motion_tick ends with it, the board calls
 * it at init too. The joints (0x50..0x5B) and the IMU's registers
 * (0x62..0x68) are not among them: a read forms them from the servos'
 * angles and the IMU's outputs (board.c), which only a tick changes. */
void xgo_motion_publish(const xgo_motion_t *m, xgo_regs_t *r);

/* Where the feet are, body frame (z up): the FK of the joints as they are
 * after the last tick (xgo_board_feet_um). */
void xgo_motion_feet_body(const xgo_motion_t *m, xgo_vec3_t out[XGO_LEG_COUNT]);

#ifdef __cplusplus
}
#endif

#endif /* XGO_MOTION_H */
