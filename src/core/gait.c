/*
 * gait.c - phase-based gait generator (see gait.h and docs/gait.md).
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
 * The tick is that sequence of stages over one context (gait_tick_t):
 *   1. limit        the command clamped, the speed limited to what fits;
 *   2. ramp         the produced velocity ramps toward it, governed
 *                   (gait_governor.c) so planted feet stay in reach;
 *   3. cadence      nominal, fitted and transient rates -> this tick's rate;
 *   4. phase        the master phase advances: touchdowns, gait switch,
 *                   lift-offs;
 *   5. trajectories stance feet move with the ground, swing feet fly
 *                   (4 and 5 leg by leg: step_legs).
 * (CHAMP's phase generator / trajectory planner split, in fixed point.)
 *
 * Integer arithmetic only. Positions are kept in 1/256 um so that slow
 * velocities integrate without rounding drift.
 */
#include "check.h"
#include "gait_internal.h"

#include <stddef.h> /* offsetof */
#include <string.h> /* memcmp */

#include "fixed.h"
/* On a 64-bit host the swing's sine inline (fixed.h's bodies: the same
 * code as xgo_sincos, so the same value), without the cosine it does not
 * use; an MCU calls xgo_sincos (flash). */
#if XGO_CORE_DIV64_NATIVE
#define XGO_FIXED_BODIES
#define XGO_FIXED_INLINE
#include "fixed.h"
#endif

/* sin a: one a tick (the swing's height profile). */
XGO_ALWAYS_INLINE xgo_q30_t swing_sin(xgo_bam_t a)
{
    xgo_q30_t s;
#if XGO_CORE_DIV64_NATIVE
    xgo_sincos_inline(a, &s, 0);
#else
    xgo_q30_t c;
    xgo_sincos(a, &s, &c);
#endif
    return s;
}

/* ------------------------------------------------------------ tables */

#define Q32(num, den) ((uint32_t)((4294967296ULL * (uint64_t)(num)) / (uint64_t)(den)))
/* Phase advance per tick for a cycle of ms milliseconds: 2^32 * 1000 /
 * (ms * TICKS_PER_S) (2^33 / ms at 500 Hz). */
#define RATE(ms) ((uint32_t)(4294967296000ULL / ((uint64_t)(ms) * TICKS_PER_S)))
/* Duty D = dn/dd: D * 2^31 / TICKS_PER_S and D * 2^39 / TICKS_PER_S (see
 * fit_rate, tau; D * 2^32 / 1000 and D * 2^40 / 1000 at 500 Hz). */
#define KRATE(dn, dd) ((uint32_t)((2147483648ULL * (uint64_t)(dn)) / ((uint64_t)TICKS_PER_S * (dd))))
#define KHALF(ms) ((uint32_t)(((uint64_t)(ms) << 22) / 1000u))
#define KTAU(dn, dd) ((uint32_t)((549755813888ULL * (uint64_t)(dn)) / ((uint64_t)TICKS_PER_S * (dd))))
/* Swing S = sn/sd: S * 2^40 / TICKS_PER_S, so that k_swing / (rate >> 8) is
 * the swing's duration in s Q16 (S of a cycle of 2^32 / (rate TICKS_PER_S) s). */
#define KSWING(sn, sd) ((uint32_t)((1099511627776ULL * (uint64_t)(sn)) / ((uint64_t)TICKS_PER_S * (sd))))
/* Dwell delta (Q26) of a quarter tick at the shortest period ms of a swing
 * S = sn/sd: 1 / (4 S ms TICKS_PER_S / 1000), and its gain 1 / (1 - 2 delta)
 * (Q26). The trots' swings last >= 56 ticks: no dwell (docs/gait.md). */
#define KDWELL(ms, sn, sd) \
    ((int32_t)((1000ULL << 26) * (uint64_t)(sd) / (4ULL * (sn) * (ms) * (uint64_t)TICKS_PER_S)))
#define KDWELL_GAIN(ms, sn, sd) ((int32_t)((1ULL << 52) / ((1ULL << 26) - 2ULL * (uint64_t)KDWELL(ms, sn, sd))))
#define NO_DWELL 0, (1 << 26)

/* Trot: diagonal pairs LF+RH and RF+LH half a cycle apart, duty 0.5.
 * Walk: lateral sequence LH, LF, RH, RF, a quarter cycle apart, duty 0.75.
 * Periods (normal, slow, high) and the shortest allowed period in ms. */
#define TROT_LIFT { 0u, Q32(1, 2), 0u, Q32(1, 2) }
#define WALK_LIFT { Q32(1, 4), Q32(3, 4), Q32(1, 2), 0u }

static const gait_table_t k_tables[XGO_GAIT_TYPE_COUNT] = {
    /* XGO_GAIT_TROT */
    { Q32(1, 2), 2u << 16, TROT_LIFT, KRATE(1, 2), KTAU(1, 2), KSWING(1, 2),
      { RATE(400), RATE(600), RATE(300) }, RATE(240), KHALF(240), { 400, 600, 300 },
      20000, 0, 50, NO_DWELL },
    /* XGO_GAIT_WALK */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4), KSWING(1, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(220), KHALF(220), { 800, 1200, 600 },
      20000, 1, 75, KDWELL(220, 1, 4), KDWELL_GAIN(220, 1, 4) },
    /* XGO_GAIT_HIGH_WALK: the walk's timing, a higher swing */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4), KSWING(1, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(220), KHALF(220), { 800, 1200, 600 },
      30000, 1, 75, KDWELL(220, 1, 4), KDWELL_GAIN(220, 1, 4) },
    /* XGO_GAIT_SLOW_TROT: trot pairs, duty 0.6, longer periods */
    { Q32(2, 5), (5u << 16) / 2u, TROT_LIFT, KRATE(3, 5), KTAU(3, 5), KSWING(2, 5),
      { RATE(600), RATE(800), RATE(450) }, RATE(280), KHALF(280), { 600, 800, 450 },
      20000, 2, 60, NO_DWELL },
};

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

void gait_foot_velocity(const int32_t v[2], int32_t w_q24, int32_t x_um, int32_t y_um, int32_t out[2])
{
    out[0] = v[0] - mul_w_q24(w_q24, y_um);
    out[1] = v[1] + mul_w_q24(w_q24, x_um);
}

