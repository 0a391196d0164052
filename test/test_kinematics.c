/*
 * Profiles, leg IK/FK, body IK and register byte codes against an
 * independent double-precision model written here (transform chain for FK,
 * law of cosines for IK, rotation matrices from libm for body IK), over
 * dense grids of the workspace and the whole register ranges, plus the
 * projection of unreachable targets and every extreme input.
 *
 * The measured maxima are printed (INFO lines) and quoted in
 * docs/geometry.md.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "board_io.h" /* xgo_test_xorshift64 */
#include "codec.h"
#include "reference.h"
#include "unity.h"
#include "kinematics.h"
#include "xgo/regs.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define DEG (M_PI / 180.0)

/* The bounds asserted: what was measured (the INFO lines, docs/fixed-point.md)
 * plus a small margin. Issue 3's goal is 0.1 degree for the leg IK; the
 * integer IK's error is its rounding to whole millidegrees (0.0005) plus
 * the atan2 and square roots' last bits. */
#define IK_BOUND_DEG 0.0007   /* measured 0.00059 deg */
#define FK_IK_BOUND_UM 3.0    /* measured 2.45 um */
#define FK_BOUND_UM 1.0       /* measured 0.87 um */
#define BODY_BOUND_UM 1.6     /* measured 1.38 um (rotation cut to Q18) */

void setUp(void) {}
void tearDown(void) {}

static uint64_t rng_state = 0x2545F4914F6CDD1Dull;
static uint32_t rnd32(void)
{
    return xgo_test_xorshift64(&rng_state);
}
static double rnd_unit(void) /* [0, 1) */
{
    return (double)rnd32() / 4294967296.0;
}

static void report(const char *what, double value, const char *unit)
{
    char msg[200];
    snprintf(msg, sizeof msg, "measured %s: %.4g %s", what, value, unit);
    TEST_MESSAGE(msg);
}

/* ------------------------------------------------------------ reference */

typedef struct {
    double x, y, z;
} dvec;

static int side_y(int leg)
{
    return (leg == 0 || leg == 3) ? 1 : -1;
}
static int side_x(int leg)
{
    return (leg == 0 || leg == 1) ? 1 : -1;
}

/* Reference FK as a transform chain in a z-up frame at the thigh joint
 * (mini2 URDF layout): abduction axis at y = -s*d about +x (outward = s*phi),
 * hip pitch and knee about +y, foot at (L2 cos k, 0, -L2 sin k) from the knee
 * at x1 = 0 (k = knee offset). Returns the foot in the leg frame (z down), mm. */
static dvec ref_fk(const xgo_profile_t *p, int leg, const double q_deg[3])
{
    double s = side_y(leg);
    double d = p->abad_offset_um / 1000.0, l1 = p->thigh_um / 1000.0, l2 = p->shank_um / 1000.0;
    double k = p->knee_offset_mdeg / 1000.0 * DEG;
    double a = s * q_deg[2] * DEG, t2 = q_deg[1] * DEG, t1 = q_deg[0] * DEG;
    /* shank vector, rotated by the knee about +y: Ry(t)(x,0,z) = (x c + z s, 0, -x s + z c) */
    double fx = l2 * cos(k), fz = -l2 * sin(k);
    double sx = fx * cos(t1) + fz * sin(t1), sz = -fx * sin(t1) + fz * cos(t1);
    /* plus the thigh, rotated by the hip pitch */
    double tx = sx, tz = sz - l1;
    double hx = tx * cos(t2) + tz * sin(t2), hz = -tx * sin(t2) + tz * cos(t2);
    /* plus the offset to the thigh joint, rotated about +x by a:
     * Rx(a)(0,y,z) = (0, y c - z s, y s + z c) */
    double oy = s * d, oz = hz;
    dvec r;
    r.x = hx;
    r.y = -s * d + oy * cos(a) - oz * sin(a);
    r.z = -(oy * sin(a) + oz * cos(a));
    return r;
}

/* Reference IK of one branch (foot in the leg frame, mm -> degrees), law of
 * cosines. branch +1: foot at or below the thigh joint's level in the leg
 * plane, -1: above it. Returns 0 when the point is outside the link lengths. */
static int ref_ik_branch(const xgo_profile_t *p, int leg, dvec f, int branch, double q_deg[3])
{
    double s = side_y(leg);
    double d = p->abad_offset_um / 1000.0, l1 = p->thigh_um / 1000.0, l2 = p->shank_um / 1000.0;
    double wp = s * f.y + d, z = f.z;
    double h2 = wp * wp + z * z - d * d, h, r, cg, cb;
    if (h2 < 0) {
        return 0;
    }
    h = branch * sqrt(h2);
    /* (wp, z) = Rot(phi) (d, h): cos phi ~ d wp + h z, sin phi ~ h wp - d z */
    q_deg[2] = atan2(h * wp - d * z, d * wp + h * z) / DEG;
    r = sqrt(f.x * f.x + h * h);
    cg = (l1 * l1 + l2 * l2 - r * r) / (2 * l1 * l2); /* interior knee angle */
    cb = (l1 * l1 + r * r - l2 * l2) / (2 * l1 * r);  /* hip-to-foot vs thigh */
    if (cg < -1 || cg > 1 || cb < -1 || cb > 1) {
        return 0;
    }
    q_deg[0] = acos(cg) / DEG - 90.0 - p->knee_offset_mdeg / 1000.0;
    q_deg[1] = atan2(-f.x, h) / DEG + acos(cb) / DEG;
    if (q_deg[1] > 180.0) {
        q_deg[1] -= 360.0; /* the sum of two angles may leave (-180, 180] */
    }
    return 1;
}

static int ref_within_limits(const xgo_profile_t *p, const double q[3], double margin_deg)
{
    int j;
    for (j = 0; j < 3; ++j) {
        if (q[j] < p->joint_mdeg[j].lo / 1000.0 + margin_deg ||
            q[j] > p->joint_mdeg[j].hi / 1000.0 - margin_deg) {
            return 0;
        }
    }
    return 1;
}

/* Reference IK with the branch rule of docs/geometry.md: the lower branch if
 * it is within the limits (by margin_deg), else the upper one. Returns 1 and
 * the angles when one is, 0 when neither is. */
static int ref_ik_margin(const xgo_profile_t *p, int leg, dvec f, double q_deg[3], double margin_deg)
{
    if (ref_ik_branch(p, leg, f, 1, q_deg) && ref_within_limits(p, q_deg, margin_deg)) {
        return 1;
    }
    if (ref_ik_branch(p, leg, f, -1, q_deg) && ref_within_limits(p, q_deg, margin_deg)) {
        return 1;
    }
    return 0;
}

static int ref_ik(const xgo_profile_t *p, int leg, dvec f, double q_deg[3])
{
    return ref_ik_margin(p, leg, f, q_deg, 0.0);
}

static double dist_um(const xgo_vec3_t *a, dvec b_mm)
{
    double dx = a->x / 1000.0 - b_mm.x, dy = a->y / 1000.0 - b_mm.y, dz = a->z / 1000.0 - b_mm.z;
    return sqrt(dx * dx + dy * dy + dz * dz) * 1000.0;
}

static xgo_vec3_t to_um(dvec v)
{
    xgo_vec3_t r;
    r.x = (int32_t)lround(v.x * 1000.0);
    r.y = (int32_t)lround(v.y * 1000.0);
    r.z = (int32_t)lround(v.z * 1000.0);
    return r;
}

static dvec to_mm(const xgo_vec3_t *v)
{
    dvec r;
    r.x = v->x / 1000.0;
    r.y = v->y / 1000.0;
    r.z = v->z / 1000.0;
    return r;
}

static void assert_within_limits(const xgo_profile_t *p, const int32_t q[3])
{
    int j;
    for (j = 0; j < 3; ++j) {
        TEST_ASSERT_TRUE(q[j] >= p->joint_mdeg[j].lo && q[j] <= p->joint_mdeg[j].hi);
    }
}

/* ------------------------------------------------------------ profiles */

/* ------------------------------------------------------------ conventions */

