/*
 * gait.c - phase-based gait generator (see xgo/gait.h and docs/gait.md).
 *
 * One master phase (uint32, 2^32 = one cycle) advances every tick by the
 * cadence `rate`. Leg i lifts off when the phase crosses lift[i]; it swings
 * while theta = phase - lift[i] < swing (the swing fraction of the cycle) and
 * is in stance for the rest of the cycle. Stance feet are integrated with the
 * ground velocity -(v + w x p); swing feet are interpolated from the lift-off
 * point to a touchdown point that tracks the current velocity (Raibert:
 * half the stance travel ahead of the stance point).
 *
 * The cadence is the largest of
 *   - the nominal rate of the gait and pace (slewed after changes),
 *   - the fit rate: the stride |v_foot| * T_stance must fit the half-stride
 *     budget (x: 32 mm; y: 16.5 mm + yaw share) around the stance point,
 *     with at most 30 degrees of body turn per stance and the stance arc's
 *     second-order extent included,
 *   - the transient rate: every stance foot must reach its lift-off before
 *     it crosses the edge of that budget at its current velocity;
 * capped per gait. If the fit rate of the command exceeds the cap the
 * command is scaled down (never inside the vendor ranges). A governor lets
 * the velocity ramp only as far as every planted foot can still finish its
 * stance inside its reach box at the capped cadence.
 *
 * Integer arithmetic only. Positions are kept in 1/256 um so that slow
 * velocities integrate without rounding drift.
 */
#include "xgo/gait.h"

#include "xgo/config.h" /* XGO_TICK_HZ */
#include "xgo/fixed.h"

/* ------------------------------------------------------------ tables */

#define TICKS_PER_S XGO_TICK_HZ
#define Q32(num, den) ((uint32_t)((4294967296ULL * (uint64_t)(num)) / (uint64_t)(den)))
/* Phase advance per tick for a cycle of ms milliseconds: 2^32 * 1000 /
 * (ms * TICKS_PER_S) (2^33 / ms at 500 Hz). */
#define RATE(ms) ((uint32_t)(4294967296000ULL / ((uint64_t)(ms) * TICKS_PER_S)))
/* Duty D = dn/dd: D * 2^31 / TICKS_PER_S and D * 2^39 / TICKS_PER_S (see
 * fit_rate, tau; D * 2^32 / 1000 and D * 2^40 / 1000 at 500 Hz). */
#define KRATE(dn, dd) ((uint32_t)((2147483648ULL * (uint64_t)(dn)) / ((uint64_t)TICKS_PER_S * (dd))))
#define KHALF(ms) ((uint32_t)(((uint64_t)(ms) << 22) / 1000u))
#define KTAU(dn, dd) ((uint32_t)((549755813888ULL * (uint64_t)(dn)) / ((uint64_t)TICKS_PER_S * (dd))))

typedef struct gait_table_s {
    uint32_t swing;         /* swing fraction S of the cycle, Q32 */
    uint32_t inv_swing_q16; /* 1 / S, Q16 */
    uint32_t lift[XGO_LEG_COUNT]; /* lift-off phase per leg, Q32 */
    uint32_t k_rate;        /* D * 2^31 / TICKS_PER_S (D = 1 - S, the duty factor) */
    uint32_t k_tau;         /* D * 2^39 / TICKS_PER_S */
    uint32_t rate[XGO_PACE_COUNT]; /* nominal cadence per pace */
    uint32_t rate_max;      /* cadence cap */
    uint32_t k_half;        /* shortest period (ms) * 2^22 / 1000, see half_time_q16 */
    uint16_t period_ms[XGO_PACE_COUNT];
    int32_t height_um;      /* swing height */
    uint8_t timing;         /* tables with the same timing switch at once */
    uint8_t duty_pct;
} gait_table_t;

/* Trot: diagonal pairs LF+RH and RF+LH half a cycle apart, duty 0.5.
 * Walk: lateral sequence LH, LF, RH, RF, a quarter cycle apart, duty 0.75.
 * Periods (normal, slow, high) and the shortest allowed period in ms. */
#define TROT_LIFT { 0u, Q32(1, 2), 0u, Q32(1, 2) }
#define WALK_LIFT { Q32(1, 4), Q32(3, 4), Q32(1, 2), 0u }