#if XGO_CORE_NARROW_CPU
/* mul_w_q24(x->w_q24, p) with the yaw rate's halves split (x->w_hi, w_lo):
 * the same sum of three products when |w| < 2^26 and |p| < 2^20. */
XGO_ALWAYS_INLINE int32_t tick_w_q24(const gait_tick_t *x, int32_t p)
{
    if (x->w_hi != INT32_MIN && (uint32_t)p + (1u << 20) < (1u << 21)) {
        const int32_t ph = p >> 16;
        const uint32_t pl = (uint32_t)p & 0xFFFFu;
        return (x->w_hi * p + (int32_t)x->w_lo * ph + (int32_t)((x->w_lo * pl) >> 16) + (1 << 7)) >> 8;
    }
    return mul_q(x->w_q24, p, 24u);
}

void gait_tick_foot_velocity(const gait_tick_t *x, int32_t x_um, int32_t y_um, int32_t out[2])
{
    out[0] = x->vel[0] - tick_w_q24(x, y_um);
    out[1] = x->vel[1] + tick_w_q24(x, x_um);
}

/* The split of x->w_q24 tick_w_q24 uses (INT32_MIN: beyond its range). */
static void split_w(gait_tick_t *x)
{
    const int32_t w = x->w_q24;
    x->w_hi = (uint32_t)w + (1u << 26) < (1u << 27) ? w >> 16 : INT32_MIN;
    x->w_lo = (uint32_t)w & 0xFFFFu;
}
#else
static void split_w(gait_tick_t *x)
{
    (void)x;
}
#endif

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
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
    return (uint32_t)(xgo_umul_wide(q, k_rate) >> 11);
}

/* A foot's x, y and contact; z is the swing's, set by swing_step (every
 * swinging foot takes a swing step each tick), 0 for a planted foot. */
XGO_ALWAYS_INLINE void publish_foot(xgo_gait_t *g, int leg, int swinging)
{
    g->foot_um[leg].x = (g->pos_q8[leg][0] + 128) >> 8;
    g->foot_um[leg].y = (g->pos_q8[leg][1] + 128) >> 8;
    if (!swinging) {
        g->foot_um[leg].z = 0;
    }
    g->contact[leg] = (uint8_t)!swinging;
}

static void publish(xgo_gait_t *g)
{
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        publish_foot(g, leg, g->swinging[leg]);
    }
}

static int at_stance(const xgo_gait_t *g, int leg)
{
    return g->pos_q8[leg][0] == g->stance_um[leg][0] * 256 &&
           g->pos_q8[leg][1] == g->stance_um[leg][1] * 256;
}

/* ------------------------------------------------------------ API */

/* GAIT_HOST_CACHES: a 64-bit host keeps the swing feet's end tangents
 * (swing_tangents) and a steady tick's front stages (steady_front) across
 * ticks, in xgo_gait_t's fields for them (board_state.h); on the 32-bit
 * cores the RAM is budgeted, and the narrow build (tests) computes as they
 * do. */
#define GAIT_HOST_CACHES (XGO_GAIT_HOST_CACHES && !XGO_CORE_NARROW_CPU)

/* The kept tangents no longer hold: all of them (the velocity, the cadence
 * or the swing time changed), or one leg's (a lift-off point moved). */
static void forget_tangents(xgo_gait_t *g)
{
#if GAIT_HOST_CACHES
    g->tangents_kept = 0;
#else
    (void)g;
#endif
}

static void forget_leg_tangents(xgo_gait_t *g, int leg)
{
#if GAIT_HOST_CACHES
    g->tangents_kept = (uint8_t)(g->tangents_kept & ~(1u << leg));
#else
    (void)g;
    (void)leg;
#endif
}

/* A tick's front stages will not repeat the last ones' (steady_front). */
static void forget_front(xgo_gait_t *g)
{
#if GAIT_HOST_CACHES
    g->front_kept = 0;
#else
    (void)g;
#endif
}

static void invalidate_caches(xgo_gait_t *g)
{
    g->cache_cmd[0] = g->cache_cmd[1] = g->cache_cmd[2] = INT32_MIN;
    g->cache_v[0] = g->cache_v[1] = g->cache_v[2] = INT32_MIN;
    g->cache_cmd_type = g->cache_v_type = 0xFFu;
    g->cache_lambda_q16 = 65536;
    g->cache_rate_base = 0;
    g->cache_rate_fit = 0;
    g->land_is_td = 0;
    forget_tangents(g);
    forget_front(g);
}

void xgo_gait_init(xgo_gait_t *g, const xgo_vec3_t stance_um[XGO_LEG_COUNT])
{
    int leg;
    int c;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        g->stance_um[leg][0] = clamp32(stance_um[leg].x, -STANCE_CLAMP_UM, STANCE_CLAMP_UM);
        g->stance_um[leg][1] = clamp32(stance_um[leg].y, -STANCE_CLAMP_UM, STANCE_CLAMP_UM);
        for (c = 0; c < 2; ++c) {
            g->pos_q8[leg][c] = g->stance_um[leg][c] * 256;
            g->lift_q8[leg][c] = g->pos_q8[leg][c];
            g->land_q8[leg][c] = g->pos_q8[leg][c];
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
    publish(g);
}

/* ------------------------------------------------------------ geometry */

/* Half-stride budget in y for yaw rate w: grows with |w| up to the
 * reference rate (the reach box grows alongside, see gait_reach_y). */
static uint32_t half_stride_y(int32_t w_mdeg_s)
{
    return XGO_GAIT_HALF_STRIDE_Y_UM + gait_yaw_widening_um(w_mdeg_s);
}

/* Touchdown point of a leg: the stance point plus half the stance travel,
 * to second order so that the stance arc is centred on the stance point:
 * p_td = nom + f tau + (w x f) tau^2 / 2, f = v + w x nom, tau = T_st / 2. */
static void touchdown_q8(const xgo_gait_t *g, gait_tick_t *x, int leg, int32_t td[2])
{
    int32_t f[2];
    int32_t wf[2];
    int c;
    if (!x->have_tau) {
        /* the stance time at the fitted cadence, of the table it was fitted
         * for; < 2^16, as the short products need (mul_q_u16): the rate is
         * at least the slowest nominal rate (RATE(1200) >> 8 = 27962; every
         * cap is faster), so tau <= KTAU(3, 4) / 27962 = 29491; tau^2 / 2^17
         * < 2^15. Only ticks whose touchdown points moved need it (a division
         * a steady tick less on an M0). */
        x->tau_q16 = table_of(g->cache_v_type)->k_tau / (g->cache_rate_fit >> 8);
        XGO_ASSERT(x->tau_q16 < 65536u);
        x->tau2_q16 = (uint32_t)mul_q_u16((int32_t)x->tau_q16, x->tau_q16, 17u);
        x->have_tau = 1;
    }
    gait_tick_foot_velocity(x, g->stance_um[leg][0], g->stance_um[leg][1], f);
    wf[0] = -mul_q(x->w_q24, f[1], 24u);
    wf[1] = mul_q(x->w_q24, f[0], 24u);
    for (c = 0; c < 2; ++c) {
        td[c] = (g->stance_um[leg][c] + mul_q_u16(f[c], x->tau_q16, 16u) + mul_q_u16(wf[c], x->tau2_q16, 16u)) * 256;
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
        gait_foot_velocity(v, w_q24, g->stance_um[leg][0], g->stance_um[leg][1], f[leg]);
        max_fx = max_u(max_fx, abs_u(f[leg][0]));
        max_fy = max_u(max_fy, abs_u(f[leg][1]));
    }
    rate = max_u(floor, max_u(fit_rate(max_fx, hx, t->k_rate), fit_rate(max_fy, hy, t->k_rate)));
    {
        /* |w| / turn in Q11, then like fit_rate: turn = D / rate. */
        uint32_t q = (uint32_t)(xgo_umul_wide(abs_u(w_q24), K_TURN) >> 32);
        rate = max_u(rate, (uint32_t)(xgo_umul_wide(q, t->k_rate) >> 11));
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
        uint64_t r2 = xgo_umul_wide(rate, ratio) >> 12;
        rate = r2 > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)r2;
    }
    return rate;
}

