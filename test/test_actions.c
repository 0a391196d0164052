/*
 * Preset actions (register 0x3E) on virtual time: every action's length to
 * the tick, the player's contract (unknown ids, restart, stop), smoothness,
 * the Mini's body ranges, and the joint limits on every tick of every
 * action - through an independent double-precision IK written here and
 * through the core's fixed-point kinematics (xgo/kinematics.h).
 *
 * Sign conventions of the reference IK below (the same as docs/geometry.md
 * and xgo/kinematics.h, which are the authority):
 *   machine frame x forward, y left, z up; body attitude R = Rz(yaw)
 *   Ry(pitch) Rx(roll), right-hand rule; feet stay on the ground at their
 *   stance points (+-hip_x, +-(hip_y + d), 0) plus the pose's foot offset,
 *   the body centre is at (x, y, stand_height + z);
 *   leg frame: origin at the thigh joint (+-hip_x, +-(hip_y + d), 0) of the
 *   body frame, x forward, y left, z DOWN;
 *   x3 abduction: 0 = leg plane vertical, + = foot outward;
 *   x2 hip: 0 = thigh straight down, + = thigh swung backward (the knee
 *   points backward: the thigh lies behind the hip-foot line);
 *   x1 knee: interior thigh-shank angle = 90 deg + x1 + knee_offset
 *   (+ = extended).
 * The geometry numbers come from the Mini profile (xgo/profile.h): thigh
 * 59.9 mm, shank 76.0 mm, abduction offset 31.0 mm, hips at (+-75,
 * +-22.5) mm, standing height 97.5 mm.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "reference.h"
#include "unity.h"
#include "actions.h"
#include "xgo/board.h"
#include "kinematics.h"
#include "xgo/profile.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define DEG (180.0 / M_PI)

/* Margin kept from every joint limit, degrees. */
#define JOINT_MARGIN_DEG 1.0
/* Largest change of any pose channel in one tick (um or mdeg): 0.6 mm or
 * 0.6 degree per 2 ms = 300 mm/s, 300 deg/s. */
#define MAX_STEP 600
/* Largest change of that change between two ticks (um or mdeg per tick^2):
 * 40 um/tick^2 = 10 m/s^2. */
#define MAX_ACCEL 40
/* Largest change of a joint angle in one tick, degrees (1 deg / 2 ms =
 * 500 deg/s, within a bus servo's no-load speed). */
#define MAX_JOINT_STEP_DEG 1.0
/* Fixed-point vs double IK agreement, degrees. */
#define IK_AGREE_DEG 0.05

static const uint8_t k_vendor_seconds[XGO_ACTION_LAST + 1] = {
    0, 3, 3, 5, 5, 4, 4, 4, 4, 4, 7, 7, 5, 7, 10, 6, 6, 4, 6, 10, 9, 8, 7, 6, 7,
};

static const char *const k_spec_names[20] = {
    NULL,      "lie down", "stand up", "creep", "circle", "step", "squat", "roll", "pitch",
    "yaw",     "three-axis rotation", "pee", "sit", "beckon", "stretch", "wave", "sway",
    "beg for food", "search for food", "shake hands",
};

static char msg[256];

void setUp(void)
{
}

void tearDown(void)
{
}

/* Ids with a table: 1..24 and 255. */
static int has_table(unsigned id)
{
    return (id >= 1u && id <= XGO_ACTION_LAST) || id == XGO_ACTION_RESET;
}

/* The 18 channels in table order: body x, y, z, roll, pitch, yaw, then
 * x, y, z of each foot. */
static void flatten(const xgo_pose_t *p, int32_t v[18])
{
    int l;
    v[0] = p->body.x_um;
    v[1] = p->body.y_um;
    v[2] = p->body.z_um;
    v[3] = p->body.roll_mdeg;
    v[4] = p->body.pitch_mdeg;
    v[5] = p->body.yaw_mdeg;
    for (l = 0; l < 4; ++l) {
        v[6 + 3 * l] = p->feet_um[l].x;
        v[7 + 3 * l] = p->feet_um[l].y;
        v[8 + 3 * l] = p->feet_um[l].z;
    }
}

static int is_zero_pose(const xgo_pose_t *p)
{
    int32_t v[18];
    int i;
    flatten(p, v);
    for (i = 0; i < 18; ++i) {
        if (v[i] != 0) {
            return 0;
        }
    }
    return 1;
}

/* ------------------------------------------------------------ timing */

static void test_durations_are_the_vendor_waits(void)
{
    unsigned id;
    for (id = 1; id <= XGO_ACTION_LAST; ++id) {
        TEST_ASSERT_EQUAL_UINT32(k_vendor_seconds[id] * XGO_TICK_HZ, xgo_action_duration_ticks((uint8_t)id));
    }
    TEST_ASSERT_EQUAL_UINT32(5000u, xgo_action_duration_ticks(XGO_ACTION_STRETCH));
    TEST_ASSERT_EQUAL_UINT32(1u * XGO_TICK_HZ, xgo_action_duration_ticks(XGO_ACTION_RESET));
    TEST_ASSERT_EQUAL_UINT32(0u, xgo_action_duration_ticks(0));
    for (id = XGO_ACTION_LAST + 1u; id < 255u; ++id) {
        TEST_ASSERT_EQUAL_UINT32(0u, xgo_action_duration_ticks((uint8_t)id));
    }
}

/* After start: ticks 1..N-1 return 1 with the id running; tick N returns 0,
 * writes the zero pose and the player is idle; later ticks likewise. */