static const gait_table_t k_tables[XGO_GAIT_TYPE_COUNT] = {
    /* XGO_GAIT_TROT */
    { Q32(1, 2), 2u << 16, TROT_LIFT, KRATE(1, 2), KTAU(1, 2),
      { RATE(400), RATE(600), RATE(300) }, RATE(240), KHALF(240), { 400, 600, 300 },
      20000, 0, 50 },
    /* XGO_GAIT_WALK */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(220), KHALF(220), { 800, 1200, 600 },
      20000, 1, 75 },
    /* XGO_GAIT_HIGH_WALK: the walk's timing, a higher swing */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(220), KHALF(220), { 800, 1200, 600 },
      30000, 1, 75 },
    /* XGO_GAIT_SLOW_TROT: trot pairs, duty 0.6, longer periods */
    { Q32(2, 5), (5u << 16) / 2u, TROT_LIFT, KRATE(3, 5), KTAU(3, 5),
      { RATE(600), RATE(800), RATE(450) }, RATE(280), KHALF(280), { 600, 800, 450 },
      20000, 2, 60 },
};

/* mdeg/s -> rad/s in Q24: pi / 180000 * 2^24 * 2^16 (applied with q = 16). */
#define K_MDEG_TO_RAD_Q24_Q16 19190957
/* um/s -> 1/256 um per tick: 256 / TICKS_PER_S * 2^31, rounded (applied
 * with q = 31). */
#define K_UMS_TO_Q8_TICK_Q31 ((int32_t)((((uint64_t)256u << 31) + TICKS_PER_S / 2u) / TICKS_PER_S))
/* Largest body turn per stance: 30 degrees = 0.5236 rad. K_TURN maps a yaw
 * rate in rad/s Q24 to (|w| / turn) * 2 in Q11 after >> 32:
 * 2 / 0.5236 * 2^(11 + 32 - 24). */
#define K_TURN 2002633u
#define STANCE_CLAMP_UM 200000
/* Last-resort box for stance feet (never reached in the tests). */
#define CLAMP_Y_UM (XGO_GAIT_REACH_Y_UM + XGO_GAIT_YAW_REACH_Y_UM)

static const gait_table_t *table_of(uint8_t type)
{
    return &k_tables[type < XGO_GAIT_TYPE_COUNT ? type : XGO_GAIT_TROT];
}

uint32_t xgo_gait_period_ms(uint8_t type, uint8_t pace)
{
    return table_of(type)->period_ms[pace < XGO_PACE_COUNT ? pace : XGO_PACE_NORMAL];
}

uint32_t xgo_gait_duty_pct(uint8_t type)
{
    return table_of(type)->duty_pct;
}

/* ------------------------------------------------------------ helpers */

/* (a * b) / 2^q rounded, 1 <= q <= 31: xgo_mul_q without the saturation,
 * inlined (it is the hot spot). Every use below has |a * b| < 2^56 and a
 * result well inside int32 by the clamps on the command (twice the vendor
 * ranges), the stance (+-200 mm) and the reach box. */
static inline int32_t mul_q(int32_t a, int32_t b, unsigned q)
{
    return (int32_t)(((int64_t)a * b + ((int64_t)1 << (q - 1u))) >> q);
}

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static uint32_t abs_u(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint32_t max_u(uint32_t a, uint32_t b)
{
    return a > b ? a : b;
}

/* Cadence at which a foot moving at speed (um/s) covers twice the half
 * stride h (um) in one stance: D * speed / (2 h) cycles per second, as a
 * phase rate per tick: (speed / h) * D * 2^31 / TICKS_PER_S. speed < 2^21. */
static uint32_t fit_rate(uint32_t speed, uint32_t h, uint32_t k_rate)
{
    uint32_t q = (speed << 11) / h; /* speed / h in Q11 */
    return (uint32_t)(((uint64_t)q * k_rate) >> 11);
}

/* Foot velocity relative to the ground for a point (x, y) of the body:
 * v + w x p, in um/s. w in rad/s Q24. */
static void foot_velocity(const int32_t v[2], int32_t w_q24, int32_t x_um, int32_t y_um,
                          int32_t out[2])
{
    out[0] = v[0] - mul_q(w_q24, y_um, 24u);
    out[1] = v[1] + mul_q(w_q24, x_um, 24u);
}

static void publish(xgo_gait_t *g, const int32_t z_um[XGO_LEG_COUNT])
{
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        g->foot_um[leg][0] = (g->pos_q8[leg][0] + 128) >> 8;
        g->foot_um[leg][1] = (g->pos_q8[leg][1] + 128) >> 8;
        g->foot_um[leg][2] = z_um[leg];
        g->contact[leg] = (uint8_t)!g->swinging[leg];
    }
}

