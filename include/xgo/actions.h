/*
 * xgo/actions.h - the preset actions of register 0x3E (lie down, sit, wave,
 * shake hands, ...) as keyframe tables played back in fixed point.
 *
 * An action is a const table of keyframes (docs/actions.md has the format).
 * A keyframe is a *pose* - body translation and attitude plus a foot offset
 * per leg - not joint angles, so an action goes through the same body/leg
 * IK as walking (xgo/kinematics.h). The player interpolates between
 * keyframes every control tick with a monotone cubic Hermite curve in
 * integer arithmetic: the pose starts and ends at rest, passes through
 * every keyframe exactly, has a continuous velocity and never overshoots a
 * keyframe (a keyframe that is a turning point of a channel is reached with
 * zero velocity, like an ease-in/ease-out).
 *
 * Timing contract (1 tick = 1 / XGO_TICK_HZ s = 2 ms, N =
 * xgo_action_duration_ticks(id) = the vendor library's wait in seconds x 500):
 *   after xgo_action_start(), ticks 1 .. N-1 return 1 and write the pose at
 *   that time; tick N returns 0 and writes the zero pose (the stance, which
 *   is also the action's last keyframe); xgo_action_running() reports the id
 *   from the start until tick N, 0 from then on. So register 0x3E reads the
 *   action for exactly N ticks and the pose is back in the stance exactly
 *   when the vendor library stops waiting.
 *
 * Every action starts from the zero pose (the board brings the dog to the
 * stance first), ends in it, and stays inside the Mini's body ranges and
 * joint limits (test/test_actions.c checks every tick of every action).
 *
 * Bad input is expected input: unknown ids are reported (0 / NULL), never
 * asserted. Portable: C99, no floating point, no heap, no globals except
 * const tables, no OS calls.
 */
#ifndef XGO_ACTIONS_H
#define XGO_ACTIONS_H

#include <stdint.h>

#include "xgo/types.h" /* xgo_pose_t: an action's pose is an offset from the standing pose */

#ifdef __cplusplus
extern "C" {
#endif

/* Action ids (register 0x3E). 1..19 are the spec's list; 20..24 are our
 * own motions, named after the XGO family's action lists (the Mini's
 * protocol document has no names for them; docs/actions.md); 255 is the
 * reset (1 s in the stance). */
#define XGO_ACTION_NONE 0u
#define XGO_ACTION_LIE_DOWN 1u
#define XGO_ACTION_STAND_UP 2u
#define XGO_ACTION_CREEP 3u
#define XGO_ACTION_CIRCLE 4u
#define XGO_ACTION_STEP 5u
#define XGO_ACTION_SQUAT 6u
#define XGO_ACTION_ROLL 7u
#define XGO_ACTION_PITCH 8u
#define XGO_ACTION_YAW 9u
#define XGO_ACTION_THREE_AXIS 10u
#define XGO_ACTION_PEE 11u
#define XGO_ACTION_SIT 12u
#define XGO_ACTION_BECKON 13u
#define XGO_ACTION_STRETCH 14u
#define XGO_ACTION_WAVE 15u
#define XGO_ACTION_SWAY 16u
#define XGO_ACTION_BEG 17u
#define XGO_ACTION_SEARCH 18u
#define XGO_ACTION_SHAKE_HANDS 19u
#define XGO_ACTION_CHICKEN_HEAD 20u
#define XGO_ACTION_PUSH_UP 21u
#define XGO_ACTION_LOOK_AROUND 22u
#define XGO_ACTION_DANCE 23u
#define XGO_ACTION_NAUGHTY 24u
#define XGO_ACTION_LAST 24u  /* highest preset id */
#define XGO_ACTION_RESET 255u

/* Player state: which action, and where in it. Small and plain: copy it,
 * zero it, keep one per board. Read it only through the functions below. */
typedef struct xgo_action_player_s {
    uint8_t id;    /* running action, 0 = none */
    uint16_t seg;  /* segment (keyframe interval) being played */
    uint16_t tick; /* ticks into that segment */
} xgo_action_player_t;

/* Idle player. */
void xgo_action_init(xgo_action_player_t *p);

/* Start action id from its beginning. Returns 1 if id has a table (1..24,
 * 255); otherwise returns 0 and nothing changes (a running action keeps
 * running). Starting while an action runs (the same one included) restarts
 * with the new one at its first tick: the new action begins at the stance,
 * so bringing the robot there first is the caller's job. */
int xgo_action_start(xgo_action_player_t *p, uint8_t id);

/* Stop at once; the next tick returns 0 with the zero pose. */
void xgo_action_stop(xgo_action_player_t *p);

/* Advance one tick and write the pose at the new time to *out. Returns 1
 * while the action is running, 0 when it finished with this tick or none
 * runs (then *out is the zero pose). See the timing contract above. */
int xgo_action_tick(xgo_action_player_t *p, xgo_pose_t *out);

/* The running action's id, 0 when none (what register 0x3E reads). */
uint8_t xgo_action_running(const xgo_action_player_t *p);

/* Length of action id in ticks (vendor seconds x XGO_TICK_HZ); 0 for an id
 * without a table. */
uint32_t xgo_action_duration_ticks(uint8_t id);

/* English name ("lie down", ..., "reset"); NULL for an id without a table. */
const char *xgo_action_name(uint8_t id);

/* Perform mode (register 0x03 = 1): the action to play after id. The cycle
 * is 3, 4, ..., 24, 3, ...: every preset except the two posture changes
 * (1 lie down, 2 stand up). Any id outside the cycle (0, 1, 2, 255, unknown)
 * gives its first action, 3. */
uint8_t xgo_action_next_in_cycle(uint8_t id);

#ifdef __cplusplus
}
#endif

#endif /* XGO_ACTIONS_H */
