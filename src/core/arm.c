/*
 * The Mini2's arm (see arm.h): kinematics, servos, registers.
 */
#include "arm.h"

#include <string.h>

#include "codec.h"
#include "xgo/config.h"
#include "fixed.h"
#include "wide.h"

#if XGO_WITH_MINI2 /* else the board has no arm (arm.h) */

#define QUARTER_TURN ((xgo_bam_t)0x40000000u)

/* v * q (Q30), in the unit of v, rounded. */
static int32_t mul_q30(int32_t v, xgo_q30_t q)
{
    return (int32_t)((xgo_mul_wide(v, q) + (1 << 29)) >> 30);
}

static int32_t clamp_range(int32_t v, const xgo_range_t *r)
{
    return v < r->lo ? r->lo : (v > r->hi ? r->hi : v);
}

/* Geometric angle (BAM) of a servo angle: minus the servo's zero. */
static xgo_bam_t geo_angle(const xgo_arm_geometry_t *g, xgo_arm_joint_t j, int32_t servo_mdeg)
{
    return xgo_mdeg_to_bam(servo_mdeg - g->zero_mdeg[j]);
}

/* Servo angle of a geometric angle (BAM). */
static int32_t servo_angle(const xgo_arm_geometry_t *g, xgo_arm_joint_t j, xgo_bam_t geo)
{
    return xgo_bam_to_mdeg(geo) + g->zero_mdeg[j];
}

void xgo_arm_points(const xgo_arm_geometry_t *g, const int32_t q_mdeg[XGO_ARM_JOINT_COUNT],
                    int32_t *elbow_x, int32_t *elbow_z, int32_t *claw_x, int32_t *claw_z)
{
    const xgo_bam_t s = geo_angle(g, XGO_ARM_SHOULDER, q_mdeg[XGO_ARM_SHOULDER]);
    xgo_q30_t ss, cs, sb, cb;
    xgo_sincos(s, &ss, &cs);
    xgo_sincos(s + geo_angle(g, XGO_ARM_ELBOW, q_mdeg[XGO_ARM_ELBOW]), &sb, &cb);
    *elbow_x = mul_q30(g->upper_um, ss);
    *elbow_z = mul_q30(g->upper_um, cs);
    *claw_x = *elbow_x + mul_q30(g->fore_um, cb);
    *claw_z = *elbow_z - mul_q30(g->fore_um, sb);
}

void xgo_arm_fk(const xgo_arm_geometry_t *g, const int32_t q_mdeg[XGO_ARM_JOINT_COUNT],
                int32_t *x_um, int32_t *z_um)
{
    int32_t ex, ez;
    xgo_arm_points(g, q_mdeg, &ex, &ez, x_um, z_um);
}

static int64_t miss2(const xgo_arm_geometry_t *g, const int32_t q[XGO_ARM_JOINT_COUNT], int32_t x,
                     int32_t z)
{
    int32_t px, pz;
    xgo_arm_fk(g, q, &px, &pz);
    return xgo_mul_wide(px - x, px - x) + xgo_mul_wide(pz - z, pz - z);
}

/* The angle k between the upper arm and the forearm's direction for a claw
 * point at distance^2 d2 (law of cosines), clamped to [0, 180] degrees
 * (too far: stretched; too close: folded). */
static xgo_bam_t fold_angle(const xgo_arm_geometry_t *g, int64_t d2)
{
    const int64_t num = d2 - (int64_t)g->upper_um * g->upper_um - (int64_t)g->fore_um * g->fore_um;
    const int64_t den = ((int64_t)2 * g->upper_um * g->fore_um) >> 10; /* > 2^20 */
    /* Q30, |num| < 2^43; only [-1, 1] matters (no 64-bit division) */
    const uint64_t mag = (uint64_t)(num < 0 ? -num : num) << 20;
    const int32_t c = (int32_t)xgo_udiv64_cap(mag, (uint64_t)den, (uint32_t)1 << 30);
    return xgo_acos(num < 0 ? -c : c);
}