/* ------------------------------------------------------------ 1. limit */

/* The command as the gait takes it (all of it is expected input, gait.h):
 * speeds clamped to twice the vendor ranges, the mark-time height to its cap,
 * unknown gait types and paces to the defaults; mark time always trots. */
static void limit_command(const xgo_gait_command_t *cmd, gait_tick_t *x)
{
    x->target[0] = clamp32(cmd->vx_um_s, -XGO_GAIT_VX_CLAMP_UM_S, XGO_GAIT_VX_CLAMP_UM_S);
    x->target[1] = clamp32(cmd->vy_um_s, -XGO_GAIT_VY_CLAMP_UM_S, XGO_GAIT_VY_CLAMP_UM_S);
    x->target[2] = clamp32(cmd->vyaw_mdeg_s, -XGO_GAIT_VYAW_CLAMP_MDEG_S, XGO_GAIT_VYAW_CLAMP_MDEG_S);
    x->mark = clamp32(cmd->mark_time_um, 0, XGO_GAIT_MAX_HEIGHT_UM);
    x->height = clamp32(cmd->step_height_um, 0, XGO_GAIT_MAX_HEIGHT_UM);
    x->want_type = x->mark > 0 ? (uint8_t)XGO_GAIT_TROT
                               : (cmd->type < XGO_GAIT_TYPE_COUNT ? cmd->type : (uint8_t)XGO_GAIT_TROT);
    x->pace = cmd->pace < XGO_PACE_COUNT ? cmd->pace : (uint8_t)XGO_PACE_NORMAL;
    x->resting = x->target[0] == 0 && x->target[1] == 0 && x->target[2] == 0 && x->mark == 0;
}

/* While standing the gait and pace asked for apply at once. A zero command
 * keeps the robot standing: returns 0, nothing moves this tick. Anything
 * else starts it, the first lift-off firing on this very tick. */
static int start_or_stand(xgo_gait_t *g, gait_tick_t *x)
{
    if (g->standing) {
        g->type = x->want_type;
        g->rate_base = k_tables[x->want_type].rate[x->pace];
        g->brake = 0;
        if (x->resting) {
            g->rate = 0;
            return 0; /* outputs unchanged: feet at stance */
        }
        g->standing = 0;
        g->phase = 0xFFFFFFFFu;
    }
    x->t = table_of(g->type);
    if (x->want_type == g->type) {
        g->brake = 0;
    }
    return 1;
}

/* Speed limit: does the command's stride fit at the fastest cadence? If not,
 * it is scaled down as a whole (the fitted cadence is proportional to the
 * speed; never inside the vendor ranges). The scale is cached per command
 * and table. Braking for a pending gait switch heads for zero. */
static void limit_speed(xgo_gait_t *g, gait_tick_t *x)
{
    const gait_table_t *t = x->t;
    int c;
    if (g->brake) {
        x->target[0] = x->target[1] = x->target[2] = 0;
    }
    x->hx = XGO_GAIT_HALF_STRIDE_X_UM;
    if (x->target[0] != g->cache_cmd[0] || x->target[1] != g->cache_cmd[1] ||
        x->target[2] != g->cache_cmd[2] || g->type != g->cache_cmd_type) {
        uint32_t rate_fit;
        g->cache_cmd[0] = x->target[0];
        g->cache_cmd[1] = x->target[1];
        g->cache_cmd[2] = x->target[2];
        g->cache_cmd_type = g->type;
        g->cache_lambda_q16 = 65536;
        rate_fit = fitted_rate(g, t, x->target, yaw_q24(x->target[2]), x->hx,
                               half_stride_y(x->target[2]), 0u);
        if (rate_fit > t->rate_max) {
            g->cache_lambda_q16 =
                (int32_t)xgo_udiv64_cap((uint64_t)t->rate_max << 16, rate_fit, 65536u);
        }
    }
    if (g->cache_lambda_q16 < 65536) {
        for (c = 0; c < 3; ++c) {
            x->target[c] = gait_scale_q16(x->target[c], g->cache_lambda_q16);
        }
        g->limited_ticks++;
    }
}

/* ------------------------------------------------------------ 2. ramp */

/* ramp_velocity skips the ramp when the velocity is at its target, not when
 * a step would not move it: the same test while every step is positive */
typedef char xgo_gait_ramp_steps_positive[XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S > 0 &&
                                                  XGO_GAIT_YAW_ACCEL_MDEG_S2 / (int32_t)TICKS_PER_S > 0
                                              ? 1
                                              : -1];