static int at_stance(const xgo_gait_t *g, int leg)
{
    return g->pos_q8[leg][0] == g->stance_um[leg][0] * 256 &&
           g->pos_q8[leg][1] == g->stance_um[leg][1] * 256;
}

/* ------------------------------------------------------------ API */

static void invalidate_caches(xgo_gait_t *g)
{
    g->cache_cmd[0] = g->cache_cmd[1] = g->cache_cmd[2] = INT32_MIN;
    g->cache_v[0] = g->cache_v[1] = g->cache_v[2] = INT32_MIN;
    g->cache_cmd_type = g->cache_v_type = 0xFFu;
    g->cache_lambda_q16 = 65536;
    g->cache_rate_base = 0;
    g->cache_rate_fit = 0;
}

void xgo_gait_init(xgo_gait_t *g, const int32_t stance_um[XGO_LEG_COUNT][3])
{
    static const int32_t zero_z[XGO_LEG_COUNT] = { 0, 0, 0, 0 };
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (c = 0; c < 2; ++c) {
            g->stance_um[leg][c] = clamp32(stance_um[leg][c], -STANCE_CLAMP_UM, STANCE_CLAMP_UM);
            g->pos_q8[leg][c] = g->stance_um[leg][c] * 256;
            g->lift_q8[leg][c] = g->pos_q8[leg][c];
        }
        g->swing_height_um[leg] = 0;
        g->reach_y_um[leg] = XGO_GAIT_REACH_Y_UM;
        g->swinging[leg] = 0;
    }
    g->phase = 0;
    g->rate = 0;
    g->rate_base = k_tables[XGO_GAIT_TROT].rate[XGO_PACE_NORMAL];
    g->type = XGO_GAIT_TROT;
    g->standing = 1;
    g->v_ramp[0] = g->v_ramp[1] = g->v_ramp[2] = 0;
    g->vx_um_s = g->vy_um_s = g->vyaw_mdeg_s = 0;
    g->brake = 0;
    invalidate_caches(g);
    g->ticks = 0;
    g->governed_ticks = 0;
    g->outside_ticks = 0;
    g->limited_ticks = 0;
    g->boosted_ticks = 0;
    g->clamped_ticks = 0;
    g->switches = 0;
    publish(g, zero_z);
}

int xgo_gait_is_standing(const xgo_gait_t *g)
{
    return g->standing != 0;
}

/* ------------------------------------------------------------ governor */

/* Reach box of a stance foot (um) for yaw rate w: x fixed, y widened by the
 * yaw share. */
static int32_t reach_y(int32_t w_mdeg_s)
{
    uint32_t yaw = abs_u(w_mdeg_s);
    if (yaw > (uint32_t)XGO_GAIT_YAW_REF_MDEG_S) {
        yaw = XGO_GAIT_YAW_REF_MDEG_S;
    }
    return XGO_GAIT_REACH_Y_UM +
           (int32_t)(yaw * (uint32_t)XGO_GAIT_YAW_REACH_Y_UM / (uint32_t)XGO_GAIT_YAW_REF_MDEG_S);
}

/* End-of-stance bounds for one foot component: a foot at offset off (um)
 * from its stance point, moving at ground speed s (um/s) for r more phase
 * at the capped cadence, ends at off - s * r / k with k = TICKS_PER_S * rate_max.
 * It stays in [-reach, reach] (widened to include off, so that s = 0 always
 * fits) iff s * r lies in [lo, hi] computed here. */
static void end_bounds(int32_t off, int32_t reach, int64_t k, int64_t *lo, int64_t *hi)
{
    int32_t up = off > reach ? off : reach;
    int32_t down = -off > reach ? -off : reach;
    *lo = (int64_t)(off - up) * k;
    *hi = (int64_t)(off + down) * k;
}

/* Largest lambda (Q16, 0..65536) for which a + lambda * b keeps s * r in
 * [lo, hi]. When a itself is outside (rounding, or the arc's third-order
 * terms), only steps that do not make it worse are allowed (and *outside is
 * set). One 64-bit division, only when the full step does not fit. */