/* Servo angles for the solution with fold angle k (either sign). Math
 * angles: x forward, z up; phi1 the upper arm's direction, phi1 - k the
 * forearm's. */
static void solve_with(const xgo_arm_geometry_t *g, int32_t x, int32_t z, xgo_bam_t k,
                       int32_t q[XGO_ARM_JOINT_COUNT])
{
    xgo_q30_t sk, ck;
    xgo_bam_t phi1, s;
    xgo_sincos(k, &sk, &ck);
    phi1 = xgo_atan2(z, x) + xgo_atan2(mul_q30(g->fore_um, sk), g->upper_um + mul_q30(g->fore_um, ck));
    s = QUARTER_TURN - phi1;
    q[XGO_ARM_SHOULDER] = servo_angle(g, XGO_ARM_SHOULDER, s);
    /* the forearm's angle below horizontal, k - phi1, less the shoulder's */
    q[XGO_ARM_ELBOW] = servo_angle(g, XGO_ARM_ELBOW, (k - phi1) - s);
}

/* A point reached exactly at a limit may come out a few mdeg past it
 * (rounding): within this slack it counts as within, clamped onto the
 * limit. */
#define LIMIT_SLACK_MDEG 5

static int in_limits(const xgo_arm_geometry_t *g, int32_t q[XGO_ARM_JOINT_COUNT])
{
    const xgo_range_t *re = &g->joint_mdeg[XGO_ARM_ELBOW], *rs = &g->joint_mdeg[XGO_ARM_SHOULDER];
    if (q[XGO_ARM_ELBOW] < re->lo - LIMIT_SLACK_MDEG || q[XGO_ARM_ELBOW] > re->hi + LIMIT_SLACK_MDEG ||
        q[XGO_ARM_SHOULDER] < rs->lo - LIMIT_SLACK_MDEG ||
        q[XGO_ARM_SHOULDER] > rs->hi + LIMIT_SLACK_MDEG) {
        return 0;
    }
    q[XGO_ARM_ELBOW] = clamp_range(q[XGO_ARM_ELBOW], re);
    q[XGO_ARM_SHOULDER] = clamp_range(q[XGO_ARM_SHOULDER], rs);
    return 1;
}

/* Keeps cand in best when it lands nearer the target. */
static void consider(const xgo_arm_geometry_t *g, int32_t x, int32_t z,
                     const int32_t cand[XGO_ARM_JOINT_COUNT], int32_t best[XGO_ARM_JOINT_COUNT],
                     int64_t *best_miss)
{
    const int64_t m = miss2(g, cand, x, z);
    if (m < *best_miss) {
        *best_miss = m;
        memcpy(best, cand, sizeof(int32_t) * XGO_ARM_JOINT_COUNT);
    }
}

/* Out of reach: the nearest of the points the limits allow among both
 * solutions clamped, the shoulder at a limit with the forearm aimed at the
 * target, and the elbow at a limit with the whole arm turned toward it. */
