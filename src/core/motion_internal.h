/*
 * motion_internal.h - what the motion core's files share (private to
 * motion.c, motion_writes.c, motion_pose.c; docs/motion.md).
 */
#ifndef XGO_MOTION_INTERNAL_H
#define XGO_MOTION_INTERNAL_H

#include "compiler.h" /* XGO_OWN_FRAME: functions whose locals are dead while the tick
                        * goes deep (reach search, leg IK) stay out of its frame */
#include "motion.h"

/* The host's writes since the last tick, in the documented order (a reset
 * comes last, so it wins). */
void xgo_motion_take_writes(xgo_motion_t *m, xgo_regs_t *r);

/* Start a transition from where the robot is (was_mode: the mode it was in):
 * the feet on their way home to the stance, the gait waiting there
 * (settle.h); a body that was walking coasts to rest. */
void xgo_motion_begin_settle(xgo_motion_t *m, uint8_t was_mode);

/* The body pose the whole-unit registers ask for this tick: 0x33..0x38 with
 * the periodic motions (advancing their phases) and self-stabilisation.
 * base: the same with the periodic channels at their middle; spread: their
 * amplitudes, 0 elsewhere (reach.h). */
void xgo_motion_asked_pose(xgo_motion_t *m, const xgo_regs_t *r, xgo_body_pose_t *pose,
                           xgo_body_pose_t *base, xgo_body_pose_t *spread);

/* The gait command of 0x30..0x32, 0x3C, 0x09, 0x3D. */
void xgo_motion_gait_command(xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd);

/* Walking under cmd, how far each planted foot runs from its stance point
 * either way (for reach.h); 0 (stroke untouched) for a command that stands. */
int xgo_motion_stroke(const xgo_motion_t *m, const xgo_gait_command_t *cmd,
                      xgo_vec3_t stroke[XGO_LEG_COUNT]);

#endif /* XGO_MOTION_INTERNAL_H */
