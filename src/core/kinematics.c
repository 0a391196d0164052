/*
 * kinematics.c - leg IK/FK, body IK and register byte codes in integer
 * arithmetic. Geometry, frames and sign conventions: docs/geometry.md.
 *
 * Internal units: angles as binary angles (xgo_bam_t, signed view for
 * limits), lengths in the leg plane in 1/16 um ("q4") so square roots keep
 * sub-micrometre resolution; squares and products are int64.
 *
 * Leg model (one leg, leg frame, w = outward lateral coordinate = side * y):
 *   abduction axis: parallel to x through (w = -d, z = 0); the leg plane is
 *   at distance d from it and turns by phi (x3) about it;
 *   in the leg plane (x forward, h "down" along the plane):
 *     knee = L1 * u(t2),  foot = knee + L2 * u(t2 + g - 90deg),
 *     u(a) = (-sin a, cos a), t2 = x2, g = x1 + knee_offset;
 *   back to the leg frame: w + d = d cos phi + h sin phi,
 *                          z     = -d sin phi + h cos phi.
 */
#include "kinematics.h"

#include "compiler.h"
#include "wide.h" /* 32 x 32 -> 64 products without a libgcc call on a Cortex-M0 */

/* On a 64-bit host the leg IK inlines its square roots, arctangents and
 * sines (fixed.h's bodies: the same code as the out-of-line functions,
 * so the same values); elsewhere it calls them (flash, and the static
 * stack bound: docs/mcu.md). */
#if XGO_CORE_DIV64_NATIVE
#define XGO_FIXED_BODIES
#define XGO_FIXED_INLINE
#include "fixed.h"
#endif

#define Q4_SHIFT 4             /* planar lengths in 1/16 um */
#define Q4_ONE 16              /* 2^Q4_SHIFT: scale by multiplying (<< of a negative value is undefined) */
#define FAR_LIMIT_UM (1 << 20) /* targets beyond ~1 m are scaled down */

/* Kept out of line: a helper's locals must not widen the frame of the
 * function that goes deepest (leg IK -> branch -> projection; the static
 * stack bound, docs/mcu.md): XGO_OWN_FRAME. */

/* ------------------------------------------------------------ helpers */

/* Inline on a 64-bit host, where a call costs its saved registers and
 * argument moves and the stack is no budget; out of line on an MCU (the
 * static stack bound and flash, docs/mcu.md). */
#if XGO_CORE_DIV64_NATIVE
#define HOST_INLINE XGO_ALWAYS_INLINE
#else
#define HOST_INLINE static
#endif

static int64_t round_shift(int64_t v, unsigned n)
{
    return (v + ((int64_t)1 << (n - 1u))) >> n;
}

/* A 32 x 32 -> 64-bit product for the colder paths (FK, the projection's
 * clamp, per-call constants): one out-of-line copy where xgo_mul_wide is
 * long (Cortex-M0: about 40 bytes inline), inlined where it is one
 * instruction. */
static int64_t mul_cold(int32_t a, int32_t b)
{
    return xgo_mul_wide(a, b);
}

/* v^2: on a Cortex-M0 the unsigned square of |v| (no sign fix-ups, three
 * MULS), elsewhere one multiply; the same value. */
XGO_INLINE_FAST int64_t square_wide(int32_t v)
{
#if XGO_CORE_NARROW_CPU
    const uint32_t u = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    return (int64_t)xgo_usquare_wide(u);
#else
    return xgo_mul_wide(v, v);
#endif
}

/* Local copy of xgo_sat32 so the hot loops can inline it. */
static int32_t sat_i32(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : (v < INT32_MIN ? INT32_MIN : (int32_t)v);
}

static int32_t clamp_i32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Signed binary angle of a limit given in mdeg (limits are within +-180). */
static int32_t limit_bam(int32_t mdeg)
{
    return xgo_bam_signed(xgo_mdeg_to_bam(mdeg));
}

/* Clamp angle a into the arc that starts at lo and runs counter-clockwise
 * over width (< one turn): the point of the arc nearest to a on the circle
 * (the distance to a circle point grows with the angular distance). */
static xgo_bam_t clamp_arc(xgo_bam_t a, xgo_bam_t lo, uint32_t width)
{
    uint32_t mid = lo + width / 2u;
    int32_t half = (int32_t)(width / 2u);
    int32_t off = xgo_bam_signed(a - mid);
    if (off > half) {
        return lo + width;
    }
    if (off < -half) {
        return lo;
    }
    return a;
}

/* The leg IK's sines and cosines, square roots and arctangents: inline
 * on a 64-bit host. */
XGO_ALWAYS_INLINE void ik_sincos(xgo_bam_t a, xgo_q30_t *s, xgo_q30_t *c)
{
#if XGO_CORE_DIV64_NATIVE
    xgo_sincos_inline(a, s, c);
#else
    xgo_sincos(a, s, c);
#endif
}

XGO_ALWAYS_INLINE uint32_t ik_sqrt64_near(uint64_t x)
{
#if XGO_CORE_DIV64_NATIVE
    return xgo_sqrt64_near_inline(x);
#else
    return xgo_sqrt64_near(x);
#endif
}

XGO_ALWAYS_INLINE xgo_bam_t ik_atan2_len30(int32_t y, int32_t x)
{
#if XGO_CORE_DIV64_NATIVE
    return xgo_atan2_len30_inline(y, x);
#else
    return xgo_atan2_len30(y, x);
#endif
}

XGO_ALWAYS_INLINE xgo_bam_t ik_atan2_64(int64_t y, int64_t x)
{
#if XGO_CORE_DIV64_NATIVE
    return xgo_atan2_64_inline(y, x);
#else
    return xgo_atan2_64(y, x);
#endif
}

/* round(sqrt(v)) for v < 2^62 (every caller: at most 2^60): the floor of
 * sqrt(4v) = 2 sqrt(v), halved with the carry. */
static uint32_t isqrt64_round(uint64_t v)
{
    return (xgo_isqrt64(v << 2) + 1u) >> 1;
}

/* The same within a unit (xgo_sqrt64_near): the hot path's two roots. */
HOST_INLINE uint32_t sqrt64_round_near(uint64_t v)
{
    return (ik_sqrt64_near(v << 2) + 1u) >> 1;
}

/* (a + ib)(c + id), every factor and a + b, c + d, d - c within int32 and
 * the products within int64. On a Cortex-M0 three wide products instead of
 * four (Karatsuba: a wide product is four MULS and carries there),
 * elsewhere four single multiplies; the same exact value. */
XGO_ALWAYS_INLINE void complex_mul(int32_t a, int32_t b, int32_t c, int32_t d, int64_t *re, int64_t *im)
{
#if XGO_CORE_NARROW_CPU
    const int64_t k1 = xgo_mul_wide(c, a + b), k2 = xgo_mul_wide(a, d - c), k3 = xgo_mul_wide(b, c + d);
    *re = k1 - k3;
    *im = k1 + k2;
#else
    *re = xgo_mul_wide(a, c) - xgo_mul_wide(b, d);
    *im = xgo_mul_wide(a, d) + xgo_mul_wide(b, c);
#endif
}

/* ------------------------------------------------------------ planar IK */

/* planar_init's constants for the Mini's links (every built-in profile's),
 * as constant expressions of what planar_init works out: 2 l1 l2 is below
 * 2^42 and at least 2^41 (checked below), so it is cut by 12 bits; the knee
 * offset's binary angle as xgo_mdeg_to_bam gives it (a positive angle). */
#define MINI_L1 ((int64_t)XGO_MINI_THIGH_UM * Q4_ONE)
#define MINI_L2 ((int64_t)XGO_MINI_SHANK_UM * Q4_ONE)
#define MINI_TWO_L1L2 (2 * MINI_L1 * MINI_L2)
#define MINI_D_SHIFT 12
#define MINI_DN (MINI_TWO_L1L2 >> MINI_D_SHIFT)
#define MINI_KNEE_OFF                                                                        \
    ((uint32_t)XGO_MINI_KNEE_OFFSET_MDEG * 11930u +                                          \
     (uint32_t)(((int64_t)XGO_MINI_KNEE_OFFSET_MDEG * 1995919024 + ((int64_t)1 << 31)) >> 32))
