/*
 * servos.h - the twelve emulated serial-bus servos.
 *
 * Each joint moves from its current angle toward its target by at most a
 * given step per control tick (the servo's speed), never past the profile's
 * joint limits. Unloaded joints are limp: they hold the angle they have and
 * ignore targets; reloading one makes it hold where it is (no jump).
 * Zero offsets are what "set zero" (0x21) records in calibration: the raw
 * servo position that corresponds to 0 deg. The emulated joints are ideal, so
 * offsets only change xgo_servos_raw(), which a tool or a real-hardware port
 * would send to the servos; they are the board's non-volatile data.
 *
 * Joint order everywhere: index = 3 * leg + joint (profile.h), i.e. register
 * order 0x50..0x5B. Angles in millidegrees.
 * Checks: targets and steps of any value are clamped (expected); a joint
 * index past 11 for xgo_servos_raw is a caller bug (XGO_ASSERT; released:
 * 0).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_SERVOS_H
#define XGO_SERVOS_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_servos_t */
#include "xgo/profile.h"

#ifdef __cplusplus
extern "C" {
#endif


/* All joints loaded at `initial` (clamped to the limits), no offsets. */
void xgo_servos_init(xgo_servos_t *s, const xgo_profile_t *profile,
                     const int32_t initial_mdeg[XGO_SERVO_COUNT]);

/* New targets for every loaded joint, clamped to the joint limits. */
void xgo_servos_set_targets(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT]);

/* Move every loaded joint toward its target by at most max_step_mdeg. */
void xgo_servos_tick(xgo_servos_t *s, int32_t max_step_mdeg);

/* Both in one pass: xgo_servos_set_targets, then xgo_servos_tick (the
 * control tick's form). Returns 1 when every joint is now exactly at
 * target_mdeg (none limited, none short of it), 0 when one is not, so the
 * caller need not compare the twelve angles (exact on every core). */
int xgo_servos_follow(xgo_servos_t *s, const int32_t target_mdeg[XGO_SERVO_COUNT], int32_t max_step_mdeg);

/* Unload / load the joints in mask (bit i = joint i). Loading a joint sets
 * its target to where it is. */
void xgo_servos_unload(xgo_servos_t *s, uint16_t mask);
void xgo_servos_load(xgo_servos_t *s, uint16_t mask);

/* Record the current position as the zero position (set-zero in
 * calibration): each offset grows by the current angle, which becomes 0. */
void xgo_servos_record_zero(xgo_servos_t *s);

/* Raw position a real servo would be sent: angle + zero offset. */
int32_t xgo_servos_raw(const xgo_servos_t *s, unsigned joint);

/* Mask of the three joints of a leg (0..3). */
#define XGO_SERVO_LEG_MASK(leg) ((uint16_t)(0x7u << (3u * (unsigned)(leg))))
#define XGO_SERVO_ALL_MASK ((uint16_t)0x0FFFu)

#ifdef __cplusplus
}
#endif

#endif /* XGO_SERVOS_H */