static void test_sign_conventions_and_zero_pose(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    int32_t zero[3] = {0, 0, 0};
    xgo_vec3_t f, g;
    int leg;
    for (leg = 0; leg < 4; ++leg) {
        int32_t q[3] = {0, 0, 0};
        /* x1 = x2 = x3 = 0 is the URDF pose: thigh down, foot 75.988 mm
         * ahead of the knee and 1 mm below it */
        xgo_leg_fk(p, (xgo_leg_t)leg, zero, &f);
        TEST_ASSERT_INT32_WITHIN(1, 75988, f.x);
        TEST_ASSERT_INT32_WITHIN(1, 0, f.y);
        TEST_ASSERT_INT32_WITHIN(1, 60900, f.z);
        /* + abduction moves the foot outward */
        q[XGO_JOINT_ABAD] = 10000;
        xgo_leg_fk(p, (xgo_leg_t)leg, q, &g);
        TEST_ASSERT_TRUE(side_y(leg) * g.y > 5000);
        /* + hip pitch swings the foot backward */
        q[XGO_JOINT_ABAD] = 0;
        q[XGO_JOINT_HIP] = 10000;
        xgo_leg_fk(p, (xgo_leg_t)leg, q, &g);
        TEST_ASSERT_TRUE(g.x < f.x - 5000);
        /* + knee extends the leg (foot farther from the thigh joint) */
        q[XGO_JOINT_HIP] = 0;
        q[XGO_JOINT_KNEE] = 10000;
        xgo_leg_fk(p, (xgo_leg_t)leg, q, &g);
        TEST_ASSERT_TRUE((double)g.x * g.x + (double)g.z * g.z > (double)f.x * f.x + (double)f.z * f.z);
    }
}

static void test_standing_pose(void)
{
    const xgo_profile_t *profiles[2];
    int i, leg;
    profiles[0] = xgo_profile_mini();
    profiles[1] = xgo_profile_lite();
    for (i = 0; i < 2; ++i) {
        const xgo_profile_t *p = profiles[i];
        xgo_body_pose_t pose;
        xgo_vec3_t feet[4], legs[4];
        int32_t q[4][3];
        uint8_t bytes[12];
        char msg[160];
        xgo_body_pose_stand(p, &pose);
        xgo_stance_feet(p, feet);
        xgo_body_ik(p, &pose, feet, legs);
        for (leg = 0; leg < 4; ++leg) {
            TEST_ASSERT_EQUAL_INT32(0, legs[leg].x);
            TEST_ASSERT_EQUAL_INT32(0, legs[leg].y);
            TEST_ASSERT_EQUAL_INT32(p->stand_height_um, legs[leg].z);
        }
        TEST_ASSERT_EQUAL_UINT(0u, xgo_body_to_joints(p, &pose, feet, q));
        xgo_joints_to_bytes(p, (const int32_t(*)[3])q, bytes);
        for (leg = 1; leg < 4; ++leg) {
            TEST_ASSERT_EQUAL_INT32(q[0][0], q[leg][0]);
            TEST_ASSERT_EQUAL_INT32(q[0][1], q[leg][1]);
            TEST_ASSERT_EQUAL_INT32(0, q[leg][2]);
        }
        TEST_ASSERT_EQUAL_HEX8(0x7F, bytes[2]); /* abduction 0 -> 0x7F, as the vendor sends */
        snprintf(msg, sizeof msg,
                 "%s standing at %d um: x1 %d mdeg (0x%02X), x2 %d mdeg (0x%02X), x3 %d (0x%02X)",
                 p->name, (int)p->stand_height_um, (int)q[0][0], bytes[0], (int)q[0][1], bytes[1],
                 (int)q[0][2], bytes[2]);
        TEST_MESSAGE(msg);
    }
}

/* ------------------------------------------------------------ FK */

static void test_fk_against_reference(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    double max_err = 0;
    int leg, a, b, c;
    for (leg = 0; leg < 4; ++leg) {
        for (a = 0; a <= 30; ++a) {
            for (b = 0; b <= 30; ++b) {
                for (c = 0; c <= 10; ++c) {
                    /* beyond the limits too: FK takes any angle */
                    int32_t q[3];
                    double qd[3];
                    xgo_vec3_t f;
                    double e;
                    q[0] = -90000 + a * 6000 + (int32_t)(rnd32() % 1000);
                    q[1] = -120000 + b * 8000 + (int32_t)(rnd32() % 1000);
                    q[2] = -45000 + c * 9000 + (int32_t)(rnd32() % 1000);
                    qd[0] = q[0] / 1000.0;
                    qd[1] = q[1] / 1000.0;
                    qd[2] = q[2] / 1000.0;
                    xgo_leg_fk(p, (xgo_leg_t)leg, q, &f);
                    e = dist_um(&f, ref_fk(p, leg, qd));
                    if (e > max_err) {
                        max_err = e;
                    }
                }
            }
        }
    }
    report("FK error vs double reference", max_err, "um");
    TEST_ASSERT_TRUE(max_err <= FK_BOUND_UM);
}

/* ------------------------------------------------------------ IK grids */

typedef struct {
    double max_angle_err_deg;
    double max_fk_err_um;
    long points;
    long projected;
    long skipped;
} ik_stats_t;

static void ik_check_point(const xgo_profile_t *p, int leg, const xgo_vec3_t *target, ik_stats_t *st)
{
    int32_t q[3];
    double qr[3];
    xgo_vec3_t back;
    int j, res;
    dvec t = to_mm(target);
    res = xgo_leg_ik(p, (xgo_leg_t)leg, target, q);
    st->points++;
    if (res != XGO_IK_REACHED) {
        st->projected++;
        return;
    }
    assert_within_limits(p, q);
    TEST_ASSERT_TRUE(ref_ik(p, leg, t, qr));
    for (j = 0; j < 3; ++j) {
        double e = fabs(q[j] / 1000.0 - qr[j]);
        if (e > st->max_angle_err_deg) {
            st->max_angle_err_deg = e;
        }
    }
    xgo_leg_fk(p, (xgo_leg_t)leg, q, &back);
    {
        double e = dist_um(&back, t);
        if (e > st->max_fk_err_um) {
            st->max_fk_err_um = e;
        }
    }
}

/* The operational workspace: every foot position the foot registers can
 * express, on a 1 mm grid (Mini: 71 x 37 x 41 = 107,707 points per leg). */
static void test_ik_register_box_grid_all_legs(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    int leg;
    ik_stats_t st;
    char msg[200];
    memset(&st, 0, sizeof st);
    for (leg = 0; leg < 4; ++leg) {
        int32_t x, y, z;
        long before = st.points;
        for (x = p->foot_um[0].lo; x <= p->foot_um[0].hi; x += 1000) {
            for (y = p->foot_um[1].lo; y <= p->foot_um[1].hi; y += 1000) {
                for (z = p->foot_um[2].lo; z <= p->foot_um[2].hi; z += 1000) {
                    xgo_vec3_t t;
                    t.x = x;
                    t.y = y;
                    t.z = z;
                    ik_check_point(p, leg, &t, &st);
                }
            }
        }
        TEST_ASSERT_TRUE(st.points - before >= 100000);
    }
    snprintf(msg, sizeof msg, "register-box grid: %ld points (4 legs), %ld projected", st.points,
             st.projected);
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT32(0, st.projected); /* the whole box is reachable */
    report("IK max joint error vs double reference (register box)", st.max_angle_err_deg, "deg");
    report("max |FK(IK(p)) - p| (register box)", st.max_fk_err_um, "um");
    TEST_ASSERT_TRUE(st.max_angle_err_deg <= IK_BOUND_DEG);
    TEST_ASSERT_TRUE(st.max_fk_err_um <= FK_IK_BOUND_UM);
}

/* The whole reachable workspace: a 48^3 grid in joint space (110,592 points
 * per leg, 0.01 degree inside every limit), mapped to foot positions by the
 * reference FK and rounded to whole micrometres. */
