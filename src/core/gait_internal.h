/*
 * gait_internal.h - what the gait's files share (private to gait.c and
 * gait_governor.c): the gait tables' type, the per-tick context the stages
 * pass along, and the small arithmetic helpers of the hot paths (inline).
 * The model and the notation are at the top of gait.c.
 */
#ifndef XGO_CORE_GAIT_INTERNAL_H
#define XGO_CORE_GAIT_INTERNAL_H

#include <stdint.h>

#include "xgo/config.h" /* XGO_TICK_HZ */
#include "gait.h"
#include "wide.h"

#define TICKS_PER_S XGO_TICK_HZ

/* mdeg/s -> rad/s in Q24: pi / 180000 * 2^24 * 2^16 (applied with q = 16). */
#define K_MDEG_TO_RAD_Q24_Q16 19190957

typedef struct gait_table_s {
    uint32_t swing;         /* swing fraction S of the cycle, Q32 */
    uint32_t inv_swing_q16; /* 1 / S, Q16 */
    uint32_t lift[XGO_LEG_COUNT]; /* lift-off phase per leg, Q32 */
    uint32_t k_rate;        /* D * 2^31 / TICKS_PER_S (D = 1 - S, the duty factor) */
    uint32_t k_tau;         /* D * 2^39 / TICKS_PER_S */
    uint32_t k_swing;       /* S * 2^40 / TICKS_PER_S (swing time, see swing_time_q16) */
    uint32_t rate[XGO_PACE_COUNT]; /* nominal cadence per pace */
    uint32_t rate_max;      /* cadence cap */
    uint32_t k_half;        /* shortest period (ms) * 2^22 / 1000, see half_time_q16 */
    uint16_t period_ms[XGO_PACE_COUNT];
    int32_t height_um;      /* swing height */
    uint8_t timing;         /* tables with the same timing switch at once */
    uint8_t duty_pct;
    int32_t dwell_q26;      /* delta: share of the swing at either end in which the foot
                               moves with the ground (rises only), Q26; see swing_step */
    int32_t dwell_gain_q26; /* 1 / (1 - 2 delta), Q26 */
} gait_table_t;

/* The swing curve's weights at one point of the swing (swing_weights in
 * gait.c): legs that lift together, a trot's diagonal pairs, share them. */
typedef struct gait_swing_weights_s {
    uint32_t theta;   /* phase since lift-off they are for */
    int32_t h;        /* share of the way from lift-off to landing point, Q26 */
    int32_t ca, cb;   /* weights of the two end tangents, Q26 */
    int32_t s2;       /* sin^2(pi psi): the share of the step height, Q30 */
    int32_t follow;   /* share of the gap the landing point follows, Q26 */
} gait_swing_weights_t;

/* One tick's working state, filled stage by stage (xgo_gait_tick). */
typedef struct gait_tick_s {
    /* the command, limited (limit stage) */
    int32_t target[3];   /* vx, vy (um/s), vyaw (mdeg/s) the ramp heads for */
    int32_t mark;        /* mark-time swing height, 0 = off */
    int32_t height;      /* swing height asked for, 0 = the table's */
    uint8_t want_type;   /* gait table asked for */
    uint8_t pace;
    int resting;         /* zero command: stop once every foot is home */
    /* the table in use and the produced velocity (ramp stage) */
    const gait_table_t *t;
    uint32_t hx, hy;     /* half-stride budget, um */
    int32_t reach_y;     /* y reach the planted feet grow to (transient_rate's
                            pass; 0: ramp_velocity grew them already) */
    int32_t vel[2];      /* produced vx, vy */
    int32_t w_q24;       /* produced yaw rate, rad/s Q24 */
#if XGO_CORE_NARROW_CPU
    int32_t w_hi;        /* w_q24 >> 16 and its low 16 bits, for tick_foot_velocity; */
    uint32_t w_lo;       /* w_hi = INT32_MIN: |w_q24| >= 2^26 (the general product) */
#endif
    /* the cadence (cadence stage) */
    uint32_t tau_q16;    /* half the stance time at the fitted cadence, s Q16 */
    uint32_t swing_q16;  /* the swing's duration at this tick's rate, s Q16 */
    uint32_t tau2_q16;   /* tau^2 / 2, s^2 Q16 */
    int have_tau;        /* tau_q16, tau2_q16 hold them (worked out when a
                            touchdown point is: touchdown_q8) */
    uint32_t rate;       /* phase advance of this tick */
    int32_t vf[XGO_LEG_COUNT][2]; /* ground velocity of each planted foot */
    /* trajectories */
    int have_weights;             /* weights holds a swing leg's this tick */
    gait_swing_weights_t weights;
} gait_tick_t;