/* The produced velocity steps toward the target by at most the ramp's
 * acceleration, as far as the governor lets it (gait_governor.c). A planted
 * foot's y reach only grows while it is down (with the yaw rate it sees). */
static void ramp_velocity(xgo_gait_t *g, gait_tick_t *x)
{
    static const int32_t step_max[3] = {
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_YAW_ACCEL_MDEG_S2 / (int32_t)TICKS_PER_S,
    };
    int32_t prop[3];
    /* the yaw widening of the reach (gait_reach_y) and of the stride budget
     * (half_stride_y) is one value: worked out once, again only if the ramp
     * moves the yaw rate */
    int32_t yaw = g->v_ramp[2];
    uint32_t widening = gait_yaw_widening_um(yaw);
    int leg;
    int c;
    /* the planted feet's reach grows with the yaw rate before the ramp;
     * nothing reads it before transient_rate, whose pass over them does it
     * (x->reach_y) unless the ramp moves (the governor reads it) */
    x->reach_y = XGO_GAIT_REACH_Y_UM + (int32_t)widening;
    /* at the target (a steady walk) the step is zero: nothing to ramp */
    if (x->target[0] != g->v_ramp[0] || x->target[1] != g->v_ramp[1] || x->target[2] != g->v_ramp[2]) {
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            if (!g->swinging[leg] && x->reach_y > g->reach_y_um[leg]) {
                g->reach_y_um[leg] = x->reach_y;
            }
        }
        x->reach_y = 0; /* done: below every reach */
        for (c = 0; c < 3; ++c) {
            prop[c] = g->v_ramp[c] + clamp32(x->target[c] - g->v_ramp[c], -step_max[c], step_max[c]);
        }
        gait_governed_ramp(g, x->t, prop); /* a call only while ramping */
        if (g->v_ramp[2] != yaw) {
            yaw = g->v_ramp[2];
            widening = gait_yaw_widening_um(yaw);
        }
    }
    x->hy = XGO_GAIT_HALF_STRIDE_Y_UM + widening;
    x->vel[0] = g->v_ramp[0];
    x->vel[1] = g->v_ramp[1];
    x->w_q24 = yaw_q24(g->v_ramp[2]);
    split_w(x);
    x->resting = x->resting && g->v_ramp[0] == 0 && g->v_ramp[1] == 0 && g->v_ramp[2] == 0;
}

/* ------------------------------------------------------------ 3. cadence */

/* The nominal rate follows a pace or gait change by ~0.8 % per tick. */
static void slew_rate_base(xgo_gait_t *g, const gait_tick_t *x)
{
    uint32_t nominal = x->t->rate[x->pace];
    uint32_t step = (max_u(nominal, g->rate_base) >> 7) + 1u;
    if (g->rate_base + step < nominal) {
        g->rate_base += step;
    } else if (g->rate_base > nominal + step) {
        g->rate_base -= step;
    } else {
        g->rate_base = nominal;
    }
}

/* The cadence fitted to the produced velocity, capped; cached, as it only
 * changes with the velocity, the table or the nominal rate. */
static uint32_t fit_cadence(xgo_gait_t *g, const gait_tick_t *x)
{
    if (g->v_ramp[0] != g->cache_v[0] || g->v_ramp[1] != g->cache_v[1] ||
        g->v_ramp[2] != g->cache_v[2] || g->type != g->cache_v_type ||
        g->rate_base != g->cache_rate_base) {
        uint32_t rate_fit;
        g->cache_v[0] = g->v_ramp[0];
        g->cache_v[1] = g->v_ramp[1];
        g->cache_v[2] = g->v_ramp[2];
        g->cache_v_type = g->type;
        g->cache_rate_base = g->rate_base;
        rate_fit = fitted_rate(g, x->t, x->vel, x->w_q24, x->hx, x->hy, g->rate_base);
        if (rate_fit > x->t->rate_max) {
            rate_fit = x->t->rate_max;
        }
        g->cache_rate_fit = rate_fit;
        /* the swing time at that rate (swing_time): < 2^16, as the short
         * products with it need (mul_q_u16): rate_fit is at least the
         * slowest nominal rate (RATE(1200) >> 8 = 27962; every cap is
         * faster), so it is at most KSWING(1, 2) / 27962 = 39321. Kept with
         * the rate: no library division in a steady tick on an M0. */
        XGO_ASSERT(x->t->k_swing / (rate_fit >> 8) < 65536u);
        g->cache_swing_q16 = (uint16_t)(x->t->k_swing / (rate_fit >> 8));
        /* the touchdown points move with the velocity and the cadence, the
         * swing's end tangents with them and the swing time */
        g->land_is_td = 0;
        forget_tangents(g);
    }
    return g->cache_rate_fit;
}

/* The transient rule on one axis of a planted foot (transient_rate): its
 * mean ground speed fm (um/s) along the axis, off (um) from its stance
 * point, the half-stride budget h, the phase left before its lift-off;
 * returns the rate, raised if the foot would cross the budget's edge before
 * it lifts at this one. Inline with the axis' fields: no arrays indexed by
 * the axis. */
XGO_INLINE_FAST uint32_t transient_axis(const gait_table_t *t, int32_t fm, int32_t off, uint32_t h,
                                        uint32_t remaining, uint32_t rate)
{
    int32_t d;
    uint64_t travel;
    uint64_t room;
    if (fm == 0) {
        return rate;
    }
    d = (int32_t)h + (fm > 0 ? off : -off);
    if (d <= 0) {
        return t->rate_max;
    }
#if XGO_CORE_NARROW_CPU
    if (gait_quick_fit(abs_u(fm), remaining, (uint32_t)d, rate)) {
        return rate; /* travel <= room: the two wide products spared */
    }
#endif
    travel = xgo_umul_wide(abs_u(fm), remaining);
    room = xgo_umul_wide(TICKS_PER_S * (uint32_t)d, rate);
    if (travel > room) {
        /* the quotient only matters up to rate_max */
        rate = xgo_udiv64_cap(travel, TICKS_PER_S * (uint32_t)d, t->rate_max);
        rate = rate < t->rate_max ? rate + 1u : t->rate_max;
    }
    return rate;
}

/* Transient rule: every planted foot must reach its lift-off before it
 * crosses the edge of the stride budget at its current velocity; returns
 * the rate that ensures it (at least `rate`, at most the cap). Keeps each
 * planted foot's ground velocity in x->vf for the stance step, and grows
 * its y reach to x->reach_y (ramp_velocity). */
