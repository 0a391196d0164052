/*
 * Leg odometry: the body's motion on the floor from its planted feet
 * (see odometry.h for the model and the frame).
 */
#include "odometry.h"

#include <string.h>

#include "wide.h"

#if XGO_CORE_DIV64_NATIVE && XGO_WITH_ODOMETRY
/* the atan2 machinery inline for turn_of's usual case (fixed.h's bodies) */
#define XGO_FIXED_BODIES
#define XGO_FIXED_INLINE
#include "fixed.h"
#endif

void xgo_odometry_init(xgo_odometry_t *o)
{
    memset(o, 0, sizeof *o);
#if XGO_WITH_ODOMETRY /* the inertial model needs it too */
    xgo_sincos(o->yaw, &o->yaw_sc[0], &o->yaw_sc[1]);
#endif
}

#if XGO_WITH_ODOMETRY /* else the pose stays at the origin (odometry.h) */
static int64_t round_shift64(int64_t v, unsigned n)
{
    return (v + ((int64_t)1 << (n - 1))) >> n;
}

/* round_shift64(a x - b y, k) for Q30 a, b and 21 <= k <= 30: one
 * coordinate of a turned point. On a Cortex-M0, for |x|, |y| < 2^19 (a
 * tick's step, a trot's planted pair's sums: nearly always), from the
 * factors' 10-bit pieces, a = a2 2^20 + a1 2^10 + a0 (a2 = a >> 20, a1, a0
 * in 0..1023): with S = a x - b y, floor(S / 2^20) = (a2 x - b2 y) +
 * floor(((a1 x - b1 y) + floor((a0 x - b0 y) / 2^10)) / 2^10), every term
 * within int32, and floor((S + 2^(k-1)) / 2^k) = floor((floor(S / 2^20) +
 * 2^(k-21)) / 2^(k-20)): exact, six MULS instead of two wide products.
 * Elsewhere the wide products. test_odometry (_narrow) checks it. The
 * range tests are (v >> k) == (v >> 31), i.e. -2^k <= v < 2^k: two shifts,
 * no constants to load on the M0. */
XGO_ALWAYS_INLINE int64_t turn_round(xgo_q30_t a, int32_t x, xgo_q30_t b, int32_t y, unsigned k)
{
#if XGO_CORE_NARROW_CPU
    if ((x >> 19) == (x >> 31) && (y >> 19) == (y >> 31)) {
        int32_t u = (x * (a & 1023) - y * (b & 1023)) >> 10;
        u = (x * ((a >> 10) & 1023) - y * ((b >> 10) & 1023) + u) >> 10;
        return (x * (a >> 20) - y * (b >> 20) + u + (1 << (k - 21u))) >> (k - 20u);
    }
#endif
    return round_shift64(xgo_mul_wide(a, x) - xgo_mul_wide(b, y), k);
}

/* xgo_sat32(v) inline for the value that fits (a tick's translation:
 * always), the call only beyond: twice a walking tick. */
XGO_ALWAYS_INLINE int32_t sat32_fit(int64_t v)
{
    const int32_t lo = (int32_t)(uint32_t)(uint64_t)v;
    return (int64_t)lo == v ? lo : xgo_sat32(v);
}

/* v / n for the support sizes 2..4, without a library division on cores
 * that have none (3: multiply by 2^32 / 3, error below 1e-9 relative). */
static int32_t div_small(int32_t v, unsigned n)
{
    /* 2, 4: floor((v + 2^(k-1)) / 2^k) in 32 bits (no 64-bit sum; exact
     * for every v): floor(v / 2^k) plus one when v's low k bits reach
     * half. */
    switch (n) {
    case 2:
        return (v >> 1) + (v & 1);
    case 3:
        return (int32_t)round_shift64(xgo_mul_wide(v, 1431655765), 32);
    default:
        return (v >> 2) + ((v & 3) >= 2 ? 1 : 0);
    }
}