/* (a * b) / 2^q rounded, 1 <= q <= 31: xgo_mul_q without the saturation
 * (it is the hot spot: about 80 a trotting tick). Every use has
 * |a * b| < 2^56 and a result well inside int32 by the clamps on the
 * command (twice the vendor ranges), the stance (+-200 mm) and the reach
 * box. On a Cortex-M0 the product is wide.h's four 16-bit MULS and the
 * rounding shift works on its two 32-bit words: libgcc's 64 x 64 multiply
 * and 64-bit shifts by a variable q (the compiler does not inline this at
 * -Os) cost about three times as much. Both forms give the same low 32 bits
 * of the shifted sum, so the same result. mul_q_inline: the same, always
 * inline (at a constant q the shifts fold): for the few sites that run
 * several times a tick inside one small function (gait_foot_velocity). */
XGO_ALWAYS_INLINE int32_t mul_q_inline(int32_t a, int32_t b, unsigned q)
{
#if XGO_CORE_NARROW_CPU
    /* floor((p + 2^(q-1)) / 2^q) = floor(p / 2^q) + bit q-1 of p: no carry
     * to move between the words */
    const uint64_t p = (uint64_t)xgo_mul_wide(a, b);
    const uint32_t lo = (uint32_t)p, hi = (uint32_t)(p >> 32);
    return (int32_t)(((lo >> q) | (hi << (32u - q))) + ((lo >> (q - 1u)) & 1u));
#else
    return (int32_t)(((int64_t)a * b + ((int64_t)1 << (q - 1u))) >> q);
#endif
}

static inline int32_t mul_q(int32_t a, int32_t b, unsigned q)
{
    return mul_q_inline(a, b, q);
}

/* mul_q(a, b, 26) for 0 <= a <= 2^26 and |b| < 2^30: the swing's basis
 * (a Q26 value of [0, 1] - its progress, powers of it - times a Q26
 * polynomial of it below 10). On a Cortex-M0 from 13-bit pieces, a = ah
 * 2^13 + al, b = bh 2^13 + bl (0 <= al, bl < 2^13; ah <= 2^13, |bh| <
 * 2^17): ab = P 2^26 + M 2^13 + L with P = ah bh (|P| <= 2^30), M = ah bl
 * + al bh (|M| < 2^30 + 2^26) and L = al bl (< 2^26), so
 *   floor((ab + 2^25) / 2^26) = P + floor((M + floor((L + 2^25) / 2^13)) / 2^13),
 * every term within int32: four MULS instead of a call of the wide
 * product. Elsewhere mul_q. The same value; test_gait_arith compares. */
XGO_INLINE_FAST int32_t mul_q26_unit(int32_t a, int32_t b)
{
#if XGO_CORE_NARROW_CPU
    const int32_t ah = a >> 13, al = a & 8191, bh = b >> 13, bl = b & 8191;
    return ah * bh + ((ah * bl + al * bh + ((al * bl + (1 << 25)) >> 13)) >> 13);
#else
    return mul_q(a, b, 26u);
#endif
}

/* mul_q(w, b, 26) for a swing curve's weight w and a span b (1/256 um):
 * the same pieces as mul_q26_unit where they fit int32, |w| < 2^27 and |b|
 * < 2^29 (every weight is within [-1, 1] and every span within a few
 * hundred mm: always while walking), else mul_q. (|P| <= 2^30 and |M| <
 * 2^29 + 2^27 there.) The same value; test_gait_arith compares. */