static void joint_space_grid(const xgo_profile_t *p, int n, ik_stats_t *st)
{
    int leg, a, b, c;
    for (leg = 0; leg < 4; ++leg) {
        for (a = 0; a < n; ++a) {
            for (b = 0; b < n; ++b) {
                for (c = 0; c < n; ++c) {
                    double q[3];
                    int idx[3];
                    int j;
                    xgo_vec3_t t;
                    idx[0] = a;
                    idx[1] = b;
                    idx[2] = c;
                    for (j = 0; j < 3; ++j) {
                        double lo = p->joint_mdeg[j].lo / 1000.0 + 0.01;
                        double hi = p->joint_mdeg[j].hi / 1000.0 - 0.01;
                        q[j] = lo + (hi - lo) * idx[j] / (n - 1);
                    }
                    t = to_um(ref_fk(p, leg, q));
                    {
                        /* Rounding the target to whole um moves its joint
                         * angles by up to ~0.03 degree where the foot is
                         * near the thigh joint's level (the abduction is
                         * ill-conditioned there): keep only the points the
                         * reference puts 0.002 degree inside every limit. */
                        double qr[3];
                        if (!ref_ik_margin(p, leg, to_mm(&t), qr, 0.002)) {
                            st->skipped++;
                            continue;
                        }
                    }
                    ik_check_point(p, leg, &t, st);
                }
            }
        }
    }
}

static void test_ik_joint_space_grid_whole_workspace(void)
{
    ik_stats_t st;
    char msg[200];
    memset(&st, 0, sizeof st);
    joint_space_grid(xgo_profile_mini(), 48, &st);
    snprintf(msg, sizeof msg,
             "joint-space grid (mini): %ld points (4 legs), %ld projected, %ld left out (within 0.002 deg of a limit after rounding)",
             st.points, st.projected, st.skipped);
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT32(0, st.projected);
    report("IK max joint error vs double reference (whole workspace)", st.max_angle_err_deg, "deg");
    report("max |FK(IK(p)) - p| (whole workspace)", st.max_fk_err_um, "um");
    TEST_ASSERT_TRUE(st.max_angle_err_deg <= IK_BOUND_DEG);
    TEST_ASSERT_TRUE(st.max_fk_err_um <= FK_IK_BOUND_UM);

    memset(&st, 0, sizeof st);
    joint_space_grid(xgo_profile_lite(), 20, &st);
    TEST_ASSERT_EQUAL_INT32(0, st.projected);
    report("IK max joint error (lite, 20^3 grid)", st.max_angle_err_deg, "deg");
    TEST_ASSERT_TRUE(st.max_angle_err_deg <= IK_BOUND_DEG);
    TEST_ASSERT_TRUE(st.max_fk_err_um <= FK_IK_BOUND_UM);

    /* Links other than the Mini's (every built-in profile has its links): the
     * IK works out its constants instead of taking the Mini's kept ones. */
    {
        xgo_profile_t other = *xgo_profile_mini();
        other.thigh_um += 1500;
        other.shank_um -= 2000;
        other.knee_offset_mdeg = 2000;
        memset(&st, 0, sizeof st);
        joint_space_grid(&other, 20, &st);
        TEST_ASSERT_EQUAL_INT32(0, st.projected);
        report("IK max joint error (other links, 20^3 grid)", st.max_angle_err_deg, "deg");
        TEST_ASSERT_TRUE(st.max_angle_err_deg <= IK_BOUND_DEG);
        TEST_ASSERT_TRUE(st.max_fk_err_um <= FK_IK_BOUND_UM);
    }
}

/* ------------------------------------------------------------ projection */

/* Brute-force nearest point of the leg plane's reachable region (knee and
 * hip limits) to the in-plane target (x, h), abduction fixed: returns the
 * distance in mm. */
static double ref_plane_min_dist(const xgo_profile_t *p, double x, double h)
{
    double l1 = p->thigh_um / 1000.0, l2 = p->shank_um / 1000.0;
    double k = p->knee_offset_mdeg / 1000.0;
    double best = 1e300;
    int i, j;
    const int n = 400;
    for (i = 0; i <= n; ++i) {
        double x1 = (p->joint_mdeg[0].lo + (p->joint_mdeg[0].hi - p->joint_mdeg[0].lo) * (double)i / n) / 1000.0;
        double g = (x1 + k) * DEG;
        for (j = 0; j <= n; ++j) {
            double t2 = (p->joint_mdeg[1].lo + (p->joint_mdeg[1].hi - p->joint_mdeg[1].lo) * (double)j / n) / 1000.0 * DEG;
            double fx = -l1 * sin(t2) + l2 * cos(t2 + g);
            double fh = l1 * cos(t2) + l2 * sin(t2 + g);
            double dd = (fx - x) * (fx - x) + (fh - h) * (fh - h);
            if (dd < best) {
                best = dd;
            }
        }
    }
    return sqrt(best);
}

static void test_unreachable_targets_are_projected(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    int i, n_proj = 0, n_plane = 0;
    double worst_excess = -1e9;
    for (i = 0; i < 3000; ++i) {
        int leg = (int)(rnd32() % 4);
        xgo_vec3_t t, back;
        int32_t q[3];
        double qr[3];
        int res, ref_ok;
        t.x = (int32_t)(rnd_unit() * 500000.0) - 250000;
        t.y = (int32_t)(rnd_unit() * 500000.0) - 250000;
        t.z = (int32_t)(rnd_unit() * 500000.0) - 250000;
        res = xgo_leg_ik(p, (xgo_leg_t)leg, &t, q);
        assert_within_limits(p, q);
        ref_ok = ref_ik_margin(p, leg, to_mm(&t), qr, 0.001);
        if (ref_ok) {
            TEST_ASSERT_EQUAL_INT(XGO_IK_REACHED, res);
            continue;
        }
        if (!ref_ik_margin(p, leg, to_mm(&t), qr, -0.001)) {
            TEST_ASSERT_EQUAL_INT(XGO_IK_PROJECTED, res);
        }
        if (res != XGO_IK_PROJECTED) {
            continue;
        }
        ++n_proj;
        xgo_leg_fk(p, (xgo_leg_t)leg, q, &back);
        /* When the abduction was not clamped, the answer must be the nearest
         * point of that leg plane's reachable region. */
        if (q[2] > p->joint_mdeg[2].lo && q[2] < p->joint_mdeg[2].hi && n_plane < 300) {
            double s = side_y(leg), d = p->abad_offset_um / 1000.0;
            double phi = q[2] / 1000.0 * DEG;
            dvec tm = to_mm(&t);
            double wp = s * tm.y + d;
            double hp = wp * sin(phi) + tm.z * cos(phi);        /* in-plane coordinates */
            double off = wp * cos(phi) - tm.z * sin(phi) - d;   /* distance off the plane */
            double got = dist_um(&back, tm) / 1000.0;
            double in_plane = sqrt(got * got - off * off > 0 ? got * got - off * off : 0);
            double best = ref_plane_min_dist(p, tm.x, hp);
            double excess = in_plane - best;
            ++n_plane;
            if (excess > worst_excess) {
                worst_excess = excess;
            }
            /* the grid minimum is an upper bound of the true minimum */
            TEST_ASSERT_TRUE(in_plane <= best + 0.005);
        }
    }
    {
        char msg[160];
        snprintf(msg, sizeof msg,
                 "%d projected targets, %d checked against a brute-force nearest point; "
                 "worst (ours - grid minimum) %.4f mm",
                 n_proj, n_plane, worst_excess);
        TEST_MESSAGE(msg);
    }
    TEST_ASSERT_TRUE(n_proj > 1000);
    TEST_ASSERT_TRUE(n_plane > 100);
}