/* bx ay - by ax, exactly. On a narrow core, when b is a small change of a
 * (planted feet from one tick to the next: |b - a| < 2^11 um) and |a| <
 * 2^19 (a planted pair's spread: always), as (bx - ax) ay - (by - ay) ax:
 * the ax ay terms cancel, each product is within +-2^30 and their
 * difference within int32, two MULS instead of two wide products. (The
 * differences wrap as unsigned: one that overflowed is never small while a
 * is.) Elsewhere the wide products. */
XGO_ALWAYS_INLINE int64_t cross_of(int32_t bx, int32_t by, int32_t ax, int32_t ay)
{
#if XGO_CORE_NARROW_CPU
    const int32_t ex = (int32_t)((uint32_t)bx - (uint32_t)ax), ey = (int32_t)((uint32_t)by - (uint32_t)ay);
    if ((ex >> 11) == (ex >> 31) && (ey >> 11) == (ey >> 31) && (ax >> 19) == (ax >> 31) &&
        (ay >> 19) == (ay >> 31)) {
        return ex * ay - ey * ax;
    }
#endif
    return xgo_mul_wide(bx, ay) - xgo_mul_wide(by, ax);
}

int64_t xgo_odometry_cross(int32_t bx, int32_t by, int32_t ax, int32_t ay)
{
    return cross_of(bx, by, ax, ay);
}

/* The turn of the fit, the signed angle of (dot, cross), as
 * xgo_atan2_64 gives it. On a 64-bit host its usual case inline: a tick's
 * turn is small and dot large (a planted pair's spread squared: above 2^32
 * at every walking tick), so the vector is in the first or eighth octant
 * with a larger component of 33 bits or more; there xgo_atan2_64 is the
 * octant's arctangent of the two rounded to 25 bits, negated for a
 * negative cross (atan_octant, fold with no swap and x > 0: the same
 * steps, so the same value), without the call and its general case.
 * Elsewhere (and for any other vector) the call. test_odometry compares it
 * with xgo_atan2_64. */
XGO_ALWAYS_INLINE int32_t turn_of(int64_t cross, int64_t dot)
{
#if XGO_CORE_DIV64_NATIVE
    const uint64_t ay = cross < 0 ? 0u - (uint64_t)cross : (uint64_t)cross;
    if (dot >= ((int64_t)1 << 32) && ay <= (uint64_t)dot) {
        const unsigned k = 39u - xgo_clz32_nz((uint32_t)((uint64_t)dot >> 32));
        const uint32_t a = atan_octant(xgo_round_shr64((uint64_t)dot, k), xgo_round_shr64(ay, k));
        return cross < 0 ? -(int32_t)a : (int32_t)a;
    }
#endif
    return (cross == 0) ? 0 : xgo_bam_signed(xgo_atan2_64(cross, dot));
}

int32_t xgo_odometry_turn(int64_t cross, int64_t dot)
{
    return turn_of(cross, dot);
}

typedef char xgo_odometry_four_legs_[XGO_LEG_COUNT == 4 ? 1 : -1];

/* The lowest leg in a non-empty contact mask: a table lookup, not a chain
 * of tests (twice a walking tick). */
static unsigned first_leg(unsigned mask)
{
    static const uint8_t lowest[16] = {0, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};
    return lowest[mask & 0x0Fu];
}

/* The rigid motion (rotation dyaw, translation d) that maps this tick's
 * planted feet b onto last tick's a: a = R(dyaw) b + d, least squares. */