static void test_every_action_lasts_its_duration_to_the_tick(void)
{
    unsigned id;
    for (id = 1; id <= 255u; ++id) {
        xgo_action_player_t p;
        xgo_pose_t pose;
        uint32_t n = xgo_action_duration_ticks((uint8_t)id), k;
        if (!has_table(id)) {
            continue;
        }
        xgo_action_init(&p);
        TEST_ASSERT_EQUAL_INT(1, xgo_action_start(&p, (uint8_t)id));
        TEST_ASSERT_EQUAL_UINT8(id, xgo_action_running(&p));
        for (k = 1; k < n; ++k) {
            int r = xgo_action_tick(&p, &pose);
            if (r != 1 || xgo_action_running(&p) != id) {
                snprintf(msg, sizeof msg, "action %u ended early at tick %lu of %lu", id,
                         (unsigned long)k, (unsigned long)n);
                TEST_FAIL_MESSAGE(msg);
            }
        }
        { /* tick N-1 is already next to the stance (it is approached at rest) */
            int32_t v[18];
            int i;
            flatten(&pose, v);
            for (i = 0; i < 18; ++i) {
                snprintf(msg, sizeof msg, "action %u channel %d at tick N-1", id, i);
                TEST_ASSERT_INT32_WITHIN_MESSAGE(20, 0, v[i], msg);
            }
        }
        memset(&pose, 0x5A, sizeof pose);
        snprintf(msg, sizeof msg, "action %u at tick %lu", id, (unsigned long)n);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, xgo_action_tick(&p, &pose), msg);
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(0, xgo_action_running(&p), msg);
        TEST_ASSERT_TRUE_MESSAGE(is_zero_pose(&pose), msg);
        memset(&pose, 0x5A, sizeof pose);
        TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &pose));
        TEST_ASSERT_TRUE(is_zero_pose(&pose));
        TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
    }
}

static void test_idle_player_ticks_the_zero_pose(void)
{
    xgo_action_player_t p;
    xgo_pose_t pose;
    xgo_action_init(&p);
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
    memset(&pose, 0x33, sizeof pose);
    TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &pose));
    TEST_ASSERT_TRUE(is_zero_pose(&pose));
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
    /* a few words of state (the lead-in and its time scale included) */
    TEST_ASSERT_TRUE(sizeof(xgo_action_player_t) <= 16u);
}

/* ------------------------------------------------------------ contract */

static void test_unknown_ids_start_nothing(void)
{
    xgo_action_player_t p, ref;
    xgo_pose_t a, b;
    unsigned id, k;
    xgo_action_init(&p);
    TEST_ASSERT_EQUAL_INT(0, xgo_action_start(&p, 0));
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
    for (id = XGO_ACTION_LAST + 1u; id < 255u; ++id) {
        TEST_ASSERT_EQUAL_INT(0, xgo_action_start(&p, (uint8_t)id));
        TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
        TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &a));
    }
    /* a running action is not disturbed by an unknown id */
    xgo_action_init(&ref);
    TEST_ASSERT_EQUAL_INT(1, xgo_action_start(&p, XGO_ACTION_WAVE));
    TEST_ASSERT_EQUAL_INT(1, xgo_action_start(&ref, XGO_ACTION_WAVE));
    for (k = 0; k < 700u; ++k) {
        if (k % 50u == 0u) {
            TEST_ASSERT_EQUAL_INT(0, xgo_action_start(&p, (uint8_t)(25u + k / 50u)));
            TEST_ASSERT_EQUAL_INT(0, xgo_action_start(&p, 0));
        }
        TEST_ASSERT_EQUAL_INT(xgo_action_tick(&ref, &b), xgo_action_tick(&p, &a));
        TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
        TEST_ASSERT_EQUAL_UINT8(XGO_ACTION_WAVE, xgo_action_running(&p));
    }
}

/* Starting while an action runs restarts with the new one from its start:
 * it then lasts its full duration and plays exactly as if started idle. */
static void test_start_while_running_restarts(void)
{
    xgo_action_player_t p, ref;
    xgo_pose_t a, b;
    uint32_t k, n = xgo_action_duration_ticks(XGO_ACTION_PITCH);
    int ra, rb;
    xgo_action_init(&p);
    xgo_action_start(&p, XGO_ACTION_ROLL);
    for (k = 0; k < 777u; ++k) {
        xgo_action_tick(&p, &a);
    }
    TEST_ASSERT_EQUAL_INT(1, xgo_action_start(&p, XGO_ACTION_PITCH));
    TEST_ASSERT_EQUAL_UINT8(XGO_ACTION_PITCH, xgo_action_running(&p));
    xgo_action_init(&ref);
    xgo_action_start(&ref, XGO_ACTION_PITCH);
    for (k = 1; k <= n; ++k) {
        ra = xgo_action_tick(&p, &a);
        rb = xgo_action_tick(&ref, &b);
        TEST_ASSERT_EQUAL_INT(rb, ra);
        TEST_ASSERT_EQUAL_INT(k < n ? 1 : 0, ra);
        TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
    }
    /* the same id again restarts it too */
    xgo_action_start(&p, XGO_ACTION_SIT);
    for (k = 0; k < 1000u; ++k) {
        xgo_action_tick(&p, &a);
    }
    xgo_action_start(&p, XGO_ACTION_SIT);
    for (k = 1; k < xgo_action_duration_ticks(XGO_ACTION_SIT); ++k) {
        TEST_ASSERT_EQUAL_INT(1, xgo_action_tick(&p, &a));
    }
    TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &a));
}