XGO_INLINE_FAST int32_t mul_q26_weight(int32_t w, int32_t b)
{
#if XGO_CORE_NARROW_CPU
    if ((w >> 27) == (w >> 31) && (b >> 29) == (b >> 31)) {
        const int32_t wh = w >> 13, wl = w & 8191, bh = b >> 13, bl = b & 8191;
        return wh * bh + ((wh * bl + wl * bh + ((wl * bl + (1 << 25)) >> 13)) >> 13);
    }
#endif
    return mul_q(w, b, 26u);
}

/* mul_q(s, s, 30) for |s| <= 2^30 (a sine's square: the swing's lift).
 * On a Cortex-M0 from 15-bit pieces of u = |s| = uh 2^15 + ul (uh <=
 * 2^15): u^2 = uh^2 2^30 + 2 uh ul 2^15 + ul^2, so floor((u^2 + 2^29) /
 * 2^30) = uh^2 + floor((2 uh ul + floor((ul^2 + 2^29) / 2^15)) / 2^15),
 * the sum below 2^31 + 2^16 (unsigned): three MULS instead of a
 * call of the wide product. The same value; test_gait_arith compares. */
XGO_INLINE_FAST int32_t square_q30(int32_t s)
{
#if XGO_CORE_NARROW_CPU
    const uint32_t u = s < 0 ? 0u - (uint32_t)s : (uint32_t)s;
    const uint32_t uh = u >> 15, ul = u & 0x7FFFu;
    return (int32_t)(uh * uh + ((2u * uh * ul + ((ul * ul + (1u << 29)) >> 15)) >> 15));
#else
    return mul_q(s, s, 30u);
#endif
}

/* um/s -> 1/256 um per tick: 256 / TICKS_PER_S * 2^31, rounded (applied
 * with q = 31). */
#define K_UMS_TO_Q8_TICK_Q31 ((int32_t)((((uint64_t)256u << 31) + TICKS_PER_S / 2u) / TICKS_PER_S))

/* mul_q(v, K_UMS_TO_Q8_TICK_Q31, 31): a velocity v (um/s) as 1/256 um per
 * tick (a planted foot's step: four a trotting tick). On a Cortex-M0, for
 * |v| < 2^20 (1 m/s: every foot's), from K's 10-bit pieces
 * (xgo_mul_round_pieces10, wide.h; K >> 20 < 2^11, checked below): three
 * MULS by constants instead of a call of the wide product.
 * test_gait_arith compares it with mul_q. */
XGO_INLINE_FAST int32_t ums_to_q8_tick(int32_t v)
{
#if XGO_CORE_NARROW_CPU
    if ((v >> 20) == (v >> 31)) {
        return xgo_mul_round_pieces10(v, K_UMS_TO_Q8_TICK_Q31, 31u);
    }
#endif
    return mul_q(v, K_UMS_TO_Q8_TICK_Q31, 31u);
}
typedef char xgo_gait_ums_pieces_fit_[(K_UMS_TO_Q8_TICK_Q31 >> 20) < 2048 ? 1 : -1];

/* mul_q(a, b, q) for 0 <= b < 2^16, any a, 1 <= q <= 31: the same result,
 * bit for bit (where mul_q's result wraps, this one wraps alike; callers
 * state why their b fits). On a Cortex-M0 the short factor saves half of the
 * product: a = ah 2^16 + al (ah = a >> 16, 0 <= al < 2^16) gives
 * a b = (ah b) 2^16 + al b, two MULS with |ah b| <= 2^15 (2^16 - 1) and
 * 0 <= al b <= (2^16 - 1)^2; the rounding is taken on the two words:
 *   q >= 16: floor((a b + 2^(q-1)) / 2^q)
 *          = floor((ah b + floor((al b + 2^(q-1)) / 2^16)) / 2^(q-16))
 *   q < 16:  = ah b 2^(16-q) + floor((al b + 2^(q-1)) / 2^q)   (mod 2^32)
 * (floor(floor(x / m) / n) = floor(x / (m n)); for q > 16 the 2^(q-1) is a
 * multiple of 2^16 and is added after the shift, where the low word cannot
 * overflow; the sum ah b + 2^16 + 2^14 stays below 2^31). Inline with q a
 * constant: about 12 instructions instead of a 45-instruction call.
 * test/test_gait_arith.c sweeps the edges against a 64-bit product.
 * Elsewhere (one widening multiply instruction): plain mul_q. */
