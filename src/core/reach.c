/*
 * reach.c - the nearest body pose the legs hold (reach.h).
 */
#include "reach.h"

#include <string.h>

#include "compiler.h"
#include "kinematics.h"
#include "wide.h" /* XGO_CORE_DIV64_NATIVE: a 64-bit host */

/* A 64-bit host hands out the pose of an ended search under unchanged
 * keys, the usual tick, without saving registers (reach_held); the plain
 * tick out of line. An MCU the plain way, inline. */
#define REACH_HELD_FIRST XGO_CORE_DIV64_NATIVE

#define SCALE_ONE 8        /* the whole deviation from the standing pose */
#define STEP_START_UM 8000 /* the descent's first probes */
#define STEP_MIN_UM 1000   /* and its last */
#define JUMP 6u            /* dir: the jump by the mean miss, before the probes */
#define SHIFT_MAX_UM 30000 /* the search shifts the body at most this far */

/* Equal poses. The tick compares four keys: on a 32-bit core word by word
 * (an MCU's memcmp is a byte loop, about 70 instructions each on the M0; no
 * early exit, the usual answer is "equal"), on a 64-bit host the C
 * library's memcmp (vector compares) is cheaper. */
static int same_pose(const xgo_body_pose_t *a, const xgo_body_pose_t *b)
{
#if XGO_CORE_DIV64_NATIVE
    return memcmp(a, b, sizeof *a) == 0;
#else
    return ((uint32_t)(a->x_um ^ b->x_um) | (uint32_t)(a->y_um ^ b->y_um) | (uint32_t)(a->z_um ^ b->z_um) |
            (uint32_t)(a->roll_mdeg ^ b->roll_mdeg) | (uint32_t)(a->pitch_mdeg ^ b->pitch_mdeg) |
            (uint32_t)(a->yaw_mdeg ^ b->yaw_mdeg)) == 0u;
#endif
}

/* The search sits on the deepest stack path (reach -> leg IK -> branch ->
 * projection; docs/mcu.md): helpers with locals of their own stay out of
 * line (XGO_OWN_FRAME), so their frames are not on it. */

/* The feet stance + sign * stroke (stroke NULL: the stance) with the body
 * at pose, in the leg frames (body IK in place). */
XGO_OWN_FRAME static void feet_in_legs(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                                   const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                                   int sign, xgo_vec3_t feet[XGO_LEG_COUNT])
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg] = stance[leg];
        if (stroke != NULL) {
            feet[leg].x += sign * stroke[leg].x;
            feet[leg].y += sign * stroke[leg].y;
        }
    }
    xgo_body_ik(p, pose, feet, feet);
}

/* The feet stance + sign * stroke with the body at pose: the legs out of
 * reach, and the sum of their misses (target minus the point the projected
 * solution reaches) and of their sizes (|x| + |y| + |z|). The misses are in
 * the body frame (a leg frame with z up): the search shifts the body by them
 * in the machine frame, off by the attitude's turn (at most 22 degrees) -
 * the descent after the jump takes care of the rest. */
XGO_OWN_FRAME static unsigned check_feet(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                                     const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                                     int sign, xgo_vec3_t *miss_sum, uint32_t *total)
{
    xgo_vec3_t leg_feet[XGO_LEG_COUNT];
    unsigned mask = 0, leg;
    feet_in_legs(p, pose, stance, stroke, sign, leg_feet);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        int32_t q[XGO_JOINT_COUNT];
        xgo_vec3_t at;
        if (xgo_leg_ik(p, (xgo_leg_t)leg, &leg_feet[leg], q) != XGO_IK_REACHED) {
            int32_t mx, my, mz;
            mask |= 1u << leg;
            xgo_leg_fk(p, (xgo_leg_t)leg, q, &at);
            mx = leg_feet[leg].x - at.x;
            my = leg_feet[leg].y - at.y;
            mz = at.z - leg_feet[leg].z; /* leg frames: z down */
            miss_sum->x += mx;
            miss_sum->y += my;
            miss_sum->z += mz;
            *total += (uint32_t)(mx < 0 ? -mx : mx) + (uint32_t)(my < 0 ? -my : my) +
                      (uint32_t)(mz < 0 ? -mz : mz);
        }
    }
    return mask;
}

