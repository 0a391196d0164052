/*
 * Actions that match their names (issue 9 part 3), played by the board and
 * measured with its own forward kinematics (the joints as they are) and
 * odometry on virtual time: lying down puts the belly on the floor, sitting
 * puts the rump down with the front legs straight, begging sits with both
 * front paws up, creeping crawls forward low, circling turns the dog round,
 * waving looks nothing like beckoning. Every action keeps its joints 1 degree
 * inside their limits and its planted feet from sliding.
 *
 * Heights come from the FK feet and the body pose the board reports: a point
 * p of the body frame is R p + t above the ground, R = Rz(yaw) Ry(pitch)
 * Rx(roll) (docs/geometry.md), computed here in double precision.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "actions.h" /* xgo_action_duration_ticks */
#include "board_io.h"
#include "reference.h"
#include "unity.h"
#include "xgo/board.h"

static xgo_board_t board;
static char msg[200];

void setUp(void)
{
    xgo_board_init(&board, NULL);
}

void tearDown(void)
{
}

static void wr(uint8_t addr, uint8_t v)
{
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_CLI, addr, &v, 1));
}

/* A body-frame point (mm) in the machine frame (mm), with the body pose the
 * board reports. */
static void to_machine(const double body[3], double out[3])
{
    xgo_body_pose_t p;
    double m[3][3];
    int i;
    xgo_board_body_pose(&board, &p);
    xgo_ref_rotation(p.roll_mdeg / 1000.0 * M_PI / 180.0, p.pitch_mdeg / 1000.0 * M_PI / 180.0,
                     p.yaw_mdeg / 1000.0 * M_PI / 180.0, m);
    for (i = 0; i < 3; i++) {
        out[i] = m[i][0] * body[0] + m[i][1] * body[1] + m[i][2] * body[2];
    }
    out[0] += p.x_um / 1000.0;
    out[1] += p.y_um / 1000.0;
    out[2] += p.z_um / 1000.0;
}

/* Height above the ground of foot `leg` (FK) and of the hips of the front
 * (front = 1) or rear pair: the middle of their abduction axes. */
static double foot_height(unsigned leg)
{
    xgo_vec3_t f[XGO_LEG_COUNT];
    double b[3], w[3];
    xgo_board_feet_um(&board, f);
    b[0] = f[leg].x / 1000.0;
    b[1] = f[leg].y / 1000.0;
    b[2] = f[leg].z / 1000.0;
    to_machine(b, w);
    return w[2];
}

static double hips_height(int front)
{
    const xgo_profile_t *p = xgo_profile_mini();
    double b[3], w[3];
    b[0] = (front ? 1 : -1) * p->hip_x_um / 1000.0;
    b[1] = 0.0;
    b[2] = 0.0;
    to_machine(b, w);
    return w[2];
}

/* How straight a leg is: the distance from its thigh joint to its foot
 * (FK) over the most the leg can stretch (its knee at the limit). */
static double straightness(unsigned leg)
{
    const xgo_profile_t *p = xgo_profile_mini();
    xgo_vec3_t f[XGO_LEG_COUNT];
    const double l1 = p->thigh_um / 1000.0, l2 = p->shank_um / 1000.0;
    const double g = (p->joint_mdeg[XGO_JOINT_KNEE].hi + p->knee_offset_mdeg) / 1000.0 * M_PI / 180.0;
    const double most = sqrt(l1 * l1 + l2 * l2 + 2.0 * l1 * l2 * sin(g));
    double dx, dy, dz;
    xgo_board_feet_um(&board, f);
    dx = f[leg].x / 1000.0 - xgo_leg_side_x((xgo_leg_t)leg) * p->hip_x_um / 1000.0;
    dy = f[leg].y / 1000.0 - xgo_leg_side_y((xgo_leg_t)leg) * (p->hip_y_um + p->abad_offset_um) / 1000.0;
    dz = f[leg].z / 1000.0;
    return sqrt(dx * dx + dy * dy + dz * dz) / most;
}

/* ------------------------------------------------------------ every action */

/* Footprint and joints over a whole action: planted feet keep their
 * pairwise distances (2 mm), joints 1 degree inside their limits, at most
 * 1.2 degrees per tick. */
typedef struct watch_s {
    double ref[XGO_LEG_COUNT][XGO_LEG_COUNT];
    int both[XGO_LEG_COUNT][XGO_LEG_COUNT];
    double worst_slide, least_margin;
    int32_t last[XGO_SERVO_COUNT];
} watch_t;

