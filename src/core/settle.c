/*
 * settle.c - the feet home to the stance, one move at a time (settle.h).
 */
#include "settle.h"

#include <string.h>

#include "compiler.h" /* XGO_OWN_FRAME */
#include "fixed.h"

#define PAIR_A 0x05u         /* LF + RH: the trot's first pair */
#define PAIR_B 0x0Au         /* RF + LH */
#define STEP_LIFT_MIN_UM 4000 /* a planted foot clears the ground by this at least */
#define LIFT_MAX_UM 15000
#define ONE_Q16 65536

static int64_t sq(int32_t v)
{
    return (int64_t)v * v;
}

static int32_t distance_um(const xgo_vec3_t *a, const xgo_vec3_t *b, int with_z)
{
    const int64_t d2 = sq(a->x - b->x) + sq(a->y - b->y) + (with_z ? sq(a->z - b->z) : 0);
    return (int32_t)xgo_isqrt64((uint64_t)d2);
}

void xgo_settle_coast(xgo_settle_t *s, const int32_t v[3])
{
    memcpy(s->v, v, sizeof s->v);
    if (v[0] != 0 || v[1] != 0 || v[2] != 0) {
        s->active = 1;
    }
}

void xgo_settle_velocity(const xgo_settle_t *s, int32_t v[3])
{
    memcpy(v, s->v, sizeof s->v);
}

static int32_t slow_down(int32_t v, int32_t dv)
{
    return v > dv ? v - dv : (v < -dv ? v + dv : 0);
}

/* The body coasting to rest: the planted feet (not moving in a step) go by
 * -(v + w x p) dt in the machine frame, the velocity slows down. */
static void coast(xgo_settle_t *s)
{
    /* mdeg/s * um -> um per tick: pi / 180000 / TICKS, Q40 (pi 2^40 = 3454217652224) */
    static const int64_t k_w_q40 = (int64_t)(3454217652224ULL / (180000ULL * XGO_TICK_HZ));
    unsigned leg;
    if ((s->v[0] | s->v[1] | s->v[2]) == 0) {
        return;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (((s->planted & ~s->moving) >> leg) & 1u) {
            xgo_vec3_t *p = &s->foot[leg];
            const int32_t wx = (int32_t)(((int64_t)s->v[2] * p->x * k_w_q40) >> 40);
            const int32_t wy = (int32_t)(((int64_t)s->v[2] * p->y * k_w_q40) >> 40);
            p->x -= s->v[0] / (int32_t)XGO_TICK_HZ - wy;
            p->y -= s->v[1] / (int32_t)XGO_TICK_HZ + wx;
        }
    }
    s->v[0] = slow_down(s->v[0], XGO_SETTLE_DECEL_UM_S2 / (int32_t)XGO_TICK_HZ);
    s->v[1] = slow_down(s->v[1], XGO_SETTLE_DECEL_UM_S2 / (int32_t)XGO_TICK_HZ);
    s->v[2] = slow_down(s->v[2], XGO_SETTLE_YAW_DECEL_MDEG_S2 / (int32_t)XGO_TICK_HZ);
}

/* Planted feet that are home (or within XGO_SETTLE_HOME_UM of it) are put
 * there; returns the legs that still have to move. */
static uint8_t legs_away(xgo_settle_t *s, const xgo_vec3_t stance[XGO_LEG_COUNT])
{
    uint8_t away = 0;
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        const int planted = (s->planted >> leg) & 1u;
        if (planted && distance_um(&s->foot[leg], &stance[leg], 1) <= XGO_SETTLE_HOME_UM) {
            s->foot[leg] = stance[leg];
        } else {
            away |= (uint8_t)(1u << leg);
        }
    }
    return away;
}

void xgo_settle_start(xgo_settle_t *s, const xgo_vec3_t feet[XGO_LEG_COUNT], uint8_t contact,
                      const xgo_vec3_t stance[XGO_LEG_COUNT])
{
    memcpy(s->foot, feet, sizeof s->foot);
    s->planted = (uint8_t)(contact & 0x0Fu);
    s->moving = 0;
    s->v[0] = s->v[1] = s->v[2] = 0;
    s->active = legs_away(s, stance) != 0;
}

/* The next move: the feet in the air first, then the pair with the foot
 * farthest from home. Clears active when there is none. */