static void fit_motion(const xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                       uint8_t common, unsigned n, int32_t d_q8[2], int32_t *dyaw)
{
    int32_t sa[2] = {0, 0}, sb[2] = {0, 0};
    int64_t cross = 0, dot = 0;
    xgo_q30_t s, c;
    unsigned leg;
    if (n == 2u) {
        /* A trot's planted pair (every walking tick), legs i and j: centred
         * and scaled by n, the first foot's coordinates are p_i - p_j (2 p_i
         * - (p_i + p_j)) and the second's their negation, so its terms equal
         * the first's - taken twice, four wide products less, and no loops
         * over the legs. */
        const unsigned i = first_leg(common), j = first_leg(common & (common - 1u));
        const xgo_vec3_t *pi = &o->prev_um[i], *pj = &o->prev_um[j];
        const int32_t ax = pi->x - pj->x, ay = pi->y - pj->y;
        const int32_t bx = feet_um[i].x - feet_um[j].x, by = feet_um[i].y - feet_um[j].y;
        sa[0] = pi->x + pj->x;
        sa[1] = pi->y + pj->y;
        sb[0] = feet_um[i].x + feet_um[j].x;
        sb[1] = feet_um[i].y + feet_um[j].y;
        cross = 2 * cross_of(bx, by, ax, ay);
        dot = 2 * (xgo_mul_wide(bx, ax) + xgo_mul_wide(by, ay));
    } else {
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (common & (1u << leg)) {
                sa[0] += o->prev_um[leg].x;
                sa[1] += o->prev_um[leg].y;
                sb[0] += feet_um[leg].x;
                sb[1] += feet_um[leg].y;
            }
        }
        /* centred coordinates, scaled by n so they stay integers */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (common & (1u << leg)) {
                const int32_t ax = (int32_t)n * o->prev_um[leg].x - sa[0];
                const int32_t ay = (int32_t)n * o->prev_um[leg].y - sa[1];
                const int32_t bx = (int32_t)n * feet_um[leg].x - sb[0];
                const int32_t by = (int32_t)n * feet_um[leg].y - sb[1];
                cross += cross_of(bx, by, ax, ay);
                dot += xgo_mul_wide(bx, ax) + xgo_mul_wide(by, ay);
            }
        }
    }
    *dyaw = turn_of(cross, dot);
    xgo_sincos_near0((xgo_bam_t)*dyaw, &s, &c); /* a tick's turn: small */
    /* n d = Sa - R Sb, in 1/256 um */
    {
        const int64_t rx = turn_round(c, sb[0], s, sb[1], 22u);
        const int64_t ry = turn_round(s, sb[0], -c, sb[1], 22u);
        d_q8[0] = div_small(sat32_fit(((int64_t)sa[0] * 256) - rx), n);
        d_q8[1] = div_small(sat32_fit(((int64_t)sa[1] * 256) - ry), n);
    }
}

/* Move the world pose by d (in the body's frame of last tick) and dyaw. */
static void apply_motion(xgo_odometry_t *o, const int32_t d_q8[2], int32_t dyaw)
{
    const xgo_q30_t s = o->yaw_sc[0], c = o->yaw_sc[1];
    o->x_q8 += turn_round(c, d_q8[0], s, d_q8[1], 30u);
    o->y_q8 += turn_round(s, d_q8[0], -c, d_q8[1], 30u);
    if (dyaw != 0) {
        o->yaw += (xgo_bam_t)dyaw;
        xgo_sincos(o->yaw, &o->yaw_sc[0], &o->yaw_sc[1]);
    }
}

/* The feet have not moved on the floor plane (z does not count). */
static int same_xy(const xgo_vec3_t a[XGO_LEG_COUNT], const xgo_vec3_t b[XGO_LEG_COUNT])
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (a[leg].x != b[leg].x || a[leg].y != b[leg].y) {
            return 0;
        }
    }
    return 1;
}