static void test_stop(void)
{
    xgo_action_player_t p;
    xgo_pose_t pose;
    unsigned k;
    xgo_action_init(&p);
    xgo_action_start(&p, XGO_ACTION_SHAKE_HANDS);
    for (k = 0; k < 1500u; ++k) {
        TEST_ASSERT_EQUAL_INT(1, xgo_action_tick(&p, &pose));
    }
    TEST_ASSERT_FALSE(is_zero_pose(&pose));
    xgo_action_stop(&p);
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
    TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &pose));
    TEST_ASSERT_TRUE(is_zero_pose(&pose));
    xgo_action_stop(&p); /* stopping an idle player is harmless */
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
}

/* Lead-in (issue 9): held, the action runs (its id, its ticks) with the zero
 * pose while the board brings the robot to the stance; from xgo_action_go
 * the keyframes play time-scaled into the ticks left and it still ends at
 * tick N. Held for half of sit's 2500 ticks, the rest plays at twice the
 * speed: the pose at tick 1250 + k is the unheld pose at tick 2k, exactly. */
static void test_lead_in_holds_then_plays_time_scaled(void)
{
    const uint32_t n = xgo_action_duration_ticks(XGO_ACTION_SIT);
    xgo_action_player_t p, ref;
    xgo_pose_t a, b;
    uint32_t k;
    xgo_action_init(&p);
    xgo_action_start(&p, XGO_ACTION_SIT);
    xgo_action_hold(&p);
    TEST_ASSERT_TRUE(xgo_action_held(&p));
    for (k = 1; k <= n / 2; ++k) {
        TEST_ASSERT_EQUAL_INT(1, xgo_action_tick(&p, &a));
        TEST_ASSERT_TRUE(is_zero_pose(&a));
        TEST_ASSERT_EQUAL_UINT8(XGO_ACTION_SIT, xgo_action_running(&p));
    }
    xgo_action_go(&p);
    TEST_ASSERT_FALSE(xgo_action_held(&p));
    xgo_action_init(&ref);
    xgo_action_start(&ref, XGO_ACTION_SIT);
    for (k = 1; k < n / 2; ++k) {
        TEST_ASSERT_EQUAL_INT(1, xgo_action_tick(&p, &a));
        xgo_action_tick(&ref, &b);
        xgo_action_tick(&ref, &b);
        TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
    }
    TEST_ASSERT_EQUAL_INT(0, xgo_action_tick(&p, &a)); /* tick N */
    TEST_ASSERT_TRUE(is_zero_pose(&a));
    TEST_ASSERT_EQUAL_UINT8(0, xgo_action_running(&p));
}

/* Let go at once, a held action plays exactly as one never held. */
static void test_lead_in_of_no_ticks_changes_nothing(void)
{
    xgo_action_player_t p, ref;
    xgo_pose_t a, b;
    uint32_t k;
    xgo_action_init(&p);
    xgo_action_init(&ref);
    xgo_action_start(&p, XGO_ACTION_WAVE);
    xgo_action_hold(&p);
    xgo_action_go(&p);
    xgo_action_start(&ref, XGO_ACTION_WAVE);
    for (k = 1; k <= xgo_action_duration_ticks(XGO_ACTION_WAVE); ++k) {
        TEST_ASSERT_EQUAL_INT(xgo_action_tick(&ref, &b), xgo_action_tick(&p, &a));
        TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
    }
}

static void test_names(void)
{
    unsigned id;
    for (id = 1; id <= 19u; ++id) {
        TEST_ASSERT_EQUAL_STRING(k_spec_names[id], xgo_action_name((uint8_t)id));
    }
    for (id = 20; id <= XGO_ACTION_LAST; ++id) {
        TEST_ASSERT_NOT_NULL(xgo_action_name((uint8_t)id));
        TEST_ASSERT_TRUE(strlen(xgo_action_name((uint8_t)id)) > 0u);
    }
    TEST_ASSERT_EQUAL_STRING("reset", xgo_action_name(XGO_ACTION_RESET));
    TEST_ASSERT_NULL(xgo_action_name(0));
    for (id = XGO_ACTION_LAST + 1u; id < 255u; ++id) {
        TEST_ASSERT_NULL(xgo_action_name((uint8_t)id));
    }
}

/* Perform mode: 3, 4, ..., 24, 3, ...; anything else leads into it at 3. */
static void test_perform_cycle(void)
{
    int seen[256];
    unsigned id = 3, k;
    memset(seen, 0, sizeof seen);
    for (k = 0; k < XGO_ACTION_LAST - 2u; ++k) {
        TEST_ASSERT_TRUE(has_table(id));
        TEST_ASSERT_EQUAL_INT(0, seen[id]);
        seen[id] = 1;
        id = xgo_action_next_in_cycle((uint8_t)id);
    }
    TEST_ASSERT_EQUAL_UINT(3, id);
    for (k = 3; k <= XGO_ACTION_LAST; ++k) {
        TEST_ASSERT_EQUAL_INT(1, seen[k]);
    }
    TEST_ASSERT_EQUAL_UINT8(4, xgo_action_next_in_cycle(3));
    TEST_ASSERT_EQUAL_UINT8(20, xgo_action_next_in_cycle(19));
    TEST_ASSERT_EQUAL_UINT8(3, xgo_action_next_in_cycle(24));
    for (k = 0; k < 256u; ++k) {
        if (k < 3u || k > XGO_ACTION_LAST) {
            TEST_ASSERT_EQUAL_UINT8(3, xgo_action_next_in_cycle((uint8_t)k));
        }
    }
}