typedef char xgo_mini_cut_is_12_bits[(MINI_TWO_L1L2 >> 41) == 1 ? 1 : -1];
typedef char xgo_mini_knee_offset_positive[XGO_MINI_KNEE_OFFSET_MDEG >= 0 ? 1 : -1];

typedef struct planar_s {
    int32_t l1, l2;     /* q4 */
    int64_t sum_sq;     /* l1^2 + l2^2 */
    int64_t two_l1l2;   /* 2 l1 l2, and the shift that cuts it to 30 bits */
    int64_t l1_dn;      /* l1 times dn: a constant of planar_ik's (a, b) */
    int32_t dn;         /* 2 l1 l2 cut to 30 bits */
    uint8_t d_shift;
    /* Only a projection needs the limits as binary angles and the boundary
     * arcs of the reachable region (they depend on the limits only):
     * computed on the first projection, reused by the second branch.
     * (Bytes, as d_shift: the struct is on the tick's deepest stack path.) */
    uint8_t arcs_ready;
    const xgo_profile_t *p;
    xgo_bam_t knee_off; /* g = x1 + knee_off */
    int32_t g_lo, g_hi; /* geometric knee angle limits, signed BAM */
    int32_t t_lo, t_hi; /* hip pitch limits, signed BAM */
    int32_t hip_r[2];    /* g at g_lo / g_hi: radius of the foot's circle about the hip, q4 */
    xgo_bam_t hip_a[2];  /* and the foot's u-angle past the thigh */
    int32_t knee_x[2], knee_h[2]; /* t2 at t_lo / t_hi: the knee, q4 */
} planar_t;

typedef struct candidate_s {
    int64_t dist2;
    xgo_bam_t g, t2;
} candidate_t;

/* u-angle of a plane vector: u(a) = (-sin a, cos a) points along (x, h);
 * |x|, |h| < 2^30 (the projection's vectors: below 2^28), so the 32-bit
 * atan2 (xgo_atan2_64 gives the same for such values). */
static xgo_bam_t u_angle(int32_t x, int32_t h)
{
    return xgo_atan2(-x, h);
}

static void consider(candidate_t *best, int64_t px, int64_t ph, int32_t x, int32_t h, xgo_bam_t g, xgo_bam_t t2)
{
    /* |d| < 2^27: 32-bit values, their squares fit */
    const int64_t d2 = square_wide((int32_t)(px - x)) + square_wide((int32_t)(ph - h));
    if (d2 < best->dist2) {
        best->dist2 = d2;
        best->g = g;
        best->t2 = t2;
    }
}

/* The boundary arcs' circles for the limits of one side (0: lo, 1: hi).
 * Out of line, as are the candidates below: the projection is on the
 * deepest stack path (docs/mcu.md), and each keeps its own locals. */
XGO_OWN_FRAME static void planar_arc(planar_t *pl, int side)
{
    /* g fixed at a limit: foot on a circle about the hip */
    const int32_t gl = side ? pl->g_hi : pl->g_lo, tl = side ? pl->t_hi : pl->t_lo;
    xgo_q30_t sg, cg;
    int64_t fx, fh;
    ik_sincos((uint32_t)gl, &sg, &cg);
    fx = round_shift(mul_cold(pl->l2, cg), 30); /* foot in the thigh frame */
    fh = pl->l1 + round_shift(mul_cold(pl->l2, sg), 30);
    pl->hip_r[side] = (int32_t)isqrt64_round((uint64_t)(fx * fx + fh * fh));
    pl->hip_a[side] = u_angle((int32_t)fx, (int32_t)fh); /* foot direction past the thigh */
    /* t2 fixed at a limit: foot on a circle about the knee */
    ik_sincos((uint32_t)tl, &sg, &cg);
    pl->knee_x[side] = (int32_t)-round_shift(mul_cold(pl->l1, sg), 30);
    pl->knee_h[side] = (int32_t)round_shift(mul_cold(pl->l1, cg), 30);
}

#if XGO_CORE_DIV64_NATIVE
/* On a 64-bit host the arcs of the Mini's knee and hip limits (the Mini's
 * and the Mini2's profiles: profile.c) with its links are kept, as
 * planar_arcs works them out: a projection (a leg in about one tick in
 * 25) then skips about 760 instructions of sines, a root and an atan2.
 * test_kinematics checks them against planar_arcs through projections.
 * Not on an MCU: the table and the tests would cost flash. */
#define MINI_KNEE_LO_MDEG (-73000)
#define MINI_KNEE_HI_MDEG 57000
#define MINI_HIP_LO_MDEG (-66000)
#define MINI_HIP_HI_MDEG 93000

static int mini_arcs(planar_t *pl, const xgo_range_t *knee, const xgo_range_t *hip)
{
    if (pl->l1 != MINI_L1 || pl->l2 != MINI_L2 || pl->knee_off != MINI_KNEE_OFF || knee->lo != MINI_KNEE_LO_MDEG ||
        knee->hi != MINI_KNEE_HI_MDEG || hip->lo != MINI_HIP_LO_MDEG || hip->hi != MINI_HIP_HI_MDEG) {
        return 0;
    }
    pl->g_lo = -861928354;
    pl->g_hi = 689032059;
    pl->t_lo = -787410671;
    pl->t_hi = 1109533218;
    pl->hip_r[0] = 421089;
    pl->hip_r[1] = 2090023;
    pl->hip_a[0] = 2883634221u;
    pl->hip_a[1] = 4079218564u;
    pl->knee_x[0] = 875542;
    pl->knee_x[1] = -957087;
    pl->knee_h[0] = 389816;
    pl->knee_h[1] = -50159;
    pl->arcs_ready = 1;
    return 1;
}
#endif

static void planar_arcs(planar_t *pl)
{
    const xgo_range_t *knee = &pl->p->joint_mdeg[XGO_JOINT_KNEE], *hip = &pl->p->joint_mdeg[XGO_JOINT_HIP];
#if XGO_CORE_DIV64_NATIVE
    if (mini_arcs(pl, knee, hip)) {
        return;
    }
#endif
    pl->g_lo = xgo_bam_signed(xgo_mdeg_to_bam(knee->lo) + pl->knee_off);
    pl->g_hi = xgo_bam_signed(xgo_mdeg_to_bam(knee->hi) + pl->knee_off);
    pl->t_lo = limit_bam(hip->lo);
    pl->t_hi = limit_bam(hip->hi);
    planar_arc(pl, 0);
    planar_arc(pl, 1);
    pl->arcs_ready = 1;
}

/* The candidates: inline into the projection on a 64-bit host (the stack
 * is no budget there), each with its own frame on an MCU. */
#if XGO_CORE_DIV64_NATIVE
#define CANDIDATE_FN XGO_ALWAYS_INLINE
#else
#define CANDIDATE_FN XGO_OWN_FRAME static
#endif

/* The candidate on the circle about the hip where g is at a limit. */
CANDIDATE_FN void hip_candidate(const planar_t *pl, int side, int32_t x, int32_t h, xgo_bam_t target,
                                        candidate_t *best)
{
    const int32_t r = pl->hip_r[side];
    const xgo_bam_t a = pl->hip_a[side];
    xgo_q30_t sp, cp;
    xgo_bam_t psi = clamp_arc(target, (uint32_t)pl->t_lo + a, (uint32_t)pl->t_hi - (uint32_t)pl->t_lo);
    ik_sincos(psi, &sp, &cp);
    consider(best, -round_shift(mul_cold(r, sp), 30), round_shift(mul_cold(r, cp), 30), x, h,
             (uint32_t)(side ? pl->g_hi : pl->g_lo), psi - a);
}

/* The candidate on the circle about the knee where t2 is at a limit. */
CANDIDATE_FN void knee_candidate(const planar_t *pl, int side, int32_t x, int32_t h, candidate_t *best)
{
    const int32_t tl = side ? pl->t_hi : pl->t_lo;
    const int32_t kx = pl->knee_x[side], kh = pl->knee_h[side];
    xgo_q30_t sb, cb;
    /* shank u-angle b = t2 + g - 90deg, g within its limits */
    const xgo_bam_t b_lo = (uint32_t)tl + (uint32_t)pl->g_lo - XGO_BAM_90;
    const xgo_bam_t b = clamp_arc(u_angle(x - kx, h - kh), b_lo,
                                  (uint32_t)pl->g_hi - (uint32_t)pl->g_lo);
    ik_sincos(b, &sb, &cb);
    consider(best, kx - round_shift(mul_cold(pl->l2, sb), 30), kh + round_shift(mul_cold(pl->l2, cb), 30), x, h,
             b - (uint32_t)tl + XGO_BAM_90, (uint32_t)tl);
}