/* The planted feet in a contact mask (every tick): a table lookup. */
static unsigned popcount4(uint8_t m)
{
    static const uint8_t count[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    return count[m & 0x0Fu];
}

int xgo_odometry_needs_all(const xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                           uint8_t contact, uint8_t measured)
{
    const uint8_t common = o->have_prev ? (uint8_t)(o->prev_contact & contact & 0x0Fu) : 0u;
    const uint8_t exact = (uint8_t)(measured & ~o->prev_unmeasured);
    unsigned leg;
    if (common != contact) {
        return 0; /* a foot set down: no "nothing moved", only planted feet are read */
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (((exact >> leg) & 1u) != 0 &&
            (o->prev_um[leg].x != feet_um[leg].x || o->prev_um[leg].y != feet_um[leg].y)) {
            return 0; /* a foot known at both ends moved: the test fails whatever the others */
        }
    }
    return 1;
}

void xgo_odometry_set_prev(xgo_odometry_t *o, unsigned leg, const xgo_vec3_t *foot_um)
{
    o->prev_um[leg] = *foot_um;
    o->prev_unmeasured = (uint8_t)(o->prev_unmeasured & ~(1u << leg));
}

void xgo_odometry_update(xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                         uint8_t contact)
{
    xgo_odometry_update_measured(o, feet_um, contact, 0x0Fu);
}

void xgo_odometry_update_measured(xgo_odometry_t *o, const xgo_vec3_t feet_um[XGO_LEG_COUNT],
                                  uint8_t contact, uint8_t measured)
{
    const uint8_t common = o->have_prev ? (uint8_t)(o->prev_contact & contact & 0x0Fu) : 0u;
    const unsigned n = popcount4(common);
    if (common == contact && same_xy(o->prev_um, feet_um)) {
        /* nothing moved (standing): no motion, and nothing to remember */
        o->last_d_q8[0] = o->last_d_q8[1] = 0;
        o->last_dyaw = 0;
        return;
    }
    if (n >= 2) {
        int32_t d_q8[2];
        int32_t dyaw;
        fit_motion(o, feet_um, common, n, d_q8, &dyaw);
        apply_motion(o, d_q8, dyaw);
        o->last_d_q8[0] = d_q8[0];
        o->last_d_q8[1] = d_q8[1];
        o->last_dyaw = dyaw;
    } else if (o->have_prev && (o->last_d_q8[0] | o->last_d_q8[1] | o->last_dyaw) != 0) {
        /* A support switch (no foot planted at both ends of the tick): the
         * body keeps last tick's motion for this one tick. Used once, so a
         * robot with no feet down does not glide on. */
        apply_motion(o, o->last_d_q8, o->last_dyaw);
        o->last_d_q8[0] = o->last_d_q8[1] = 0;
        o->last_dyaw = 0;
        o->extrapolated_ticks++;
    }
    /* foot by foot on an MCU, no memcpy call and no loop (every walking
     * tick; four legs, as the masks' tables above assume); on a 64-bit
     * host a memcpy of the whole array, which the compiler makes three
     * 16-byte moves (12-byte feet copy as 8 + 4 bytes each: 24 moves) */
#if XGO_CORE_DIV64_NATIVE
    memcpy(o->prev_um, feet_um, sizeof o->prev_um);
#else
    o->prev_um[0] = feet_um[0];
    o->prev_um[1] = feet_um[1];
    o->prev_um[2] = feet_um[2];
    o->prev_um[3] = feet_um[3];
#endif
    o->prev_contact = contact;
    o->prev_unmeasured = (uint8_t)(~measured & 0x0Fu);
    o->have_prev = 1;
}

#endif /* XGO_WITH_ODOMETRY */

void xgo_odometry_pose(const xgo_odometry_t *o, xgo_world_pose_t *out)
{
#if XGO_WITH_ODOMETRY
    out->x_um = xgo_sat32(round_shift64(o->x_q8, 8));
    out->y_um = xgo_sat32(round_shift64(o->y_q8, 8));
    out->yaw_mdeg = xgo_bam_to_mdeg(o->yaw);
#else /* no state kept: the origin (odometry.h) */
    (void)o;
    out->x_um = 0;
    out->y_um = 0;
    out->yaw_mdeg = 0;
#endif
}