static unsigned count4(unsigned m)
{
    return (m & 1u) + ((m >> 1) & 1u) + ((m >> 2) & 1u) + ((m >> 3) & 1u);
}

/* The check, with the total of the misses (sum of |x| + |y| + |z|, um):
 * the stance feet, and with a stroke both ends of it. */
static unsigned check(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                      const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                      xgo_vec3_t *miss_um, uint32_t *total)
{
    xgo_vec3_t sum = {0, 0, 0};
    unsigned mask, n;
    *total = 0;
    mask = check_feet(p, pose, stance, NULL, 0, &sum, total);
    n = count4(mask);
    if (stroke != NULL) { /* and both ends: a leg holds its middle and ends, not always between */
        const unsigned fore = check_feet(p, pose, stance, stroke, 1, &sum, total);
        const unsigned aft = check_feet(p, pose, stance, stroke, -1, &sum, total);
        mask |= fore | aft;
        n += count4(fore) + count4(aft);
    }
    if (miss_um != NULL) {
        const int32_t k = n == 0 ? 1 : (int32_t)n;
        miss_um->x = sum.x / k;
        miss_um->y = sum.y / k;
        miss_um->z = sum.z / k;
    }
    return mask;
}

unsigned xgo_reach_check(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                         const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                         xgo_vec3_t *miss_um)
{
    uint32_t total;
    return check(p, pose, stance, stroke, miss_um, &total);
}

void xgo_reach_init(xgo_reach_t *s, const xgo_body_pose_t *stand)
{
    memset(s, 0, sizeof *s);
    s->stand = *stand;
    s->held = *stand;
    s->scale = SCALE_ONE;
}

/* The transform of the search: stand + (from - stand) * scale / 8, plus the
 * shift (translations). */
static void transform(const xgo_reach_t *s, const xgo_vec3_t *shift, const xgo_body_pose_t *from,
                      xgo_body_pose_t *c)
{
    const int32_t k = s->scale;
    if (k == SCALE_ONE) { /* the usual end of a search: the whole deviation, (v 8) / 8 = v */
        c->x_um = from->x_um + shift->x;
        c->y_um = from->y_um + shift->y;
        c->z_um = from->z_um + shift->z;
        c->roll_mdeg = from->roll_mdeg;
        c->pitch_mdeg = from->pitch_mdeg;
        c->yaw_mdeg = from->yaw_mdeg;
        return;
    }
    c->x_um = s->stand.x_um + (from->x_um - s->stand.x_um) * k / SCALE_ONE + shift->x;
    c->y_um = s->stand.y_um + (from->y_um - s->stand.y_um) * k / SCALE_ONE + shift->y;
    c->z_um = s->stand.z_um + (from->z_um - s->stand.z_um) * k / SCALE_ONE + shift->z;
    c->roll_mdeg = s->stand.roll_mdeg + (from->roll_mdeg - s->stand.roll_mdeg) * k / SCALE_ONE;
    c->pitch_mdeg = s->stand.pitch_mdeg + (from->pitch_mdeg - s->stand.pitch_mdeg) * k / SCALE_ONE;
    c->yaw_mdeg = s->stand.yaw_mdeg + (from->yaw_mdeg - s->stand.yaw_mdeg) * k / SCALE_ONE;
}

static int32_t *channel(xgo_body_pose_t *p, unsigned c)
{
    switch (c) {
    case 0: return &p->x_um;
    case 1: return &p->y_um;
    case 2: return &p->z_um;
    case 3: return &p->roll_mdeg;
    case 4: return &p->pitch_mdeg;
    default: return &p->yaw_mdeg;
    }
}

/* The poses a periodic motion reaches at its extremes: the key's base with
 * each periodic channel at +-spread - every corner for up to two periodic
 * channels, each channel's two ends alone for more. Returns how many there
 * are; corner i in *out. */