/* Nearest point of the reachable region to (x, h) (q4, |x|, |h| < 2^26):
 * the region is the image of the limit box, so its boundary is four arcs
 * (g at a limit: circles about the hip; t2 at a limit: circles about the
 * knee). */
static void planar_project(planar_t *pl, int32_t x, int32_t h, xgo_bam_t *g, xgo_bam_t *t2)
{
    candidate_t best;
    const xgo_bam_t target = u_angle(x, h);
    if (!pl->arcs_ready) {
        planar_arcs(pl);
    }
    best.dist2 = INT64_MAX;
    best.g = (uint32_t)pl->g_lo;
    best.t2 = (uint32_t)pl->t_lo;
    hip_candidate(pl, 0, x, h, target, &best);
    hip_candidate(pl, 1, x, h, target, &best);
    knee_candidate(pl, 0, x, h, &best);
    knee_candidate(pl, 1, x, h, &best);
    *g = best.g;
    *t2 = best.t2;
}

typedef struct leg_solution_s {
    xgo_bam_t phi, g, t2;
    int32_t q[XGO_JOINT_COUNT]; /* the same in mdeg (knee without the offset) */
    int projected;
} leg_solution_t;

/* The joint angle in mdeg, and whether it is within the joint's limits.
 * The rounded mdeg decide unless they land on a limit; there the binary
 * angle is compared with the limit's (exactly as if every limit had been
 * converted): no conversion of the limits on the way of most targets.
 * Inline: three calls a leg, and the call cost about as much as the
 * common path (M3 tick -177; static stack bound unchanged). */
XGO_ALWAYS_INLINE int joint_in(const planar_t *pl, unsigned joint, xgo_bam_t a, int32_t *mdeg)
{
    const xgo_range_t *r = &pl->p->joint_mdeg[joint];
    *mdeg = xgo_bam_to_mdeg(a);
    if (*mdeg > r->lo && *mdeg < r->hi) { /* the usual answer first: on neither limit */
        return 1;
    }
    if (*mdeg == r->lo) {
        return xgo_bam_signed(a) >= limit_bam(r->lo);
    }
    if (*mdeg == r->hi) {
        return xgo_bam_signed(a) <= limit_bam(r->hi);
    }
    return 0;
}

/* The right shift that brings m to 30 bits (its bit length - 30, or 0
 * when it fits), with the core's inline CLZ: xgo_bit_length's is a libgcc
 * call on a Cortex-M0 (__clzsi2). Out of line where the CLZ is the binary
 * search (M0): inline, its registers widened the frame of solve_branch,
 * which is on the deepest stack path. */
#if XGO_CLZ_BUILTIN
XGO_ALWAYS_INLINE unsigned cut_to_30(uint64_t m)
#else
XGO_OWN_FRAME static unsigned cut_to_30(uint64_t m)
#endif
{
    const uint32_t hi = (uint32_t)(m >> 32);
    unsigned bits;
    if (hi != 0u) { /* always, for the hip's products */
        return 34u - xgo_clz32_nz(hi); /* 64 - clz - 30 */
    }
    bits = xgo_bit_length_inline(m);
    return bits > 30u ? bits - 30u : 0u;
}

/* In-plane IK for (x, h) in q4 (|x|, |h| < 2^26). Returns 1 if the target
 * had to be projected. */
HOST_INLINE int planar_ik(planar_t *pl, int32_t x, int32_t h, leg_solution_t *s)
{
    const int64_t r2 = square_wide(x) + square_wide(h);
    const int64_t n = r2 - pl->sum_sq, d = pl->two_l1l2;
    const int32_t dn = pl->dn;
    int32_t nn;
    uint32_t cn;
    if ((uint64_t)n + (uint64_t)d > 2u * (uint64_t)d) { /* |n| > d: n + d outside [0, 2d] (d < 2^62) */
        planar_project(pl, x, h, &s->g, &s->t2);
        return 1;
    }
    /* sin g = n / d, cos g = sqrt((d - n)(d + n)) / d; n and d scaled to
     * 30 bits so the product fits 64 bits (relative precision 2^-30). */
    nn = xgo_shr64_to32(n, pl->d_shift);
    /* n <= d gives nn <= dn (both floors of a shift); n >= -d only nn >=
     * -dn - 1 (the floor of a negative value), so only that side clamps */
    nn = nn < -dn ? -dn : nn;
    cn = sqrt64_round_near(xgo_umul_wide((uint32_t)(dn - nn), (uint32_t)(dn + nn))); /* < 2^30 */
    s->g = ik_atan2_len30(nn, (int32_t)cn); /* |(nn, cn)| = dn in [2^29, 2^30) */
    /* t2 = u-angle of the foot (x, h) minus the foot's angle past the thigh,
     * the u-angle of (a, b) = (L2 cos g, L1 + L2 sin g) (scaled by dn). As
     * complex numbers h - ix and b - ia, the difference of their angles is
     * the angle of (h - ix)(b + ia) = (hb + xa) + i(ha - xb): one atan2.
     * a and b are cut to 30 bits first so the products fit 64 bits. */
    {
        int64_t a = (int64_t)xgo_umul_wide((uint32_t)pl->l2, cn);
        int64_t b = pl->l1_dn + xgo_mul_wide(pl->l2, nn);
        const unsigned cut = cut_to_30((uint64_t)a | (uint64_t)(b < 0 ? -b : b));
        const int32_t a30 = xgo_shr64_to32(a, cut), b30 = xgo_shr64_to32(b, cut);
        int64_t im, re;
        complex_mul(h, -x, b30, a30, &re, &im); /* |terms| < 2^57 */
        s->t2 = ik_atan2_64(im, re);
    }
    if (!joint_in(pl, XGO_JOINT_KNEE, s->g - pl->knee_off, &s->q[XGO_JOINT_KNEE]) ||
        !joint_in(pl, XGO_JOINT_HIP, s->t2, &s->q[XGO_JOINT_HIP])) {
        planar_project(pl, x, h, &s->g, &s->t2);
        return 1;
    }
    return 0;
}

/* ------------------------------------------------------------ leg IK / FK */

#if XGO_CORE_NARROW_CPU
static int32_t dot30(int32_t a, int32_t b, int32_t c, int32_t d);

/* floor((a b + c d + half) / 2^30) from 15-bit pieces (a = ah 2^15 + al,
 * 0 <= al < 2^15): ab + cd = P 2^30 + M 2^15 + L with P = ah bh + ch dh,
 * M = ah bl + al bh + ch dl + cl dh and L = al bl + cl dl (< 2^31), each
 * MULS within int32, the floors nested exactly; half 2^29 (rounded: dot30)
 * or 0. For |a|, |b|, |c|, |d| <= 2^30 with the result within int32. */
XGO_INLINE_FAST int32_t dot_pieces(int32_t a, int32_t b, int32_t c, int32_t d, uint32_t half)
{
    const int32_t ah = a >> 15, al = a & 0x7FFF, bh = b >> 15, bl = b & 0x7FFF;
    const int32_t ch = c >> 15, cl = c & 0x7FFF, dh = d >> 15, dl = d & 0x7FFF;
    const int32_t m1 = ah * bl + al * bh, m2 = ch * dl + cl * dh; /* each within +-2^31 */
    const uint32_t lo = ((uint32_t)(al * bl) + (uint32_t)(cl * dl) + half) >> 15; /* < 2^17 */
    return ah * bh + ch * dh + (m1 >> 15) + (m2 >> 15) + (((m1 & 0x7FFF) + (m2 & 0x7FFF) + (int32_t)lo) >> 15);
}

/* round((a b + c d) / 2^34), ties up, for the FK's turn about the abduction
 * axis (a, c below 2^22, b, d Q30): with ab + cd = q 2^30 + r (0 <= r <
 * 2^30), floor((ab + cd + 2^33) / 2^34) = floor((q + 8) / 16). The same
 * value as the wide products' rounded sum. */