/* ------------------------------------------------------------ per tick */

/* Runs action id from the stance and calls fn with each tick's pose
 * (tick 0 is the stance before the start, tick N the zero pose after). */
typedef void (*pose_fn)(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose);

static void play(unsigned id, pose_fn fn, void *ctx)
{
    xgo_action_player_t p;
    xgo_pose_t pose;
    uint32_t n = xgo_action_duration_ticks((uint8_t)id), k;
    memset(&pose, 0, sizeof pose);
    xgo_action_init(&p);
    xgo_action_start(&p, (uint8_t)id);
    fn(ctx, id, 0, &pose);
    for (k = 1; k <= n; ++k) {
        xgo_action_tick(&p, &pose);
        fn(ctx, id, k, &pose);
    }
}

static void play_all(pose_fn fn, void *ctx)
{
    unsigned id;
    for (id = 1; id <= 255u; ++id) {
        if (has_table(id)) {
            play(id, fn, ctx);
        }
    }
}

typedef struct smooth_s {
    int32_t prev[18], prev_step[18];
    int32_t max_step, max_accel;
} smooth_t;

static void check_smooth(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    smooth_t *s = (smooth_t *)ctx;
    int32_t v[18];
    int i;
    flatten(pose, v);
    if (tick == 0u) {
        memcpy(s->prev, v, sizeof v);
        memset(s->prev_step, 0, sizeof s->prev_step);
        return;
    }
    for (i = 0; i < 18; ++i) {
        int32_t step = v[i] - s->prev[i];
        int32_t accel = step - s->prev_step[i];
        if (step < 0) {
            step = -step;
        }
        if (accel < 0) {
            accel = -accel;
        }
        if (step > s->max_step) {
            s->max_step = step;
        }
        if (accel > s->max_accel) {
            s->max_accel = accel;
        }
        if (step > MAX_STEP || accel > MAX_ACCEL) {
            snprintf(msg, sizeof msg, "action %u tick %lu channel %d: step %ld accel %ld", id,
                     (unsigned long)tick, i, (long)step, (long)accel);
            TEST_FAIL_MESSAGE(msg);
        }
        s->prev_step[i] = v[i] - s->prev[i];
    }
    memcpy(s->prev, v, sizeof v);
}

/* The pose moves from the stance to the stance in small steps: per tick no
 * channel changes by more than MAX_STEP and the change itself changes by at
 * most MAX_ACCEL (continuous velocity: no jerks at keyframes, at the start
 * or at the end). */
static void test_poses_change_smoothly(void)
{
    smooth_t s;
    memset(&s, 0, sizeof s);
    play_all(check_smooth, &s);
    snprintf(msg, sizeof msg, "largest step %ld um|mdeg/tick, largest accel %ld um|mdeg/tick^2",
             (long)s.max_step, (long)s.max_accel);
    TEST_MESSAGE(msg);
}

/* Body translation and attitude within the Mini's register ranges
 * (vendor library: x +-35 mm, y +-19.5 mm, height 75..120 mm around the
 * 97.5 mm stance, roll +-20, pitch +-22, yaw +-16 degrees) - except where
 * lying down and sitting need more (issue 9: the belly on the floor, hips
 * 49 mm low; the rump 56 mm back and down, nose up 30 degrees): x -60..35,
 * z -50..22, pitch -30..22. Feet within the foot registers' x/y ranges and
 * never below the ground. */
static void check_ranges(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    static const int32_t lo[6] = {-60000, -19500, -50000, -20000, -30000, -16000};
    static const int32_t hi[6] = {35000, 19500, 22000, 20000, 22000, 16000};
    int32_t v[18];
    int i, l;
    (void)ctx;
    snprintf(msg, sizeof msg, "action %u tick %lu", id, (unsigned long)tick);
    flatten(pose, v); /* v[0..2] body translation, v[3..5] attitude */
    for (i = 0; i < 6; ++i) {
        TEST_ASSERT_TRUE_MESSAGE(v[i] >= lo[i] && v[i] <= hi[i], msg);
    }
    for (l = 0; l < 4; ++l) {
        TEST_ASSERT_TRUE_MESSAGE(pose->feet_um[l].x >= -35000 && pose->feet_um[l].x <= 35000, msg);
        TEST_ASSERT_TRUE_MESSAGE(pose->feet_um[l].y >= -18000 && pose->feet_um[l].y <= 18000, msg);
        TEST_ASSERT_TRUE_MESSAGE(pose->feet_um[l].z >= 0 && pose->feet_um[l].z <= 60000, msg);
    }
}

static void test_poses_stay_in_the_body_ranges(void)
{
    play_all(check_ranges, NULL);
}

/* ------------------------------------------------------------ joint limits */

typedef struct geom_s {
    double l1, l2, d, hx, hy, h0, koff; /* mm, mm, mm, mm, mm, mm, deg */
    double lo[3], hi[3];                /* joint limits, deg, by joint index */
} geom_t;