static void test_projection_examples(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    xgo_vec3_t t, back;
    int32_t q[3];
    double qr[3];
    /* straight down, too far: the leg stretches toward it, knee at its limit */
    t.x = 0;
    t.y = 0;
    t.z = 200000;
    TEST_ASSERT_EQUAL_INT(XGO_IK_PROJECTED, xgo_leg_ik(p, XGO_LEG_LF, &t, q));
    TEST_ASSERT_EQUAL_INT32(p->joint_mdeg[0].hi, q[0]);
    TEST_ASSERT_INT32_WITHIN(10, 0, q[2]);
    xgo_leg_fk(p, XGO_LEG_LF, q, &back);
    TEST_ASSERT_INT32_WITHIN(5, 0, back.x);
    TEST_ASSERT_TRUE(back.z > 125000 && back.z < 131000);
    /* the thigh joint itself (inside the inner limit) */
    t.z = 0;
    TEST_ASSERT_EQUAL_INT(XGO_IK_PROJECTED, xgo_leg_ik(p, XGO_LEG_RH, &t, q));
    assert_within_limits(p, q);
    TEST_ASSERT_EQUAL_INT32(p->joint_mdeg[0].lo, q[0]);
    /* far beyond 1 m: scaled, no overflow, same answer as a nearer point on
     * the same ray */
    t.x = 0;
    t.y = 0;
    t.z = INT32_MAX;
    TEST_ASSERT_EQUAL_INT(XGO_IK_PROJECTED, xgo_leg_ik(p, XGO_LEG_LF, &t, q));
    TEST_ASSERT_EQUAL_INT32(p->joint_mdeg[0].hi, q[0]);
    /* a reachable target stays put */
    t.x = 10000;
    t.y = -5000;
    t.z = 90000;
    TEST_ASSERT_EQUAL_INT(XGO_IK_REACHED, xgo_leg_ik(p, XGO_LEG_RF, &t, q));
    TEST_ASSERT_TRUE(ref_ik(p, XGO_LEG_RF, to_mm(&t), qr));
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(qr[1] * 1000.0), q[1]);
}

static void test_extreme_inputs_never_overflow(void)
{
    static const int32_t ext[] = {INT32_MIN, INT32_MIN + 1, -1000000, -30988, -1, 0, 1,
                                  30988, 1000000, INT32_MAX - 1, INT32_MAX};
    const size_t n = sizeof ext / sizeof ext[0];
    const xgo_profile_t *profiles[2];
    size_t i, j, k;
    int pi, leg;
    profiles[0] = xgo_profile_mini();
    profiles[1] = xgo_profile_lite();
    for (pi = 0; pi < 2; ++pi) {
        const xgo_profile_t *p = profiles[pi];
        for (leg = 0; leg < 4; ++leg) {
            for (i = 0; i < n; ++i) {
                for (j = 0; j < n; ++j) {
                    for (k = 0; k < n; ++k) {
                        xgo_vec3_t t, f;
                        int32_t q[3];
                        int res;
                        t.x = ext[i];
                        t.y = ext[j];
                        t.z = ext[k];
                        res = xgo_leg_ik(p, (xgo_leg_t)leg, &t, q);
                        TEST_ASSERT_TRUE(res == XGO_IK_REACHED || res == XGO_IK_PROJECTED);
                        assert_within_limits(p, q);
                        /* FK of any angles, including absurd ones */
                        q[0] = ext[i];
                        q[1] = ext[j];
                        q[2] = ext[k];
                        xgo_leg_fk(p, (xgo_leg_t)leg, q, &f);
                        TEST_ASSERT_TRUE(f.x > -200000 && f.x < 200000);
                    }
                }
            }
        }
        /* body IK with absurd poses and feet */
        for (i = 0; i < n; ++i) {
            for (j = 0; j < n; ++j) {
                xgo_body_pose_t pose;
                xgo_vec3_t feet[4], legs[4];
                int32_t q[4][3];
                for (leg = 0; leg < 4; ++leg) {
                    feet[leg].x = ext[(i + (size_t)leg) % n];
                    feet[leg].y = ext[j];
                    feet[leg].z = ext[(i * 3 + j) % n];
                }
                pose.x_um = ext[i];
                pose.y_um = ext[j];
                pose.z_um = ext[(i + j) % n];
                pose.roll_mdeg = ext[j];
                pose.pitch_mdeg = ext[i];
                pose.yaw_mdeg = ext[(i * 7 + j) % n];
                xgo_body_ik(p, &pose, feet, legs);
                (void)xgo_body_to_joints(p, &pose, feet, q);
                for (leg = 0; leg < 4; ++leg) {
                    assert_within_limits(p, q[leg]);
                }
            }
        }
    }
}

/* ------------------------------------------------------------ body IK */

static double max_body_err_um;

/* Reference body IK: R = Rz(yaw) Ry(pitch) Rx(roll) from libm;
 * body = R^T (foot - t); leg = (bx - ox, by - oy, -bz). */
static void check_body(const xgo_profile_t *p, const xgo_body_pose_t *pose, const xgo_vec3_t feet[4])
{
    xgo_vec3_t legs[4];
    double r = pose->roll_mdeg / 1000.0 * DEG, pt = pose->pitch_mdeg / 1000.0 * DEG,
           y = pose->yaw_mdeg / 1000.0 * DEG;
    double R[3][3];
    int leg;
    xgo_ref_rotation(r, pt, y, R);
    xgo_body_ik(p, pose, feet, legs);
    for (leg = 0; leg < 4; ++leg) {
        double v[3], b[3];
        dvec ref;
        int i;
        double e;
        v[0] = (feet[leg].x - pose->x_um) / 1000.0;
        v[1] = (feet[leg].y - pose->y_um) / 1000.0;
        v[2] = (feet[leg].z - pose->z_um) / 1000.0;
        for (i = 0; i < 3; ++i) {
            b[i] = R[0][i] * v[0] + R[1][i] * v[1] + R[2][i] * v[2];
        }
        ref.x = b[0] - side_x(leg) * p->hip_x_um / 1000.0;
        ref.y = b[1] - side_y(leg) * (p->hip_y_um + p->abad_offset_um) / 1000.0;
        ref.z = -b[2];
        e = dist_um(&legs[leg], ref);
        if (e > max_body_err_um) {
            max_body_err_um = e;
        }
    }
}

static void body_register_sweep(const xgo_profile_t *p, long *poses)
{
    static const uint8_t levels[] = {0, 37, 90, 127, 128, 219, 255};
    const size_t nl = sizeof levels / sizeof levels[0];
    xgo_vec3_t stance[4], feet[4];
    size_t a, b, c, d, e, f;
    int axis, leg;
    xgo_stance_feet(p, stance);
    /* every combination of 8 levels on all six body registers */
    for (a = 0; a < nl; ++a)
        for (b = 0; b < nl; ++b)
            for (c = 0; c < nl; ++c)
                for (d = 0; d < nl; ++d)
                    for (e = 0; e < nl; ++e)
                        for (f = 0; f < nl; ++f) {
                            uint8_t bytes[6];
                            xgo_body_pose_t pose;
                            bytes[0] = levels[a];
                            bytes[1] = levels[b];
                            bytes[2] = levels[c];
                            bytes[3] = levels[d];
                            bytes[4] = levels[e];
                            bytes[5] = levels[f];
                            xgo_bytes_to_body_pose(p, bytes, &pose);
                            for (leg = 0; leg < 4; ++leg) {
                                feet[leg] = stance[leg];
                                /* feet moved by a step too */
                                feet[leg].x += (int32_t)(rnd32() % 60001) - 30000;
                                feet[leg].y += (int32_t)(rnd32() % 30001) - 15000;
                                feet[leg].z += (int32_t)(rnd32() % 30001);
                            }
                            check_body(p, &pose, feet);
                            ++*poses;
                        }
    /* every byte of every register on its own */
    for (axis = 0; axis < 6; ++axis) {
        int v;
        for (v = 0; v < 256; ++v) {
            uint8_t bytes[6] = {127, 127, 127, 127, 127, 127};
            xgo_body_pose_t pose;
            bytes[axis] = (uint8_t)v;
            xgo_bytes_to_body_pose(p, bytes, &pose);
            check_body(p, &pose, stance);
            ++*poses;
        }
    }
}

static void test_body_ik_against_reference_over_register_ranges(void)
{
    long poses = 0;
    char msg[120];
    max_body_err_um = 0;
    body_register_sweep(xgo_profile_mini(), &poses);
    body_register_sweep(xgo_profile_lite(), &poses);
    snprintf(msg, sizeof msg, "body IK: %ld poses x 4 legs (mini + lite)", poses);
    TEST_MESSAGE(msg);
    report("body IK max error vs double reference", max_body_err_um, "um");
    TEST_ASSERT_TRUE(max_body_err_um <= BODY_BOUND_UM);
}

