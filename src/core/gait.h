/*
 * gait.h - the gait generator: a body velocity command in physical units
 * in, four foot positions per control tick out.
 *
 * Data flow (CHAMP's split): command -> velocity ramp -> phase generator
 * (one master phase per gait cycle, a lift-off phase per leg) -> per-leg
 * trajectory (stance: the foot moves with the ground; swing: lift, carry,
 * place) -> foot positions. Body pose and leg IK are not done here: the
 * caller (the board) adds the body pose and runs xgo_body_ik on foot_um.
 * The module knows nothing about registers; the caller decodes 0x30..0x32,
 * 0x09, 0x3C and 0x3D into an xgo_gait_command_t.
 *
 *   xgo_gait_init(&g, stance);          // standing, four feet at stance
 *   every 1/XGO_TICK_HZ s:
 *     xgo_gait_tick(&g, &cmd);          // one period
 *     use g.foot_um, g.contact, g.vx_um_s, g.vy_um_s, g.vyaw_mdeg_s
 *
 * Frames and units: the machine frame relative to the body, x forward,
 * y left, z UP, z = 0 on the ground; lengths in int32 micrometres (_um),
 * speeds in um/s, angles in millidegrees (_mdeg), yaw counter-clockwise
 * positive seen from above.
 *
 * Guarantees (docs/gait.md has the derivations and the measured numbers):
 *   - stance feet move with velocity -(v + w x p) where v, w are the values
 *     published in vx_um_s, vy_um_s, vyaw_mdeg_s: integrating those gives
 *     exactly the motion the stance feet describe (odometry);
 *   - the published velocity follows the command with bounded acceleration
 *     (XGO_GAIT_ACCEL_UM_S2, XGO_GAIT_YAW_ACCEL_MDEG_S2; a planted foot that
 *     cannot absorb a change holds it back) and equals it after the ramp
 *     everywhere inside the vendor ranges (no speed limiting there);
 *   - no foot moves more than XGO_GAIT_MAX_STEP_UM in one tick (in the trots
 *     XGO_GAIT_MAX_STEP_TROT_UM), whatever the command sequence;
 *   - planted feet stay within +-XGO_GAIT_REACH_X_UM in x and
 *     +-XGO_GAIT_REACH_Y_UM in y of their stance points, y widened by up to
 *     XGO_GAIT_YAW_REACH_Y_UM in proportion to |w| (up to 100 deg/s) while
 *     turning; a swing foot may pass that box by XGO_GAIT_SWING_OVERSHOOT_UM
 *     (it reaches a little ahead and comes back to land at the ground's
 *     speed); z from 0 to the step height;
 *   - swing feet leave and meet the ground moving like a planted foot
 *     (velocity -(v + w x p), no acceleration relative to it);
 *   - a zero command ends, within XGO_GAIT_STOP_TICKS_MAX ticks, with four
 *     feet down exactly at the stance points.
 *
 * Input policy: every command value is expected input. Out-of-range gait
 * types and paces select the defaults (trot, normal); speeds are clamped to
 * twice the vendor ranges, mark-time height to XGO_GAIT_MAX_HEIGHT_UM.
 * Pointers must not be NULL (a caller bug: XGO_ASSERT, src/core/check.h).
 *
 * Portable: C99, integer arithmetic only (fixed.h), no OS calls, no heap,
 * no globals. Cost (x86-64, the host build at -O3 with -flto, bench_board):
 * about 740 instructions a tick in bench_board's trot (a 64-bit host keeps a
 * steady tick's front stages and each swing's end tangents across ticks);
 * one sine per swing phase; 64-bit division only in rare transients
 * (docs/gait.md).
 */
#ifndef XGO_GAIT_H
#define XGO_GAIT_H

#include <stdint.h>

#include "xgo/config.h" /* XGO_TICK_HZ */
#include "xgo/board_state.h" /* xgo_gait_t */
#include "xgo/types.h"       /* xgo_vec3_t */

/* Legs 1..4 = indices 0..3: XGO_LEG_LF, _RF, _RH, _LH and XGO_LEG_COUNT, from
 * the one place legs are numbered (only the enum is used here). */
#include "xgo/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Register 0x09. */
typedef enum xgo_gait_type_e {
    XGO_GAIT_TROT = 0,
    XGO_GAIT_WALK = 1,
    XGO_GAIT_HIGH_WALK = 2,
    XGO_GAIT_SLOW_TROT = 3
} xgo_gait_type_t;
#define XGO_GAIT_TYPE_COUNT 4

/* Register 0x3D: step frequency. */
typedef enum xgo_pace_e { XGO_PACE_NORMAL = 0, XGO_PACE_SLOW = 1, XGO_PACE_HIGH = 2 } xgo_pace_t;
#define XGO_PACE_COUNT 3