static void watch_start(watch_t *w)
{
    memset(w, 0, sizeof *w);
    w->least_margin = 1e9;
    xgo_board_joints_mdeg(&board, w->last);
}

static void watch_tick(watch_t *w)
{
    xgo_vec3_t f[XGO_LEG_COUNT];
    int32_t q[XGO_SERVO_COUNT];
    const uint8_t c = xgo_board_contacts(&board);
    unsigned i, j;
    xgo_board_feet_um(&board, f);
    for (i = 0; i < XGO_LEG_COUNT; i++) {
        for (j = i + 1; j < XGO_LEG_COUNT; j++) {
            const double dx = (f[i].x - f[j].x) / 1000.0, dy = (f[i].y - f[j].y) / 1000.0;
            const double dz = (f[i].z - f[j].z) / 1000.0, d = sqrt(dx * dx + dy * dy + dz * dz);
            const int both = ((c >> i) & 1u) && ((c >> j) & 1u);
            if (both && w->both[i][j]) {
                w->worst_slide = fabs(d - w->ref[i][j]) > w->worst_slide ? fabs(d - w->ref[i][j]) : w->worst_slide;
            } else if (both) {
                w->ref[i][j] = d;
            }
            w->both[i][j] = both;
        }
    }
    xgo_board_joints_mdeg(&board, q);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        int32_t lo, hi, margin;
        xgo_board_joint_limits_mdeg(&board, i, &lo, &hi);
        margin = q[i] - lo < hi - q[i] ? q[i] - lo : hi - q[i];
        w->least_margin = margin / 1000.0 < w->least_margin ? margin / 1000.0 : w->least_margin;
        TEST_ASSERT_LESS_OR_EQUAL_INT32(1200, abs(q[i] - w->last[i]));
    }
    memcpy(w->last, q, sizeof q);
}

static void test_every_action_keeps_its_feet_and_its_joints(void)
{
    unsigned id;
    for (id = 1; id <= XGO_ACTION_LAST; id++) {
        watch_t w;
        uint32_t k;
        xgo_board_init(&board, NULL);
        wr(XGO_REG_ACTION, (uint8_t)id);
        watch_start(&w);
        for (k = 0; k < xgo_action_duration_ticks((uint8_t)id); k++) {
            xgo_test_ticks(&board, 1);
            watch_tick(&w);
        }
        snprintf(msg, sizeof msg, "action %u (%s): planted feet slid %.3f mm, joints %.2f deg inside their limits",
                 id, xgo_action_name((uint8_t)id), w.worst_slide, w.least_margin);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(w.worst_slide <= 2.0, msg);
        TEST_ASSERT_TRUE_MESSAGE(w.least_margin >= 1.0, msg);
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(0, xgo_board_action(&board), msg);
    }
}

/* ------------------------------------------------------------ the names */

/* Plays action id and calls fn every tick with the tick number. */
typedef void (*tick_fn)(void *ctx, uint32_t tick);

static void play(uint8_t id, tick_fn fn, void *ctx)
{
    uint32_t k;
    xgo_board_init(&board, NULL);
    wr(XGO_REG_ACTION, id);
    for (k = 1; k <= xgo_action_duration_ticks(id); k++) {
        xgo_test_ticks(&board, 1);
        fn(ctx, k);
    }
}

typedef struct lowest_s {
    double rear, front, rear_at_rest, front_straight, paws_up;
    uint32_t rest_from, rest_to;
} lowest_t;

static void track_low(void *ctx, uint32_t tick)
{
    lowest_t *l = (lowest_t *)ctx;
    const double rear = hips_height(0), front = hips_height(1);
    l->rear = rear < l->rear ? rear : l->rear;
    l->front = front < l->front ? front : l->front;
    if (tick >= l->rest_from && tick <= l->rest_to) {
        const double s = straightness(XGO_LEG_LF) < straightness(XGO_LEG_RF) ? straightness(XGO_LEG_LF)
                                                                             : straightness(XGO_LEG_RF);
        const double paws = foot_height(XGO_LEG_LF) < foot_height(XGO_LEG_RF) ? foot_height(XGO_LEG_LF)
                                                                              : foot_height(XGO_LEG_RF);
        l->rear_at_rest = rear > l->rear_at_rest ? rear : l->rear_at_rest;
        l->front_straight = s < l->front_straight ? s : l->front_straight;
        l->paws_up = paws > l->paws_up ? paws : l->paws_up;
    }
}