XGO_OWN_FRAME static unsigned corner(xgo_reach_t *s, unsigned i, xgo_body_pose_t *out)
{
    unsigned c, k = 0, n;
    unsigned idx[6];
    for (c = 0; c < 6; c++) {
        if (*channel(&s->spread, c) != 0) {
            idx[k++] = c;
        }
    }
    n = k <= 2u ? 1u << k : 2u * k;
    *out = s->key;
    for (c = 0; c < k; c++) {
        const int32_t a = *channel(&s->spread, idx[c]);
        if (k <= 2u) {
            *channel(out, idx[c]) += ((i >> c) & 1u) ? a : -a;
        } else if (i / 2u == c) {
            *channel(out, idx[c]) += (i & 1u) ? a : -a;
        }
    }
    return n;
}

static int32_t clamp_shift(int32_t v)
{
    return v > SHIFT_MAX_UM ? SHIFT_MAX_UM : (v < -SHIFT_MAX_UM ? -SHIFT_MAX_UM : v);
}

/* The probe of the descent: the shift moved by step along axis dir / 2,
 * positive for even dir. */
static xgo_vec3_t probe(const xgo_reach_t *s)
{
    xgo_vec3_t at = s->shift;
    const int32_t d = (s->dir & 1u) ? -s->step : s->step;
    if (s->dir < 2u) {
        at.x = clamp_shift(at.x + d);
    } else if (s->dir < 4u) {
        at.y = clamp_shift(at.y + d);
    } else {
        at.z = clamp_shift(at.z + d);
    }
    return at;
}

/* Next scale down (none left: the standing pose, always reachable). */
static void scale_down(xgo_reach_t *s)
{
    if (s->scale == 0) { /* the standing pose, whatever is asked: always held */
        s->found.x = s->found.y = s->found.z = 0;
        s->searching = 0;
        return;
    }
    s->scale--;
    s->step = 0; /* a new start: first the jump */
}

/* The transform with the body shifted by `shift`, at every corner of the
 * key: 1 (and the search done) when every foot holds at all of them; else
 * 0 and the misses, summed over the corners. */
static int try_shift(xgo_reach_t *s, const xgo_profile_t *p, const xgo_vec3_t stance[XGO_LEG_COUNT],
                     const xgo_vec3_t *shift, xgo_vec3_t *miss, uint32_t *total)
{
    unsigned i, n = 1, bad = 0;
    miss->x = miss->y = miss->z = 0;
    *total = 0;
    for (i = 0; i < n; i++) {
        xgo_body_pose_t c;
        xgo_vec3_t m;
        uint32_t t;
        n = corner(s, i, &c);
        transform(s, shift, &c, &c); /* field by field: in place is fine */
        if (check(p, &c, stance, s->walking ? s->stroke : NULL, &m, &t) != 0) {
            miss->x += m.x;
            miss->y += m.y;
            miss->z += m.z;
            *total += t;
            bad++;
        }
    }
    if (bad == 0) {
        s->found = *shift;
        s->searching = 0;
        return 1;
    }
    miss->x /= (int32_t)bad;
    miss->y /= (int32_t)bad;
    miss->z /= (int32_t)bad;
    return 0;
}

/* One check of the search. At each scale: the candidate with the shift so
 * far, then shifted by the mean miss (a jump), then a descent on the total
 * miss: probes of +-step along x, y, z, a probe that lowers it taken and
 * tried again, the step halved after six probes in vain, from
 * STEP_START_UM down to STEP_MIN_UM; no luck: take less of the deviation
 * from the standing pose. */
static void search_step(xgo_reach_t *s, const xgo_profile_t *p, const xgo_vec3_t stance[XGO_LEG_COUNT])
{
    xgo_vec3_t miss, at = s->shift;
    uint32_t total;
    if (s->step == 0) { /* the start at this scale */
        if (!try_shift(s, p, stance, &at, &miss, &total)) {
            s->shift.x = clamp_shift(at.x + miss.x);
            s->shift.y = clamp_shift(at.y + miss.y);
            s->shift.z = clamp_shift(at.z + miss.z);
            s->step = STEP_START_UM;
            s->dir = JUMP;
        }
        return;
    }
    if (s->dir != JUMP) {
        at = probe(s);
    }
    if (try_shift(s, p, stance, &at, &miss, &total)) {
        return;
    }
    if (s->dir == JUMP || total < s->best) { /* better: keep it, try this way again */
        s->best = total;
        s->shift = at;
        s->dir = s->dir == JUMP ? 0u : s->dir;
        return;
    }
    if (++s->dir == JUMP) {
        s->dir = 0;
        s->step /= 2;
        if (s->step < STEP_MIN_UM) {
            scale_down(s);
        }
    }
}