static void test_body_ik_identities(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    xgo_body_pose_t pose;
    xgo_vec3_t feet[4], legs[4];
    int leg;
    xgo_stance_feet(p, feet);
    /* shifting the body forward moves every foot backward in its leg frame */
    xgo_body_pose_stand(p, &pose);
    pose.x_um = 20000;
    xgo_body_ik(p, &pose, feet, legs);
    for (leg = 0; leg < 4; ++leg) {
        TEST_ASSERT_EQUAL_INT32(-20000, legs[leg].x);
        TEST_ASSERT_EQUAL_INT32(0, legs[leg].y);
        TEST_ASSERT_EQUAL_INT32(p->stand_height_um, legs[leg].z);
    }
    /* rolling right side down (positive roll about +x raises the left side):
     * left feet end up farther below their hips than right feet */
    xgo_body_pose_stand(p, &pose);
    pose.roll_mdeg = 10000;
    xgo_body_ik(p, &pose, feet, legs);
    TEST_ASSERT_TRUE(legs[XGO_LEG_LF].z > legs[XGO_LEG_RF].z + 10000);
    /* pitching nose down (positive pitch about +y): front feet closer */
    xgo_body_pose_stand(p, &pose);
    pose.pitch_mdeg = 10000;
    xgo_body_ik(p, &pose, feet, legs);
    TEST_ASSERT_TRUE(legs[XGO_LEG_LF].z < legs[XGO_LEG_LH].z - 10000);
    /* yaw 90 degrees: a foot ahead of the body is on the body's right */
    xgo_body_pose_stand(p, &pose);
    pose.yaw_mdeg = 90000;
    feet[0].x = 100000;
    feet[0].y = 0;
    xgo_body_ik(p, &pose, feet, legs);
    TEST_ASSERT_INT32_WITHIN(1, -100000 - (p->hip_y_um + p->abad_offset_um), legs[0].y);
    TEST_ASSERT_INT32_WITHIN(1, -p->hip_x_um, legs[0].x);
}

/* The body IK's foot - body differences are taken in 32 bits: one that
 * wraps there must still take the saturating far path (a wrapped -3 is
 * not near), and the near bound itself is inclusive. Zero angles: both
 * paths are exact, so the values are known. */
static void test_body_ik_differences_beyond_int32(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    const int32_t ox = p->hip_x_um, oy = p->hip_y_um + p->abad_offset_um;
    xgo_body_pose_t pose;
    xgo_vec3_t feet[4], legs[4];
    xgo_stance_feet(p, feet);
    xgo_body_pose_stand(p, &pose);
    pose.x_um = INT32_MIN + 2;
    pose.y_um = INT32_MAX;
    pose.z_um = 1000;
    feet[XGO_LEG_LF].x = INT32_MAX;                /* 2^32 - 3 away, wraps to -3 */
    feet[XGO_LEG_LF].y = INT32_MIN + 5;            /* -(2^32 - 6) away, wraps to 6 */
    feet[XGO_LEG_RF].x = pose.x_um + ((1 << 22) - 1); /* the near bound */
    feet[XGO_LEG_RF].y = pose.y_um - ((1 << 22) - 1);
    feet[XGO_LEG_RF].z = pose.z_um - ((1 << 22) - 1);
    feet[XGO_LEG_RH].x = pose.x_um + (1 << 22); /* just beyond it */
    feet[XGO_LEG_RH].y = pose.y_um - (1 << 22);
    feet[XGO_LEG_RH].z = pose.z_um + (1 << 22);
    xgo_body_ik(p, &pose, feet, legs);
    TEST_ASSERT_EQUAL_INT32(INT32_MAX - ox, legs[XGO_LEG_LF].x);
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, legs[XGO_LEG_LF].y);
    TEST_ASSERT_EQUAL_INT32((1 << 22) - 1 - ox, legs[XGO_LEG_RF].x);
    TEST_ASSERT_EQUAL_INT32(-((1 << 22) - 1) + oy, legs[XGO_LEG_RF].y);
    TEST_ASSERT_EQUAL_INT32((1 << 22) - 1, legs[XGO_LEG_RF].z);
    TEST_ASSERT_EQUAL_INT32((1 << 22) + ox, legs[XGO_LEG_RH].x);
    TEST_ASSERT_EQUAL_INT32(-(1 << 22) + oy, legs[XGO_LEG_RH].y);
    TEST_ASSERT_EQUAL_INT32(-(1 << 22), legs[XGO_LEG_RH].z);
    TEST_ASSERT_EQUAL_INT32(1000, legs[XGO_LEG_LF].z);
}

/* xgo_body_rotation takes a short cut when the yaw is 0 (no table, 4
 * products instead of 14): it must give exactly what the general formula
 * gives with sin yaw = 0, cos yaw = 1, which a yaw of one full turn
 * (360000 mdeg, binary angle 0) still takes. */
static void test_body_rotation_without_yaw_is_the_general_one(void)
{
    static const int32_t edge[] = {0, 1, -1, 90000, -90000, 180000, -180000, 45000, 359999, INT32_MAX, INT32_MIN};
    const size_t ne = sizeof edge / sizeof edge[0];
    uint64_t seed = 0x5eed1234abcdULL;
    long n;
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_mdeg_to_bam(360000));
    for (n = 0; n < 200000; ++n) {
        xgo_body_pose_t pose;
        xgo_q30_t fast[XGO_ROT_COUNT], general[XGO_ROT_COUNT];
        memset(&pose, 0, sizeof pose);
        if (n < (long)(ne * ne)) {
            pose.roll_mdeg = edge[n % (long)ne];
            pose.pitch_mdeg = edge[n / (long)ne];
        } else {
            pose.roll_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
            pose.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        }
        xgo_body_rotation(&pose, fast);
        pose.yaw_mdeg = 360000;
        xgo_body_rotation(&pose, general);
        TEST_ASSERT_EQUAL_INT32_ARRAY(general, fast, XGO_ROT_COUNT);
    }
}

/* xgo_body_rotation_next takes the roll's sine and cosine from the last
 * rotation when neither pose has a yaw and the roll is the same: whatever
 * the pair, it must give exactly xgo_body_rotation(pose). */
static void test_body_rotation_next_is_the_rotation(void)
{
    static const int32_t roll[] = {0, 1, -1, 12000, -12000, 90000, 180000, -180000, INT32_MAX, INT32_MIN};
    const size_t nr = sizeof roll / sizeof roll[0];
    uint64_t seed = 0x0b0d7e57ULL;
    long n, shortcut = 0;
    for (n = 0; n < 200000; ++n) {
        xgo_body_pose_t last, pose;
        xgo_q30_t next[XGO_ROT_COUNT], direct[XGO_ROT_COUNT];
        const unsigned pick = (unsigned)(xgo_test_xorshift64(&seed) % 8u);
        memset(&last, 0, sizeof last);
        last.roll_mdeg = n < (long)nr ? roll[n] : (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        last.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose = last;
        pose.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        if (pick == 5u) {
            pose.roll_mdeg += 1; /* another roll */
        } else if (pick == 6u) {
            last.yaw_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000; /* last had a yaw */
        } else if (pick == 7u) {
            pose.yaw_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000; /* pose has one */
        } else {
            ++shortcut;
        }
        xgo_body_rotation(&last, next);
        xgo_body_rotation_next(&last, &pose, next);
        xgo_body_rotation(&pose, direct);
        TEST_ASSERT_EQUAL_INT32_ARRAY(direct, next, XGO_ROT_COUNT);
    }
    TEST_ASSERT_TRUE(shortcut > 100000);
}

/* The masked body-to-machine transform: the measured legs as the full one
 * gives them, each other one at the body centre's image (the full one's
 * answer for a foot at the origin), whatever its input holds; random
 * poses, feet near and far, every mask. */
static void test_body_to_machine_legs_is_the_full_one(void)
{
    uint64_t seed = 0x1e95a5cULL;
    long n;
    for (n = 0; n < 100000; ++n) {
        xgo_body_pose_t pose;
        xgo_q30_t rot[XGO_ROT_COUNT];
        xgo_vec3_t body[XGO_LEG_COUNT], zeroed[XGO_LEG_COUNT], full[XGO_LEG_COUNT], part[XGO_LEG_COUNT];
        const unsigned mask = (unsigned)(n & 15);
        const int far = (n & 64) != 0;
        unsigned leg;
        memset(&pose, 0, sizeof pose);
        pose.roll_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose.yaw_mdeg = (n & 32) ? (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000 : 0;
        pose.x_um = (int32_t)(xgo_test_xorshift64(&seed) % 400001u) - 200000;
        pose.y_um = (int32_t)(xgo_test_xorshift64(&seed) % 400001u) - 200000;
        pose.z_um = (int32_t)(xgo_test_xorshift64(&seed) % 400001u) - 200000;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            const uint32_t span = far ? 0xFFFFFFFFu : 600001u;
            body[leg].x = far ? (int32_t)(uint32_t)xgo_test_xorshift64(&seed)
                              : (int32_t)(xgo_test_xorshift64(&seed) % span) - 300000;
            body[leg].y = far ? (int32_t)(uint32_t)xgo_test_xorshift64(&seed)
                              : (int32_t)(xgo_test_xorshift64(&seed) % span) - 300000;
            body[leg].z = far ? (int32_t)(uint32_t)xgo_test_xorshift64(&seed)
                              : (int32_t)(xgo_test_xorshift64(&seed) % span) - 300000;
            zeroed[leg] = body[leg];
            if (((mask >> leg) & 1u) == 0) {
                zeroed[leg].x = zeroed[leg].y = zeroed[leg].z = 0;
            }
        }
        xgo_body_rotation(&pose, rot);
        xgo_body_to_machine_rotated(&pose, rot, zeroed, full);
        xgo_body_to_machine_legs(&pose, rot, mask, body, part);
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            TEST_ASSERT_EQUAL_INT32(full[leg].x, part[leg].x);
            TEST_ASSERT_EQUAL_INT32(full[leg].y, part[leg].y);
            TEST_ASSERT_EQUAL_INT32(full[leg].z, part[leg].z);
        }
    }
}

