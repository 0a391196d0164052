/*
 * actions.h - the preset actions of register 0x3E (lie down, sit, wave,
 * shake hands, ...) as keyframe tables played back in fixed point.
 *
 * An action is a const table of keyframes (docs/actions.md has the format).
 * A keyframe is a *pose* - body translation and attitude plus a foot offset
 * per leg - not joint angles, so an action goes through the same body/leg
 * IK as walking (kinematics.h). The player interpolates between
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

#include "xgo/board_state.h" /* xgo_action_player_t */
#include "xgo/regs.h"        /* the action ids XGO_ACTION_*, xgo_action_name */
#include "xgo/types.h"       /* xgo_pose_t: an action's pose is an offset from the standing pose */

#ifdef __cplusplus
extern "C" {
#endif

/* Idle player. */
void xgo_action_init(xgo_action_player_t *p);

/* Start action id from its beginning. Returns 1 if id has a table (1..24,
 * 255); otherwise returns 0 and nothing changes (a running action keeps
 * running). Starting while an action runs (the same one included) restarts
 * with the new one at its first tick: the new action begins at the stance,
 * so bringing the robot there first is the caller's job. */
int xgo_action_start(xgo_action_player_t *p, uint8_t id);

/* Lead-in (issue 9): right after xgo_action_start, tell the player that the
 * board first brings the robot to the stance. Until xgo_action_go, ticks
 * return 1 with the zero pose (the action is running: 0x3E reads its id) and
 * count toward its N ticks; from xgo_action_go on, the whole keyframe
 * sequence plays in the ticks that are left, time-scaled, so the action
 * still ends at tick N. Without a hold (or a go at once) the timing is
 * exactly that of xgo_action_start alone. */
void xgo_action_hold(xgo_action_player_t *p);
void xgo_action_go(xgo_action_player_t *p);
/* 1 while held in the lead-in. */
int xgo_action_held(const xgo_action_player_t *p);

/* The command of an action that walks (creep, circle): velocity in um/s and
 * mdeg/s, swing height, gait type and pace (registers 0x09, 0x3D values). */
typedef struct xgo_action_walk_s {
    int32_t vx_um_s, vy_um_s, vyaw_mdeg_s;
    int32_t step_height_um; /* the swing height, 0 = the gait's */
    uint8_t type, pace;
} xgo_action_walk_t;

/* 1 if the running action walks: its feet come from the gait, its
 * keyframes give only the body (and the player's feet offsets are zero);
 * then *w is the gait's command at the keyframe time of the last tick -
 * zero before and after its walking window and during a lead-in. 0 (and a
 * zero command) for every other action. */
int xgo_action_walk(const xgo_action_player_t *p, xgo_action_walk_t *w);

/* Stop at once; the next tick returns 0 with the zero pose. */
void xgo_action_stop(xgo_action_player_t *p);

/* Advance one tick and write the pose at the new time to *out. Returns 1
 * while the action is running, 0 when it finished with this tick or none
 * runs (then *out is the zero pose). See the timing contract above. */
int xgo_action_tick(xgo_action_player_t *p, xgo_pose_t *out);

/* The running action's id, 0 when none (what register 0x3E reads). */
uint8_t xgo_action_running(const xgo_action_player_t *p);

/* Perform mode (register 0x03 = 1): the action to play after id. The cycle
 * is 3, 4, ..., 24, 3, ...: every preset except the two posture changes
 * (1 lie down, 2 stand up). Any id outside the cycle (0, 1, 2, 255, unknown)
 * gives its first action, 3. */
uint8_t xgo_action_next_in_cycle(uint8_t id);

#ifdef __cplusplus
}
#endif

#endif /* XGO_ACTIONS_H */