static int32_t segment_limit(int32_t a, int32_t b, uint32_t r, int64_t lo, int64_t hi, int *outside)
{
    int64_t ar = (int64_t)a * r;
    int64_t er = (int64_t)(a + b) * r;
    int64_t room;
    int64_t span;
    int64_t l;
    if (ar > hi || ar < lo) {
        *outside = 1;
        return (ar > hi ? er <= ar : er >= ar) ? 65536 : 0;
    }
    if (er <= hi && er >= lo) {
        return 65536;
    }
    room = er > hi ? hi - ar : ar - lo;
    span = (er > hi ? er - ar : ar - er) >> 16;
    if (span <= 0) {
        return 0;
    }
    l = room / span;
    return l > 65536 ? 65536 : (int32_t)l;
}

/* Half-stride budget in y for yaw rate w: grows with |w| up to the
 * reference rate (the reach box grows alongside, see reach_y). */
static uint32_t half_stride_y(int32_t w_mdeg_s)
{
    uint32_t yaw = abs_u(w_mdeg_s);
    if (yaw > (uint32_t)XGO_GAIT_YAW_REF_MDEG_S) {
        yaw = XGO_GAIT_YAW_REF_MDEG_S;
    }
    return XGO_GAIT_HALF_STRIDE_Y_UM +
           yaw * (uint32_t)XGO_GAIT_YAW_HALF_STRIDE_Y_UM / (uint32_t)XGO_GAIT_YAW_REF_MDEG_S;
}

/* Per-tick context shared by the stages below. */
typedef struct tick_ctx_s {
    const gait_table_t *t;
    int32_t vel[2];   /* produced vx, vy */
    int32_t w_q24;    /* produced yaw rate, rad/s Q24 */
    uint32_t tau_q16; /* half the stance time at the fitted cadence, s Q16 */
} tick_ctx_t;

static int32_t yaw_q24(int32_t w_mdeg_s)
{
    return mul_q(w_mdeg_s, K_MDEG_TO_RAD_Q24_Q16, 16u);
}

/* Half the time (s, Q16) a planted foot with r phase left stays down at the
 * capped cadence of table t: r / rate_max ticks, halved (k_half does not
 * depend on the tick rate). */
static uint32_t half_time_q16(const gait_table_t *t, uint32_t r)
{
    return (uint32_t)(((uint64_t)r * t->k_half) >> 39);
}

/* Midpoint of the rest of a planted foot's path (um), estimated with the
 * velocity (v, w): q = p - (v + w x p) * T/2. Under yaw the path is an arc;
 * the ground velocity at q is the foot's mean velocity over the rest of its
 * stance to second order, and it is linear in (v, w) for a fixed q. */
static void stance_midpoint(const xgo_gait_t *g, int leg, const int32_t v[2], int32_t w_q24,
                            uint32_t half_q16, int32_t q[2])
{
    int32_t f[2];
    int32_t px = g->pos_q8[leg][0] >> 8;
    int32_t py = g->pos_q8[leg][1] >> 8;
    foot_velocity(v, w_q24, px, py, f);
    q[0] = px - mul_q(f[0], (int32_t)half_q16, 16u);
    q[1] = py - mul_q(f[1], (int32_t)half_q16, 16u);
}

/* Largest step lambda (Q16) from base towards prop that every stance foot
 * can absorb before its lift-off at the capped cadence; *outside is set when
 * base itself does not quite fit (then no step may make that foot worse). */
static int32_t governor_lambda(const xgo_gait_t *g, const gait_table_t *t, uint32_t phase,
                               const int32_t base[3], const int32_t prop[3], int *outside)
{
    int64_t k = (int64_t)TICKS_PER_S * t->rate_max;
    int32_t wb = yaw_q24(base[2]);
    int32_t wp = yaw_q24(prop[2]);
    int32_t lambda = 65536;
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t q[2];
        int32_t a[2], e[2];
        uint32_t r;
        if (g->swinging[leg]) {
            continue;
        }
        r = 0u - (phase - t->lift[leg]);
        stance_midpoint(g, leg, base, wb, half_time_q16(t, r), q);
        foot_velocity(base, wb, q[0], q[1], a);
        foot_velocity(prop, wp, q[0], q[1], e);
        for (c = 0; c < 2; ++c) {
            int64_t lo, hi;
            int32_t l;
            end_bounds((g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c],
                       c == 0 ? XGO_GAIT_REACH_X_UM : g->reach_y_um[leg], k, &lo, &hi);
            l = segment_limit(a[c], e[c] - a[c], r, lo, hi, outside);
            if (l < lambda) {
                lambda = l;
            }
        }
    }
    return lambda;
}