/* The body IK as its contract states it, for the comparison below: each
 * foot's difference from the pose exact (64 bits); within +-(2^22 - 1) um
 * on every axis the rotation cut to Q18 (rounded) and the exact sum rounded
 * once to um, else the Q30 entries on the differences saturated to int32,
 * rounded, then saturated. */
static int32_t ref_sat32(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : (v < INT32_MIN ? INT32_MIN : (int32_t)v);
}

static void ref_body_ik_rotated(const xgo_profile_t *p, const xgo_body_pose_t *pose,
                                const xgo_q30_t rot[XGO_ROT_COUNT], const xgo_vec3_t feet[XGO_LEG_COUNT],
                                xgo_vec3_t out[XGO_LEG_COUNT])
{
    const int64_t lim = (1 << 22) - 1;
    int64_t q[XGO_ROT_COUNT];
    int leg, i;
    for (i = 0; i < XGO_ROT_COUNT; ++i) {
        q[i] = ((int64_t)rot[i] + 2048) >> 12;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        const int32_t ox = side_x(leg) * p->hip_x_um, oy = side_y(leg) * (p->hip_y_um + p->abad_offset_um);
        const int64_t d[3] = {(int64_t)feet[leg].x - pose->x_um, (int64_t)feet[leg].y - pose->y_um,
                              (int64_t)feet[leg].z - pose->z_um};
        int64_t s[3];
        int axis;
        if (d[0] >= -lim && d[0] <= lim && d[1] >= -lim && d[1] <= lim && d[2] >= -lim && d[2] <= lim) {
            for (axis = 0; axis < 3; ++axis) {
                s[axis] = (q[axis] * d[0] + q[3 + axis] * d[1] + q[6 + axis] * d[2] + (1 << 17)) >> 18;
            }
        } else {
            const int64_t x = ref_sat32(d[0]), y = ref_sat32(d[1]), z = ref_sat32(d[2]);
            for (axis = 0; axis < 3; ++axis) {
                s[axis] = ((int64_t)rot[axis] * x + (int64_t)rot[3 + axis] * y + (int64_t)rot[6 + axis] * z +
                           ((int64_t)1 << 29)) >> 30;
            }
        }
        out[leg].x = ref_sat32(s[0] - ox);
        out[leg].y = ref_sat32(s[1] - oy);
        out[leg].z = ref_sat32(-s[2]);
    }
}

/* One coordinate of a foot, about at (near 0) c: mostly within 2 m of it
 * (the 64-bit host's one-test path), else on the edges of that range and of
 * the near one (+-2^21, +-(2^22 - 1), +-2^22 and their neighbours), between
 * them, or any int32. */
static int32_t body_foot_coord(uint64_t *seed, int32_t c)
{
    static const int64_t edges[] = {(1 << 21) - 1, 1 << 21, (1 << 21) + 1, (1 << 22) - 2, (1 << 22) - 1, 1 << 22};
    const uint32_t kind = xgo_test_xorshift64(seed) % 16u;
    int64_t d;
    if (kind < 10u) {
        d = (int64_t)(xgo_test_xorshift64(seed) % 400001u) - 200000;
    } else if (kind < 13u) {
        d = edges[xgo_test_xorshift64(seed) % 6u];
        d = (xgo_test_xorshift64(seed) & 1u) ? -d : d;
    } else if (kind < 15u) {
        d = (int64_t)(xgo_test_xorshift64(seed) % (1u << 24)) - (1 << 23);
    } else {
        return (int32_t)xgo_test_xorshift64(seed);
    }
    return ref_sat32(c + d);
}

/* xgo_body_ik_rotated (a 64-bit host: one range test for the usual feet,
 * the Q18 products on the differences with R(1, 0)'s dropped when it is
 * 0) against the contract's plain form: random rotations with and without
 * yaw, poses near and far, feet on every range's edges, both profiles'
 * leg origins, the output in place of the input too. */
static void test_body_ik_rotated_is_the_plain_one(void)
{
    xgo_profile_t other = *xgo_profile_mini();
    uint64_t seed = 0xb0d1e5ULL;
    long n;
    other.hip_x_um = 93000;
    other.hip_y_um = 41000;
    other.abad_offset_um = 17500;
    for (n = 0; n < 300000; ++n) {
        const xgo_profile_t *p = (n & 1) ? &other : xgo_profile_mini();
        xgo_body_pose_t pose;
        xgo_q30_t rot[XGO_ROT_COUNT];
        xgo_vec3_t feet[XGO_LEG_COUNT], out[XGO_LEG_COUNT], want[XGO_LEG_COUNT];
        const int far_pose = (n & 30) == 0;
        unsigned leg;
        pose.roll_mdeg = (n & 8) ? 0 : (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose.yaw_mdeg = (n & 6) ? 0 : (int32_t)(xgo_test_xorshift64(&seed) % 720001u) - 360000;
        pose.x_um = (int32_t)(xgo_test_xorshift64(&seed) % 60001u) - 30000;
        pose.y_um = (int32_t)(xgo_test_xorshift64(&seed) % 60001u) - 30000;
        if (far_pose) { /* differences beyond int32 */
            pose.x_um = (int32_t)xgo_test_xorshift64(&seed);
            pose.y_um = (int32_t)xgo_test_xorshift64(&seed);
        }
        pose.z_um = (int32_t)(xgo_test_xorshift64(&seed) % 200001u) + 20000;
        xgo_body_rotation(&pose, rot);
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            feet[leg].x = body_foot_coord(&seed, pose.x_um);
            feet[leg].y = body_foot_coord(&seed, pose.y_um);
            feet[leg].z = body_foot_coord(&seed, pose.z_um);
        }
        ref_body_ik_rotated(p, &pose, rot, feet, want);
        xgo_body_ik_rotated(p, &pose, rot, feet, out);
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            TEST_ASSERT_EQUAL_INT32(want[leg].x, out[leg].x);
            TEST_ASSERT_EQUAL_INT32(want[leg].y, out[leg].y);
            TEST_ASSERT_EQUAL_INT32(want[leg].z, out[leg].z);
        }
        xgo_body_ik_rotated(p, &pose, rot, feet, feet); /* in place */
        TEST_ASSERT_EQUAL_MEMORY(want, feet, sizeof want);
    }
}