static geom_t geom(void)
{
    const xgo_profile_t *pr = xgo_profile_mini();
    geom_t g;
    int j;
    g.l1 = pr->thigh_um / 1000.0;
    g.l2 = pr->shank_um / 1000.0;
    g.d = pr->abad_offset_um / 1000.0;
    g.hx = pr->hip_x_um / 1000.0;
    g.hy = pr->hip_y_um / 1000.0;
    g.h0 = pr->stand_height_um / 1000.0;
    g.koff = pr->knee_offset_mdeg / 1000.0;
    for (j = 0; j < 3; ++j) {
        g.lo[j] = pr->joint_mdeg[j].lo / 1000.0;
        g.hi[j] = pr->joint_mdeg[j].hi / 1000.0;
    }
    return g;
}

static const int k_side_x[4] = {1, 1, -1, -1};
static const int k_side_y[4] = {1, -1, -1, 1};

/* Pose -> each foot in its leg frame (mm), feet fixed on the ground. */
static void ref_body_ik(const geom_t *g, const xgo_pose_t *pose, double feet[4][3])
{
    double m[3][3]; /* R = Rz(y) Ry(p) Rx(r) */
    double pos[3];
    int l, i;
    xgo_ref_rotation(pose->body.roll_mdeg / 1000.0 / DEG, pose->body.pitch_mdeg / 1000.0 / DEG,
                     pose->body.yaw_mdeg / 1000.0 / DEG, m);
    pos[0] = pose->body.x_um / 1000.0;
    pos[1] = pose->body.y_um / 1000.0;
    pos[2] = g->h0 + pose->body.z_um / 1000.0;
    for (l = 0; l < 4; ++l) {
        double foot[3], v[3], b[3];
        foot[0] = k_side_x[l] * g->hx + pose->feet_um[l].x / 1000.0;
        foot[1] = k_side_y[l] * (g->hy + g->d) + pose->feet_um[l].y / 1000.0;
        foot[2] = pose->feet_um[l].z / 1000.0;
        for (i = 0; i < 3; ++i) {
            v[i] = foot[i] - pos[i];
        }
        for (i = 0; i < 3; ++i) { /* R^T v */
            b[i] = m[0][i] * v[0] + m[1][i] * v[1] + m[2][i] * v[2];
        }
        feet[l][0] = b[0] - k_side_x[l] * g->hx;
        feet[l][1] = b[1] - k_side_y[l] * (g->hy + g->d);
        feet[l][2] = -b[2];
    }
}

/* Leg frame foot (mm) -> knee, hip, abduction (deg). 0 if unreachable. */
static int ref_leg_ik(const geom_t *g, int leg, const double f[3], double q[3])
{
    double w = k_side_y[leg] * f[1] + g->d; /* outward, from the abduction axis */
    double z = f[2];
    double h2 = w * w + z * z - g->d * g->d, h, r, ck, ca;
    if (h2 <= 0.0) {
        return 0;
    }
    h = sqrt(h2); /* foot below the thigh joint, in the leg plane */
    q[2] = (atan2(w, z) - atan2(g->d, h)) * DEG;
    r = sqrt(f[0] * f[0] + h * h);
    ck = (g->l1 * g->l1 + g->l2 * g->l2 - r * r) / (2.0 * g->l1 * g->l2);
    ca = (g->l1 * g->l1 + r * r - g->l2 * g->l2) / (2.0 * g->l1 * r);
    if (ck < -1.0 || ck > 1.0 || ca < -1.0 || ca > 1.0) {
        return 0;
    }
    q[0] = acos(ck) * DEG - 90.0 - g->koff;
    q[1] = (acos(ca) - atan2(f[0], h)) * DEG;
    return 1;
}

typedef struct joints_s {
    geom_t g;
    double prev[4][3];
    double lo[3], hi[3];   /* extremes seen, all actions */
    double max_step;       /* deg per tick */
    double max_disagree;   /* fixed-point vs reference, deg */
    unsigned long checked; /* leg solutions checked */
} joints_t;

static void check_joints(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    static const char *const jn[3] = {"knee x1", "hip x2", "abduction x3"};
    joints_t *s = (joints_t *)ctx;
    double feet[4][3];
    int l, j;
    ref_body_ik(&s->g, pose, feet);
    for (l = 0; l < 4; ++l) {
        double q[3];
        if (!ref_leg_ik(&s->g, l, feet[l], q)) {
            snprintf(msg, sizeof msg, "action %u tick %lu leg %d unreachable (%.1f %.1f %.1f mm)", id,
                     (unsigned long)tick, l + 1, feet[l][0], feet[l][1], feet[l][2]);
            TEST_FAIL_MESSAGE(msg);
        }
        for (j = 0; j < 3; ++j) {
            if (q[j] < s->g.lo[j] + JOINT_MARGIN_DEG || q[j] > s->g.hi[j] - JOINT_MARGIN_DEG) {
                snprintf(msg, sizeof msg, "action %u tick %lu leg %d %s = %.2f deg, limits %.0f..%.0f",
                         id, (unsigned long)tick, l + 1, jn[j], q[j], s->g.lo[j], s->g.hi[j]);
                TEST_FAIL_MESSAGE(msg);
            }
            if (q[j] < s->lo[j]) {
                s->lo[j] = q[j];
            }
            if (q[j] > s->hi[j]) {
                s->hi[j] = q[j];
            }
            if (tick > 0u) {
                double st = fabs(q[j] - s->prev[l][j]);
                if (st > s->max_step) {
                    s->max_step = st;
                }
                if (st > MAX_JOINT_STEP_DEG) {
                    snprintf(msg, sizeof msg, "action %u tick %lu leg %d %s moves %.3f deg in a tick",
                             id, (unsigned long)tick, l + 1, jn[j], st);
                    TEST_FAIL_MESSAGE(msg);
                }
            }
            s->prev[l][j] = q[j];
        }
        s->checked++;
    }
}