static uint32_t transient_rate(xgo_gait_t *g, gait_tick_t *x, uint32_t rate)
{
    const gait_table_t *t = x->t;
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        uint32_t remaining;
        int32_t q[2];
        int32_t fm[2];
        int32_t px, py;
        if (g->swinging[leg]) {
            continue;
        }
        if (x->reach_y > g->reach_y_um[leg]) {
            g->reach_y_um[leg] = x->reach_y; /* ramp_velocity's, for a steady velocity */
        }
        px = g->pos_q8[leg][0] >> 8;
        py = g->pos_q8[leg][1] >> 8;
        gait_tick_foot_velocity(x, px, py, x->vf[leg]);
        remaining = 0u - (g->phase - t->lift[leg]);
        gait_midpoint_of(g, leg, x->vf[leg], half_time_q16(t, remaining), q);
        gait_tick_foot_velocity(x, q[0], q[1], fm);
        rate = transient_axis(t, fm[0], px - g->stance_um[leg][0], x->hx, remaining, rate);
        rate = transient_axis(t, fm[1], py - g->stance_um[leg][1], x->hy, remaining, rate);
    }
    return rate;
}

/* This tick's rate: the largest of the nominal, fitted and transient rates
 * (the nominal one is the fit's floor: rate_fit, from fit_cadence), capped
 * per gait. */
static void pick_cadence(xgo_gait_t *g, gait_tick_t *x, uint32_t rate_fit)
{
    x->have_tau = 0; /* touchdown_q8 works tau out if a touchdown point moved */
    x->rate = transient_rate(g, x, rate_fit);
    if (x->rate > rate_fit) {
        g->boosted_ticks++;
    }
}

/* ------------------------------------------------------------ 4. phase */

/* A foot changes between stance and swing at an event inside the tick, theta
 * (< rate) of phase before the tick's end: for the share of the tick it is
 * down - the part after a touchdown, or before a lift-off (`before`) - it
 * moves with the ground like any planted foot, so its ground speed does not
 * jump at the event (docs/gait.md, Swing). */
static void stance_part(const gait_tick_t *x, int32_t pos_q8[2], uint32_t theta, int before)
{
    const uint32_t r = x->rate >> 16;
    uint32_t share = r == 0u ? 0u : theta / r; /* after the event, Q16 */
    int32_t f[2];
    int c;
    share = share > 65536u ? 65536u : share;
    if (before) {
        share = 65536u - share;
    }
    gait_tick_foot_velocity(x, pos_q8[0] >> 8, pos_q8[1] >> 8, f);
    for (c = 0; c < 2; ++c) {
        pos_q8[c] -= mul_q(ums_to_q8_tick(f[c]), (int32_t)share, 16u);
    }
}

/* A touchdown under the table in use: a swinging foot whose swing ended is
 * placed at its touchdown point. Returns 1 if it touched down. */
XGO_ALWAYS_INLINE int touch_down(xgo_gait_t *g, const gait_tick_t *x, int leg)
{
    const gait_table_t *t = x->t;
    if (g->phase - t->lift[leg] < t->swing) {
        return 0;
    }
    g->swinging[leg] = 0;
    g->pos_q8[leg][0] = g->land_q8[leg][0];
    g->pos_q8[leg][1] = g->land_q8[leg][1];
    /* down for the part of the tick after the touchdown */
    stance_part(x, g->pos_q8[leg], g->phase - t->lift[leg] - t->swing, 0);
    g->reach_y_um[leg] = gait_reach_y(g->v_ramp[2]);
    return 1;
}

/* Gait change: tables with the same timing switch at once; otherwise at a
 * lift-off event of a front leg with all four feet down, entering the new
 * table at that leg's lift-off phase, if the planted feet can carry the
 * current velocity under the new timing; else slow down (brake) and retry.
 * Stopping, the switch waits until the robot stands. */
static void switch_gait(xgo_gait_t *g, gait_tick_t *x, int any_swing)
{
    const gait_table_t *n = &k_tables[x->want_type];
    int f;
    if (x->want_type == g->type || x->resting) {
        return;
    }
    if (n->timing == x->t->timing) {
        g->type = x->want_type;
        x->t = n;
        g->switches++;
        return;
    }
    if (any_swing) {
        return;
    }
    for (f = XGO_LEG_LF; f <= XGO_LEG_RF; ++f) {
        uint32_t theta = g->phase - x->t->lift[f];
        if (theta < x->rate) { /* f lifts off on this tick */
            uint32_t p = n->lift[f] + theta;
            if (gait_switch_fits(g, n, p, x->rate, g->v_ramp)) {
                g->phase = p;
                g->type = x->want_type;
                g->brake = 0;
                x->t = n;
                g->switches++;
            } else {
                g->brake = 1;
            }
            return;
        }
    }
}

/* A lift-off: a planted foot whose lift-off phase passed on this tick
 * starts its swing (the table's height, or the mark-time height) from
 * where it is; stopping, a foot already home stays down. Returns 1 if it
 * lifted. */
static int lift_foot(xgo_gait_t *g, const gait_tick_t *x, int leg)
{
    if (g->phase - x->t->lift[leg] < x->rate) {
        if (x->resting && at_stance(g, leg)) {
            return 0;
        }
        g->swinging[leg] = 1;
        forget_leg_tangents(g, leg); /* they start here */
        g->lift_q8[leg][0] = g->pos_q8[leg][0];
        g->lift_q8[leg][1] = g->pos_q8[leg][1];
        /* still down for the part of the tick before the lift-off */
        stance_part(x, g->lift_q8[leg], g->phase - x->t->lift[leg], 1);
        g->swing_height_um[leg] = x->mark > 0 ? x->mark : (x->height > 0 ? x->height : x->t->height_um);
        return 1;
    }
    return 0;
}

/* ------------------------------------------------------------ 5. trajectories */

/* Stance: the ground moves by -(v + w x p) dt under the foot; a foot that
 * would leave the last-resort box stays at its edge (counted). */
