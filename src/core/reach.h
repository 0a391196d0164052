/*
 * reach.h - the body pose the legs can actually hold (issue 9 part 2).
 *
 * At the vendor's ranges (pitch +-22, roll +-20, yaw +-16 degrees, with the
 * height and shift registers) the legs cannot always reach the ground:
 * standing at pitch -22 the hind hips hit their limit; walking, the stance
 * feet at the back of their stroke cannot be reached over a wide part of
 * the range. The IK would then project the feet (xgo_leg_ik returns
 * XGO_IK_PROJECTED) and the body would not be where it is said to be.
 *
 * Here the pose asked for is turned into the nearest pose the legs hold
 * with all four feet on the ground:
 *   1. the pose itself, if every foot is reachable;
 *   2. else the same attitude with the body shifted (x, y) and raised or
 *      lowered (z) - the way a dog leans back to lift its chest - by up to
 *      30 mm;
 *   3. else the deviation from the standing pose scaled down, all six
 *      channels together, in steps of 1/8 (each with its corrections),
 *      down to the standing pose, which is always reachable.
 * The shifts: first a jump by the mean of how far the feet out of reach
 * miss their targets, then a descent on the total miss (probes of +-8 mm
 * along x, y, z, halved down to 1 mm).
 * The feet checked are the stance feet, and when walking also the two ends
 * of their stance stroke (the caller says how far each planted foot runs
 * either way): the reachable region is not convex (near the hip a leg must
 * fold more than its knee allows), so the middle is checked as well.
 *
 * A periodic motion (0x39..0x3B, 0x80..0x82) moves the pose every tick: the
 * search is for its extremes (every corner of up to two periodic channels;
 * each channel's two ends for more), so the scale and shift found hold all
 * along it and are applied to the pose of each tick.
 *
 * Cost: one check is a body IK plus 4 (standing) or 12 (walking) leg IK, and
 * a FK for each foot out of reach; times the periodic extremes (2 or 4). The
 * result is cached for the pose asked (periodic channels at their middle),
 * the amplitudes and the stroke: a robot holding a pose or running a
 * periodic motion pays a few compares per tick. When the key changes, the
 * first check runs at once (a pose that holds costs that one check); a
 * search beyond it does one check per tick, meanwhile handing out the last
 * pose handed out (the body follows its target smoothly anyway, follow.h).
 * Checks: none; every input value is handled.
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_REACH_H
#define XGO_REACH_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_reach_t */
#include "xgo/profile.h"
#include "xgo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Nothing searched yet; stand is the standing pose (always reachable). */
void xgo_reach_init(xgo_reach_t *s, const xgo_body_pose_t *stand);

/* The pose the legs hold for `now`, the pose asked this tick (out). base:
 * now with each periodic motion's channel at its middle, spread: those
 * channels' amplitudes (0 elsewhere) - the search covers the motion's
 * extremes, so the pose found holds all along it, and searches only when
 * base, spread or stroke change. stroke: NULL standing; walking, how far
 * each planted foot runs from its stance point either way (x, y; the feet
 * at stance, stance + stroke and stance - stroke are checked). The result is
 * stand + (now - stand) * scale + shift, the scale and shift found for the
 * key. Returns 1 when out differs from now (clamped, or still searching). */
int xgo_reach_tick(xgo_reach_t *s, const xgo_profile_t *p, const xgo_body_pose_t *now,
                   const xgo_body_pose_t *base, const xgo_body_pose_t *spread,
                   const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                   xgo_body_pose_t *out);

/* One check: 0 if every foot is reachable with the body at pose; else the
 * mask of legs out of reach, and in miss_um (if not NULL) the mean of how
 * far they miss (target minus reached, body frame). */
unsigned xgo_reach_check(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                         const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                         xgo_vec3_t *miss_um);

#ifdef __cplusplus
}
#endif

#endif /* XGO_REACH_H */