/* ------------------------------------------------------------ byte codes */

/* The vendor library's encoder, as Python evaluates it in double. */
static int vendor_encode(double v, double lo, double hi)
{
    double f = 255.0 / (hi - lo) * (v - lo);
    int b = (int)f; /* int() truncates toward zero */
    return b < 0 ? 0 : (b > 255 ? 255 : b);
}

static void check_range_codes(const xgo_range_t *r, double unit, long *mismatch, long *checked)
{
    int32_t v;
    int b;
    int32_t step = (r->hi - r->lo) / 20000 + 1;
    /* decode: within one unit of the exact value, and encode(decode) == b */
    for (b = 0; b < 256; ++b) {
        int32_t dv = xgo_byte_to_range(r, (uint8_t)b);
        double exact = r->lo + b / 255.0 * (r->hi - r->lo);
        TEST_ASSERT_TRUE(dv >= exact - 1e-9 && dv < exact + 1.0);
        TEST_ASSERT_EQUAL_UINT8(b, xgo_range_to_byte(r, dv));
    }
    TEST_ASSERT_EQUAL_INT32(r->lo, xgo_byte_to_range(r, 0));
    TEST_ASSERT_EQUAL_INT32(r->hi, xgo_byte_to_range(r, 255));
    /* encode: the library's own formula, beyond both ends too */
    for (v = r->lo - 5000; v <= r->hi + 5000; v += step) {
        int got = xgo_range_to_byte(r, v);
        int ref = vendor_encode(v / unit, r->lo / unit, r->hi / unit);
        ++*checked;
        if (got != ref) {
            /* only where the exact value is a whole number and the float
             * product lands just below it */
            int64_t num = 255 * ((int64_t)v - r->lo);
            TEST_ASSERT_EQUAL_INT64(0, num % ((int64_t)r->hi - r->lo));
            TEST_ASSERT_EQUAL_INT(got - 1, ref);
            ++*mismatch;
        }
    }
    TEST_ASSERT_EQUAL_UINT8(0, xgo_range_to_byte(r, INT32_MIN));
    TEST_ASSERT_EQUAL_UINT8(255, xgo_range_to_byte(r, INT32_MAX));
}

/* The leg and body IK give the bits they always gave: every joint angle,
 * the projected mask and the body IK's feet of 400,000 random cases
 * folded into one digest, for the Mini and a profile of other links (the
 * general constants) with tighter limits. The cases: targets all over the
 * workspace and far beyond it (projections, both abduction branches, the
 * axis cylinder), feet put by the FK at joint angles on and next to every
 * limit (the limit checks' exact comparisons), random poses. The golden
 * digest was taken before the rewrites it guards (the limit checks, the
 * cut of the hip's products, the inline paths of a 64-bit host, the body
 * IK's hoisted constants), on the host and the _narrow build alike. */
#define IK_DIGEST 0x0f763f12ff0acf0cull

static uint64_t fold_ik(uint64_t digest, uint32_t v)
{
    return (digest ^ v) * 0x100000001B3ull;
}

/* Far targets are halved until every coordinate is within 1 m (2^20 um):
 * the leg IK's test of that (on a 64-bit host first all three at once)
 * at the limit and either side of it, in each coordinate and sign. With
 * links of 0.6 m, where a halving changes the answer (with the Mini's a
 * target 1 m away and one 0.5 m away in about the same direction project
 * to the same joint angles), checked two ways: beyond the limit the IK of
 * the target equals that of the target halved as the rule says (then
 * within, not halved again); at the limit itself, not halved, the joint
 * angles are within a few mdeg of the target's 1 um nearer. */
static void test_ik_far_limit_edges(void)
{
    static const int32_t edge[] = {1 << 20, (1 << 20) + 1, (1 << 20) + 2, (1 << 21) + 1};
    uint64_t seed = 0xFA11FA11ULL;
    xgo_profile_t big = *xgo_profile_mini();
    unsigned n;
    big.thigh_um = 600000;
    big.shank_um = 600000;
    for (n = 0; n < 4000u; ++n) {
        const xgo_leg_t leg = (xgo_leg_t)(n % XGO_LEG_COUNT);
        const unsigned axis = (n / 4u) % 3u, which = (n / 12u) % 4u;
        const int32_t sign = ((n / 48u) & 1u) ? -1 : 1;
        int32_t v[3], w[3], q[XGO_JOINT_COUNT], qr[XGO_JOINT_COUNT];
        xgo_vec3_t foot, ref;
        int i, r, rr;
        for (i = 0; i < 3; ++i) {
            v[i] = (int32_t)(xgo_test_xorshift64(&seed) % 400001u) - 200000;
        }
        v[axis] = sign * edge[which];
        for (i = 0; i < 3; ++i) {
            w[i] = v[i];
        }
        if (which == 0u) { /* at the limit: the target 1 um nearer */
            w[axis] -= sign;
        } else {
            while (w[0] > (1 << 20) || w[0] < -(1 << 20) || w[1] > (1 << 20) || w[1] < -(1 << 20) ||
                   w[2] > (1 << 20) || w[2] < -(1 << 20)) {
                for (i = 0; i < 3; ++i) {
                    w[i] /= 2;
                }
            }
        }
        foot.x = v[0];
        foot.y = v[1];
        foot.z = v[2];
        ref.x = w[0];
        ref.y = w[1];
        ref.z = w[2];
        r = xgo_leg_ik(&big, leg, &foot, q);
        rr = xgo_leg_ik(&big, leg, &ref, qr);
        if (which == 0u) {
            for (i = 0; i < XGO_JOINT_COUNT; ++i) {
                TEST_ASSERT_INT32_WITHIN(5, qr[i], q[i]);
            }
        } else {
            TEST_ASSERT_EQUAL_INT(rr, r);
            TEST_ASSERT_EQUAL_INT32_ARRAY(qr, q, XGO_JOINT_COUNT);
        }
    }
}

static void test_ik_same_bits_as_before(void)
{
    xgo_profile_t other = *xgo_profile_mini();
    const xgo_profile_t *profiles[2];
    uint64_t seed = 0x1c0ffee5ULL, digest = 0;
    long n;
    other.thigh_um = 61000;
    other.shank_um = 70500;
    other.knee_offset_mdeg = -1200;
    other.joint_mdeg[XGO_JOINT_ABAD].lo += 4000;
    other.joint_mdeg[XGO_JOINT_HIP].hi -= 9000;
    profiles[0] = xgo_profile_mini();
    profiles[1] = &other;
    for (n = 0; n < 100000; ++n) {
        const xgo_profile_t *p = profiles[n & 1];
        xgo_vec3_t machine[XGO_LEG_COUNT], legs[XGO_LEG_COUNT];
        int32_t q[XGO_LEG_COUNT][XGO_JOINT_COUNT];
        xgo_body_pose_t pose;
        unsigned leg, mask;
        int j;
        xgo_body_pose_stand(p, &pose);
        pose.x_um = (int32_t)(xgo_test_xorshift64(&seed) % 40001u) - 20000;
        pose.y_um = (int32_t)(xgo_test_xorshift64(&seed) % 40001u) - 20000;
        pose.z_um += (int32_t)(xgo_test_xorshift64(&seed) % 60001u) - 30000;
        pose.roll_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 40001u) - 20000;
        pose.pitch_mdeg = (int32_t)(xgo_test_xorshift64(&seed) % 40001u) - 20000;
        pose.yaw_mdeg = (n & 6) == 0 ? (int32_t)(xgo_test_xorshift64(&seed) % 40001u) - 20000 : 0;
        xgo_stance_feet(p, machine);
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            const unsigned kind = (unsigned)(xgo_test_xorshift64(&seed) % 8u);
            const int32_t span = kind == 7u ? 2000000 : (kind == 6u ? 400000 : 90000);
            machine[leg].x += (int32_t)(xgo_test_xorshift64(&seed) % (uint32_t)(2 * span + 1)) - span;
            machine[leg].y += (int32_t)(xgo_test_xorshift64(&seed) % (uint32_t)(2 * span + 1)) - span;
            machine[leg].z += (int32_t)(xgo_test_xorshift64(&seed) % (uint32_t)(2 * span + 1)) - span;
        }
        xgo_body_ik(p, &pose, machine, legs);
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            if ((xgo_test_xorshift64(&seed) & 3u) == 0u) { /* a foot the FK puts at joints on or by a limit */
                int32_t qa[XGO_JOINT_COUNT];
                for (j = 0; j < XGO_JOINT_COUNT; ++j) {
                    const xgo_range_t *r = &p->joint_mdeg[j];
                    const uint64_t pick = xgo_test_xorshift64(&seed) % 6u;
                    qa[j] = pick < 2u ? r->lo + (int32_t)pick : (pick < 4u ? r->hi - (int32_t)(pick - 2u)
                                                                           : r->lo + (int32_t)((uint32_t)(r->hi - r->lo) / 2u));
                }
                xgo_leg_fk(p, (xgo_leg_t)leg, qa, &legs[leg]);
            }
            digest = fold_ik(digest, (uint32_t)legs[leg].x);
            digest = fold_ik(digest, (uint32_t)legs[leg].y);
            digest = fold_ik(digest, (uint32_t)legs[leg].z);
        }
        mask = xgo_legs_ik(p, legs, q);
        digest = fold_ik(digest, mask);
        for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
            for (j = 0; j < XGO_JOINT_COUNT; ++j) {
                digest = fold_ik(digest, (uint32_t)q[leg][j]);
            }
        }
    }
    printf("IK digest 0x%016llx\n", (unsigned long long)digest);
    TEST_ASSERT_TRUE(digest == IK_DIGEST);
}