/* Would the velocity v fit every planted foot under table n entered at
 * phase p (legs lifting at p excluded)? */
static int switch_fits(const xgo_gait_t *g, const gait_table_t *n, uint32_t p, uint32_t rate,
                       const int32_t v[3])
{
    int64_t k = (int64_t)TICKS_PER_S * n->rate_max;
    int32_t w = yaw_q24(v[2]);
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t q[2];
        int32_t f[2];
        uint32_t r = 0u - (p - n->lift[leg]);
        if (p - n->lift[leg] < rate) {
            continue; /* lifts now */
        }
        stance_midpoint(g, leg, v, w, half_time_q16(n, r), q);
        foot_velocity(v, w, q[0], q[1], f);
        for (c = 0; c < 2; ++c) {
            int64_t lo, hi;
            int64_t s = (int64_t)f[c] * r;
            end_bounds((g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c],
                       c == 0 ? XGO_GAIT_REACH_X_UM : g->reach_y_um[leg], k, &lo, &hi);
            if (s < lo || s > hi) {
                return 0;
            }
        }
    }
    return 1;
}

/* Touchdown point of a leg: the stance point plus half the stance travel,
 * to second order so that the stance arc is centred on the stance point:
 * p_td = nom + f tau + (w x f) tau^2 / 2, f = v + w x nom, tau = T_st / 2. */
static void touchdown_q8(const xgo_gait_t *g, const tick_ctx_t *x, int leg, int32_t td[2])
{
    int32_t f[2];
    int32_t wf[2];
    int32_t tau2 = mul_q((int32_t)x->tau_q16, (int32_t)x->tau_q16, 17u); /* tau^2 / 2 */
    int c;
    foot_velocity(x->vel, x->w_q24, g->stance_um[leg][0], g->stance_um[leg][1], f);
    wf[0] = -mul_q(x->w_q24, f[1], 24u);
    wf[1] = mul_q(x->w_q24, f[0], 24u);
    for (c = 0; c < 2; ++c) {
        td[c] = (g->stance_um[leg][c] + mul_q(f[c], (int32_t)x->tau_q16, 16u) + mul_q(wf[c], tau2, 16u)) *
                256;
    }
}

/* The cadence that fits every stance (phase rate per tick), at least
 * `floor`:
 *   1. first order: |v_foot| * T_st <= 2 h per component, at the stance
 *      points;
 *   2. the body turns at most 30 degrees per stance (K_TURN);
 *   3. second order: under yaw the stance path is an arc; its half extent
 *      |f| tau + |w x f| tau^2 / 2 (tau = T_st / 2) must stay within h too:
 *      the rate of 1.-2. is raised by the worst ratio extent / h (one step
 *      is enough: the extent shrinks faster than tau). */
static uint32_t fitted_rate(const xgo_gait_t *g, const gait_table_t *t, const int32_t v[2], int32_t w_q24,
                            uint32_t hx, uint32_t hy, uint32_t floor)
{
    int32_t f[XGO_LEG_COUNT][2];
    uint32_t max_fx = 0, max_fy = 0;
    uint32_t rate;
    uint32_t tau;
    int32_t tau2;
    uint32_t ext_x = 0, ext_y = 0;
    uint32_t ratio;
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        foot_velocity(v, w_q24, g->stance_um[leg][0], g->stance_um[leg][1], f[leg]);
        max_fx = max_u(max_fx, abs_u(f[leg][0]));
        max_fy = max_u(max_fy, abs_u(f[leg][1]));
    }
    rate = max_u(floor, max_u(fit_rate(max_fx, hx, t->k_rate), fit_rate(max_fy, hy, t->k_rate)));
    {
        /* |w| / turn in Q11, then like fit_rate: turn = D / rate. */
        uint32_t q = (uint32_t)(((uint64_t)abs_u(w_q24) * K_TURN) >> 32);
        rate = max_u(rate, (uint32_t)(((uint64_t)q * t->k_rate) >> 11));
    }
    if (w_q24 == 0 || rate > t->rate_max || rate < (1u << 16)) {
        return rate; /* no yaw, hopeless, or too slow to matter */
    }
    tau = t->k_tau / (rate >> 8);
    tau2 = mul_q((int32_t)tau, (int32_t)tau, 17u);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        uint32_t wfx = abs_u(mul_q(w_q24, f[leg][1], 24u));
        uint32_t wfy = abs_u(mul_q(w_q24, f[leg][0], 24u));
        ext_x = max_u(ext_x, (uint32_t)mul_q((int32_t)abs_u(f[leg][0]), (int32_t)tau, 16u) +
                                 (uint32_t)mul_q((int32_t)wfx, tau2, 16u));
        ext_y = max_u(ext_y, (uint32_t)mul_q((int32_t)abs_u(f[leg][1]), (int32_t)tau, 16u) +
                                 (uint32_t)mul_q((int32_t)wfy, tau2, 16u));
    }
    /* extents are < 2^19 um: Q12 ratios fit 32 bits */
    ratio = max_u((ext_x << 12) / hx, (ext_y << 12) / hy);
    if (ratio > (1u << 12)) {
        uint64_t r2 = ((uint64_t)rate * ratio) >> 12;
        rate = r2 > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)r2;
    }
    return rate;
}