static int32_t dot34(int32_t a, int32_t b, int32_t c, int32_t d)
{
    return (dot_pieces(a, b, c, d, 0u) + 8) >> 4;
}
#endif

/* Foot position (leg frame, um) of binary joint angles; g includes the knee
 * offset. Products of a length (< 2^31) and a Q30 value: 32 x 32 bits. On
 * the M0 the leg plane's x and h (q4) are dot30's rounded sums (from 15-bit
 * pieces, no wide product; lengths below 2^21, results far inside its
 * clamp: the same value as the wide products' sum rounded); elsewhere the
 * wide products (M3: dot30 was slower there). */
static void fk_bam(const xgo_profile_t *p, int side_y, xgo_bam_t phi, xgo_bam_t g, xgo_bam_t t2,
                   xgo_vec3_t *foot_um)
{
    xgo_q30_t s2, c2, s12, c12, sp, cp;
    const int32_t l1 = p->thigh_um, l2 = p->shank_um, d = p->abad_offset_um;
    int32_t h4;
#if !XGO_CORE_NARROW_CPU
    int64_t x30, wp34, z34;
#endif
    xgo_sincos(t2, &s2, &c2);
    xgo_sincos(t2 + g, &s12, &c12);
    xgo_sincos(phi, &sp, &cp);
    /* in the leg plane: x = -L1 sin t2 + L2 cos(t2 + g), h = L1 cos t2 + L2 sin(t2 + g) */
#if XGO_CORE_NARROW_CPU
    foot_um->x = dot30(-l1, s2, l2, c12);
    h4 = dot30(l1 * Q4_ONE, c2, l2 * Q4_ONE, s12); /* q4 */
#else
    x30 = -mul_cold(l1, s2) + mul_cold(l2, c12);                                  /* um * 2^30 */
    h4 = (int32_t)round_shift(mul_cold(l1, c2) + mul_cold(l2, s12), 30 - Q4_SHIFT); /* q4 */
    foot_um->x = (int32_t)round_shift(x30, 30);
#endif
    /* about the abduction axis, in um * 2^34 */
#if XGO_CORE_NARROW_CPU
    foot_um->y = side_y * (dot34(d * Q4_ONE, cp, h4, sp) - d);
    foot_um->z = dot34(-d * Q4_ONE, sp, h4, cp);
#else
    wp34 = mul_cold(d * Q4_ONE, cp) + mul_cold(h4, sp);
    z34 = -mul_cold(d * Q4_ONE, sp) + mul_cold(h4, cp);
    foot_um->y = (int32_t)(side_y * (round_shift(wp34, 34) - d));
    foot_um->z = (int32_t)round_shift(z34, 34);
#endif
}

/* The abduction angle that puts (wp, z) (um) at h (q4) in the leg plane:
 * (wp, z) is the plane point (d, h) turned by phi,
 *   wp = d cos phi + h sin phi,  z = -d sin phi + h cos phi,
 * so cos phi ~ d wp + h z and sin phi ~ h wp - d z (all in q4). */
HOST_INLINE xgo_bam_t branch_phi(const planar_t *pl, int32_t wp, int32_t z, int32_t h)
{
    const int32_t d4 = pl->p->abad_offset_um * Q4_ONE, wp4 = wp * Q4_ONE, z4 = z * Q4_ONE;
    int64_t re, im;
    complex_mul(wp4, z4, d4, -h, &re, &im); /* (wp + iz)(d - ih): |terms| < 2^52 */
    return ik_atan2_64(-im, re);
}

/* One branch of the abduction solution: the foot at h = branch * |h| in the
 * leg plane (branch +1: at or below the thigh joint, -1: above it). All
 * values in q4 are below 2^26, so every product is 32 x 32 bits. */
HOST_INLINE void solve_branch(planar_t *pl, int32_t xq, int32_t wp, int32_t z, int32_t h_abs, int branch,
                              leg_solution_t *s)
{
    const xgo_range_t *ar = &pl->p->joint_mdeg[XGO_JOINT_ABAD];
    int32_t h = branch > 0 ? h_abs : -h_abs;
    s->projected = 0;
    s->phi = branch_phi(pl, wp, z, h);
    if (!joint_in(pl, XGO_JOINT_ABAD, s->phi, &s->q[XGO_JOINT_ABAD])) {
        /* clamp, then project the target onto that leg plane */
        xgo_q30_t sp, cp;
        s->q[XGO_JOINT_ABAD] = s->q[XGO_JOINT_ABAD] < ar->lo ? ar->lo : ar->hi;
        s->phi = xgo_mdeg_to_bam(s->q[XGO_JOINT_ABAD]);
        ik_sincos(s->phi, &sp, &cp);
        h = (int32_t)round_shift(mul_cold(wp, sp) + mul_cold(z, cp), 30 - Q4_SHIFT);
        s->projected = 1;
    }
    if (planar_ik(pl, xq, h, s)) {
        s->projected = 1;
        s->q[XGO_JOINT_KNEE] = xgo_bam_to_mdeg(s->g - pl->knee_off);
        s->q[XGO_JOINT_HIP] = xgo_bam_to_mdeg(s->t2);
    }
}

/* The upper branch (rare: the lower one projected). On a 64-bit host out
 * of line, so the inline lower one keeps the registers; elsewhere the call
 * of solve_branch itself (no frame more on the deepest stack path). */
#if XGO_CORE_DIV64_NATIVE
#define UPPER_BRANCH_FN XGO_OWN_FRAME static
#else
#define UPPER_BRANCH_FN XGO_ALWAYS_INLINE
#endif
UPPER_BRANCH_FN void solve_upper(planar_t *pl, int32_t xq, int32_t wp, int32_t z, int32_t h_abs, leg_solution_t *s)
{
    solve_branch(pl, xq, wp, z, h_abs, -1, s);
}

static int64_t dist2_um(const xgo_vec3_t *a, int32_t x, int32_t y, int32_t z)
{
    /* all within ~2^21 (a foot near the leg, a target within ~1 m): 32-bit
     * values whose squares fit */
    return square_wide(a->x - x) + square_wide(a->y - y) + square_wide(a->z - z);
}

/* Squared distance (um^2) of a branch's foot from the target (x, y, z),
 * the target as given: a far one scaled down points the same way. */
XGO_OWN_FRAME static int64_t miss2(const xgo_profile_t *p, int side, const leg_solution_t *s, int32_t x,
                                   int32_t y, int32_t z)
{
    xgo_vec3_t f;
    fk_bam(p, side, s->phi, s->g, s->t2, &f);
    return dist2_um(&f, x, y, z);
}

/* The lower branch is projected: whether the upper one may land nearer.
 * Where the upper branch's abduction is past a limit, its foot lies in the
 * leg plane at that limit, wp cos phi - z sin phi = d, at least the
 * target's distance from that plane away: when that exceeds the lower
 * foot's miss by more than both feet's rounding (FK within 1 um of the
 * exact foot, each coordinate rounded), the upper one cannot win the
 * comparison below and is not solved. Sets *miss2_below when it worked it
 * out (else leaves it negative). */
XGO_OWN_FRAME static int upper_may_win(const planar_t *pl, int side, const leg_solution_t *below, int32_t wp,
                                       int32_t z, int32_t h_abs, int32_t x_um, int32_t y_um,
                                       int64_t *miss2_below)
{
    const xgo_range_t *ar = &pl->p->joint_mdeg[XGO_JOINT_ABAD];
    int32_t q, off;
    xgo_q30_t sp, cp;
    if (joint_in(pl, XGO_JOINT_ABAD, branch_phi(pl, wp, z, -h_abs), &q)) {
        return 1;
    }
    ik_sincos(xgo_mdeg_to_bam(q < ar->lo ? ar->lo : ar->hi), &sp, &cp);
    off = (int32_t)round_shift(mul_cold(wp, cp) - mul_cold(z, sp), 30) - pl->p->abad_offset_um;
    off = (off < 0 ? -off : off) - 8; /* the margin: 2 um is enough */
    *miss2_below = miss2(pl->p, side, below, x_um, y_um, z);
    return off <= 0 || square_wide(off) <= *miss2_below;
}