static void test_byte_codes_match_the_vendor_library(void)
{
    const xgo_profile_t *profiles[2];
    long mismatch = 0, checked = 0;
    int i, j;
    char msg[160];
    profiles[0] = xgo_profile_mini();
    profiles[1] = xgo_profile_lite();
    for (i = 0; i < 2; ++i) {
        const xgo_profile_t *p = profiles[i];
        for (j = 0; j < 3; ++j) {
            check_range_codes(&p->joint_mdeg[j], 1000.0, &mismatch, &checked);
            check_range_codes(&p->foot_um[j], 1000.0, &mismatch, &checked);
            check_range_codes(&p->body_um[j], 1000.0, &mismatch, &checked);
            check_range_codes(&p->body_mdeg[j], 1000.0, &mismatch, &checked);
        }
        /* zero on a symmetric range is 0x7F, as the library sends it */
        TEST_ASSERT_EQUAL_HEX8(0x7F, xgo_joint_to_byte(p, XGO_JOINT_ABAD, 0));
        TEST_ASSERT_EQUAL_HEX8(0x7F, xgo_foot_to_byte(p, XGO_AXIS_X, 0));
        TEST_ASSERT_EQUAL_HEX8(0x00, xgo_joint_to_byte(p, XGO_JOINT_KNEE, p->joint_mdeg[0].lo));
        TEST_ASSERT_EQUAL_HEX8(0xFF, xgo_joint_to_byte(p, XGO_JOINT_HIP, p->joint_mdeg[1].hi));
    }
    /* Mini examples: 0x80 decodes to just above the middle */
    TEST_ASSERT_EQUAL_INT32(122, xgo_byte_to_joint(xgo_profile_mini(), XGO_JOINT_ABAD, 0x80));
    TEST_ASSERT_EQUAL_INT32(95079, xgo_byte_to_foot(xgo_profile_mini(), XGO_AXIS_Z, 0x80));
    snprintf(msg, sizeof msg,
             "byte encode: %ld values checked against the library formula, %ld float-rounding "
             "differences (exact integer products only)",
             checked, mismatch);
    TEST_MESSAGE(msg);
}

static void test_twelve_register_blocks(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    uint8_t in[12], out[12];
    int32_t q[4][3];
    xgo_vec3_t feet[4];
    uint8_t body[6], body2[6];
    xgo_body_pose_t pose;
    int i;
    for (i = 0; i < 12; ++i) {
        in[i] = (uint8_t)(i * 21 + 3);
    }
    xgo_bytes_to_joints(p, in, q);
    TEST_ASSERT_EQUAL_INT32(xgo_byte_to_joint(p, XGO_JOINT_HIP, in[4]), q[1][1]);
    xgo_joints_to_bytes(p, (const int32_t(*)[3])q, out);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(in, out, 12);
    xgo_bytes_to_feet(p, in, feet);
    TEST_ASSERT_EQUAL_INT32(xgo_byte_to_foot(p, XGO_AXIS_Z, in[8]), feet[2].z);
    xgo_feet_to_bytes(p, feet, out);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(in, out, 12);
    for (i = 0; i < 6; ++i) {
        body[i] = (uint8_t)(i * 40 + 10);
    }
    xgo_bytes_to_body_pose(p, body, &pose);
    TEST_ASSERT_EQUAL_INT32(xgo_byte_to_range(&p->body_mdeg[1], body[4]), pose.pitch_mdeg);
    xgo_body_pose_to_bytes(p, &pose, body2);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(body, body2, 6);
}

/* ------------------------------------------------------------ the Mini's kept limit arcs */

/* On a 64-bit host the leg IK keeps the arcs of the Mini's knee and hip
 * limits instead of working them out for each projection; the narrow build
 * (test_kinematics_narrow) works them out. Both must give these bits, those
 * of the code before the arcs were kept: targets of every kind, most of
 * them projected, every leg. */
#define MINI_PROJECTION_DIGEST 0x0f424443082ecc6dULL

static void test_projection_with_kept_arcs_same_bits(void)
{
    const xgo_profile_t *p = xgo_profile_mini();
    uint64_t seed = 0xa4c5f00dULL, digest = 0;
    long n, projected = 0;
    for (n = 0; n < 200000; ++n) {
        const xgo_leg_t leg = (xgo_leg_t)(n & 3);
        xgo_vec3_t foot;
        int32_t q[XGO_JOINT_COUNT];
        int r, j;
        foot.x = (int32_t)(xgo_test_xorshift64(&seed) % 400001u) - 200000;
        foot.y = (int32_t)(xgo_test_xorshift64(&seed) % 240001u) - 120000;
        foot.z = (int32_t)(xgo_test_xorshift64(&seed) % 300001u) - 80000;
        r = xgo_leg_ik(p, leg, &foot, q);
        projected += r != XGO_IK_REACHED;
        digest = fold_ik(digest, (uint32_t)r);
        for (j = 0; j < XGO_JOINT_COUNT; ++j) {
            digest = fold_ik(digest, (uint32_t)q[j]);
        }
    }
    printf("projection digest 0x%016llx, %ld of 200000 projected\n", (unsigned long long)digest, projected);
    TEST_ASSERT_TRUE(projected > 100000);
    TEST_ASSERT_TRUE(digest == MINI_PROJECTION_DIGEST);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sign_conventions_and_zero_pose);
    RUN_TEST(test_standing_pose);
    RUN_TEST(test_fk_against_reference);
    RUN_TEST(test_ik_register_box_grid_all_legs);
    RUN_TEST(test_ik_joint_space_grid_whole_workspace);
    RUN_TEST(test_unreachable_targets_are_projected);
    RUN_TEST(test_projection_examples);
    RUN_TEST(test_extreme_inputs_never_overflow);
    RUN_TEST(test_body_ik_against_reference_over_register_ranges);
    RUN_TEST(test_body_ik_identities);
    RUN_TEST(test_body_ik_differences_beyond_int32);
    RUN_TEST(test_body_rotation_without_yaw_is_the_general_one);
    RUN_TEST(test_body_rotation_next_is_the_rotation);
    RUN_TEST(test_body_to_machine_legs_is_the_full_one);
    RUN_TEST(test_body_ik_rotated_is_the_plain_one);
    RUN_TEST(test_byte_codes_match_the_vendor_library);
    RUN_TEST(test_twelve_register_blocks);
    RUN_TEST(test_ik_same_bits_as_before);
    RUN_TEST(test_ik_far_limit_edges);
    RUN_TEST(test_projection_with_kept_arcs_same_bits);
    return UNITY_END();
}
