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
 *     budget (x: 32 mm; y: 16 mm + yaw share) around the stance point,
 *   - the transient rate: every stance foot must reach its lift-off before
 *     it crosses the edge of that budget at its current velocity;
 * capped per gait. If the fit rate exceeds the cap the velocity is scaled
 * down (never inside the vendor ranges).
 *
 * Integer arithmetic only. Positions are kept in 1/256 um so that slow
 * velocities integrate without rounding drift.
 */
#include "xgo/gait.h"

#include "xgo/fixed.h"

/* ------------------------------------------------------------ tables */

#define Q32(num, den) ((uint32_t)((4294967296ULL * (uint64_t)(num)) / (uint64_t)(den)))
/* Phase advance per 2 ms tick for a cycle of ms milliseconds: 2^33 / ms. */
#define RATE(ms) ((uint32_t)(8589934592ULL / (uint64_t)(ms)))
/* Duty dn/dd: D * 2^32 / 1000 and D * 2^40 / 1000 (see fit_rate, tau). */
#define KRATE(dn, dd) ((uint32_t)((4294967296ULL * (uint64_t)(dn)) / (1000ULL * (uint64_t)(dd))))
#define KTAU(dn, dd) ((uint32_t)((1099511627776ULL * (uint64_t)(dn)) / (1000ULL * (uint64_t)(dd))))

typedef struct gait_table_s {
    uint32_t swing;         /* swing fraction S of the cycle, Q32 */
    uint32_t inv_swing_q16; /* 1 / S, Q16 */
    uint32_t lift[XGO_LEG_COUNT]; /* lift-off phase per leg, Q32 */
    uint32_t k_rate;        /* D * 2^32 / 1000 (D = 1 - S, the duty factor) */
    uint32_t k_tau;         /* D * 2^40 / 1000 */
    uint32_t rate[XGO_PACE_COUNT]; /* nominal cadence per pace */
    uint32_t rate_max;      /* cadence cap */
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
      { RATE(400), RATE(600), RATE(300) }, RATE(240), { 400, 600, 300 },
      20000, 0, 50 },
    /* XGO_GAIT_WALK */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(240), { 800, 1200, 600 },
      20000, 1, 75 },
    /* XGO_GAIT_HIGH_WALK: the walk's timing, a higher swing */
    { Q32(1, 4), 4u << 16, WALK_LIFT, KRATE(3, 4), KTAU(3, 4),
      { RATE(800), RATE(1200), RATE(600) }, RATE(240), { 800, 1200, 600 },
      30000, 1, 75 },
    /* XGO_GAIT_SLOW_TROT: trot pairs, duty 0.6, longer periods */
    { Q32(2, 5), (5u << 16) / 2u, TROT_LIFT, KRATE(3, 5), KTAU(3, 5),
      { RATE(600), RATE(800), RATE(450) }, RATE(300), { 600, 800, 450 },
      20000, 2, 60 },
};

/* mdeg/s -> rad/s in Q24: pi / 180000 * 2^24 * 2^16 (applied with q = 16). */
#define K_MDEG_TO_RAD_Q24_Q16 19190957
/* um/s -> 1/256 um per tick: 256 / 500 * 2^31 (applied with q = 31). */
#define K_UMS_TO_Q8_TICK_Q31 1099511628
#define TICKS_PER_S 500u
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
 * phase rate per tick: (speed / h) * D * 2^32 / 1000. speed < 2^21. */
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
    out[0] = v[0] - xgo_mul_q(w_q24, y_um, 24u);
    out[1] = v[1] + xgo_mul_q(w_q24, x_um, 24u);
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
        g->swinging[leg] = 0;
    }
    g->phase = 0;
    g->rate = 0;
    g->rate_base = k_tables[XGO_GAIT_TROT].rate[XGO_PACE_NORMAL];
    g->type = XGO_GAIT_TROT;
    g->standing = 1;
    g->v_ramp[0] = g->v_ramp[1] = g->v_ramp[2] = 0;
    g->vx_um_s = g->vy_um_s = g->vyaw_mdeg_s = 0;
    g->ticks = 0;
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