static void planar_init(planar_t *pl, const xgo_profile_t *p)
{
    pl->p = p;
    pl->arcs_ready = 0;
#if XGO_CORE_NARROW_CPU || XGO_CORE_DIV64_NATIVE
    /* Every call of xgo_legs_ik (a tick): no products, no bit count (M0:
     * about 180 instructions less). Not on the other 32-bit cores (M3): a
     * widening multiply and a CLZ make the work a few instructions, and the
     * kept constants cost flash. */
    if (p->thigh_um == XGO_MINI_THIGH_UM && p->shank_um == XGO_MINI_SHANK_UM &&
        p->knee_offset_mdeg == XGO_MINI_KNEE_OFFSET_MDEG) {
        pl->l1 = (int32_t)MINI_L1;
        pl->l2 = (int32_t)MINI_L2;
        pl->knee_off = MINI_KNEE_OFF;
        pl->sum_sq = MINI_L1 * MINI_L1 + MINI_L2 * MINI_L2;
        pl->two_l1l2 = MINI_TWO_L1L2;
        pl->d_shift = MINI_D_SHIFT;
        pl->dn = (int32_t)MINI_DN;
        pl->l1_dn = MINI_L1 * MINI_DN;
        return;
    }
#endif
    pl->l1 = p->thigh_um * Q4_ONE;
    pl->l2 = p->shank_um * Q4_ONE;
    pl->knee_off = xgo_mdeg_to_bam(p->knee_offset_mdeg);
    pl->sum_sq = square_wide(pl->l1) + square_wide(pl->l2);
    pl->two_l1l2 = 2 * xgo_mul_wide(pl->l1, pl->l2);
    {
        const unsigned bits = xgo_bit_length((uint64_t)pl->two_l1l2);
        pl->d_shift = (uint8_t)(bits > 30u ? bits - 30u : 0u);
    }
    pl->dn = xgo_shr64_to32(pl->two_l1l2, pl->d_shift);
    pl->l1_dn = mul_cold(pl->l1, pl->dn);
}

static int32_t clamp_joint(const xgo_profile_t *p, unsigned joint, int32_t v)
{
    return clamp_i32(v, p->joint_mdeg[joint].lo, p->joint_mdeg[joint].hi);
}

/* |v| > FAR_LIMIT_UM for any of the three, an unsigned compare each (v +
 * FAR_LIMIT_UM modulo 2^32 is within [0, 2 FAR_LIMIT_UM] exactly when v
 * is within the limit). On a 64-bit host first the usual answer, all
 * three below 2 FAR_LIMIT_UM (a power of two) at once: one test of their
 * bits or-ed (tick -46; on an MCU 20 bytes of flash for 4 instructions). */
typedef char xgo_far_limit_power_of_two[(FAR_LIMIT_UM & (FAR_LIMIT_UM - 1)) == 0 ? 1 : -1];

XGO_ALWAYS_INLINE int beyond_far3(int32_t x, int32_t y, int32_t z)
{
    const uint32_t ux = (uint32_t)x + (uint32_t)FAR_LIMIT_UM, uy = (uint32_t)y + (uint32_t)FAR_LIMIT_UM,
                   uz = (uint32_t)z + (uint32_t)FAR_LIMIT_UM, lim = 2u * (uint32_t)FAR_LIMIT_UM;
#if XGO_CORE_DIV64_NATIVE
    if ((ux | uy | uz) < lim) {
        return 0;
    }
#endif
    return (ux > lim) | (uy > lim) | (uz > lim);
}

/* The leg IK with the profile's constants in pl (shared by the legs of one
 * call of xgo_legs_ik, and the limit arcs with them). */
HOST_INLINE int leg_ik_in(planar_t *pl, xgo_leg_t leg, const xgo_vec3_t *foot_um, int32_t q_mdeg[XGO_JOINT_COUNT])
{
    const xgo_profile_t *p = pl->p;
    int32_t x = foot_um->x, y = foot_um->y, z = foot_um->z;
    const int32_t d = p->abad_offset_um;
    const int side = xgo_leg_side_y(leg);
    int32_t wp, h_abs;
    int64_t h2;
    leg_solution_t below, above;
    const leg_solution_t *sol = &below;
    int inside_axis_cylinder;

    /* Far targets: halve all three until within ~1 m (direction kept). */
    while (beyond_far3(x, y, z)) {
        x /= 2;
        y /= 2;
        z /= 2;
    }

    /* Across the abduction axis: wp is the target's outward distance from
     * the axis, h its distance along the leg plane (Pythagoras with d). A
     * target closer to the axis than d is in no leg plane (h = 0 then). */
    wp = (side > 0 ? y : -y) + d; /* |wp| <= 2^21 */
    h2 = xgo_mul_wide(wp - d, wp + d) + square_wide(z); /* wp^2 - d^2 + z^2, exactly */
    inside_axis_cylinder = h2 < 0;
    h_abs = h2 > 0 ? (int32_t)sqrt64_round_near((uint64_t)h2 << (2 * Q4_SHIFT)) : 0; /* q4, < 2^26 */

    /* Two solutions: foot below the thigh joint's level in the leg plane
     * (the normal one), or above it. Take the first that reaches the target
     * within every limit; if neither does, the one landing nearer (the
     * upper one only solved when it may). */
    solve_branch(pl, x * Q4_ONE, wp, z, h_abs, 1, &below);
    if (!below.projected && !inside_axis_cylinder) { /* within every limit already */
        q_mdeg[XGO_JOINT_KNEE] = below.q[XGO_JOINT_KNEE];
        q_mdeg[XGO_JOINT_HIP] = below.q[XGO_JOINT_HIP];
        q_mdeg[XGO_JOINT_ABAD] = below.q[XGO_JOINT_ABAD];
        return XGO_IK_REACHED;
    }
    if (below.projected && h_abs > 0) {
        int64_t below2 = -1;
        if (upper_may_win(pl, side, &below, wp, z, h_abs, x, y, &below2)) {
            solve_upper(pl, x * Q4_ONE, wp, z, h_abs, &above);
            if (!above.projected) {
                sol = &above;
            } else {
                if (below2 < 0) {
                    below2 = miss2(p, side, &below, x, y, z);
                }
                if (miss2(p, side, &above, x, y, z) < below2) {
                    sol = &above;
                }
            }
        }
    }
    q_mdeg[XGO_JOINT_KNEE] = clamp_joint(p, XGO_JOINT_KNEE, sol->q[XGO_JOINT_KNEE]);
    q_mdeg[XGO_JOINT_HIP] = clamp_joint(p, XGO_JOINT_HIP, sol->q[XGO_JOINT_HIP]);
    q_mdeg[XGO_JOINT_ABAD] = clamp_joint(p, XGO_JOINT_ABAD, sol->q[XGO_JOINT_ABAD]);
    return (sol->projected || inside_axis_cylinder) ? XGO_IK_PROJECTED : XGO_IK_REACHED;
}

int xgo_leg_ik(const xgo_profile_t *p, xgo_leg_t leg, const xgo_vec3_t *foot_um,
               int32_t q_mdeg[XGO_JOINT_COUNT])
{
    planar_t pl;
    planar_init(&pl, p);
    return leg_ik_in(&pl, leg, foot_um, q_mdeg);
}

/* On a 64-bit host (GCC) the four legs' IK written out: each copy knows
 * its leg's side and offsets (tick -60; the stack and flash of an MCU
 * would not take four copies). */
#if XGO_CORE_DIV64_NATIVE && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8
#define UNROLL_LEGS _Pragma("GCC unroll 4")
#else
#define UNROLL_LEGS
#endif

unsigned xgo_legs_ik(const xgo_profile_t *p, const xgo_vec3_t feet_leg_um[XGO_LEG_COUNT],
                     int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT])
{
    planar_t pl;
    unsigned mask = 0;
    int leg;
    planar_init(&pl, p);
    UNROLL_LEGS
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (leg_ik_in(&pl, (xgo_leg_t)leg, &feet_leg_um[leg], q_mdeg[leg]) != XGO_IK_REACHED) {
            mask |= 1u << leg;
        }
    }
    return mask;
}