XGO_ALWAYS_INLINE void stance_axis(xgo_gait_t *g, const gait_tick_t *x, int leg, int c, int32_t lim)
{
    const int32_t nom = g->stance_um[leg][c] * 256;
    int32_t p = g->pos_q8[leg][c] - ums_to_q8_tick(x->vf[leg][c]);
    /* p > nom + lim or p < nom - lim: one unsigned compare (|p - nom| is a
     * stance box and a tick's travel, far inside int32) */
    if ((uint32_t)p - (uint32_t)nom + (uint32_t)lim > 2u * (uint32_t)lim) {
        p = clamp32(p, nom - lim, nom + lim);
        g->clamped_ticks++;
    }
    g->pos_q8[leg][c] = p;
}

static void stance_step(xgo_gait_t *g, const gait_tick_t *x, int leg)
{
    stance_axis(g, x, leg, 0, XGO_GAIT_REACH_X_UM * 256);
    stance_axis(g, x, leg, 1, CLAMP_Y_UM * 256);
}

/* The landing point follows the touchdown point (which moves with the
 * velocity) during the first half of the swing; over the second half it
 * follows less and less (a share 1 - smoothstep of the gap per tick) and not
 * at all at the end, so a velocity ramp does not drag the foot along the
 * ground as it lands. td (in) becomes the landing point (out); follow is
 * that share (land_follow of the swing progress, Q26; following it all
 * leaves td as it is). */
static int32_t land_follow(int32_t u)
{
    const int32_t half = 1 << 25;
    int32_t r;
    if (u < half) {
        return 1 << 26;
    }
    r = 2 * (u - half); /* 0..1 over the second half, Q26 */
    return (1 << 26) - mul_q26_unit(mul_q26_unit(r, r), 3 * (1 << 26) - 2 * r);
}

static void land_point(xgo_gait_t *g, int leg, int32_t follow, int32_t td[2])
{
    const uint8_t bit = (uint8_t)(1u << leg);
    int same = 1;
    int c;
    if (follow != 1 << 26) {
        for (c = 0; c < 2; ++c) {
            const int32_t to = g->land_q8[leg][c] + mul_q(td[c] - g->land_q8[leg][c], follow, 26u);
            same &= to == td[c];
            td[c] = to;
        }
    }
    g->land_q8[leg][0] = td[0];
    g->land_q8[leg][1] = td[1];
    /* landing point = touchdown point: while the velocity and the cadence
     * stay (the cache key of fit_cadence), so does the touchdown point, and
     * following it changes nothing (a zero gap moves by zero) */
    g->land_is_td = (uint8_t)(same ? g->land_is_td | bit : g->land_is_td & ~bit);
}

/* Swing: from the lift-off point to the touchdown point (which tracks the
 * velocity) on a quintic Hermite curve: at both ends the foot moves like a
 * planted one - velocity -(v + w x p) (the end tangents, times the swing
 * time) and no acceleration relative to it - so it leaves and meets the
 * ground at the ground's speed, without skimming; lifted on a sin^2 arc in
 * the swing progress psi to the latched height. The curve's cubic term still
 * moves the foot over the ground in the tick of a lift-off or touchdown
 * (20 mm/s in the walks' 29-tick swings), so for a dwell delta at either end
 * (a quarter tick at the fastest cadence) the foot only rises and moves with
 * the ground, and the curve runs in w = (psi - delta) / (1 - 2 delta) from
 * p_lift + m0 delta to p_land - m1 delta. Basis in Q26 (w <= 1):
 *   h(w) = w^3 (10 - 15w + 6w^2)         0 -> 1
 *   a(w) = w + w^3 (-6 + 8w - 3w^2)      start tangent
 *   b(w) = w^3 (-4 + 7w - 3w^2)          end tangent */
static void swing_weights(const gait_table_t *t, uint32_t theta, gait_swing_weights_t *wt)
{
    const int32_t one = 1 << 26;
    const int32_t dw = t->dwell_q26;
    const uint32_t psi = (uint32_t)(xgo_umul_wide(theta, t->inv_swing_q16) >> 16);
    const int32_t u = (int32_t)(psi >> 6);
    const int32_t w = dw == 0 ? u : clamp32(mul_q(u - dw, t->dwell_gain_q26, 26u), 0, one);
    /* w, w^2, w^3 in [0, 1] and the polynomials below 10: mul_q26_unit's ranges */
    XGO_ASSERT(w >= 0 && w <= one);
    const int32_t w2 = mul_q26_unit(w, w), w3 = mul_q26_unit(w2, w);
    const int32_t h = mul_q26_unit(w3, 10 * one - 15 * w + 6 * w2);
    const int32_t a = w + mul_q26_unit(w3, -6 * one + 8 * w - 3 * w2);
    const int32_t b = mul_q26_unit(w3, -4 * one + 7 * w - 3 * w2);
    xgo_q30_t s;
    wt->theta = theta;
    wt->h = h;
    wt->ca = a;
    wt->cb = b;
    if (dw != 0) {
        /* p = p_lift + D h + m0 A + m1 B (D = p_land - p_lift); with the
         * dwells A = (1 - 2 delta) a - delta h + min(psi, delta) and
         * B = (1 - 2 delta) b - delta h + max(psi - 1 + delta, 0) */
        const int32_t dh = mul_q(h, dw, 26u);
        wt->ca = a - mul_q(a, 2 * dw, 26u) - dh + (u < dw ? u : dw);
        wt->cb = b - mul_q(b, 2 * dw, 26u) - dh + (u > one - dw ? u - (one - dw) : 0);
    }
    s = swing_sin(psi >> 1); /* angle pi * psi */
    wt->s2 = square_q30(s);
    wt->follow = land_follow(u);
}

/* A swing's end tangent on one axis, in 1/256 um per unit of psi: -f
 * T_swing for the ground velocity f at that end (T_swing < 2^16,
 * swing_time). */
XGO_ALWAYS_INLINE int32_t swing_tangent(const gait_tick_t *x, int32_t f)
{
    return -mul_q_u16(f, x->swing_q16, 8u);
}

/* One coordinate of a swing foot on the curve (swing_step), landing at
 * td, with the end tangents m0 (lift-off) and m1 (landing). */
XGO_ALWAYS_INLINE void swing_coord(xgo_gait_t *g, const gait_tick_t *x, int leg, int c, int32_t td, int32_t m0,
                                   int32_t m1)
{
    const gait_swing_weights_t *wt = &x->weights;
    const int32_t lift = g->lift_q8[leg][c];
    g->pos_q8[leg][c] = lift + mul_q26_weight(wt->h, td - lift) + mul_q26_weight(wt->ca, m0) +
                        mul_q26_weight(wt->cb, m1);
}