/* ------------------------------------------------------------ tick */

void xgo_gait_tick(xgo_gait_t *g, const xgo_gait_command_t *cmd)
{
    static const int32_t step_max[3] = {
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_YAW_ACCEL_MDEG_S2 / (int32_t)TICKS_PER_S,
    };
    tick_ctx_t x;
    int32_t target[3];
    int32_t prop[3];
    int32_t mark;
    uint8_t want_type;
    uint8_t pace;
    const gait_table_t *t;
    uint32_t hx, hy;
    uint32_t rate_fit, rate;
    int32_t vf[XGO_LEG_COUNT][2];
    int32_t z_um[XGO_LEG_COUNT] = { 0, 0, 0, 0 };
    uint8_t moved[XGO_LEG_COUNT]; /* position already set this tick */
    int resting;
    int any_swing;
    int leg;
    int c;

    g->ticks++;

    /* ---- the command ---- */
    target[0] = clamp32(cmd->vx_um_s, -XGO_GAIT_VX_CLAMP_UM_S, XGO_GAIT_VX_CLAMP_UM_S);
    target[1] = clamp32(cmd->vy_um_s, -XGO_GAIT_VY_CLAMP_UM_S, XGO_GAIT_VY_CLAMP_UM_S);
    target[2] = clamp32(cmd->vyaw_mdeg_s, -XGO_GAIT_VYAW_CLAMP_MDEG_S, XGO_GAIT_VYAW_CLAMP_MDEG_S);
    mark = clamp32(cmd->mark_time_um, 0, XGO_GAIT_MAX_HEIGHT_UM);
    want_type = mark > 0 ? (uint8_t)XGO_GAIT_TROT
                         : (cmd->type < XGO_GAIT_TYPE_COUNT ? cmd->type : (uint8_t)XGO_GAIT_TROT);
    pace = cmd->pace < XGO_PACE_COUNT ? cmd->pace : (uint8_t)XGO_PACE_NORMAL;
    resting = target[0] == 0 && target[1] == 0 && target[2] == 0 && mark == 0;

    if (g->standing) {
        g->type = want_type;
        g->rate_base = k_tables[want_type].rate[pace];
        g->brake = 0;
        if (resting) {
            g->rate = 0;
            return; /* outputs unchanged: feet at stance */
        }
        /* Start: the first lift-off event fires on this tick. */
        g->standing = 0;
        g->phase = 0xFFFFFFFFu;
    }
    t = table_of(g->type);
    if (want_type == g->type) {
        g->brake = 0;
    }

    /* ---- velocity: speed limit, ramp, governor ---- */
    if (g->brake) {
        target[0] = target[1] = target[2] = 0;
    }
    hx = XGO_GAIT_HALF_STRIDE_X_UM;
    if (target[0] != g->cache_cmd[0] || target[1] != g->cache_cmd[1] || target[2] != g->cache_cmd[2] ||
        g->type != g->cache_cmd_type) {
        /* New command (or table): does its stride fit at the fastest cadence? */
        g->cache_cmd[0] = target[0];
        g->cache_cmd[1] = target[1];
        g->cache_cmd[2] = target[2];
        g->cache_cmd_type = g->type;
        g->cache_lambda_q16 = 65536;
        rate_fit = fitted_rate(g, t, target, yaw_q24(target[2]), hx, half_stride_y(target[2]), 0u);
        if (rate_fit > t->rate_max) {
            /* No: scale the command down as a whole (the fitted cadence is
             * proportional to the speed). */
            g->cache_lambda_q16 = (int32_t)(((uint64_t)t->rate_max << 16) / rate_fit);
        }
    }
    if (g->cache_lambda_q16 < 65536) {
        for (c = 0; c < 3; ++c) {
            target[c] = (int32_t)(((int64_t)target[c] * g->cache_lambda_q16) / 65536);
        }
        g->limited_ticks++;
    }
    for (c = 0; c < 3; ++c) {
        prop[c] = g->v_ramp[c] + clamp32(target[c] - g->v_ramp[c], -step_max[c], step_max[c]);
    }
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t ry = reach_y(g->v_ramp[2]);
        if (!g->swinging[leg] && ry > g->reach_y_um[leg]) {
            g->reach_y_um[leg] = ry;
        }
    }
    if (prop[0] != g->v_ramp[0] || prop[1] != g->v_ramp[1] || prop[2] != g->v_ramp[2]) {
        /* Planted feet must be able to absorb the change before lifting. */
        int outside = 0;
        int32_t lambda = governor_lambda(g, t, g->phase, g->v_ramp, prop, &outside);
        if (lambda < 65536) {
            g->governed_ticks++;
        }
        if (outside) {
            g->outside_ticks++;
        }
        for (c = 0; c < 3; ++c) {
            g->v_ramp[c] += (int32_t)(((int64_t)(prop[c] - g->v_ramp[c]) * lambda) / 65536);
        }
    }
    hy = half_stride_y(g->v_ramp[2]);
    x.t = t;
    x.vel[0] = g->v_ramp[0];
    x.vel[1] = g->v_ramp[1];
    x.w_q24 = yaw_q24(g->v_ramp[2]);
    resting = resting && g->v_ramp[0] == 0 && g->v_ramp[1] == 0 && g->v_ramp[2] == 0;

    /* ---- cadence ---- */
    {
        uint32_t nominal = t->rate[pace];
        uint32_t step = (max_u(nominal, g->rate_base) >> 7) + 1u; /* ~0.8 %/tick */
        if (g->rate_base + step < nominal) {
            g->rate_base += step;
        } else if (g->rate_base > nominal + step) {
            g->rate_base -= step;
        } else {
            g->rate_base = nominal;
        }
    }
    if (g->v_ramp[0] != g->cache_v[0] || g->v_ramp[1] != g->cache_v[1] || g->v_ramp[2] != g->cache_v[2] ||
        g->type != g->cache_v_type || g->rate_base != g->cache_rate_base) {
        g->cache_v[0] = g->v_ramp[0];
        g->cache_v[1] = g->v_ramp[1];
        g->cache_v[2] = g->v_ramp[2];
        g->cache_v_type = g->type;
        g->cache_rate_base = g->rate_base;
        rate_fit = fitted_rate(g, t, x.vel, x.w_q24, hx, hy, g->rate_base);
        if (rate_fit > t->rate_max) {
            rate_fit = t->rate_max;
        }
        g->cache_rate_fit = rate_fit;
    }
    rate_fit = g->cache_rate_fit;
    x.tau_q16 = t->k_tau / (rate_fit >> 8);

    /* Transient rule: every planted foot must reach its lift-off before it
     * crosses the edge of the stride budget at its current velocity. */
    rate = rate_fit;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        uint32_t remaining;
        int32_t q[2];
        int32_t fm[2];
        moved[leg] = 0;
        if (g->swinging[leg]) {
            continue;
        }
        foot_velocity(x.vel, x.w_q24, g->pos_q8[leg][0] >> 8, g->pos_q8[leg][1] >> 8, vf[leg]);
        remaining = 0u - (g->phase - t->lift[leg]);
        stance_midpoint(g, leg, x.vel, x.w_q24, half_time_q16(t, remaining), q);
        foot_velocity(x.vel, x.w_q24, q[0], q[1], fm);
        for (c = 0; c < 2; ++c) {
            int32_t off = (g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c];
            int32_t d;
            uint64_t travel;
            uint64_t room;
            if (fm[c] == 0) {
                continue;
            }
            d = (int32_t)(c == 0 ? hx : hy) + (fm[c] > 0 ? off : -off);
            if (d <= 0) {
                rate = t->rate_max;
                continue;
            }
            travel = (uint64_t)abs_u(fm[c]) * remaining;
            room = (uint64_t)(TICKS_PER_S * (uint32_t)d) * rate;
            if (travel > room) {
                rate = (uint32_t)(travel / (TICKS_PER_S * (uint32_t)d)) + 1u;
                if (rate > t->rate_max) {
                    rate = t->rate_max;
                }
            }
        }
    }
    if (rate > rate_fit) {
        g->boosted_ticks++;
    }

    /* ---- phase and events ---- */
    g->phase += rate;
    g->rate = rate;

    /* Touchdowns under the table in use: placed at the touchdown point. */
    any_swing = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (g->swinging[leg]) {
            if (g->phase - t->lift[leg] >= t->swing) {
                g->swinging[leg] = 0;
                touchdown_q8(g, &x, leg, g->pos_q8[leg]);
                g->reach_y_um[leg] = reach_y(g->v_ramp[2]);
                moved[leg] = 1;
            } else {
                any_swing = 1;
            }
        }
    }

    /* Gait change: tables with the same timing switch at once; otherwise at a
     * lift-off event of a front leg with all four feet down, entering the new
     * table at that leg's lift-off phase, if the planted feet can carry the
     * current velocity under the new timing; else slow down and retry. */
    if (want_type != g->type && !resting) { /* stopping: switch once standing */
        const gait_table_t *n = &k_tables[want_type];
        if (n->timing == t->timing) {
            g->type = want_type;
            t = n;
            g->switches++;
        } else if (!any_swing) {
            int f;
            for (f = XGO_LEG_LF; f <= XGO_LEG_RF; ++f) {
                uint32_t theta = g->phase - t->lift[f];
                if (theta < rate) { /* f lifts off on this tick */
                    uint32_t p = n->lift[f] + theta;
                    if (switch_fits(g, n, p, rate, g->v_ramp)) {
                        g->phase = p;
                        g->type = want_type;
                        g->brake = 0;
                        t = n;
                        g->switches++;
                    } else {
                        g->brake = 1;
                    }
                    break;
                }
            }
        }
        x.t = t;
    }

    /* Lift-offs. */
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (!g->swinging[leg] && !moved[leg] && g->phase - t->lift[leg] < rate) {
            if (resting && at_stance(g, leg)) {
                continue; /* stopping: a foot already home stays down */
            }
            g->swinging[leg] = 1;
            g->lift_q8[leg][0] = g->pos_q8[leg][0];
            g->lift_q8[leg][1] = g->pos_q8[leg][1];
            g->swing_height_um[leg] = mark > 0 ? mark : t->height_um;
        }
    }

    /* ---- move the feet ---- */
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (moved[leg]) {
            continue;
        }
        if (!g->swinging[leg]) {
            /* Stance: the ground moves by -(v + w x p) dt. */
            int32_t lim[2];
            lim[0] = XGO_GAIT_REACH_X_UM * 256;
            lim[1] = CLAMP_Y_UM * 256;
            for (c = 0; c < 2; ++c) {
                int32_t nom = g->stance_um[leg][c] * 256;
                int32_t p = g->pos_q8[leg][c] - mul_q(vf[leg][c], K_UMS_TO_Q8_TICK_Q31, 31u);
                if (p > nom + lim[c] || p < nom - lim[c]) {
                    p = clamp32(p, nom - lim[c], nom + lim[c]);
                    g->clamped_ticks++;
                }
                g->pos_q8[leg][c] = p;
            }
        } else {
            /* Swing: from the lift-off point towards the touchdown point. */
            int32_t td[2];
            uint32_t theta = g->phase - t->lift[leg];
            uint32_t psi = (uint32_t)(((uint64_t)theta * t->inv_swing_q16) >> 16);
            xgo_q30_t s, co, h;
            touchdown_q8(g, &x, leg, td);
            xgo_sincos(psi >> 1, &s, &co);       /* angle pi * psi */
            h = (XGO_Q30_ONE >> 1) - (co >> 1);  /* 0 -> 1, zero slope at both ends */
            for (c = 0; c < 2; ++c) {
                g->pos_q8[leg][c] = g->lift_q8[leg][c] + mul_q(td[c] - g->lift_q8[leg][c], h, 30u);
            }
            z_um[leg] = mul_q(g->swing_height_um[leg], mul_q(s, s, 30u), 30u);
        }
    }

    g->vx_um_s = g->v_ramp[0];
    g->vy_um_s = g->v_ramp[1];
    g->vyaw_mdeg_s = g->v_ramp[2];

    /* ---- stopped? ---- */
    if (resting) {
        int home = 1;
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            if (g->swinging[leg] || !at_stance(g, leg)) {
                home = 0;
            }
        }
        if (home) {
            g->standing = 1;
            g->rate = 0;
        }
    }
    publish(g, z_um);
}