static void joints_init(joints_t *s)
{
    int j;
    memset(s, 0, sizeof *s);
    s->g = geom();
    for (j = 0; j < 3; ++j) {
        s->lo[j] = 1e9;
        s->hi[j] = -1e9;
    }
}

/* Every tick of every action, all four legs: reachable, inside the joint
 * limits with JOINT_MARGIN_DEG to spare, and no joint faster than
 * MAX_JOINT_STEP_DEG per tick. */
static void test_joint_limits_reference_ik(void)
{
    joints_t s;
    double q[3], f[3];
    joints_init(&s);
    /* the reference IK itself: the stance is x1 ~ 0, x2 ~ 51, x3 = 0 */
    f[0] = 0.0;
    f[1] = 0.0;
    f[2] = s.g.h0;
    TEST_ASSERT_TRUE(ref_leg_ik(&s.g, 0, f, q));
    TEST_ASSERT_DOUBLE_WITHIN(0.001, 0.0, q[2]);
    TEST_ASSERT_DOUBLE_WITHIN(2.0, 0.0, q[0]);
    TEST_ASSERT_DOUBLE_WITHIN(3.0, 51.0, q[1]);
    play_all(check_joints, &s);
    snprintf(msg, sizeof msg,
             "%lu leg solutions; knee %.1f..%.1f, hip %.1f..%.1f, abduction %.1f..%.1f deg; "
             "fastest joint %.3f deg/tick",
             s.checked, s.lo[0], s.hi[0], s.lo[1], s.hi[1], s.lo[2], s.hi[2], s.max_step);
    TEST_MESSAGE(msg);
}

/* The same through the core's fixed-point kinematics (the authority for
 * the conventions): every leg reached (not projected), inside the limits
 * with the margin, and within IK_AGREE_DEG of the reference. */
static void check_fixed_ik(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    joints_t *s = (joints_t *)ctx;
    const xgo_profile_t *pr = xgo_profile_mini();
    xgo_body_pose_t bp;
    xgo_vec3_t feet[XGO_LEG_COUNT];
    int32_t q[XGO_LEG_COUNT][XGO_JOINT_COUNT];
    double ref_feet[4][3];
    unsigned mask;
    int l, j;
    xgo_body_pose_stand(pr, &bp);
    bp.x_um += pose->body.x_um;
    bp.y_um += pose->body.y_um;
    bp.z_um += pose->body.z_um;
    bp.roll_mdeg = pose->body.roll_mdeg;
    bp.pitch_mdeg = pose->body.pitch_mdeg;
    bp.yaw_mdeg = pose->body.yaw_mdeg;
    xgo_stance_feet(pr, feet);
    for (l = 0; l < XGO_LEG_COUNT; ++l) {
        feet[l].x += pose->feet_um[l].x;
        feet[l].y += pose->feet_um[l].y;
        feet[l].z += pose->feet_um[l].z;
    }
    mask = xgo_body_to_joints(pr, &bp, feet, q);
    snprintf(msg, sizeof msg, "action %u tick %lu: projected legs mask %u", id, (unsigned long)tick, mask);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(0u, mask, msg);
    ref_body_ik(&s->g, pose, ref_feet);
    for (l = 0; l < 4; ++l) {
        double rq[3];
        TEST_ASSERT_TRUE(ref_leg_ik(&s->g, l, ref_feet[l], rq));
        for (j = 0; j < 3; ++j) {
            double v = q[l][j] / 1000.0, dis = fabs(v - rq[j]);
            snprintf(msg, sizeof msg, "action %u tick %lu leg %d joint %d: fixed %.3f ref %.3f", id,
                     (unsigned long)tick, l + 1, j, v, rq[j]);
            TEST_ASSERT_TRUE_MESSAGE(v >= s->g.lo[j] + JOINT_MARGIN_DEG && v <= s->g.hi[j] - JOINT_MARGIN_DEG, msg);
            TEST_ASSERT_TRUE_MESSAGE(dis <= IK_AGREE_DEG, msg);
            if (dis > s->max_disagree) {
                s->max_disagree = dis;
            }
        }
        s->checked++;
    }
}

static void test_joint_limits_core_kinematics(void)
{
    joints_t s;
    joints_init(&s);
    play_all(check_fixed_ik, &s);
    snprintf(msg, sizeof msg, "%lu leg solutions; largest fixed-point vs reference difference %.4f deg",
             s.checked, s.max_disagree);
    TEST_MESSAGE(msg);
}

/* Static balance: while exactly one foot is off the ground (> 3 mm), the
 * body centre's ground point lies inside the triangle of the other three
 * feet, at least BALANCE_MARGIN_MM from its edges. Mark time (5) is a trot:
 * two feet leave the ground together, it balances dynamically and is not
 * checked (nor is any tick with two feet up). */
#define BALANCE_MARGIN_MM 3.0

typedef struct balance_s {
    geom_t g;
    double worst; /* smallest margin seen, mm */
} balance_t;

/* Signed distance of p from the line a->b, positive on the side of c. */
static double side_dist(const double a[2], const double b[2], const double c[2], const double p[2])
{
    double ex = b[0] - a[0], ey = b[1] - a[1];
    double len = sqrt(ex * ex + ey * ey);
    double dp = (ex * (p[1] - a[1]) - ey * (p[0] - a[0])) / len;
    double dc = (ex * (c[1] - a[1]) - ey * (c[0] - a[0])) / len;
    return dc < 0.0 ? -dp : dp;
}