static void project(const xgo_arm_geometry_t *g, int32_t x, int32_t z,
                    const int32_t sol[2][XGO_ARM_JOINT_COUNT], int32_t q[XGO_ARM_JOINT_COUNT])
{
    const xgo_range_t *rs = &g->joint_mdeg[XGO_ARM_SHOULDER], *re = &g->joint_mdeg[XGO_ARM_ELBOW];
    int64_t best_miss = INT64_MAX;
    int32_t best[XGO_ARM_JOINT_COUNT], c[XGO_ARM_JOINT_COUNT];
    unsigned i;
    memcpy(best, q, sizeof best);
    memcpy(c, q, sizeof c);
    for (i = 0; i < 2; i++) {
        c[XGO_ARM_SHOULDER] = clamp_range(sol[i][XGO_ARM_SHOULDER], rs);
        c[XGO_ARM_ELBOW] = clamp_range(sol[i][XGO_ARM_ELBOW], re);
        consider(g, x, z, c, best, &best_miss);
    }
    for (i = 0; i < 2; i++) {
        const int32_t s = i == 0 ? rs->lo : rs->hi, e = i == 0 ? re->lo : re->hi;
        const xgo_bam_t gs = geo_angle(g, XGO_ARM_SHOULDER, s);
        xgo_q30_t ss, cs;
        int32_t p0x, p0z;
        xgo_sincos(gs, &ss, &cs);
        /* shoulder at its limit, the forearm from the elbow toward the target */
        c[XGO_ARM_SHOULDER] = s;
        c[XGO_ARM_ELBOW] = clamp_range(
            servo_angle(g, XGO_ARM_ELBOW,
                        (xgo_bam_t)0 -
                            xgo_atan2(z - mul_q30(g->upper_um, cs), x - mul_q30(g->upper_um, ss)) - gs),
            re);
        consider(g, x, z, c, best, &best_miss);
        /* elbow at its limit, the rigid arm turned about the shoulder */
        c[XGO_ARM_SHOULDER] = g->zero_mdeg[XGO_ARM_SHOULDER];
        c[XGO_ARM_ELBOW] = e;
        xgo_arm_fk(g, c, &p0x, &p0z);
        c[XGO_ARM_SHOULDER] =
            clamp_range(servo_angle(g, XGO_ARM_SHOULDER, xgo_atan2(p0z, p0x) - xgo_atan2(z, x)), rs);
        consider(g, x, z, c, best, &best_miss);
    }
    q[XGO_ARM_SHOULDER] = best[XGO_ARM_SHOULDER];
    q[XGO_ARM_ELBOW] = best[XGO_ARM_ELBOW];
}

/* The claw lands this close to the target: reached. (Near full stretch a
 * micrometre of target moves the angles by up to 0.1 degree, so "the exact
 * solution is inside the limits" would misjudge points on the edge.) */
#define REACHED_UM 20

int xgo_arm_ik(const xgo_arm_geometry_t *g, int32_t x_um, int32_t z_um,
               int32_t q_mdeg[XGO_ARM_JOINT_COUNT])
{
    int32_t sol[2][XGO_ARM_JOINT_COUNT];
    xgo_bam_t k;
    unsigned i;
    /* beyond 2 m the squares would overflow: the same direction at 1 m is
     * out of reach just the same */
    if (x_um > 2000000 || x_um < -2000000 || z_um > 2000000 || z_um < -2000000) {
        xgo_q30_t s, c;
        xgo_sincos(xgo_atan2(z_um, x_um), &s, &c);
        (void)xgo_arm_ik(g, mul_q30(1000000, c), mul_q30(1000000, s), q_mdeg);
        return XGO_ARM_PROJECTED;
    }
    k = fold_angle(g, xgo_mul_wide(x_um, x_um) + xgo_mul_wide(z_um, z_um));
    memcpy(sol[0], q_mdeg, sizeof sol[0]);
    memcpy(sol[1], q_mdeg, sizeof sol[1]);
    solve_with(g, x_um, z_um, k, sol[0]);                 /* elbow up */
    solve_with(g, x_um, z_um, (xgo_bam_t)0 - k, sol[1]);  /* elbow down */
    for (i = 0; i < 2 && !in_limits(g, sol[i]); i++) {
    }
    if (i < 2) {
        q_mdeg[XGO_ARM_SHOULDER] = sol[i][XGO_ARM_SHOULDER];
        q_mdeg[XGO_ARM_ELBOW] = sol[i][XGO_ARM_ELBOW];
    } else {
        project(g, x_um, z_um, (const int32_t(*)[XGO_ARM_JOINT_COUNT])sol, q_mdeg);
    }
    return miss2(g, q_mdeg, x_um, z_um) <= (int64_t)REACHED_UM * REACHED_UM ? XGO_ARM_REACHED
                                                                          : XGO_ARM_PROJECTED;
}