XGO_ALWAYS_INLINE int32_t mul_q_u16(int32_t a, uint32_t b, unsigned q)
{
#if XGO_CORE_NARROW_CPU
    const uint32_t hi = (uint32_t)((a >> 16) * (int32_t)b);
    const uint32_t lo = ((uint32_t)a & 0xFFFFu) * b;
    if (q > 16u) {
        return (int32_t)(hi + (lo >> 16) + (1u << (q - 17u))) >> (q - 16u);
    }
    if (q == 16u) {
        return (int32_t)(hi + ((lo + 0x8000u) >> 16));
    }
    return (int32_t)((hi << (16u - q)) + ((lo + (1u << (q - 1u))) >> q));
#else
    return mul_q(a, (int32_t)b, q);
#endif
}

/* (int32_t)((int64_t)v * lambda / 65536), C's division (toward zero), for
 * 0 <= lambda <= 2^16 and |v| < 2^31: a velocity scaled by the cadence cap
 * or the governor, every tick they limit it. On a Cortex-M0 in 32 bits, with
 * u = |v| = uh 2^16 + ul: floor(u lambda / 2^16) = uh lambda + floor(ul
 * lambda / 2^16), each product below 2^32 (no library multiply); elsewhere
 * the plain product. test/test_gait_arith.c checks it against the latter. */
XGO_INLINE_FAST int32_t gait_scale_q16(int32_t v, int32_t lambda)
{
#if XGO_CORE_NARROW_CPU
    const uint32_t u = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    const uint32_t q = (u >> 16) * (uint32_t)lambda + (((u & 0xFFFFu) * (uint32_t)lambda) >> 16);
    return v < 0 ? -(int32_t)q : (int32_t)q;
#else
    return (int32_t)(((int64_t)v * lambda) / 65536);
#endif
}

/* mul_q(w, p, 24) for a yaw rate w (rad/s Q24) times a position p (um):
 * the same result, bit for bit. On a Cortex-M0, when |w| < 2^26 (always:
 * yaw_q24 of a clamped rate, 200 deg/s = 58.6e6) and |p| < 2^20 (a point
 * within a metre of the body: always, by the clamps), three MULS do:
 * with w = wh 2^16 + wl and p = ph 2^16 + pl (wl, pl in [0, 2^16)),
 *   w p = (wh p + wl ph) 2^16 + wl pl,  |wh p| <= 2^30, |wl ph| < 2^20,
 * so floor((w p + 2^23) / 2^24) = (wh p + wl ph + floor(wl pl / 2^16) + 2^7) >> 8;
 * anything else takes the general product. test_gait_arith sweeps both. */
XGO_INLINE_FAST int32_t mul_w_q24(int32_t w, int32_t p)
{
#if XGO_CORE_NARROW_CPU
    if ((uint32_t)w + (1u << 26) < (1u << 27) && (uint32_t)p + (1u << 20) < (1u << 21)) {
        const int32_t wh = w >> 16, ph = p >> 16;
        const uint32_t wl = (uint32_t)w & 0xFFFFu, pl = (uint32_t)p & 0xFFFFu;
        return (wh * p + (int32_t)wl * ph + (int32_t)((wl * pl) >> 16) + (1 << 7)) >> 8;
    }
    return mul_q(w, p, 24u);
#else
    return mul_q_inline(w, p, 24u);
#endif
}