static lowest_t lowest(uint8_t id, uint32_t rest_from, uint32_t rest_to)
{
    lowest_t l;
    l.rear = l.front = 1e9;
    l.rear_at_rest = -1e9;
    l.front_straight = 1e9;
    l.paws_up = -1e9;
    l.rest_from = rest_from;
    l.rest_to = rest_to;
    play(id, track_low, &l);
    return l;
}

/* 1 lying down: the belly on the floor - every hip at most 50 mm above the
 * ground while it rests (1.1 .. 1.9 s); before issue 9, 78 mm. */
static void test_lying_down_puts_the_belly_on_the_floor(void)
{
    const lowest_t l = lowest(XGO_ACTION_LIE_DOWN, 550, 950);
    snprintf(msg, sizeof msg, "lying: rear hips at most %.1f mm, front hips %.1f mm", l.rear_at_rest, l.front);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(l.rear_at_rest <= 50.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(l.front <= 50.0, msg);
}

/* 12 sitting: the rump down - the rear hips at most 50 mm above the ground -
 * with the front legs straight (at least 97 % of their full stretch) all
 * the while it sits (1.2 .. 3.4 s); before issue 9 the rear hips were at
 * 68 mm. */
static void test_sitting_puts_the_rump_down_on_straight_front_legs(void)
{
    const lowest_t l = lowest(XGO_ACTION_SIT, 600, 1700);
    snprintf(msg, sizeof msg, "sitting: rear hips at most %.1f mm, front legs %.1f %% stretched", l.rear_at_rest,
             100.0 * l.front_straight);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(l.rear_at_rest <= 50.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(l.front_straight >= 0.97, msg);
}

/* 17 begging: sitting as 12 - rear hips at most 50 mm - with both front
 * paws up (at least 30 mm above the ground at once). */
static void test_begging_sits_with_both_front_paws_up(void)
{
    const lowest_t l = lowest(XGO_ACTION_BEG, 350, 1150);
    snprintf(msg, sizeof msg, "begging: rear hips at most %.1f mm, both front paws up to %.1f mm", l.rear_at_rest,
             l.paws_up);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(l.rear_at_rest <= 50.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(l.paws_up >= 30.0, msg);
}

typedef struct crawl_s {
    uint8_t last_contact;
    unsigned lifts[XGO_LEG_COUNT];
    unsigned fewest_down;
    double highest_hips;
    uint32_t from, to;
} crawl_t;

static void track_crawl(void *ctx, uint32_t tick)
{
    crawl_t *c = (crawl_t *)ctx;
    const uint8_t now = xgo_board_contacts(&board);
    unsigned leg, down = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        c->lifts[leg] += ((c->last_contact >> leg) & 1u) && !((now >> leg) & 1u);
        down += (now >> leg) & 1u;
    }
    c->fewest_down = down < c->fewest_down ? down : c->fewest_down;
    c->last_contact = now;
    if (tick >= c->from && tick <= c->to) {
        const double h = hips_height(1) > hips_height(0) ? hips_height(1) : hips_height(0);
        c->highest_hips = h > c->highest_hips ? h : c->highest_hips;
    }
}

/* 3 creeping: a low crawl forward - the hips at most 80 mm up while it
 * crawls, one foot in the air at a time, every foot stepping, and the dog
 * 10 cm further on at the end, straight ahead - and no planted foot
 * sliding on the way in or out (every action: above). */
static void test_creeping_crawls_forward_low(void)
{
    crawl_t c;
    xgo_world_pose_t w;
    unsigned leg;
    memset(&c, 0, sizeof c);
    c.last_contact = 0x0F;
    c.fewest_down = 4;
    c.from = 300;
    c.to = 1500;
    play(XGO_ACTION_CREEP, track_crawl, &c);
    xgo_board_world_pose(&board, &w);
    snprintf(msg, sizeof msg, "creep: %.1f mm forward, %.1f mm aside, %.2f deg; hips at most %.1f mm; "
             "lifts %u %u %u %u; fewest feet down %u", w.x_um / 1000.0, w.y_um / 1000.0, w.yaw_mdeg / 1000.0,
             c.highest_hips, c.lifts[0], c.lifts[1], c.lifts[2], c.lifts[3], c.fewest_down);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(w.x_um > 100000, msg);
    TEST_ASSERT_INT32_WITHIN_MESSAGE(2000, 0, w.y_um, msg);
    TEST_ASSERT_INT32_WITHIN_MESSAGE(500, 0, w.yaw_mdeg, msg);
    TEST_ASSERT_TRUE_MESSAGE(c.highest_hips <= 80.0, msg);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(3, c.fewest_down, msg);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        TEST_ASSERT_TRUE_MESSAGE(c.lifts[leg] >= 3, msg);
    }
}

typedef struct turn_s {
    int32_t last;
    double total;
} turn_t;

static void track_turn(void *ctx, uint32_t tick)
{
    turn_t *t = (turn_t *)ctx;
    xgo_world_pose_t w;
    int32_t d;
    (void)tick;
    xgo_board_world_pose(&board, &w);
    d = w.yaw_mdeg - t->last;
    d = d > 180000 ? d - 360000 : (d < -180000 ? d + 360000 : d);
    t->total += d / 1000.0;
    t->last = w.yaw_mdeg;
}

/* 4 circling: the dog turns round - its heading changes by a full turn
 * (the world pose of the odometry, unwrapped), on the spot; before issue 9
 * it only swayed its body over fixed feet. */
static void test_circling_turns_the_dog_round(void)
{
    turn_t t;
    xgo_world_pose_t w;
    t.last = 0;
    t.total = 0.0;
    play(XGO_ACTION_CIRCLE, track_turn, &t);
    xgo_board_world_pose(&board, &w);
    snprintf(msg, sizeof msg, "circle: turned %.2f deg, ended %.1f mm from where it started", t.total,
             sqrt((double)w.x_um * w.x_um + (double)w.y_um * w.y_um) / 1000.0);
    TEST_MESSAGE(msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2.0, 360.0, t.total, msg);
    TEST_ASSERT_TRUE_MESSAGE(sqrt((double)w.x_um * w.x_um + (double)w.y_um * w.y_um) < 10000.0, msg);
}

typedef struct paw_s {
    double lo[3], hi[3]; /* the left front foot's body-frame x, y and its height */
} paw_t;

static void track_paw(void *ctx, uint32_t tick)
{
    paw_t *p = (paw_t *)ctx;
    xgo_vec3_t f[XGO_LEG_COUNT];
    double v[3];
    int i;
    (void)tick;
    xgo_board_feet_um(&board, f);
    v[0] = f[XGO_LEG_LF].x / 1000.0;
    v[1] = f[XGO_LEG_LF].y / 1000.0;
    v[2] = foot_height(XGO_LEG_LF);
    for (i = 0; i < 3; i++) {
        p->lo[i] = v[i] < p->lo[i] ? v[i] : p->lo[i];
        p->hi[i] = v[i] > p->hi[i] ? v[i] : p->hi[i];
    }
}

static paw_t paw(uint8_t id)
{
    paw_t p;
    int i;
    for (i = 0; i < 3; i++) {
        p.lo[i] = 1e9;
        p.hi[i] = -1e9;
    }
    play(id, track_paw, &p);
    return p;
}

/* 15 waving and 13 beckoning look different: the waving paw goes high (at
 * least 55 mm) and swings from side to side (at least 25 mm); the beckoning
 * paw stays low (at most 45 mm), hardly moves sideways (at most 8 mm: the
 * body's lean) and curls back and forth (at least 10 mm). */
static void test_waving_is_not_beckoning(void)
{
    const paw_t w = paw(XGO_ACTION_WAVE), b = paw(XGO_ACTION_BECKON);
    snprintf(msg, sizeof msg, "wave: paw up to %.1f mm, sideways %.1f mm; beckon: up to %.1f mm, sideways %.1f mm, "
             "back and forth %.1f mm", w.hi[2], w.hi[1] - w.lo[1], b.hi[2], b.hi[1] - b.lo[1], b.hi[0] - b.lo[0]);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(w.hi[2] >= 55.0 && w.hi[1] - w.lo[1] >= 25.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(b.hi[2] <= 45.0 && b.hi[1] - b.lo[1] <= 8.0 && b.hi[0] - b.lo[0] >= 10.0, msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_action_keeps_its_feet_and_its_joints);
    RUN_TEST(test_lying_down_puts_the_belly_on_the_floor);
    RUN_TEST(test_sitting_puts_the_rump_down_on_straight_front_legs);
    RUN_TEST(test_begging_sits_with_both_front_paws_up);
    RUN_TEST(test_creeping_crawls_forward_low);
    RUN_TEST(test_circling_turns_the_dog_round);
    RUN_TEST(test_waving_is_not_beckoning);
    return UNITY_END();
}