void xgo_leg_fk(const xgo_profile_t *p, xgo_leg_t leg, const int32_t q_mdeg[XGO_JOINT_COUNT],
                xgo_vec3_t *foot_um)
{
#if XGO_CORE_NARROW_CPU || XGO_CORE_DIV64_NATIVE
    /* the Mini's knee offset kept (planar_init): one conversion less */
    const xgo_bam_t knee_off = p->knee_offset_mdeg == XGO_MINI_KNEE_OFFSET_MDEG ? (xgo_bam_t)MINI_KNEE_OFF
                                                                               : xgo_mdeg_to_bam(p->knee_offset_mdeg);
#else
    const xgo_bam_t knee_off = xgo_mdeg_to_bam(p->knee_offset_mdeg);
#endif
    fk_bam(p, xgo_leg_side_y(leg), xgo_mdeg_to_bam(q_mdeg[XGO_JOINT_ABAD]),
           xgo_mdeg_to_bam(q_mdeg[XGO_JOINT_KNEE]) + knee_off, xgo_mdeg_to_bam(q_mdeg[XGO_JOINT_HIP]), foot_um);
}

/* ------------------------------------------------------------ body IK */

/* Products of Q30 values |a|, |b| <= 2^30 (sines, cosines and their
 * products), rounded. On a Cortex-M0 in 15-bit pieces (a = ah 2^15 + al,
 * 0 <= al < 2^15): ab = ah bh 2^30 + (ah bl + al bh) 2^15 + al bl, each
 * piece one MULS within int32, the floors nested exactly; elsewhere one
 * 64-bit product. The same value. */
static int32_t mul30(int32_t a, int32_t b)
{
#if XGO_CORE_NARROW_CPU
    const int32_t ah = a >> 15, al = a & 0x7FFF, bh = b >> 15, bl = b & 0x7FFF;
    return ah * bh + ((ah * bl + al * bh + ((al * bl) >> 15) + (1 << 14)) >> 15);
#else
    return (int32_t)round_shift(xgo_mul_wide(a, b), 30);
#endif
}

/* a*b + c*d in Q30, clamped to [-1, 1] (rounding may push |x| past 1). */
static int32_t dot30(int32_t a, int32_t b, int32_t c, int32_t d)
{
#if XGO_CORE_NARROW_CPU
    const int32_t v = dot_pieces(a, b, c, d, 1u << 29);
#else
    const int64_t v = round_shift(xgo_mul_wide(a, b) + xgo_mul_wide(c, d), 30);
#endif
    return v > XGO_Q30_ONE ? XGO_Q30_ONE : (v < -XGO_Q30_ONE ? -XGO_Q30_ONE : (int32_t)v);
}

/* sin and cos of an angle in mdeg; an axis the pose leaves at 0 (often the
 * body's yaw, or all three) needs no table: xgo_sincos(0) is exactly
 * (0, 1) too. */
static void sincos_mdeg(int32_t mdeg, xgo_q30_t *s, xgo_q30_t *c)
{
    if (mdeg == 0) {
        *s = 0;
        *c = XGO_Q30_ONE;
    } else {
        xgo_sincos(xgo_mdeg_to_bam(mdeg), s, c);
    }
}

/* R without yaw from the roll's and pitch's sines and cosines: cos yaw = 1
 * and sin yaw = 0 exactly, so each product of the general formula by them
 * is the other factor and each sum has one term (mul30 and dot30 both
 * round exactly: the same entries), 4 products instead of 14. The rows 0
 * and 2 hold the pitch; row 1, (0, cos roll, -sin roll), does not, and
 * xgo_body_rotation_next leaves it as it is when only the pitch changed. */
static void rotation_pitch_rows(xgo_q30_t sr, xgo_q30_t cr, xgo_q30_t sp, xgo_q30_t cp,
                                xgo_q30_t rot[XGO_ROT_COUNT])
{
    rot[XGO_ROT(0, 0)] = cp;
    rot[XGO_ROT(0, 1)] = mul30(sp, sr);
    rot[XGO_ROT(0, 2)] = mul30(sp, cr);
    rot[XGO_ROT(2, 0)] = -sp;
    rot[XGO_ROT(2, 1)] = mul30(cp, sr);
    rot[XGO_ROT(2, 2)] = mul30(cp, cr);
}

static void rotation_without_yaw(xgo_q30_t sr, xgo_q30_t cr, xgo_q30_t sp, xgo_q30_t cp,
                                 xgo_q30_t rot[XGO_ROT_COUNT])
{
    rotation_pitch_rows(sr, cr, sp, cp, rot);
    rot[XGO_ROT(1, 0)] = 0;
    rot[XGO_ROT(1, 1)] = cr;
    rot[XGO_ROT(1, 2)] = -sr;
}

void xgo_body_rotation(const xgo_body_pose_t *pose, xgo_q30_t rot[XGO_ROT_COUNT])
{
    xgo_q30_t sr, cr, sp, cp, sy, cy;
    int32_t cysp, sysp;
    sincos_mdeg(pose->roll_mdeg, &sr, &cr);
    sincos_mdeg(pose->pitch_mdeg, &sp, &cp);
    if (pose->yaw_mdeg == 0) { /* the usual pose: the gait turns the robot */
        rotation_without_yaw(sr, cr, sp, cp, rot);
        return;
    }
    sincos_mdeg(pose->yaw_mdeg, &sy, &cy);
    cysp = mul30(cy, sp);
    sysp = mul30(sy, sp);
    rot[XGO_ROT(0, 0)] = mul30(cy, cp);
    rot[XGO_ROT(0, 1)] = dot30(cysp, sr, -sy, cr);
    rot[XGO_ROT(0, 2)] = dot30(cysp, cr, sy, sr);
    rot[XGO_ROT(1, 0)] = mul30(sy, cp);
    rot[XGO_ROT(1, 1)] = dot30(sysp, sr, cy, cr);
    rot[XGO_ROT(1, 2)] = dot30(sysp, cr, -cy, sr);
    rot[XGO_ROT(2, 0)] = -sp;
    rot[XGO_ROT(2, 1)] = mul30(cp, sr);
    rot[XGO_ROT(2, 2)] = mul30(cp, cr);
}

void xgo_body_rotation_next(const xgo_body_pose_t *last, const xgo_body_pose_t *pose,
                            xgo_q30_t rot[XGO_ROT_COUNT])
{
    if (pose->yaw_mdeg == 0 && last->yaw_mdeg == 0 && pose->roll_mdeg == last->roll_mdeg) {
        /* last's rotation without yaw holds cos roll at (1, 1) and -sin roll
         * at (1, 2) as they were: only the pitch's sine is new, and the
         * middle row (0, cos roll, -sin roll) stays as it is */
        const xgo_q30_t cr = rot[XGO_ROT(1, 1)], sr = -rot[XGO_ROT(1, 2)];
        xgo_q30_t sp, cp;
        sincos_mdeg(pose->pitch_mdeg, &sp, &cp);
        rotation_pitch_rows(sr, cr, sp, cp, rot);
        return;
    }
    xgo_body_rotation(pose, rot);
}

/* The thigh joint of a leg (leg frame origin) in the body frame from the
 * front left one's (ax, ay): the signs of xgo_leg_side_x / xgo_leg_side_y
 * (profile.c) by the leg's index here, so the body IK's loop makes no
 * calls. */
XGO_ALWAYS_INLINE void leg_origin_of(int leg, int32_t ax, int32_t ay, int32_t *ox, int32_t *oy)
{
    *ox = (leg == XGO_LEG_LF || leg == XGO_LEG_RF) ? ax : -ax;
    *oy = (leg == XGO_LEG_LF || leg == XGO_LEG_LH) ? ay : -ay;
}

static void leg_origin(const xgo_profile_t *p, int leg, int32_t *ox, int32_t *oy)
{
    leg_origin_of(leg, p->hip_x_um, p->hip_y_um + p->abad_offset_um, ox, oy);
}

void xgo_body_ik(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                 const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                 xgo_vec3_t feet_leg_um[XGO_LEG_COUNT])
{
    xgo_q30_t rot[XGO_ROT_COUNT];
    xgo_body_rotation(pose, rot);
    xgo_body_ik_rotated(p, pose, rot, feet_machine_um, feet_leg_um);
}

/* A foot's offset from the body centre in the body IK: on a 64-bit host
 * the 64-bit difference as it is (its products take it as it is, and
 * nothing is cut to 32 bits when it is near: tick -7); elsewhere 32
 * bits. */