static inline uint32_t abs_u(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/* The transient rule's test travel > room (gait.c, transient_rate), with
 * travel = s r (a planted foot's speed s in um/s times r, the phase left)
 * and room = TICKS_PER_S d rate (d um to the edge of its budget), is two
 * 32 x 32 -> 64 products: on a Cortex-M0 four MULS each. Most feet are far
 * from the edge, and 32 bits settle them: travel <= s ((r >> 20) + 1) 2^20
 * and room >= TICKS_PER_S d (rate >> 20) 2^20, so when the first factor is
 * at most the second, travel <= room. Both fit 32 bits when s < 2^20
 * (1 m/s), d < 2^17 (131 mm) and rate >> 20 < 64 (every cap is below:
 * 2^13 / 220 ms; TICKS_PER_S d (rate >> 20) < 500 2^17 64 < 2^32). Returns
 * 1 when that shows travel <= room, 0 when the exact test must run.
 * test_gait_arith checks it never says 1 where travel > room. */
static inline int gait_quick_fit(uint32_t s, uint32_t r, uint32_t d, uint32_t rate)
{
    return s < (1u << 20) && d < (1u << 17) && (rate >> 20) < 64u &&
           s * ((r >> 20) + 1u) <= (uint32_t)TICKS_PER_S * d * (rate >> 20);
}

/* Foot velocity relative to the ground for a point (x, y) of the body:
 * v + w x p, in um/s. w in rad/s Q24. About ten a tick: one copy (gait.c)
 * with its two products inline. */
void gait_foot_velocity(const int32_t v[2], int32_t w_q24, int32_t x_um, int32_t y_um, int32_t out[2]);

/* gait_foot_velocity at this tick's velocity (x->vel, x->w_q24): the same
 * result. On a Cortex-M0 the yaw rate's halves are split once a tick
 * (x->w_hi, x->w_lo: mul_w_q24's three MULS per product then need only the
 * point's), not in each of the tick's eight calls. */
#if XGO_CORE_NARROW_CPU
void gait_tick_foot_velocity(const gait_tick_t *x, int32_t x_um, int32_t y_um, int32_t out[2]);
#else
XGO_ALWAYS_INLINE void gait_tick_foot_velocity(const gait_tick_t *x, int32_t x_um, int32_t y_um, int32_t out[2])
{
    gait_foot_velocity(x->vel, x->w_q24, x_um, y_um, out);
}
#endif

/* mul_q(w, K, 16) with K = K_MDEG_TO_RAD_Q24_Q16 = Kh 2^16 + Kl: w K =
 * (w Kh) 2^16 + w Kl exactly, and (w Kh) 2^16 is a multiple of 2^16, so the
 * rounded shift is w Kh + mul_q(w, Kl, 16), modulo 2^32 as mul_q's: the
 * same bits for every w. On a Cortex-M0 one MULS and the short product
 * (mul_q_u16) instead of a full one; elsewhere plain mul_q. */
#define K_MDEG_TO_RAD_HI ((int32_t)(K_MDEG_TO_RAD_Q24_Q16 >> 16))
#define K_MDEG_TO_RAD_LO ((uint32_t)K_MDEG_TO_RAD_Q24_Q16 & 0xFFFFu)

static inline int32_t yaw_q24(int32_t w_mdeg_s)
{
#if XGO_CORE_NARROW_CPU
    return (int32_t)((uint32_t)w_mdeg_s * (uint32_t)K_MDEG_TO_RAD_HI +
                     (uint32_t)mul_q_u16(w_mdeg_s, K_MDEG_TO_RAD_LO, 16u));
#else
    return mul_q(w_mdeg_s, K_MDEG_TO_RAD_Q24_Q16, 16u);
#endif
}

/* Half the time (s, Q16) a planted foot with r phase left stays down at the
 * capped cadence of table t: r / rate_max ticks, halved (k_half does not
 * depend on the tick rate). */
static inline uint32_t half_time_q16(const gait_table_t *t, uint32_t r)
{
    return (uint32_t)(xgo_umul_wide(r, t->k_half) >> 39);
}

/* The y widening (um) of the stride budget and of the reach box under yaw:
 * min(|w|, 100 deg/s) * 14 mm / (100 deg/s), rounded down (gait.h; the
 * typedef below stops the build if those constants change). It is
 * floor(7 yaw / 50) = floor(floor(7 yaw / 2) / 25). On a Cortex-M0 (no divide
 * instruction: a libgcc call of about 100 instructions, twice a tick) the
 * last division is a reciprocal multiply: for y = floor(7 yaw / 2) <= 350000,
 * floor(y 5243 / 2^17) exceeds floor(y / 25) by at most y 3 / (25 2^17) < 0.33
 * (5243 = (2^17 + 3) / 25; y 5243 < 2^31), so by 0 or 1, which one
 * comparison takes back. test_gait_arith checks every yaw. */
typedef char gait_yaw_widening_is_7_in_50[(XGO_GAIT_YAW_HALF_STRIDE_Y_UM == 14000 &&
                                           XGO_GAIT_YAW_REACH_Y_UM == 14000 &&
                                           XGO_GAIT_YAW_REF_MDEG_S == 100000) ? 1 : -1];

static inline uint32_t gait_yaw_widening_um(int32_t w_mdeg_s)
{
    uint32_t yaw = abs_u(w_mdeg_s);
    if (yaw > (uint32_t)XGO_GAIT_YAW_REF_MDEG_S) {
        yaw = XGO_GAIT_YAW_REF_MDEG_S;
    }
#if XGO_CORE_NARROW_CPU
    {
        const uint32_t y = (yaw * 7u) >> 1;
        const uint32_t q = (y * 5243u) >> 17;
        return q * 25u > y ? q - 1u : q;
    }
#else
    return yaw * (uint32_t)XGO_GAIT_YAW_REACH_Y_UM / (uint32_t)XGO_GAIT_YAW_REF_MDEG_S;
#endif
}

/* Reach box of a stance foot (um) for yaw rate w: x fixed, y widened by the
 * yaw share. */
static inline int32_t gait_reach_y(int32_t w_mdeg_s)
{
    return XGO_GAIT_REACH_Y_UM + (int32_t)gait_yaw_widening_um(w_mdeg_s);
}

/* Midpoint of the rest of a planted foot's path (um), estimated with the
 * velocity (v, w): q = p - (v + w x p) * T/2. Under yaw the path is an arc;
 * the ground velocity at q is the foot's mean velocity over the rest of its
 * stance to second order, and it is linear in (v, w) for a fixed q.
 * gait_midpoint_of: the same given the foot's ground velocity f. */
static inline void gait_midpoint_of(const xgo_gait_t *g, int leg, const int32_t f[2],
                                    uint32_t half_q16, int32_t q[2])
{
    /* half_q16 < 2^14 (half_time_q16: r < 2^32, k_half < 2^21) */
    q[0] = (g->pos_q8[leg][0] >> 8) - mul_q_u16(f[0], half_q16, 16u);
    q[1] = (g->pos_q8[leg][1] >> 8) - mul_q_u16(f[1], half_q16, 16u);
}

static inline void gait_stance_midpoint(const xgo_gait_t *g, int leg, const int32_t v[2],
                                        int32_t w_q24, uint32_t half_q16, int32_t q[2])
{
    int32_t f[2];
    gait_foot_velocity(v, w_q24, g->pos_q8[leg][0] >> 8, g->pos_q8[leg][1] >> 8, f);
    gait_midpoint_of(g, leg, f, half_q16, q);
}

/* ---- the governor (gait_governor.c) ---- */

/* The velocity ramp, governed: moves g->v_ramp toward prop as far as every
 * planted foot can absorb before its lift-off (counts governed_ticks and
 * outside_ticks). */
void gait_governed_ramp(xgo_gait_t *g, const gait_table_t *t, const int32_t prop[3]);

/* Would the velocity v fit every planted foot under table n entered at
 * phase p (legs lifting at p excluded)? */
int gait_switch_fits(const xgo_gait_t *g, const gait_table_t *n, uint32_t p, uint32_t rate,
                     const int32_t v[3]);

#endif /* XGO_CORE_GAIT_INTERNAL_H */