void xgo_arm_polar_point(int32_t theta_mdeg, int32_t r_um, int32_t *x_um, int32_t *z_um)
{
    xgo_q30_t s, c;
    xgo_sincos(xgo_mdeg_to_bam(theta_mdeg), &s, &c);
    *x_um = mul_q30(r_um, s);
    *z_um = -mul_q30(r_um, c);
}

/* ------------------------------------------------------------ the board's arm */

void xgo_arm_init(xgo_arm_t *a, const xgo_arm_geometry_t *geo)
{
    memset(a, 0, sizeof *a);
    a->geo = geo;
    xgo_arm_reset(a);
}

void xgo_arm_reset(xgo_arm_t *a)
{
    memset(a->target_mdeg, 0, sizeof a->target_mdeg);
    a->follow_point = 0;
    a->out_of_reach = 0;
}

/* Host writes: the claw, a point (x/z or polar), or the arm servos
 * directly; servo writes in the same tick as a point win (sent later). */
static void take_arm_writes(xgo_arm_t *a, xgo_regs_t *r)
{
    const xgo_arm_geometry_t *g = a->geo;
    int cart, polar, servo;
    if (xgo_regs_take_written(r, XGO_REG_CLAW)) {
        a->target_mdeg[XGO_ARM_CLAW] =
            xgo_servo_byte_to_range_mid(&g->joint_mdeg[XGO_ARM_CLAW], xgo_regs_get(r, XGO_REG_CLAW));
    }
    cart = xgo_regs_take_written(r, XGO_REG_ARM_X);
    cart |= xgo_regs_take_written(r, XGO_REG_ARM_Z);
    polar = xgo_regs_take_written(r, XGO_REG_ARM_THETA);
    polar |= xgo_regs_take_written(r, XGO_REG_ARM_R);
    if (cart) {
        a->point_um[0] = xgo_byte_to_range_mid(&g->x_um, xgo_regs_get(r, XGO_REG_ARM_X));
        a->point_um[1] = xgo_byte_to_range_mid(&g->z_um, xgo_regs_get(r, XGO_REG_ARM_Z));
    }
    if (polar) {
        xgo_arm_polar_point(xgo_byte_to_range_mid(&g->theta_mdeg, xgo_regs_get(r, XGO_REG_ARM_THETA)),
                            xgo_byte_to_range_mid(&g->r_um, xgo_regs_get(r, XGO_REG_ARM_R)),
                            &a->point_um[0], &a->point_um[1]);
    }
    a->follow_point |= (uint8_t)(cart | polar);
    servo = 0;
    if (xgo_regs_take_written(r, XGO_REG_ARM_ELBOW)) {
        a->target_mdeg[XGO_ARM_ELBOW] = xgo_servo_byte_to_range_mid(
            &g->joint_mdeg[XGO_ARM_ELBOW], xgo_regs_get(r, XGO_REG_ARM_ELBOW));
        servo = 1;
    }
    if (xgo_regs_take_written(r, XGO_REG_ARM_SHOULDER)) {
        a->target_mdeg[XGO_ARM_SHOULDER] = xgo_servo_byte_to_range_mid(
            &g->joint_mdeg[XGO_ARM_SHOULDER], xgo_regs_get(r, XGO_REG_ARM_SHOULDER));
        servo = 1;
    }
    if (servo) {
        a->follow_point = 0;
        a->out_of_reach = 0;
    }
}

/* The commanded point in today's arm frame: itself, or (hold mode) the
 * point that stays where it was in the machine frame at the standing pose
 * while the body is shifted (x, z) and pitched. */