static void check_balance(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    balance_t *b = (balance_t *)ctx;
    double f[4][2], centre[2], m;
    int l, up = -1, n_up = 0, t[3], k = 0;
    if (id == XGO_ACTION_STEP) {
        return;
    }
    for (l = 0; l < 4; ++l) {
        f[l][0] = k_side_x[l] * b->g.hx + pose->feet_um[l].x / 1000.0;
        f[l][1] = k_side_y[l] * (b->g.hy + b->g.d) + pose->feet_um[l].y / 1000.0;
        if (pose->feet_um[l].z > 3000) {
            up = l;
            n_up++;
        } else {
            t[k < 3 ? k : 2] = l;
            k++;
        }
    }
    if (n_up != 1) {
        return;
    }
    (void)up;
    centre[0] = pose->body.x_um / 1000.0;
    centre[1] = pose->body.y_um / 1000.0;
    m = side_dist(f[t[0]], f[t[1]], f[t[2]], centre);
    if (side_dist(f[t[1]], f[t[2]], f[t[0]], centre) < m) {
        m = side_dist(f[t[1]], f[t[2]], f[t[0]], centre);
    }
    if (side_dist(f[t[2]], f[t[0]], f[t[1]], centre) < m) {
        m = side_dist(f[t[2]], f[t[0]], f[t[1]], centre);
    }
    if (m < b->worst) {
        b->worst = m;
    }
    if (m < BALANCE_MARGIN_MM) {
        snprintf(msg, sizeof msg, "action %u tick %lu: leg %d up, body centre %.1f mm from the edge",
                 id, (unsigned long)tick, up + 1, m);
        TEST_FAIL_MESSAGE(msg);
    }
}

static void test_one_foot_up_keeps_static_balance(void)
{
    balance_t b;
    b.g = geom();
    b.worst = 1e9;
    play_all(check_balance, &b);
    snprintf(msg, sizeof msg, "smallest margin %.1f mm", b.worst);
    TEST_MESSAGE(msg);
}

/* ------------------------------------------------------------ motions */

/* Each action does what its name says: a channel (index into flatten())
 * reaches at least / at most a value somewhere in the action. */
enum { BX, BY, BZ, ROLL, PITCH, YAW, LFX, LFY, LFZ, RFX, RFY, RFZ, RHX, RHY, RHZ, LHX, LHY, LHZ };

typedef struct signature_s {
    uint8_t id;
    uint8_t channel;
    int32_t min_at_most;  /* INT32_MAX: no check */
    int32_t max_at_least; /* INT32_MIN: no check */
} signature_t;

#define NOCHK_MIN INT32_MAX
#define NOCHK_MAX INT32_MIN

static const signature_t k_signatures[] = {
    {1, BZ, -47600, NOCHK_MAX},          /* lie down: hips at most 50 mm above the ground */
    {2, BZ, -47600, 12000},              /* stand up: from lying to tall */
    {3, BZ, -18000, NOCHK_MAX},          /* creep: low (its crawl is the gait's: test_motion) */
    {5, LFZ, NOCHK_MIN, 15000},          /* step: all feet lift */
    {5, RFZ, NOCHK_MIN, 15000},
    {5, RHZ, NOCHK_MIN, 15000},
    {5, LHZ, NOCHK_MIN, 15000},
    {6, BZ, -18000, 10000},              /* squat */
    {7, ROLL, -15000, 15000},            /* roll, pitch, yaw */
    {8, PITCH, -15000, 15000},
    {9, YAW, -12000, 12000},
    {10, ROLL, -12000, 12000},           /* three axes */
    {10, PITCH, -12000, 12000},
    {10, YAW, -10000, 10000},
    {11, LHZ, NOCHK_MIN, 30000},         /* pee: left hind up and out */
    {11, LHY, NOCHK_MIN, 8000},
    {12, PITCH, -27000, NOCHK_MAX},      /* sit: rump back and down, nose up */
    {12, BX, -50000, NOCHK_MAX},
    {12, BZ, -20000, NOCHK_MAX},
    {13, LFZ, 25000, 35000},             /* beckon: paw low, curling in and out */
    {13, LFX, 10000, 18000},
    {14, PITCH, -12000, 18000},          /* stretch: bow and back, hind leg back */
    {14, RHX, -18000, NOCHK_MAX},
    {15, LFZ, NOCHK_MIN, 58000},         /* wave: paw high, side to side */
    {15, LFY, -10000, 16000},
    {16, BY, -14000, 14000},             /* sway */
    {17, PITCH, -27000, NOCHK_MAX},      /* beg: sitting, both paws up */
    {17, BX, -50000, NOCHK_MAX},
    {17, LFZ, NOCHK_MIN, 40000},
    {17, RFZ, NOCHK_MIN, 40000},
    {18, PITCH, NOCHK_MIN, 12000},       /* search: nose down, looking about */
    {18, YAW, -12000, 12000},
    {19, RFZ, NOCHK_MIN, 38000},         /* shake hands: right paw forward, up */
    {19, RFX, NOCHK_MIN, 25000},
    {20, BX, -8000, 15000},              /* chicken head: pecking */
    {21, PITCH, NOCHK_MIN, 12000},       /* push-up */
    {21, BZ, -10000, NOCHK_MAX},
    {22, YAW, -12000, 12000},            /* look around */
    {23, BY, -8000, 8000},               /* dance */
    {23, LFZ, NOCHK_MIN, 12000},
    {24, YAW, -8000, 8000},              /* naughty */
};