static void plan_move(xgo_settle_t *s, const xgo_vec3_t stance[XGO_LEG_COUNT])
{
    const uint8_t away = legs_away(s, stance);
    const uint8_t air = (uint8_t)(~s->planted & 0x0Fu);
    int32_t far = -1, far_xy = 0;
    unsigned leg, far_leg = 0;
    if (away == 0) {
        return; /* nothing to step: home, or the body still coasting */
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        int32_t d;
        if (((away >> leg) & 1u) == 0u) {
            continue;
        }
        d = distance_um(&s->foot[leg], &stance[leg], 1);
        if (d > far) {
            far = d;
            far_leg = leg;
        }
    }
    s->moving = air != 0 ? air : (uint8_t)(away & ((PAIR_A >> far_leg) & 1u ? PAIR_A : PAIR_B));
    far = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if ((s->moving >> leg) & 1u) {
            const int32_t d = distance_um(&s->foot[leg], &stance[leg], 1);
            const int32_t dxy = distance_um(&s->foot[leg], &stance[leg], 0);
            far = d > far ? d : far;
            far_xy = dxy > far_xy ? dxy : far_xy;
        }
    }
    s->ticks = (uint16_t)(XGO_SETTLE_MOVE_BASE_TICKS + (uint32_t)far / 500u);
    s->ticks = s->ticks > XGO_SETTLE_MOVE_MAX_TICKS ? (uint16_t)XGO_SETTLE_MOVE_MAX_TICKS : s->ticks;
    s->lift_um = far_xy / 4 + (air != 0 ? 0 : STEP_LIFT_MIN_UM);
    s->lift_um = s->lift_um > LIFT_MAX_UM ? LIFT_MAX_UM : s->lift_um;
    s->tick = 0;
    memcpy(s->from, s->foot, sizeof s->from);
    s->planted = (uint8_t)(s->planted & ~s->moving);
}

/* a + (b - a) * f, f in Q16. Out of line: move_feet's three calls a leg
 * would each inline its 64-bit product (about 50 bytes of flash). */
XGO_OWN_FRAME static int32_t lerp(int32_t a, int32_t b, int32_t f)
{
    return a + (int32_t)(((int64_t)(b - a) * f + ONE_Q16 / 2) >> 16);
}

/* The moving feet at this tick of their move: smootherstep across (zero
 * velocity and acceleration at both ends), down to the ground, plus a bump
 * 16 u^2 (1 - u)^2 of the lift (zero slope at both ends). */
static void move_feet(xgo_settle_t *s, const xgo_vec3_t stance[XGO_LEG_COUNT])
{
    const int32_t u = (int32_t)(((uint32_t)s->tick << 16) / s->ticks); /* Q16 */
    const int32_t u2 = (int32_t)(((int64_t)u * u) >> 16), u3 = (int32_t)(((int64_t)u2 * u) >> 16);
    /* h = u^3 (10 - 15 u + 6 u^2) */
    const int32_t h = (int32_t)(((int64_t)u3 * (10 * ONE_Q16 - 15 * u + 6 * u2)) >> 16);
    const int32_t w = u - u2; /* u (1 - u), at most 1/4 */
    const int32_t bump = (int32_t)(((int64_t)16 * w * w) >> 16);
    const int32_t up = (int32_t)(((int64_t)s->lift_um * bump) >> 16);
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if ((s->moving >> leg) & 1u) {
            xgo_vec3_t *f = &s->foot[leg];
            f->x = lerp(s->from[leg].x, stance[leg].x, h);
            f->y = lerp(s->from[leg].y, stance[leg].y, h);
            f->z = lerp(s->from[leg].z, stance[leg].z, h) + up;
        }
    }
}

int xgo_settle_tick(xgo_settle_t *s, const xgo_vec3_t stance[XGO_LEG_COUNT],
                    xgo_vec3_t feet[XGO_LEG_COUNT], uint8_t *contact)
{
    if (s->active) {
        coast(s);
        if (s->moving == 0) {
            plan_move(s, stance);
        }
        if (s->moving != 0) {
            s->tick++;
            move_feet(s, stance);
            if (s->tick >= s->ticks) { /* landed exactly home */
                unsigned leg;
                for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                    if ((s->moving >> leg) & 1u) {
                        s->foot[leg] = stance[leg];
                    }
                }
                s->planted = (uint8_t)(s->planted | s->moving);
                s->moving = 0; /* the next move starts next tick, if there is one */
            }
        }
        if (s->moving == 0 && legs_away(s, stance) == 0 && (s->v[0] | s->v[1] | s->v[2]) == 0) {
            s->active = 0;
        }
    }
    if (!s->active) {
        memcpy(feet, stance, sizeof s->foot);
        *contact = 0x0Fu;
        return 0;
    }
    memcpy(feet, s->foot, sizeof s->foot);
    *contact = s->planted;
    return 1;
}