/* ------------------------------------------------------------ limits */

/* Velocity ramp: produced velocity changes by at most this much per second
 * (per component): 1 mm/s and 0.5 deg/s per tick. */
#define XGO_GAIT_ACCEL_UM_S2 500000
#define XGO_GAIT_YAW_ACCEL_MDEG_S2 250000

/* Command clamps (twice the vendor ranges; speeds beyond the vendor ranges
 * may be limited, see docs/gait.md). */
#define XGO_GAIT_VX_CLAMP_UM_S 500000
#define XGO_GAIT_VY_CLAMP_UM_S 360000
#define XGO_GAIT_VYAW_CLAMP_MDEG_S 200000
#define XGO_GAIT_MAX_HEIGHT_UM 35000 /* mark-time step height clamp */

/* Half-stride budget the cadence is fitted to (per leg, around its stance
 * point); y grows with the yaw rate: 16.5 mm + 14 mm * |w| / (100 deg/s),
 * the yaw share saturating at 100 deg/s. */
#define XGO_GAIT_HALF_STRIDE_X_UM 32000
#define XGO_GAIT_HALF_STRIDE_Y_UM 16500
#define XGO_GAIT_YAW_HALF_STRIDE_Y_UM 14000
#define XGO_GAIT_YAW_REF_MDEG_S 100000

/* The workspace box feet never leave (vendor foot ranges, Mini). */
#define XGO_GAIT_REACH_X_UM 35000
#define XGO_GAIT_REACH_Y_UM 18000
#define XGO_GAIT_YAW_REACH_Y_UM 14000

/* How far a swing foot may pass the reach box: the retraction before it
 * lands at the ground's speed (and the matching lead after lift-off);
 * docs/gait.md derives 9.7 % of the step in a steady trot. */
#define XGO_GAIT_SWING_OVERSHOOT_UM 8000

/* Largest displacement of any foot in one tick (3-D, any command sequence;
 * derivation in docs/gait.md, measured maxima in test/test_gait.c): the walks
 * at their fastest cadence, and the trots (trot, slow trot, mark time). */
#define XGO_GAIT_MAX_STEP_UM 7500
#define XGO_GAIT_MAX_STEP_TROT_UM 4500

/* Ticks from a zero command (mark time off) to standing, from any state:
 * the ramp down (0.5 s from the vendor maxima, 1 s from the clamps) plus at
 * most 1.25 cycles at the slowest cadence (slow walk, 1.2 s): 2.6 s, 1300
 * ticks at 500 Hz. */
#define XGO_GAIT_STOP_TICKS_MAX (XGO_TICK_HZ * 13u / 5u)

/* ------------------------------------------------------------ types */

typedef struct xgo_gait_command_s {
    int32_t vx_um_s;      /* body velocity, machine frame, x forward, um/s */
    int32_t vy_um_s;      /* y left, um/s */
    int32_t vyaw_mdeg_s;  /* yaw rate, counter-clockwise positive, mdeg/s */
    int32_t mark_time_um; /* > 0: keep stepping (trot timing) with this swing
                             height, in place when the velocity is zero; 0 = off */
    int32_t step_height_um; /* > 0: the swing height instead of the gait's
                               (an action's creep); 0 = the gait's */
    uint8_t type;         /* xgo_gait_type_t; out of range = trot */
    uint8_t pace;         /* xgo_pace_t; out of range = normal */
} xgo_gait_command_t;

/* Standing at the stance: stance_um[leg] = nominal foot (x, y, z) in the
 * machine frame relative to the body; z is ignored (the ground is z = 0),
 * x and y are clamped to +-200 mm. */
void xgo_gait_init(xgo_gait_t *g, const xgo_vec3_t stance_um[XGO_LEG_COUNT]);

/* Advance one control period (1 / XGO_TICK_HZ s) under cmd. */
void xgo_gait_tick(xgo_gait_t *g, const xgo_gait_command_t *cmd);

/* 1 when stopped with all four feet down exactly at the stance points. */
static inline int xgo_gait_is_standing(const xgo_gait_t *g) /* inline: several times a tick */
{
    return g->standing != 0;
}

/* Nominal cycle period of a gait at a pace in ms (the cadence at low speed;
 * faster commands raise the cadence); out-of-range arguments = defaults. */
uint32_t xgo_gait_period_ms(uint8_t type, uint8_t pace);

/* Duty factor of a gait in 1/100 (trot 50, walk 75, ...). */
uint32_t xgo_gait_duty_pct(uint8_t type);

#ifdef __cplusplus
}
#endif

#endif /* XGO_GAIT_H */