#if XGO_CORE_DIV64_NATIVE
typedef int64_t um_diff_t;
#else
typedef int32_t um_diff_t;
#endif

/* round(sum of q[i] * v[i] / 2^18) for three Q18 entries |q| <= 2^18 (the
 * rotation's Q30 entries cut to Q18, rot_q18) and |v| < 2^22 (4 m): the
 * sum S = sum q * v (< 2^42) is exact, its rounding to um the only one.
 * Error: 2^-19 of |v| per term from the Q18 entries (<= 0.9 um over the
 * three at the body's 0.3 m; docs/fixed-point.md). A Cortex-M0 has no
 * widening multiply (xgo_mul_wide is four MULS and carries there), so it
 * forms S in 32-bit pieces, v = vh * 2^11 + vl: rq * vh <= 2^29 and
 * rq * vl < 2^29, three of each fit; elsewhere S is three 64-bit products.
 * Both are exact: the same result everywhere. Inline: twelve a tick in
 * the body IK, where a call cost a third of it on the M0. */
XGO_ALWAYS_INLINE int32_t dot3_q18(int32_t q0, int32_t q1, int32_t q2, um_diff_t v0, um_diff_t v1, um_diff_t v2)
{
#if XGO_CORE_NARROW_CPU
    const int32_t hi = q0 * (v0 >> 11) + q1 * (v1 >> 11) + q2 * (v2 >> 11);
    const int32_t lo = q0 * (v0 & 0x7FF) + q1 * (v1 & 0x7FF) + q2 * (v2 & 0x7FF); /* S = hi 2^11 + lo */
    return (hi >> 7) + ((((hi & 127) << 11) + lo + (1 << 17)) >> 18);
#else
    const int64_t sum = (int64_t)q0 * v0 + (int64_t)q1 * v1 + (int64_t)q2 * v2;
    return (int32_t)((sum + (1 << 17)) >> 18);
#endif
}

/* The same out of line, for the colder body-to-machine rotation (inline,
 * as in the body IK's loop, it would cost flash for little). */
static int32_t dot3_q18_cold(int32_t q0, int32_t q1, int32_t q2, int32_t v0, int32_t v1, int32_t v2)
{
    return dot3_q18(q0, q1, q2, v0, v1, v2);
}

#define NEAR_LIMIT_UM ((1 << 22) - 1)

#if !XGO_CORE_DIV64_NATIVE /* a 64-bit host: body_ik_host's tests below */
/* Whether the exact a - b is within +-NEAR_LIMIT_UM, and if so a - b in
 * *d, all in 32 bits: the difference modulo 2^32 is exact unless a and b
 * differ in sign and it differs from a (an overflow, never near); no
 * 64-bit subtractions and compares, and a value the compiler knows is 32
 * bits (from a 64-bit difference GCC made the Cortex-M3's products below
 * 64 x 64 bits). */
XGO_ALWAYS_INLINE int near_diff(int32_t a, int32_t b, um_diff_t *d)
{
    const uint32_t ua = (uint32_t)a, ub = (uint32_t)b, r = ua - ub;
    *d = r <= (uint32_t)INT32_MAX ? (int32_t)r : -(int32_t)~r - 1; /* two's complement view */
    return ((ua ^ ub) & (ua ^ r)) < 0x80000000u && r + (uint32_t)NEAR_LIMIT_UM <= 2u * (uint32_t)NEAR_LIMIT_UM;
}

/* v within [-2^21, 2^21) (2 m): the difference of two such values is
 * within NEAR_LIMIT_UM. */
XGO_ALWAYS_INLINE int small_um(int32_t v)
{
    return (uint32_t)v + (1u << 21) < (1u << 22);
}

/* near_diff for the three coordinates of foot f and the pose's (px, py,
 * pz): first the usual case, both points within 2 m (pose_small: the
 * pose's), where the differences need no check (tick: M0 -42, M3 -92).
 * The same answer and differences either way. */
XGO_ALWAYS_INLINE int near_foot(const xgo_vec3_t *f, int32_t px, int32_t py, int32_t pz, int pose_small,
                                um_diff_t *x, um_diff_t *y, um_diff_t *z)
{
    if (pose_small & small_um(f->x) & small_um(f->y) & small_um(f->z)) {
        *x = f->x - px;
        *y = f->y - py;
        *z = f->z - pz;
        return 1;
    }
    /* (& rather than &&: all three differences are needed anyway) */
    return near_diff(f->x, px, x) & near_diff(f->y, py, y) & near_diff(f->z, pz, z);
}
#endif

static int near3(int32_t a, int32_t b, int32_t c)
{
    return a <= NEAR_LIMIT_UM && a >= -NEAR_LIMIT_UM && b <= NEAR_LIMIT_UM && b >= -NEAR_LIMIT_UM &&
           c <= NEAR_LIMIT_UM && c >= -NEAR_LIMIT_UM;
}

/* The same for any int32 v (64-bit products; far coordinates only). */
static int64_t dot3_q30_far(xgo_q30_t r0, xgo_q30_t r1, xgo_q30_t r2, int32_t v0, int32_t v1, int32_t v2)
{
    return round_shift(mul_cold(r0, v0) + mul_cold(r1, v1) + mul_cold(r2, v2), 30);
}

/* The rotation's entries in Q18, rounded (|q| <= 2^18). */
#define ROT_Q18(i) q[i] = (rot[i] + (1 << 11)) >> 12

static void rot_q18(const xgo_q30_t rot[XGO_ROT_COUNT], int32_t q[XGO_ROT_COUNT])
{
    /* written out: the loop's overhead was as much as its work */
    ROT_Q18(0);
    ROT_Q18(1);
    ROT_Q18(2);
    ROT_Q18(3);
    ROT_Q18(4);
    ROT_Q18(5);
    ROT_Q18(6);
    ROT_Q18(7);
    ROT_Q18(8);
}

#undef ROT_Q18

#if !XGO_CORE_DIV64_NATIVE
/* One foot of the body IK beyond the near range (4 m): the difference
 * saturated to int32 so the products stay within 2^61, Q30 entries. Out
 * of line: it would crowd the near path's registers. */
XGO_OWN_FRAME static void body_foot_far(const xgo_q30_t rot[XGO_ROT_COUNT], const xgo_body_pose_t *pose,
                                        const xgo_vec3_t *f, int32_t ox, int32_t oy, xgo_vec3_t *out)
{
    const int32_t x = sat_i32((int64_t)f->x - pose->x_um), y = sat_i32((int64_t)f->y - pose->y_um),
                  z = sat_i32((int64_t)f->z - pose->z_um);
    out->x = sat_i32(dot3_q30_far(rot[0], rot[3], rot[6], x, y, z) - ox);
    out->y = sat_i32(dot3_q30_far(rot[1], rot[4], rot[7], x, y, z) - oy);
    out->z = sat_i32(-dot3_q30_far(rot[2], rot[5], rot[8], x, y, z));
}
#else
/* body_foot_far from the 64-bit differences (exact: f - p of two int32),
 * so that the near path keeps nothing else of the foot live. */
XGO_OWN_FRAME static void body_diff_far(const xgo_q30_t rot[XGO_ROT_COUNT], int64_t dx, int64_t dy, int64_t dz,
                                        int32_t ox, int32_t oy, xgo_vec3_t *out)
{
    const int32_t x = sat_i32(dx), y = sat_i32(dy), z = sat_i32(dz);
    out->x = sat_i32(dot3_q30_far(rot[0], rot[3], rot[6], x, y, z) - ox);
    out->y = sat_i32(dot3_q30_far(rot[1], rot[4], rot[7], x, y, z) - oy);
    out->z = sat_i32(-dot3_q30_far(rot[2], rot[5], rot[8], x, y, z));
}

/* |v| <= NEAR_LIMIT_UM (near_diff's range) */
XGO_ALWAYS_INLINE int near64(int64_t v)
{
    return (uint64_t)(v + NEAR_LIMIT_UM) <= 2u * NEAR_LIMIT_UM;
}