static void served_point(const xgo_arm_t *a, int hold, const xgo_body_pose_t *pose,
                         const xgo_body_pose_t *stand, int32_t *x, int32_t *z)
{
    const xgo_arm_geometry_t *g = a->geo;
    xgo_q30_t sp, cp;
    int32_t tx, tz, shx, shz;
    if (!hold) {
        *x = a->point_um[0];
        *z = a->point_um[1];
        return;
    }
    xgo_sincos(xgo_mdeg_to_bam(pose->pitch_mdeg), &sp, &cp);
    /* target and shoulder in the machine frame; pitch + lowers the nose */
    tx = stand->x_um + g->shoulder_x_um + a->point_um[0];
    tz = stand->z_um + g->shoulder_z_um + a->point_um[1];
    shx = pose->x_um + mul_q30(g->shoulder_x_um, cp) + mul_q30(g->shoulder_z_um, sp);
    shz = pose->z_um - mul_q30(g->shoulder_x_um, sp) + mul_q30(g->shoulder_z_um, cp);
    /* back into the body frame: R_y(pitch)^T */
    *x = mul_q30(tx - shx, cp) - mul_q30(tz - shz, sp);
    *z = mul_q30(tx - shx, sp) + mul_q30(tz - shz, cp);
}

static void slew(xgo_arm_t *a, const xgo_regs_t *r)
{
    const int32_t per_s = xgo_servo_speed_byte_to_mdeg_s(xgo_regs_get(r, XGO_REG_ARM_SPEED));
    const int32_t step = per_s / (int32_t)XGO_TICK_HZ < 1 ? 1 : per_s / (int32_t)XGO_TICK_HZ;
    unsigned j;
    for (j = 0; j < XGO_ARM_JOINT_COUNT; j++) {
        const int32_t d = a->target_mdeg[j] - a->q_mdeg[j];
        a->q_mdeg[j] += d > step ? step : (d < -step ? -step : d);
    }
}

/* The tick of a model with the arm. Out of line, apart from the test of
 * xgo_arm_tick: a model without one (every tick of a Mini, a Lite) then
 * makes no frame for the arm's locals (x86-64: 19 instructions a tick,
 * mostly saving and restoring registers, against 3). */
static XGO_OWN_FRAME void arm_tick(xgo_arm_t *a, xgo_regs_t *r, const xgo_body_pose_t *pose,
                                   const xgo_body_pose_t *stand)
{
    take_arm_writes(a, r);
    if (a->follow_point) {
        int32_t x, z;
        served_point(a, xgo_regs_get(r, XGO_REG_ARM_MODE) == 1, pose, stand, &x, &z);
        a->out_of_reach = (uint8_t)(xgo_arm_ik(a->geo, x, z, a->target_mdeg) != XGO_ARM_REACHED);
    }
    slew(a, r);
}

void xgo_arm_tick(xgo_arm_t *a, xgo_regs_t *r, const xgo_body_pose_t *pose,
                  const xgo_body_pose_t *stand)
{
    if (a->geo != NULL) {
        arm_tick(a, r, pose, stand);
    }
}

/* The arm's bytes, for a model with one (out of line as arm_tick). */
static XGO_OWN_FRAME void arm_publish(const xgo_arm_t *a, xgo_regs_t *r)
{
    const xgo_arm_geometry_t *g = a->geo;
    xgo_regs_set(r, XGO_REG_SERVO_SPEED,
                 xgo_range_to_byte(&g->read_mdeg[XGO_ARM_CLAW], a->q_mdeg[XGO_ARM_CLAW]));
    xgo_regs_set(r, XGO_REG_ARM_ELBOW,
                 xgo_range_to_byte(&g->read_mdeg[XGO_ARM_ELBOW], a->q_mdeg[XGO_ARM_ELBOW]));
    xgo_regs_set(r, XGO_REG_ARM_SHOULDER,
                 xgo_range_to_byte(&g->read_mdeg[XGO_ARM_SHOULDER], a->q_mdeg[XGO_ARM_SHOULDER]));
}

void xgo_arm_publish(const xgo_arm_t *a, xgo_regs_t *r)
{
    if (a->geo != NULL) {
        arm_publish(a, r);
    }
}
#endif /* XGO_WITH_MINI2 */