#if GAIT_HOST_CACHES
/* A swing foot's end tangents (m0 x, y, m1 x, y), landing at td: from its
 * ground velocities at the lift-off point and at the landing point. They
 * only change with those points, the velocity and the swing time, so they
 * are kept (tangents_kept) once the landing point is the cached velocity's
 * touchdown point (land_is_td) at the cached swing time: land_is_td's bits
 * are cleared only with the kept tangents (fit_cadence), a landing point
 * moves only while its bit is clear (land_point), a lift-off point only at
 * a lift-off (forget_leg_tangents). In a steady walk a swing computes them
 * once, not each tick (two foot velocities and four tangent products fewer
 * a foot and tick). */
static void swing_tangents(xgo_gait_t *g, const gait_tick_t *x, int leg, const int32_t td[2], int32_t m[4])
{
    const unsigned bit = 1u << leg;
    /* the swing time at the cached rate: the one they were kept for */
    const int keep = x->swing_q16 == g->cache_swing_q16;
    int32_t f0[2], f1[2];
    int i;
    if (keep && (g->tangents_kept & bit) != 0u) {
        for (i = 0; i < 4; ++i) {
            m[i] = g->tangent_q8[leg][i];
        }
        return;
    }
    gait_tick_foot_velocity(x, g->lift_q8[leg][0] >> 8, g->lift_q8[leg][1] >> 8, f0);
    gait_tick_foot_velocity(x, td[0] >> 8, td[1] >> 8, f1);
    m[0] = swing_tangent(x, f0[0]);
    m[1] = swing_tangent(x, f0[1]);
    m[2] = swing_tangent(x, f1[0]);
    m[3] = swing_tangent(x, f1[1]);
    if (keep && ((g->land_is_td >> leg) & 1u) != 0u) {
        /* the landing point is the cached velocity's touchdown point */
        for (i = 0; i < 4; ++i) {
            g->tangent_q8[leg][i] = m[i];
        }
        g->tangents_kept = (uint8_t)(g->tangents_kept | bit);
    }
}
#else
/* One coordinate of a swing foot (swing_coord) from the ground velocities
 * f0 at the lift-off point and f1 at the landing point. */
XGO_INLINE_FAST void swing_axis(xgo_gait_t *g, const gait_tick_t *x, int leg, int c, int32_t td, int32_t f0,
                                int32_t f1)
{
    swing_coord(g, x, leg, c, td, swing_tangent(x, f0), swing_tangent(x, f1));
}
#endif

/* One swing foot's step on that curve. The weights depend on the phase
 * since lift-off alone, so a leg lifting with one already moved this tick
 * (the other foot of a trot's pair) takes them over: same numbers, one
 * xgo_sincos and seven products fewer. */
static void swing_step(xgo_gait_t *g, gait_tick_t *x, int leg)
{
    const uint32_t theta = g->phase - x->t->lift[leg];
    const gait_swing_weights_t *wt = &x->weights;
#if GAIT_HOST_CACHES
    int32_t td[2], m[4];
#else
    int32_t td[2], f0[2], f1[2];
#endif
    if (!x->have_weights || wt->theta != theta) {
        swing_weights(x->t, theta, &x->weights);
        x->have_weights = 1;
    }
    if ((g->land_is_td >> leg) & 1u) {
        /* the landing point is this velocity's touchdown point (land_point):
         * in a steady walk no touchdown_q8 (three foot velocities' worth of
         * products) */
        td[0] = g->land_q8[leg][0];
        td[1] = g->land_q8[leg][1];
    } else {
        touchdown_q8(g, x, leg, td);
        land_point(g, leg, wt->follow, td);
    }
#if GAIT_HOST_CACHES
    swing_tangents(g, x, leg, td, m);
    swing_coord(g, x, leg, 0, td[0], m[0], m[2]);
    swing_coord(g, x, leg, 1, td[1], m[1], m[3]);
#else
    gait_tick_foot_velocity(x, g->lift_q8[leg][0] >> 8, g->lift_q8[leg][1] >> 8, f0);
    gait_tick_foot_velocity(x, td[0] >> 8, td[1] >> 8, f1);
    swing_axis(g, x, leg, 0, td[0], f0[0], f1[0]);
    swing_axis(g, x, leg, 1, td[1], f0[1], f1[1]);
#endif
    /* the height is at most XGO_GAIT_MAX_HEIGHT_UM < 2^16 (lift_foot) */
    g->foot_um[leg].z = mul_q_u16(wt->s2, (uint32_t)g->swing_height_um[leg], 30u);
}

/* The swing's duration at this tick's rate (swing_step). */
static void swing_time(const xgo_gait_t *g, gait_tick_t *x)
{
    const uint32_t r = x->rate >> 8;
    /* at the fitted rate (no transient raised it) under the table it was
     * fitted for, the one kept with it (fit_cadence, this tick: g->type
     * differs from its cache_v_type only after a switch, and x->t is
     * g->type's table) */
    x->swing_q16 = x->rate == g->cache_rate_fit && g->type == g->cache_v_type
                       ? g->cache_swing_q16
                       : x->t->k_swing / (r == 0u ? 1u : r);
    /* < 2^16 (mul_q_u16): the rate is at least rate_fit (pick_cadence), so
     * the swing lasts at most KSWING(1, 2) / 27962 = 39321 */
    XGO_ASSERT(x->swing_q16 < 65536u);
    x->have_weights = 0;
}

/* One leg's events and step, published: a touchdown (unless the
 * touchdowns were done already: land 0), or a lift-off; then a foot not
 * just placed at its touchdown point moves on its path (stance or swing).
 * Each way knows whether the foot is in the air (publish_foot). */
static void step_leg(xgo_gait_t *g, gait_tick_t *x, int leg, int land)
{
    if (g->swinging[leg]) {
        if (land && touch_down(g, x, leg)) {
            publish_foot(g, leg, 0); /* down at its touchdown point for the rest of the tick */
            return;
        }
    } else if (!lift_foot(g, x, leg)) {
        stance_step(g, x, leg);
        publish_foot(g, leg, 0);
        return;
    }
    swing_step(g, x, leg);
    publish_foot(g, leg, 1);
}