void xgo_gait_tick(xgo_gait_t *g, const xgo_gait_command_t *cmd)
{
    static const int32_t step_max[3] = {
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_ACCEL_UM_S2 / (int32_t)TICKS_PER_S,
        XGO_GAIT_YAW_ACCEL_MDEG_S2 / (int32_t)TICKS_PER_S,
    };
    int32_t target[3];
    int32_t vel[2];
    int32_t w_q24;
    int32_t mark;
    uint8_t want_type;
    uint8_t pace;
    const gait_table_t *t;
    uint32_t hx, hy;
    uint32_t max_fx = 0, max_fy = 0;
    uint32_t rate_fit, rate, rate_state;
    uint32_t tau_q16;
    int32_t vf[XGO_LEG_COUNT][2];
    int32_t z_um[XGO_LEG_COUNT] = { 0, 0, 0, 0 };
    uint8_t was_stance[XGO_LEG_COUNT];
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

    if (g->standing) {
        g->type = want_type;
        g->rate_base = k_tables[want_type].rate[pace];
        if (target[0] == 0 && target[1] == 0 && target[2] == 0 && mark == 0) {
            g->rate = 0;
            return; /* outputs unchanged: feet at stance */
        }
        /* Start: the first lift-off event fires on this tick. */
        g->standing = 0;
        g->phase = 0xFFFFFFFFu;
    }

    /* ---- velocity ramp ---- */
    for (c = 0; c < 3; ++c) {
        int32_t d = clamp32(target[c] - g->v_ramp[c], -step_max[c], step_max[c]);
        g->v_ramp[c] += d;
    }

    /* ---- nominal cadence, slewed (about 0.8 % per tick) ---- */
    t = table_of(g->type);
    {
        uint32_t nominal = t->rate[pace];
        uint32_t step = (max_u(nominal, g->rate_base) >> 7) + 1u;
        if (g->rate_base + step < nominal) {
            g->rate_base += step;
        } else if (g->rate_base > nominal + step) {
            g->rate_base -= step;
        } else {
            g->rate_base = nominal;
        }
    }

    /* ---- stride fitting: the cadence that keeps every stride in budget ---- */
    hx = XGO_GAIT_HALF_STRIDE_X_UM;
    {
        uint32_t yaw = abs_u(g->v_ramp[2]);
        if (yaw > (uint32_t)XGO_GAIT_YAW_REF_MDEG_S) {
            yaw = XGO_GAIT_YAW_REF_MDEG_S;
        }
        hy = XGO_GAIT_HALF_STRIDE_Y_UM +
             yaw * (uint32_t)XGO_GAIT_YAW_HALF_STRIDE_Y_UM / (uint32_t)XGO_GAIT_YAW_REF_MDEG_S;
    }
    vel[0] = g->v_ramp[0];
    vel[1] = g->v_ramp[1];
    w_q24 = xgo_mul_q(g->v_ramp[2], K_MDEG_TO_RAD_Q24_Q16, 16u);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        int32_t f[2];
        foot_velocity(vel, w_q24, g->stance_um[leg][0], g->stance_um[leg][1], f);
        max_fx = max_u(max_fx, abs_u(f[0]));
        max_fy = max_u(max_fy, abs_u(f[1]));
    }
    rate_fit = max_u(g->rate_base, max_u(fit_rate(max_fx, hx, t->k_rate),
                                         fit_rate(max_fy, hy, t->k_rate)));
    if (rate_fit > t->rate_max) {
        /* Even the fastest cadence cannot fit: limit the speed. */
        int32_t lambda_q16 = (int32_t)(((uint64_t)t->rate_max << 16) / rate_fit);
        for (c = 0; c < 3; ++c) {
            g->v_ramp[c] = xgo_mul_q(g->v_ramp[c], lambda_q16, 16u);
        }
        vel[0] = g->v_ramp[0];
        vel[1] = g->v_ramp[1];
        w_q24 = xgo_mul_q(g->v_ramp[2], K_MDEG_TO_RAD_Q24_Q16, 16u);
        rate_fit = t->rate_max;
        g->limited_ticks++;
    }
    /* Half the stance time at the fitted cadence, seconds Q16. */
    tau_q16 = t->k_tau / (rate_fit >> 8);

    /* ---- transient rule: stance feet must lift before leaving the budget ---- */
    rate_state = rate_fit;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        uint32_t remaining;
        was_stance[leg] = (uint8_t)!g->swinging[leg];
        if (g->swinging[leg]) {
            continue;
        }
        foot_velocity(vel, w_q24, g->pos_q8[leg][0] >> 8, g->pos_q8[leg][1] >> 8, vf[leg]);
        remaining = 0u - (g->phase - t->lift[leg]);
        for (c = 0; c < 2; ++c) {
            int32_t off = (g->pos_q8[leg][c] >> 8) - g->stance_um[leg][c];
            int32_t d;
            uint64_t travel;
            uint64_t room;
            if (vf[leg][c] == 0) {
                continue;
            }
            d = (int32_t)(c == 0 ? hx : hy) + (vf[leg][c] > 0 ? off : -off);
            if (d <= 0) {
                rate_state = t->rate_max;
                continue;
            }
            travel = (uint64_t)abs_u(vf[leg][c]) * remaining;
            room = (uint64_t)(TICKS_PER_S * (uint32_t)d) * rate_state;
            if (travel > room) {
                rate_state = (uint32_t)(travel / (TICKS_PER_S * (uint32_t)d)) + 1u;
                if (rate_state > t->rate_max) {
                    rate_state = t->rate_max;
                }
            }
        }
    }
    rate = rate_state > t->rate_max ? t->rate_max : rate_state;
    if (rate > rate_fit) {
        g->boosted_ticks++;
    }

    /* ---- phase ---- */
    g->phase += rate;
    g->rate = rate;
    resting = target[0] == 0 && target[1] == 0 && target[2] == 0 && mark == 0 &&
              g->v_ramp[0] == 0 && g->v_ramp[1] == 0 && g->v_ramp[2] == 0;

    /* Touchdowns under the table in use. */
    any_swing = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (g->swinging[leg]) {
            if (g->phase - t->lift[leg] >= t->swing) {
                g->swinging[leg] = 0; /* placed below */
            } else {
                any_swing = 1;
            }
        }
    }

    /* Gait change: tables with the same timing switch at once; otherwise at a
     * lift-off event of a front leg with all four feet down, the new phase
     * being that leg's lift-off phase in the new table. */
    if (want_type != g->type) {
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
                    g->phase = n->lift[f] + theta;
                    g->type = want_type;
                    t = n;
                    g->switches++;
                    break;
                }
            }
        }
    }

    /* Lift-offs. */
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        if (!g->swinging[leg] && was_stance[leg] && g->phase - t->lift[leg] < rate) {
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
        if (was_stance[leg] && !g->swinging[leg]) {
            /* Stance: the ground moves by -(v + w x p) dt. */
            int32_t lim[2];
            lim[0] = XGO_GAIT_REACH_X_UM * 256;
            lim[1] = CLAMP_Y_UM * 256;
            for (c = 0; c < 2; ++c) {
                int32_t nom = g->stance_um[leg][c] * 256;
                int32_t p = g->pos_q8[leg][c] - xgo_mul_q(vf[leg][c], K_UMS_TO_Q8_TICK_Q31, 31u);
                if (p > nom + lim[c] || p < nom - lim[c]) {
                    p = clamp32(p, nom - lim[c], nom + lim[c]);
                    g->clamped_ticks++;
                }
                g->pos_q8[leg][c] = p;
            }
        } else {
            /* Swing (or touchdown this tick): towards the touchdown point,
             * half the stance travel ahead of the stance point. */
            int32_t f[2];
            int32_t td[2];
            foot_velocity(vel, w_q24, g->stance_um[leg][0], g->stance_um[leg][1], f);
            for (c = 0; c < 2; ++c) {
                td[c] = (g->stance_um[leg][c] + xgo_mul_q(f[c], (int32_t)tau_q16, 16u)) * 256;
            }
            if (!g->swinging[leg]) {
                g->pos_q8[leg][0] = td[0]; /* touchdown */
                g->pos_q8[leg][1] = td[1];
            } else {
                uint32_t theta = g->phase - t->lift[leg];
                uint32_t psi = (uint32_t)(((uint64_t)theta * t->inv_swing_q16) >> 16);
                xgo_q30_t s, co, h;
                xgo_sincos(psi >> 1, &s, &co); /* pi * psi */
                h = (XGO_Q30_ONE >> 1) - (co >> 1); /* 0 -> 1, zero slope at both ends */
                for (c = 0; c < 2; ++c) {
                    g->pos_q8[leg][c] = g->lift_q8[leg][c] +
                                        xgo_mul_q(td[c] - g->lift_q8[leg][c], h, 30u);
                }
                z_um[leg] = xgo_mul_q(g->swing_height_um[leg], xgo_mul_q(s, s, 30u), 30u);
            }
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