typedef struct extremes_s {
    int32_t lo[18], hi[18];
} extremes_t;

static void record_extremes(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    extremes_t *e = (extremes_t *)ctx;
    int32_t v[18];
    int i;
    (void)id;
    (void)tick;
    flatten(pose, v);
    for (i = 0; i < 18; ++i) {
        if (v[i] < e->lo[i]) {
            e->lo[i] = v[i];
        }
        if (v[i] > e->hi[i]) {
            e->hi[i] = v[i];
        }
    }
}

static void test_motions_are_recognisable(void)
{
    size_t i;
    for (i = 0; i < sizeof k_signatures / sizeof k_signatures[0]; ++i) {
        const signature_t *sg = &k_signatures[i];
        extremes_t e;
        memset(&e, 0, sizeof e);
        play(sg->id, record_extremes, &e);
        snprintf(msg, sizeof msg, "action %u channel %u: range %ld..%ld", sg->id, sg->channel,
                 (long)e.lo[sg->channel], (long)e.hi[sg->channel]);
        TEST_ASSERT_TRUE_MESSAGE(e.lo[sg->channel] <= sg->min_at_most, msg);
        TEST_ASSERT_TRUE_MESSAGE(e.hi[sg->channel] >= sg->max_at_least, msg);
    }
}

/* Periodic parts repeat: mark time lifts each diagonal pair eight times. */
typedef struct lifts_s {
    int up[4];
    unsigned count[4];
} lifts_t;

static void count_lifts(void *ctx, unsigned id, uint32_t tick, const xgo_pose_t *pose)
{
    lifts_t *c = (lifts_t *)ctx;
    int l;
    (void)id;
    (void)tick;
    for (l = 0; l < 4; ++l) {
        int up = pose->feet_um[l].z > 10000;
        if (up && !c->up[l]) {
            c->count[l]++;
        }
        c->up[l] = up;
    }
}

static void test_step_repeats(void)
{
    lifts_t c;
    int l;
    memset(&c, 0, sizeof c);
    play(XGO_ACTION_STEP, count_lifts, &c);
    for (l = 0; l < 4; ++l) {
        TEST_ASSERT_EQUAL_UINT(8, c.count[l]);
    }
}

/* Creep and circle walk with the gait (their feet are its, test_motion and
 * test_odometry check the steps and the way): the player gives the command
 * in its window and zero outside, while its own feet offsets stay zero. */
static void test_creep_and_circle_walk_in_their_window(void)
{
    static const uint8_t ids[2] = {XGO_ACTION_CREEP, XGO_ACTION_CIRCLE};
    unsigned i;
    for (i = 0; i < 2; ++i) {
        xgo_action_player_t p;
        xgo_action_walk_t w;
        xgo_pose_t pose;
        uint32_t k, n = xgo_action_duration_ticks(ids[i]), walking = 0;
        xgo_action_init(&p);
        TEST_ASSERT_EQUAL_INT(0, xgo_action_walk(&p, &w));
        xgo_action_start(&p, ids[i]);
        for (k = 1; k < n; ++k) {
            int l;
            xgo_action_tick(&p, &pose);
            TEST_ASSERT_EQUAL_INT(1, xgo_action_walk(&p, &w));
            walking += w.vx_um_s != 0 || w.vyaw_mdeg_s != 0;
            for (l = 0; l < 4; ++l) {
                TEST_ASSERT_EQUAL_INT32(0, pose.feet_um[l].z);
            }
            if (k == 1 || k == n - 1) { /* still at the start, already at the end */
                TEST_ASSERT_EQUAL_INT32(0, w.vx_um_s);
                TEST_ASSERT_EQUAL_INT32(0, w.vyaw_mdeg_s);
            }
        }
        TEST_ASSERT_EQUAL_UINT32(ids[i] == XGO_ACTION_CREEP ? 1250u : 1500u, walking);
    }
    {
        xgo_action_player_t p;
        xgo_action_walk_t w;
        xgo_action_init(&p);
        xgo_action_start(&p, XGO_ACTION_WAVE);
        TEST_ASSERT_EQUAL_INT(0, xgo_action_walk(&p, &w));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_durations_are_the_vendor_waits);
    RUN_TEST(test_every_action_lasts_its_duration_to_the_tick);
    RUN_TEST(test_idle_player_ticks_the_zero_pose);
    RUN_TEST(test_unknown_ids_start_nothing);
    RUN_TEST(test_start_while_running_restarts);
    RUN_TEST(test_stop);
    RUN_TEST(test_lead_in_holds_then_plays_time_scaled);
    RUN_TEST(test_lead_in_of_no_ticks_changes_nothing);
    RUN_TEST(test_names);
    RUN_TEST(test_perform_cycle);
    RUN_TEST(test_poses_change_smoothly);
    RUN_TEST(test_poses_stay_in_the_body_ranges);
    RUN_TEST(test_joint_limits_reference_ik);
    RUN_TEST(test_joint_limits_core_kinematics);
    RUN_TEST(test_one_foot_up_keeps_static_balance);
    RUN_TEST(test_motions_are_recognisable);
    RUN_TEST(test_step_repeats);
    RUN_TEST(test_creep_and_circle_walk_in_their_window);
    return UNITY_END();
}