static int same_stroke(const xgo_reach_t *s, const xgo_vec3_t *stroke)
{
#if XGO_CORE_DIV64_NATIVE
    return stroke == NULL ? !s->walking : (s->walking && memcmp(s->stroke, stroke, sizeof s->stroke) == 0);
#else
    uint32_t diff = 0;
    unsigned leg;
    if (stroke == NULL || !s->walking) {
        return stroke == NULL && !s->walking;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) { /* word by word, as same_pose */
        diff |= (uint32_t)(s->stroke[leg].x ^ stroke[leg].x) | (uint32_t)(s->stroke[leg].y ^ stroke[leg].y) |
                (uint32_t)(s->stroke[leg].z ^ stroke[leg].z);
    }
    return diff == 0u;
#endif
}

#if REACH_HELD_FIRST
/* The usual tick: a search ended (whole deviation, scale 8) for keys equal
 * to these: out = held = now shifted by found (transform), returns 1 when
 * that is not now. Else 0, nothing touched. */
static int reach_held(xgo_reach_t *s, const xgo_body_pose_t *now, const xgo_body_pose_t *base,
                      const xgo_body_pose_t *spread, const xgo_vec3_t *stroke, xgo_body_pose_t *out,
                      int *moved)
{
    if (!s->valid || s->searching || s->scale != SCALE_ONE || !same_stroke(s, stroke) ||
        !same_pose(base, &s->key) || !same_pose(spread, &s->spread)) {
        return 0;
    }
    /* transform at the whole deviation, written out (no call) */
    s->held = *now;
    s->held.x_um += s->found.x;
    s->held.y_um += s->found.y;
    s->held.z_um += s->found.z;
    *out = s->held;
    *moved = (s->found.x | s->found.y | s->found.z) != 0; /* out differs from now exactly then */
    return 1;
}
#endif

/* xgo_reach_tick the plain way (a host: off its usual tick, out of line;
 * an MCU: the whole of it). */
#if REACH_HELD_FIRST
#define PLAIN_TICK static XGO_OWN_FRAME int
#else
#define PLAIN_TICK XGO_ALWAYS_INLINE int
#endif
PLAIN_TICK reach_tick(xgo_reach_t *s, const xgo_profile_t *p, const xgo_body_pose_t *now,
                      const xgo_body_pose_t *base, const xgo_body_pose_t *spread,
                      const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke, xgo_body_pose_t *out)
{
    if (!s->valid || !same_stroke(s, stroke) || !same_pose(base, &s->key) ||
        !same_pose(spread, &s->spread)) {
        s->key = *base;
        s->spread = *spread;
        s->walking = stroke != NULL;
        if (stroke != NULL) {
            memcpy(s->stroke, stroke, sizeof s->stroke);
        }
        s->valid = 1;
        s->searching = 1;
        s->scale = SCALE_ONE;
        s->step = 0;
        s->shift.x = s->shift.y = s->shift.z = 0;
    }
    if (s->searching) {
        search_step(s, p, stance);
    }
    if (!s->searching) {
        transform(s, &s->found, now, &s->held);
    } /* else meanwhile: the last pose handed out, which the legs held */
    *out = s->held;
    return !same_pose(out, now);
}

int xgo_reach_tick(xgo_reach_t *s, const xgo_profile_t *p, const xgo_body_pose_t *now,
                   const xgo_body_pose_t *base, const xgo_body_pose_t *spread,
                   const xgo_vec3_t stance[XGO_LEG_COUNT], const xgo_vec3_t *stroke,
                   xgo_body_pose_t *out)
{
#if REACH_HELD_FIRST
    int moved;
    if (reach_held(s, now, base, spread, stroke, out, &moved)) {
        return moved;
    }
#endif
    return reach_tick(s, p, now, base, spread, stance, stroke, out);
}