/* The master phase advances by the rate; the events it crossed fire in
 * order - touchdowns, a gait switch, lift-offs - and the feet move. A switch
 * can only happen while another gait is asked for (and the command does
 * not rest), and it needs every touchdown first (it waits for four feet
 * down): then the touchdowns go first. Otherwise one leg's events and step
 * do not depend on another's, and each leg goes through them, published,
 * in one pass. */
static void step_legs(xgo_gait_t *g, gait_tick_t *x)
{
    const int switching = x->want_type != g->type && !x->resting;
    unsigned landed = 0; /* bit leg: placed at its touchdown this tick */
    int leg;
    g->phase += x->rate;
    g->rate = x->rate;
    if (switching) {
        int any_swing = 0;
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            if (g->swinging[leg]) {
                if (touch_down(g, x, leg)) {
                    landed |= 1u << leg;
                } else {
                    any_swing = 1;
                }
            }
        }
        switch_gait(g, x, any_swing);
    }
    swing_time(g, x);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (landed == 0u || ((landed >> leg) & 1u) == 0) {
            step_leg(g, x, leg, !switching);
        } else {
            publish_foot(g, leg, 0); /* placed at its touchdown point this tick */
        }
    }
}

/* Outputs: the produced velocity, standing once a zero command has brought
 * every foot home (the feet are published as they move: step_legs). */
static void publish_tick(xgo_gait_t *g, const gait_tick_t *x)
{
    int leg;
    g->vx_um_s = g->v_ramp[0];
    g->vy_um_s = g->v_ramp[1];
    g->vyaw_mdeg_s = g->v_ramp[2];
    if (x->resting) {
        int home = 1;
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            if (g->swinging[leg] || !at_stance(g, leg)) {
                home = 0;
            }
        }
        if (home) {
            g->standing = 1;
            g->rate = 0;
            forget_front(g); /* the next tick starts (start_or_stand) */
        }
    }
}

/* ------------------------------------------------------------ tick */

#if GAIT_HOST_CACHES
/* The front stages (limit, ramp, the nominal and fitted cadence) of a tick
 * that gives them what the last one did: the same command after a front
 * that changed nothing they read (kept by keep_front: walking in the gait
 * asked for, so without a brake, no ramp, the nominal rate reached). The
 * velocity, the rates and the caches they read are then as they left
 * them, so they would repeat its results (the fitted cadence from its
 * cache) and touch nothing but the limit's counter: that is done here
 * instead, from what keep_front kept. Nothing else moves them between the
 * two: a gait switch (type, brake, phase) needs another gait asked for,
 * which keep_front does not keep, and a stop forgets it (publish_tick).
 * Returns 0 (nothing done) otherwise. */
/* steady_front compares the command's five words at its start with
 * front_cmd in one memcmp */
typedef char gait_front_cmd_words[offsetof(xgo_gait_command_t, vx_um_s) == 0 &&
                                          offsetof(xgo_gait_command_t, vy_um_s) == 4 &&
                                          offsetof(xgo_gait_command_t, vyaw_mdeg_s) == 8 &&
                                          offsetof(xgo_gait_command_t, mark_time_um) == 12 &&
                                          offsetof(xgo_gait_command_t, step_height_um) == 16 &&
                                          sizeof(((xgo_gait_t *)0)->front_cmd) == 20
                                      ? 1
                                      : -1];

static int steady_front(xgo_gait_t *g, const xgo_gait_command_t *cmd, gait_tick_t *x, uint32_t *rate_fit)
{
    if (!g->front_kept || memcmp(cmd, g->front_cmd, sizeof g->front_cmd) != 0 ||
        cmd->type != g->front_cmd_type || cmd->pace != g->front_cmd_pace) {
        return 0;
    }
    x->mark = g->front_mark;
    x->height = g->front_height;
    x->want_type = g->type;
    x->resting = g->front_resting;
    x->t = &k_tables[g->type];
    x->hx = XGO_GAIT_HALF_STRIDE_X_UM;
    x->hy = XGO_GAIT_HALF_STRIDE_Y_UM + g->front_widening;
    x->reach_y = XGO_GAIT_REACH_Y_UM + (int32_t)g->front_widening;
    x->vel[0] = g->v_ramp[0];
    x->vel[1] = g->v_ramp[1];
    x->w_q24 = g->front_w_q24;
    if (g->cache_lambda_q16 < 65536) {
        g->limited_ticks++; /* limit_speed's */
    }
    *rate_fit = g->cache_rate_fit;
    return 1;
}

/* After the front stages under cmd: keep what steady_front needs when the
 * next tick's would repeat them - no ramp (x->reach_y is set only then),
 * the nominal rate reached (the slew stays), no gait switch pending (the
 * brake cleared before the limit) - else forget it. */
static void keep_front(xgo_gait_t *g, const xgo_gait_command_t *cmd, const gait_tick_t *x)
{
    g->front_kept = (uint8_t)(x->reach_y != 0 && x->want_type == g->type &&
                              g->rate_base == x->t->rate[x->pace]);
    g->front_cmd[0] = cmd->vx_um_s;
    g->front_cmd[1] = cmd->vy_um_s;
    g->front_cmd[2] = cmd->vyaw_mdeg_s;
    g->front_cmd[3] = cmd->mark_time_um;
    g->front_cmd[4] = cmd->step_height_um;
    g->front_cmd_type = cmd->type;
    g->front_cmd_pace = cmd->pace;
    g->front_mark = x->mark;
    g->front_height = x->height;
    g->front_resting = (uint8_t)x->resting;
    g->front_widening = x->hy - XGO_GAIT_HALF_STRIDE_Y_UM;
    g->front_w_q24 = x->w_q24;
}
#endif

void xgo_gait_tick(xgo_gait_t *g, const xgo_gait_command_t *cmd)
{
    gait_tick_t x;
    uint32_t rate_fit;
    XGO_ASSERT(g != NULL && cmd != NULL);
    g->ticks++;
#if GAIT_HOST_CACHES
    if (!steady_front(g, cmd, &x, &rate_fit))
#endif
    {
        limit_command(cmd, &x);
        if (!start_or_stand(g, &x)) {
            return;
        }
        limit_speed(g, &x);
        ramp_velocity(g, &x);
        slew_rate_base(g, &x);
        rate_fit = fit_cadence(g, &x);
#if GAIT_HOST_CACHES
        keep_front(g, cmd, &x);
#endif
    }
    pick_cadence(g, &x, rate_fit);
    step_legs(g, &x);
    publish_tick(g, &x);
}