/* The body IK's feet on a 64-bit host: the differences in 64 bits, then
 * whether each is within 2 m, [-2^21, 2^21), in one test (the or of the
 * offset differences has no bit from 2^22 up only if each has none; the
 * usual case), else near_diff's exact range, else the far form: the same
 * answer and values as the MCU's loop in xgo_body_ik_rotated (tick:
 * 7 instructions a foot for the test instead of 19, no copies of the feet
 * kept for the far path). q3 is q[3] apart: R(1, 0) is 0 without yaw
 * (rotation_without_yaw), and the usual call passes a literal 0, which
 * drops its four products. */
XGO_ALWAYS_INLINE void body_ik_host(const xgo_body_pose_t *pose, const xgo_q30_t rot[XGO_ROT_COUNT],
                                    const int32_t q[XGO_ROT_COUNT], int32_t q3, int32_t ax, int32_t ay,
                                    const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                                    xgo_vec3_t feet_leg_um[XGO_LEG_COUNT])
{
    const int64_t px = pose->x_um, py = pose->y_um, pz = pose->z_um;
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        const xgo_vec3_t *f = &feet_machine_um[leg];
        xgo_vec3_t *out = &feet_leg_um[leg];
        const int64_t x = f->x - px, y = f->y - py, z = f->z - pz;
        int32_t ox, oy;
        leg_origin_of(leg, ax, ay, &ox, &oy);
        if ((((x + (1 << 21)) | (y + (1 << 21)) | (z + (1 << 21))) & ~(int64_t)((1 << 22) - 1)) == 0 ||
            (near64(x) && near64(y) && near64(z))) {
            out->x = (int32_t)((q[0] * x + (int64_t)q3 * y + q[6] * z + (1 << 17)) >> 18) - ox;
            out->y = (int32_t)((q[1] * x + (int64_t)q[4] * y + q[7] * z + (1 << 17)) >> 18) - oy;
            out->z = -(int32_t)((q[2] * x + (int64_t)q[5] * y + q[8] * z + (1 << 17)) >> 18);
        } else {
            body_diff_far(rot, x, y, z, ox, oy, out);
        }
    }
}
#endif

void xgo_body_ik_rotated(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                         const xgo_q30_t rot[XGO_ROT_COUNT],
                         const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                         xgo_vec3_t feet_leg_um[XGO_LEG_COUNT])
{
#if XGO_CORE_DIV64_NATIVE
    int32_t q[XGO_ROT_COUNT];
    rot_q18(rot, q);
    if (q[3] == 0) {
        body_ik_host(pose, rot, q, 0, p->hip_x_um, p->hip_y_um + p->abad_offset_um, feet_machine_um, feet_leg_um);
    } else {
        body_ik_host(pose, rot, q, q[3], p->hip_x_um, p->hip_y_um + p->abad_offset_um, feet_machine_um,
                     feet_leg_um);
    }
#else
    int32_t q[XGO_ROT_COUNT];
    /* read once: the stores below could alias them for the compiler */
    const int32_t px = pose->x_um, py = pose->y_um, pz = pose->z_um;
    const int32_t ax = p->hip_x_um, ay = p->hip_y_um + p->abad_offset_um;
    const int pose_small = small_um(px) & small_um(py) & small_um(pz);
    int leg;
    rot_q18(rot, q);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        /* foot relative to the body centre, in machine axes, then into body
         * axes (R^T v) and the leg frame (origin at the thigh joint, z down) */
        const xgo_vec3_t *f = &feet_machine_um[leg];
        xgo_vec3_t *out = &feet_leg_um[leg];
        um_diff_t x, y, z;
        int32_t ox, oy;
        leg_origin_of(leg, ax, ay, &ox, &oy);
        if (near_foot(f, px, py, pz, pose_small, &x, &y, &z)) { /* every value below 2^24: no saturation */
            out->x = dot3_q18(q[0], q[3], q[6], x, y, z) - ox;
            out->y = dot3_q18(q[1], q[4], q[7], x, y, z) - oy;
            out->z = -dot3_q18(q[2], q[5], q[8], x, y, z);
        } else {
            body_foot_far(rot, pose, f, ox, oy, out);
        }
    }
#endif
}

void xgo_leg_to_body(const xgo_profile_t *p, xgo_leg_t leg, const xgo_vec3_t *foot_leg_um,
                     xgo_vec3_t *foot_body_um)
{
    int32_t ox, oy;
    leg_origin(p, (int)leg, &ox, &oy);
    foot_body_um->x = sat_i32((int64_t)foot_leg_um->x + ox);
    foot_body_um->y = sat_i32((int64_t)foot_leg_um->y + oy);
    foot_body_um->z = sat_i32(-(int64_t)foot_leg_um->z);
}

void xgo_body_to_machine(const xgo_body_pose_t *pose, const xgo_vec3_t body_um[XGO_LEG_COUNT],
                         xgo_vec3_t machine_um[XGO_LEG_COUNT])
{
    xgo_q30_t rot[XGO_ROT_COUNT];
    xgo_body_rotation(pose, rot);
    xgo_body_to_machine_rotated(pose, rot, body_um, machine_um);
}

void xgo_body_to_machine_rotated(const xgo_body_pose_t *pose, const xgo_q30_t rot[XGO_ROT_COUNT],
                                 const xgo_vec3_t body_um[XGO_LEG_COUNT],
                                 xgo_vec3_t machine_um[XGO_LEG_COUNT])
{
    xgo_body_to_machine_legs(pose, rot, 0x0Fu, body_um, machine_um);
}

void xgo_body_to_machine_legs(const xgo_body_pose_t *pose, const xgo_q30_t rot[XGO_ROT_COUNT], unsigned legs,
                              const xgo_vec3_t body_um[XGO_LEG_COUNT], xgo_vec3_t machine_um[XGO_LEG_COUNT])
{
    int32_t q[XGO_ROT_COUNT];
    int leg;
    rot_q18(rot, q);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t bx, by, bz;
        if (((legs >> leg) & 1u) == 0) {
            /* the body centre's image (what a foot at (0, 0, 0) gives); the
             * leg's body_um is not read */
            machine_um[leg].x = pose->x_um;
            machine_um[leg].y = pose->y_um;
            machine_um[leg].z = pose->z_um;
            continue;
        }
        bx = body_um[leg].x;
        by = body_um[leg].y;
        bz = body_um[leg].z;
        if (near3(bx, by, bz)) {
            machine_um[leg].x = sat_i32((int64_t)dot3_q18_cold(q[0], q[1], q[2], bx, by, bz) + pose->x_um);
            machine_um[leg].y = sat_i32((int64_t)dot3_q18_cold(q[3], q[4], q[5], bx, by, bz) + pose->y_um);
            machine_um[leg].z = sat_i32((int64_t)dot3_q18_cold(q[6], q[7], q[8], bx, by, bz) + pose->z_um);
        } else {
            machine_um[leg].x = sat_i32(dot3_q30_far(rot[0], rot[1], rot[2], bx, by, bz) + pose->x_um);
            machine_um[leg].y = sat_i32(dot3_q30_far(rot[3], rot[4], rot[5], bx, by, bz) + pose->y_um);
            machine_um[leg].z = sat_i32(dot3_q30_far(rot[6], rot[7], rot[8], bx, by, bz) + pose->z_um);
        }
    }
}

unsigned xgo_body_to_joints(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                            const xgo_vec3_t feet_machine_um[XGO_LEG_COUNT],
                            int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT])
{
    xgo_vec3_t feet_leg[XGO_LEG_COUNT];
    xgo_body_ik(p, pose, feet_machine_um, feet_leg);
    return xgo_legs_ik(p, feet_leg, q_mdeg);
}

void xgo_stance_feet(const xgo_profile_t *p, xgo_vec3_t feet_machine_um[XGO_LEG_COUNT])
{
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        feet_machine_um[leg].x = xgo_leg_side_x((xgo_leg_t)leg) * p->hip_x_um;
        feet_machine_um[leg].y = xgo_leg_side_y((xgo_leg_t)leg) * (p->hip_y_um + p->abad_offset_um);
        feet_machine_um[leg].z = 0;
    }
}

void xgo_body_pose_stand(const xgo_profile_t *p, xgo_body_pose_t *pose)
{
    pose->x_um = 0;
    pose->y_um = 0;
    pose->z_um = p->stand_height_um;
    pose->roll_mdeg = 0;
    pose->pitch_mdeg = 0;
    pose->yaw_mdeg = 0;
}
