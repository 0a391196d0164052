/*
 * The motion core: modes, transitions between them, and the hand-off to
 * gait, actions, kinematics, servos and sensors. The host's writes are
 * taken in motion_writes.c, the pose the registers ask for is computed in
 * motion_pose.c.
 */
#include "motion.h"

#include <stddef.h>
#include <string.h>

#include "codec.h"
#include "follow.h"
#include "motion_internal.h"
#include "reach.h"
#include "settle.h"
#include "wide.h" /* XGO_CORE_DIV64_NATIVE */

/* How the walking tick's functions are built. On a 64-bit host the stack
 * is no budget and each call costs its saved registers and argument moves:
 * the tick's stages are inline there, one frame for the walking tick. On
 * an MCU:
 * WALK_FRAME: out of line (XGO_OWN_FRAME), so their locals do not widen
 *   the frame the reach search starts from (gait_command, update_stroke,
 *   reachable_target, walk_tick, solve_joints);
 * HOST_INLINE: plain static, the compiler decides (solve_tick,
 *   whole_unit_targets);
 * HOST_APART: the other way round, inline on an MCU and out of line on the
 *   host, for a rare path whose stores the host's compiler would otherwise
 *   prepare every tick (new_stroke). */
#if XGO_CORE_DIV64_NATIVE
#define WALK_FRAME XGO_ALWAYS_INLINE
#define HOST_INLINE XGO_ALWAYS_INLINE
#define HOST_APART static XGO_OWN_FRAME
#else
#define WALK_FRAME static XGO_OWN_FRAME
#define HOST_INLINE static
#define HOST_APART XGO_ALWAYS_INLINE
#endif

/* The stroke checked grows by this when a planted foot runs out of reach
 * anyway (up to the max), see reachable_target. */
#define STROKE_MARGIN_STEP_UM 3000
#define STROKE_MARGIN_MAX_UM 15000

/* a[0..n) == b[0..n): memcmp's answer, inline (the library call costs
 * about 77 instructions on an M0, several times a tick) */
static int same_words(const int32_t *a, const int32_t *b, unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        if (a[i] != b[i]) {
            return 0;
        }
    }
    return 1;
}

static int same_pose(const xgo_body_pose_t *a, const xgo_body_pose_t *b)
{
    return a->roll_mdeg == b->roll_mdeg && a->pitch_mdeg == b->pitch_mdeg &&
           a->yaw_mdeg == b->yaw_mdeg && a->x_um == b->x_um && a->y_um == b->y_um &&
           a->z_um == b->z_um;
}

static int same_feet(const xgo_vec3_t a[XGO_LEG_COUNT], const xgo_vec3_t b[XGO_LEG_COUNT])
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (a[leg].x != b[leg].x || a[leg].y != b[leg].y || a[leg].z != b[leg].z) {
            return 0;
        }
    }
    return 1;
}

/* The servos are where the last IK put them. */
static int joints_as_solved(const xgo_motion_t *m)
{
    return same_words(m->servos.angle_mdeg, m->ik_cache.q_mdeg, XGO_SERVO_COUNT);
}

static void reset_gait(xgo_motion_t *m)
{
    xgo_gait_init(&m->gait, m->stance_um);
}

/* The standing pose is what the body registers say at their initial values
 * (height 0x80 = 97.6 mm on the Mini), so power-up, actions and the gait all
 * stand at the same height. */
static void standing_pose(const xgo_profile_t *p, xgo_body_pose_t *pose)
{
    const xgo_reg_desc_t *z = xgo_reg_find(XGO_REG_BODY_Z);
    xgo_body_pose_stand(p, pose);
    pose->z_um = xgo_byte_to_range(&p->body_um[XGO_AXIS_Z], z->initial);
}

static void measure_feet(xgo_motion_t *m, int contact_known, int at_solved);

static void standing_joints(const xgo_motion_t *m, int32_t q[XGO_SERVO_COUNT])
{
    xgo_body_to_joints(m->profile, &m->stand, m->stance_um, (int32_t(*)[XGO_JOINT_COUNT])q);
}

void xgo_motion_init(xgo_motion_t *m, const xgo_profile_t *profile, uint8_t battery_pct)
{
    int32_t q[XGO_SERVO_COUNT];
    memset(m, 0, sizeof *m);
    m->profile = profile;
    m->mode = XGO_MODE_WHOLE_UNIT;
    m->group_mode = XGO_MODE_WHOLE_UNIT;
    xgo_stance_feet(profile, m->stance_um);
    reset_gait(m);
    xgo_action_init(&m->actions);
    standing_pose(profile, &m->stand);
    m->pose = m->stand;
    m->pose_target = m->stand;
    xgo_follow_init(&m->follow, &m->stand);
    xgo_reach_init(&m->reach, &m->stand);
    standing_joints(m, q);
    xgo_servos_init(&m->servos, profile, q);
    xgo_imu_init(&m->imu);
    xgo_battery_init(&m->battery, battery_pct);
    xgo_odometry_init(&m->odom);
    xgo_heading_init(&m->heading);
    xgo_inertial_init(&m->inertial);
    xgo_arm_init(&m->arm, profile->arm);
    m->contact = 0x0Fu;
    measure_feet(m, 1, -1);
}

static void action_pose(xgo_motion_t *m, xgo_body_pose_t *pose, xgo_vec3_t feet[XGO_LEG_COUNT])
{
    xgo_pose_t ap;
    unsigned leg;
    if (!xgo_action_tick(&m->actions, &ap)) {
        m->action_id = 0;
    }
    pose->x_um = m->stand.x_um + ap.body.x_um;
    pose->y_um = m->stand.y_um + ap.body.y_um;
    pose->z_um = m->stand.z_um + ap.body.z_um;
    pose->roll_mdeg = m->stand.roll_mdeg + ap.body.roll_mdeg;
    pose->pitch_mdeg = m->stand.pitch_mdeg + ap.body.pitch_mdeg;
    pose->yaw_mdeg = m->stand.yaw_mdeg + ap.body.yaw_mdeg;
    m->contact = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg].x = m->stance_um[leg].x + ap.feet_um[leg].x;
        feet[leg].y = m->stance_um[leg].y + ap.feet_um[leg].y;
        feet[leg].z = m->stance_um[leg].z + ap.feet_um[leg].z;
        if (ap.feet_um[leg].z <= 0) {
            m->contact |= (uint8_t)(1u << leg);
        }
    }
}

/* Body + leg IK into m->ik_cache.q_mdeg (the servos' targets), skipped when
 * the pose and the feet are those of the last solve: a robot standing
 * still (the common case) then costs almost nothing, which matters on a
 * Cortex-M0 (docs/mcu.md). The leg-frame feet are not kept (48 bytes of
 * RAM; an observer works them out again, xgo_motion_feet_body); out of
 * line on an MCU, so they are not in the frame the reach search's deeper
 * path starts from. The rotation is updated from the cached one
 * (xgo_body_rotation_next) when update, else worked out whole: the same. */
XGO_ALWAYS_INLINE void solve_joints_with(xgo_motion_t *m, const xgo_body_pose_t *pose,
                                         const xgo_vec3_t feet[XGO_LEG_COUNT], int update)
{
    if (!m->ik_cache.valid || !same_pose(&m->ik_cache.pose, pose) ||
        !same_feet(m->ik_cache.feet, feet)) {
        xgo_vec3_t feet_leg[XGO_LEG_COUNT];
        if (update && m->ik_cache.valid) { /* rot_q30 is the cached pose's: its roll may serve */
            xgo_body_rotation_next(&m->ik_cache.pose, pose, m->ik_cache.rot_q30);
        } else {
            xgo_body_rotation(pose, m->ik_cache.rot_q30);
        }
        m->ik_cache.pose = *pose;
#if XGO_CORE_DIV64_NATIVE /* three 16-byte moves, inline (feet is never the cache's) */
        memcpy(m->ik_cache.feet, feet, sizeof m->ik_cache.feet);
#else
        {
            unsigned leg;
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                m->ik_cache.feet[leg] = feet[leg]; /* no memcpy call: every walking tick */
            }
        }
#endif
        xgo_body_ik_rotated(m->profile, pose, m->ik_cache.rot_q30, feet, feet_leg);
        m->ik_cache.projected = (uint8_t)xgo_legs_ik(m->profile, feet_leg,
                                                     (int32_t(*)[XGO_JOINT_COUNT])m->ik_cache.q_mdeg);
        m->ik_cache.valid = 1;
    }
}

WALK_FRAME void solve_joints(xgo_motion_t *m, const xgo_body_pose_t *pose, const xgo_vec3_t feet[XGO_LEG_COUNT])
{
    solve_joints_with(m, pose, feet, 1);
}

/* The other modes' solves (going_home, action_tick): on a 64-bit host an
 * out-of-line copy that works the rotation out whole, so that the walking
 * tick's inline copy is xgo_body_rotation_next's one caller and has it
 * inline too; on an MCU solve_joints, the one out-of-line solve. */
#if XGO_CORE_DIV64_NATIVE
static XGO_OWN_FRAME void solve_joints_apart(xgo_motion_t *m, const xgo_body_pose_t *pose,
                                             const xgo_vec3_t feet[XGO_LEG_COUNT])
{
    solve_joints_with(m, pose, feet, 0);
}
#else
#define solve_joints_apart solve_joints
#endif

/* ------------------------------------------------------------ transitions */

/* The feet in the body frame as the joints put them now (FK). */
static void feet_of_joints(const xgo_motion_t *m, xgo_vec3_t body[XGO_LEG_COUNT])
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_vec3_t foot_leg;
        xgo_leg_fk(m->profile, (xgo_leg_t)leg, &m->servos.angle_mdeg[XGO_JOINT_COUNT * leg], &foot_leg);
        xgo_leg_to_body(m->profile, (xgo_leg_t)leg, &foot_leg, &body[leg]);
    }
}

#if XGO_WITH_ODOMETRY
/* The feet in the body frame where the joints q put them (FK), for the
 * legs in mask; the others left as they are (not measured: only the
 * odometry leaves feet unmeasured, measure_feet, and xgo_body_to_machine_legs
 * with the same mask does not read them). */
static void feet_of_angles(const xgo_motion_t *m, const int32_t q[XGO_SERVO_COUNT], unsigned mask,
                           xgo_vec3_t body[XGO_LEG_COUNT])
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (((mask >> leg) & 1u) != 0) {
            xgo_vec3_t foot_leg;
            xgo_leg_fk(m->profile, (xgo_leg_t)leg, &q[XGO_JOINT_COUNT * leg], &foot_leg);
            xgo_leg_to_body(m->profile, (xgo_leg_t)leg, &foot_leg, &body[leg]);
        } /* the others are not read (xgo_body_to_machine_legs) */
    }
}
#endif

/* board_state.h cannot see kinematics.h: the cache's size is checked here. */
typedef char xgo_motion_rot_cache_check_[sizeof((xgo_motion_t *)0)->ik_cache.rot_q30 ==
                                         XGO_ROT_COUNT * sizeof(xgo_q30_t) ? 1 : -1];

/* The rotation of m->pose: the IK cache's when the last solve had the same
 * angles (the pose of this tick, in the whole-unit and action modes), else
 * worked out into scratch. */
static const xgo_q30_t *pose_rotation(const xgo_motion_t *m, xgo_q30_t scratch[XGO_ROT_COUNT])
{
    const xgo_body_pose_t *c = &m->ik_cache.pose;
    if (m->ik_cache.valid && c->roll_mdeg == m->pose.roll_mdeg &&
        c->pitch_mdeg == m->pose.pitch_mdeg && c->yaw_mdeg == m->pose.yaw_mdeg) {
        return m->ik_cache.rot_q30;
    }
    xgo_body_rotation(&m->pose, scratch);
    return scratch;
}

/* The feet in the machine frame as the joints put them now (FK, with this
 * tick's body pose), and which are down: those within 1 mm of the lowest. */
static uint8_t measured_feet(const xgo_motion_t *m, xgo_vec3_t machine[XGO_LEG_COUNT])
{
    xgo_vec3_t body[XGO_LEG_COUNT];
    int32_t low = INT32_MAX;
    uint8_t contact = 0;
    unsigned leg;
    xgo_q30_t rot[XGO_ROT_COUNT];
    feet_of_joints(m, body);
    xgo_body_to_machine_rotated(&m->pose, pose_rotation(m, rot), body, machine);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        low = machine[leg].z < low ? machine[leg].z : low;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (machine[leg].z <= low + 1000) {
            contact |= (uint8_t)(1u << leg);
        }
    }
    return contact;
}

/* A transition starts from where the robot is: the feet the IK was given
 * last tick when the joints are there (walking, an action), else the feet
 * the joints put somewhere (leg, servo, debug modes; servos still catching
 * up). The lowest foot then stands on the ground: the body is taken as that
 * much lower. The gait waits at the stance until the feet are home. */
XGO_OWN_FRAME void xgo_motion_begin_settle(xgo_motion_t *m, uint8_t was_mode)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    uint8_t contact = m->contact;
    if ((was_mode == XGO_MODE_WHOLE_UNIT || was_mode == XGO_MODE_ACTION) && m->ik_cache.valid &&
        m->ik_cache.projected == 0 &&
        joints_as_solved(m)) {
        memcpy(feet, m->ik_cache.feet, sizeof feet);
    } else {
        int32_t low = INT32_MAX;
        unsigned leg;
        contact = measured_feet(m, feet);
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            low = feet[leg].z < low ? feet[leg].z : low;
        }
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            feet[leg].z -= low;
        }
        xgo_follow_init(&m->follow, &m->pose);
        xgo_follow_shift_z(&m->follow, -low);
    }
    xgo_settle_start(&m->settle, feet, contact, m->stance_um);
    if (was_mode == XGO_MODE_WHOLE_UNIT && !xgo_gait_is_standing(&m->gait)) {
        const int32_t v[3] = {m->gait.vx_um_s, m->gait.vy_um_s, m->gait.vyaw_mdeg_s};
        xgo_settle_coast(&m->settle, v); /* no dead stop: it slows down over its feet */
    }
    reset_gait(m);
}

/* 1 while the robot is not yet home: feet at the stance, body at rest in
 * the pose `home`. */
static int away_from(const xgo_motion_t *m, const xgo_body_pose_t *home)
{
    return xgo_settle_active(&m->settle) || !xgo_follow_at(&m->follow, home);
}

/* One tick of the way home (feet to the stance, body toward `home`). */
static void transition_step(xgo_motion_t *m, const xgo_body_pose_t *home, xgo_vec3_t feet[XGO_LEG_COUNT],
                            xgo_body_pose_t *pose)
{
    (void)xgo_settle_tick(&m->settle, m->stance_um, feet, &m->contact);
    xgo_follow_tick(&m->follow, home, pose);
}

/* ------------------------------------------------------------ whole unit */

/* The gait's contacts (each 0 or 1) as the bits of m->contact. */
XGO_ALWAYS_INLINE uint8_t gait_contact_bits(const xgo_gait_t *g)
{
#if XGO_CORE_DIV64_NATIVE && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    /* One load and one multiply on a 64-bit host: the four bytes as a word
     * w = c0 + c1 2^8 + c2 2^16 + c3 2^24, and w * (2^21 + 2^14 + 2^7 + 1)
     * has ci at bit 21 + i; the other products land on bits 0, 7, 8, 14..16
     * and 29..31 (or beyond 32), no two on one bit: no carries. */
    uint32_t w;
    memcpy(&w, g->contact, sizeof w);
    return (uint8_t)((w * 0x00204081u) >> 21 & 0x0Fu);
#else
    return (uint8_t)(g->contact[0] | (g->contact[1] << 1) | (g->contact[2] << 2) | (g->contact[3] << 3));
#endif
}

typedef char xgo_motion_contact_check_[sizeof((xgo_gait_t *)0)->contact == 4 ? 1 : -1];

/* A gait tick under cmd and its contacts (its feet in m->gait.foot_um);
 * returns its yaw rate. */
static int32_t gait_step(xgo_motion_t *m, const xgo_gait_command_t *cmd)
{
    xgo_gait_tick(&m->gait, cmd);
    m->contact = gait_contact_bits(&m->gait);
    return m->gait.vyaw_mdeg_s;
}

/* The same with the gait's feet copied to feet. */
static int32_t gait_feet(xgo_motion_t *m, const xgo_gait_command_t *cmd, xgo_vec3_t feet[XGO_LEG_COUNT])
{
    const int32_t yaw_rate = gait_step(m, cmd);
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[leg] = m->gait.foot_um[leg];
    }
    return yaw_rate;
}

/* A running action: its keyframes, or while it holds them, the way to the
 * stance (lead-in); the player counts the ticks either way. An action that
 * walks (creep, circle) takes its feet from the gait, under its command. */
static void action_targets(xgo_motion_t *m, xgo_body_pose_t *pose, xgo_vec3_t feet[XGO_LEG_COUNT],
                           int32_t *yaw_rate_mdeg_s)
{
    xgo_action_walk_t w;
    if (xgo_action_held(&m->actions) && !away_from(m, &m->stand)) {
        xgo_action_go(&m->actions);
    }
    if (xgo_action_held(&m->actions)) {
        xgo_pose_t unused;
        if (!xgo_action_tick(&m->actions, &unused)) {
            m->action_id = 0; /* its time ran out on the way: whole unit goes on */
        }
        transition_step(m, &m->stand, feet, pose);
        m->pose_target = m->stand;
        return;
    }
    action_pose(m, pose, feet);
    if (xgo_action_walk(&m->actions, &w)) {
        xgo_gait_command_t cmd;
        memset(&cmd, 0, sizeof cmd);
        cmd.vx_um_s = w.vx_um_s;
        cmd.vy_um_s = w.vy_um_s;
        cmd.vyaw_mdeg_s = w.vyaw_mdeg_s;
        cmd.step_height_um = w.step_height_um;
        cmd.type = w.type;
        cmd.pace = w.pace;
        *yaw_rate_mdeg_s = gait_feet(m, &cmd, feet);
    }
    m->pose_target = *pose;
    xgo_follow_take(&m->follow, pose);
}

/* The command the gait follows: the registers', or a turn to a heading. */
WALK_FRAME void gait_command(xgo_motion_t *m, const xgo_regs_t *r, xgo_gait_command_t *cmd)
{
    xgo_motion_gait_command(m, r, cmd);
    if (xgo_heading_active(&m->heading)) {
        /* turning in place: the heading controller owns the yaw rate */
        cmd->vx_um_s = cmd->vy_um_s = cmd->mark_time_um = 0;
        cmd->vyaw_mdeg_s = xgo_heading_tick(&m->heading, m->imu.yaw_mdeg, m->gait.vyaw_mdeg_s);
    }
}

/* key (vx, vy, vyaw, mark time, kind, margin) is that of cmd with the yaw
 * rate vyaw and kind (type, pace), the margin aside. */
static int same_stroke_command(const int32_t key[6], const xgo_gait_command_t *cmd, int32_t vyaw, int32_t kind)
{
#if XGO_CORE_DIV64_NATIVE
    /* the key's first four words are the command's (checked below) when the
     * yaw rate is the command's: one 16-byte compare on a 64-bit host */
    if (vyaw == cmd->vyaw_mdeg_s) {
        return memcmp(key, cmd, 4 * sizeof *key) == 0 && key[4] == kind;
    }
#endif
    return key[0] == cmd->vx_um_s && key[1] == cmd->vy_um_s && key[2] == vyaw &&
           key[3] == cmd->mark_time_um && key[4] == kind;
}

typedef char xgo_motion_stroke_key_check_[offsetof(xgo_gait_command_t, vx_um_s) == 0 &&
                                                  offsetof(xgo_gait_command_t, vy_um_s) == 4 &&
                                                  offsetof(xgo_gait_command_t, vyaw_mdeg_s) == 8 &&
                                                  offsetof(xgo_gait_command_t, mark_time_um) == 12
                                              ? 1
                                              : -1];

/* A new key and its stroke (a command or margin changed: rare). */
HOST_APART void new_stroke(xgo_motion_t *m, const xgo_gait_command_t *cmd, int32_t vyaw, int32_t kind)
{
    int32_t *key = m->stroke_key;
    xgo_gait_command_t c = *cmd;
    c.vyaw_mdeg_s = vyaw;
    key[0] = c.vx_um_s;
    key[1] = c.vy_um_s;
    key[2] = vyaw;
    key[3] = c.mark_time_um;
    key[4] = kind;
    key[5] = m->stroke_margin_um;
    m->stroke_walks = (uint8_t)xgo_motion_stroke(m, &c, m->stroke);
}

/* The stroke the reach checks walk (reach.h): that of the command (a turn
 * to a heading: at its highest rate), recomputed when the command or the
 * learnt margin changes; it applies while walking and while still stopping
 * (the last one kept). */
WALK_FRAME void update_stroke(xgo_motion_t *m, const xgo_gait_command_t *cmd)
{
    const int32_t vyaw = xgo_heading_active(&m->heading) ? XGO_HEADING_RATE_MDEG_S : cmd->vyaw_mdeg_s;
    const int32_t kind = cmd->type | (cmd->pace << 8);
    const int same_command = same_stroke_command(m->stroke_key, cmd, vyaw, kind);
    if (!same_command) {
        m->stroke_margin_um = 0; /* a new command: nothing learnt yet */
    }
    /* compared in place, the command copied only when it changed (every
     * tick otherwise) */
    if (!same_command || m->stroke_key[5] != m->stroke_margin_um) {
        new_stroke(m, cmd, vyaw, kind);
    }
    if (m->stroke_walks) {
        m->stroke_on = 1;
    } else if (xgo_gait_is_standing(&m->gait) && !xgo_settle_active(&m->settle)) {
        m->stroke_on = 0;
    }
}

/* The pose the registers ask for, turned into one the legs hold with all
 * four feet down (reach.h), for the feet standing or running their stroke.
 * Counts the ticks where the two differ. */
WALK_FRAME void reachable_target(xgo_motion_t *m, const xgo_regs_t *r, const xgo_gait_command_t *cmd)
{
    xgo_body_pose_t asked, base, spread;
    xgo_motion_asked_pose(m, r, &asked, &base, &spread);
    update_stroke(m, cmd);
    if (xgo_reach_tick(&m->reach, m->profile, &asked, &base, &spread, m->stance_um,
                       m->stroke_on ? m->stroke : NULL, &m->pose_target)) {
        m->clamped_pose_ticks++;
    }
}

/* The pose of this tick and the feet under it made joint targets; a planted
 * foot that ran out of reach where the stroke checked did not go makes the
 * reach check a longer one (a new search from the next tick). Solved by
 * solve_joints (walking_copy) or solve_joints_apart. */
XGO_ALWAYS_INLINE void solve_tick_with(xgo_motion_t *m, const xgo_body_pose_t *pose,
                                       const xgo_vec3_t feet[XGO_LEG_COUNT], int walking_copy)
{
    m->pose = *pose;
    if (walking_copy) {
        solve_joints(m, pose, feet);
    } else {
        solve_joints_apart(m, pose, feet);
    }
    if ((m->ik_cache.projected & m->contact) != 0 && m->stroke_on && m->action_id == 0 &&
        !m->reach.searching && m->stroke_margin_um < STROKE_MARGIN_MAX_UM) {
        m->stroke_margin_um += STROKE_MARGIN_STEP_UM;
    }
}

HOST_INLINE void solve_tick(xgo_motion_t *m, const xgo_body_pose_t *pose, const xgo_vec3_t feet[XGO_LEG_COUNT])
{
    solve_tick_with(m, pose, feet, 1);
}

#if XGO_CORE_DIV64_NATIVE /* action_tick's: with solve_joints_apart */
#define solve_tick_apart(m, pose, feet) solve_tick_with((m), (pose), (feet), 0)
#else
#define solve_tick_apart solve_tick
#endif

/* A running action's tick (action_targets), solved. Out of line, as
 * walk_tick. */
static XGO_OWN_FRAME void action_tick(xgo_motion_t *m, int32_t *yaw_rate_mdeg_s)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t pose;
    action_targets(m, &pose, feet, yaw_rate_mdeg_s);
    solve_tick_apart(m, &pose, feet);
}

/* The feet of the gait (or the settle's while the feet go home) under cmd,
 * the body following the reachable target, solved; returns 1 while
 * walking or moving. Out of line on an MCU: its feet and pose are not on
 * the stack while reachable_target searches. */
WALK_FRAME int walk_tick(xgo_motion_t *m, xgo_gait_command_t *cmd, int32_t *yaw_rate_mdeg_s)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    const xgo_vec3_t *at = feet; /* the settle's, or the gait's in place (no copy) */
    xgo_body_pose_t pose;
    int walking = 1;
    if (xgo_settle_active(&m->settle)) {
        (void)xgo_settle_tick(&m->settle, m->stance_um, feet, &m->contact);
    } else {
        if (m->reach.searching && xgo_gait_is_standing(&m->gait)) {
            memset(cmd, 0, sizeof *cmd); /* the first step waits for a pose the stroke holds */
        }
        *yaw_rate_mdeg_s = gait_step(m, cmd);
        at = m->gait.foot_um;
        walking = !xgo_gait_is_standing(&m->gait);
    }
    xgo_follow_tick(&m->follow, &m->pose_target, &pose);
    walking = walking || !xgo_follow_at(&m->follow, &m->pose_target);
    solve_tick(m, &pose, at);
    return walking;
}

/* Whole unit: an action's targets, or the gait's under the reachable
 * target; the joint targets in m->ik_cache.q_mdeg. */
HOST_INLINE int whole_unit_targets(xgo_motion_t *m, const xgo_regs_t *r, int32_t *yaw_rate_mdeg_s)
{
    xgo_gait_command_t cmd;
    *yaw_rate_mdeg_s = 0;
    if (xgo_settle_active(&m->settle)) { /* a body still coasting turns on the IMU */
        int32_t v[3];
        xgo_settle_velocity(&m->settle, v);
        *yaw_rate_mdeg_s = v[2];
    }
    if (m->action_id != 0) {
        action_tick(m, yaw_rate_mdeg_s);
        return 1;
    }
    gait_command(m, r, &cmd);
    reachable_target(m, r, &cmd);
    return walk_tick(m, &cmd, yaw_rate_mdeg_s);
}

/* ------------------------------------------------------------ other modes */

/* Leg and servo modes start from home: while the way there lasts, its
 * targets (returns 1, contacts known; the targets in m->ik_cache.q_mdeg). */
static int going_home(xgo_motion_t *m)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t pose;
    if (!away_from(m, &m->stand)) {
        return 0;
    }
    transition_step(m, &m->stand, feet, &pose);
    m->pose = pose;
    m->pose_target = m->stand;
    solve_joints_apart(m, &pose, feet);
    return 1;
}

/* Each foot moves toward its registers' point at up to LEG_SPEED per axis:
 * a register written in one jump moves the foot at a speed the joints
 * follow, not in one step. */
#define LEG_STEP_UM ((int32_t)(200000 / XGO_TICK_HZ)) /* 200 mm/s */

static int32_t toward(int32_t now, int32_t goal, int32_t step)
{
    return goal > now + step ? now + step : (goal < now - step ? now - step : goal);
}

/* Leg mode once home: each foot a step toward its registers', its joints
 * the servos' targets. Out of line: its joint array is not on the stack
 * while the other modes go deep. */
static XGO_OWN_FRAME void leg_tick(xgo_motion_t *m, const xgo_regs_t *r)
{
    const xgo_profile_t *p = m->profile;
    int32_t q[XGO_SERVO_COUNT];
    unsigned leg;
    if (!m->leg_ready) { /* home: the feet start from the stance */
        xgo_body_ik(p, &m->stand, m->stance_um, m->leg_feet_um);
        m->leg_ready = 1;
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_vec3_t *foot = &m->leg_feet_um[leg];
        foot->x = toward(foot->x, xgo_signed_byte_to_value(xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_X)),
                                                          p->foot_um[XGO_AXIS_X].hi), LEG_STEP_UM);
        foot->y = toward(foot->y, xgo_signed_byte_to_value(xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Y)),
                                                          p->foot_um[XGO_AXIS_Y].hi), LEG_STEP_UM);
        foot->z = toward(foot->z, xgo_byte_to_foot(p, XGO_AXIS_Z, xgo_regs_get(r, (uint8_t)XGO_FOOT_REG(leg, XGO_AXIS_Z))),
                         LEG_STEP_UM);
        xgo_leg_ik(p, (xgo_leg_t)leg, foot, &q[XGO_JOINT_COUNT * leg]);
    }
    m->pose = m->stand;
    xgo_servos_follow(&m->servos, q, XGO_JOINT_STEP_MAX_MDEG);
}

/* Leg mode: the way home (returns 1, *q its targets), then the registers'
 * feet (returns 0, the servos already sent there, *q NULL). */
static int leg_targets(xgo_motion_t *m, const xgo_regs_t *r, const int32_t **q)
{
    if (going_home(m)) {
        *q = m->ik_cache.q_mdeg;
        return 1;
    }
    leg_tick(m, r);
    *q = NULL;
    return 0;
}

static int32_t servo_mode_step(const xgo_regs_t *r);

/* Servo mode: once home, joints the host has not written hold where they
 * are; each joint goes to its command at the speed of 0x5C. */
static int servo_targets(xgo_motion_t *m, const xgo_regs_t *r, const int32_t **q, int32_t *step)
{
    unsigned i;
    if (going_home(m)) {
        *q = m->ik_cache.q_mdeg;
        return 1;
    }
    if (!m->servo_ready) {
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            if (((m->servo_written >> i) & 1u) == 0) {
                m->servo_cmd_mdeg[i] = m->servos.angle_mdeg[i];
            }
        }
        m->servo_ready = 1;
    }
    *q = m->servo_cmd_mdeg;
    *step = servo_mode_step(r);
    m->pose = m->stand;
    return 0;
}

static int32_t servo_mode_step(const xgo_regs_t *r)
{
    const int32_t per_s = xgo_servo_speed_byte_to_mdeg_s(xgo_regs_servo_speed(r));
    const int32_t step = per_s / (int32_t)XGO_TICK_HZ;
    return step < 1 ? 1 : step;
}

/* ------------------------------------------------------------ measurement */

/* Where the feet are (FK of the joints as they are, not as commanded) and,
 * from the planted ones, how far the body moved on the floor. Outside the
 * gait and the actions nobody says which feet are down: those within 1 mm
 * of the lowest are. */
/* The feet of the legs in mask in the machine frame, where the joints put
 * them now with this tick's pose (FK); the others are not measured. */
static void measure_machine(const xgo_motion_t *m, unsigned mask, xgo_vec3_t machine[XGO_LEG_COUNT])
{
    xgo_vec3_t body[XGO_LEG_COUNT];
    xgo_q30_t rot[XGO_ROT_COUNT];
#if XGO_WITH_ODOMETRY
    feet_of_angles(m, m->servos.angle_mdeg, mask, body);
#else /* every foot (the contacts are not known) */
    mask = 0x0Fu;
    feet_of_joints(m, body);
#endif
    /* only the measured legs turned (a swing's start: two of four) */
    xgo_body_to_machine_legs(&m->pose, pose_rotation(m, rot), mask, body, machine);
}

#if XGO_WITH_ODOMETRY
/* The feet the odometry holds unmeasured, measured now from the joints and
 * the pose they had then (rare: the odometry's test that nothing moved
 * needs them). Out of line: its arrays only on this path's stack. */
static XGO_OWN_FRAME void measure_later_feet(xgo_motion_t *m)
{
    const uint8_t later = xgo_odometry_unmeasured(&m->odom);
    xgo_vec3_t body[XGO_LEG_COUNT], machine[XGO_LEG_COUNT];
    xgo_q30_t rot[XGO_ROT_COUNT];
    unsigned leg;
    if (later == 0) {
        return;
    }
    feet_of_angles(m, m->fk_later.q_mdeg, later, body);
    xgo_body_rotation(&m->fk_later.pose, rot);
    xgo_body_to_machine_legs(&m->fk_later.pose, rot, later, body, machine);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        if (((later >> leg) & 1u) != 0) {
            xgo_odometry_set_prev(&m->odom, leg, &machine[leg]);
        }
    }
}
#endif

/* On a 64-bit host with the odometry measure_feet tests for the usual
 * walking tick first and leaves the rest to this, out of line, so that
 * the usual case makes no frame for its arrays (below). Elsewhere
 * measure_feet is this: on an MCU the second call and the tests again
 * would cost a swing's start more (Cortex-M0: the p99 tick 16
 * instructions) than the usual tick saves. */
#if XGO_WITH_ODOMETRY && XGO_CORE_DIV64_NATIVE
#define MEASURE_FEET_SPLIT 1
static XGO_OWN_FRAME void measure_feet_fk(xgo_motion_t *m, int contact_known, int at_solved)
#else
#define MEASURE_FEET_SPLIT 0
static XGO_OWN_FRAME void measure_feet(xgo_motion_t *m, int contact_known, int at_solved)
#endif
{
    xgo_vec3_t machine_fk[XGO_LEG_COUNT];
    const xgo_vec3_t *machine = machine_fk;
    unsigned measured = 0x0Fu; /* bit leg: machine[leg] measured */
    int32_t low = INT32_MAX;
    unsigned leg;
    /* The joints where this tick's IK put them and every foot reachable:
     * the feet are where they were asked to be (FK of these angles agrees
     * within the IK's 2.4 um), so spare the FK. */
    if (!XGO_WITH_ODOMETRY && contact_known) {
        /* The contacts are known and no odometry takes the feet: only an
         * observer might (xgo_motion_feet_body), so the joints are compared
         * with the IK's when one asks, not every tick (the servos and the
         * IK cache change in the tick alone: the same answer). */
        m->feet_as_solved = (uint8_t)(m->ik_cache.valid && m->ik_cache.projected == 0);
        return;
    }
    m->feet_as_solved = (uint8_t)(contact_known && m->ik_cache.valid && m->ik_cache.projected == 0 &&
                                  (at_solved < 0 ? joints_as_solved(m) : at_solved));
    if (m->feet_as_solved) {
        machine = m->ik_cache.feet;
    } else {
        /* A joint lagging its target (a swing's start: about one tick in
         * twelve of a trot) is a foot in the air: with the contacts known
         * the planted feet are measured, the others only if the odometry
         * needs them (odometry.h; not while walking), a leg's FK less each. */
#if XGO_WITH_ODOMETRY
        if (contact_known) {
            measured = m->contact & 0x0Fu;
        }
#endif
        measure_machine(m, measured, machine_fk);
    }
#if XGO_WITH_ODOMETRY
    if ((measured != 0x0Fu || xgo_odometry_unmeasured(&m->odom) != 0) &&
        xgo_odometry_needs_all(&m->odom, machine, m->contact, (uint8_t)measured)) {
        if (measured != 0x0Fu) {
            measure_machine(m, 0x0Fu, machine_fk);
            measured = 0x0Fu;
        }
        measure_later_feet(m);
    }
    if (measured != 0x0Fu) { /* kept for measure_later_feet */
        for (leg = 0; leg < XGO_SERVO_COUNT; leg++) {
            m->fk_later.q_mdeg[leg] = m->servos.angle_mdeg[leg];
        }
        m->fk_later.pose = m->pose;
    }
#endif
    if (!contact_known) { /* the lowest foot only then (not while walking) */
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            low = machine[leg].z < low ? machine[leg].z : low;
        }
        m->contact = 0;
        for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
            if (machine[leg].z <= low + 1000) {
                m->contact |= (uint8_t)(1u << leg);
            }
        }
    }
    xgo_odometry_update_measured(&m->odom, machine, m->contact, (uint8_t)measured);
}

#if MEASURE_FEET_SPLIT
static XGO_OWN_FRAME void measure_feet(xgo_motion_t *m, int contact_known, int at_solved)
{
    /* Walking (about eleven ticks in twelve of a trot): the joints where
     * the IK put them, the contacts known and no foot the odometry holds
     * unmeasured; measure_feet_fk would hand the IK's feet to the
     * odometry as they are, as this does, in a tail call with no frame
     * (x86-64: 25 instructions a tick less). */
    if (contact_known && at_solved > 0 && m->ik_cache.valid && m->ik_cache.projected == 0 &&
        xgo_odometry_unmeasured(&m->odom) == 0) {
        m->feet_as_solved = 1;
        xgo_odometry_update_measured(&m->odom, m->ik_cache.feet, m->contact, 0x0Fu);
        return;
    }
    measure_feet_fk(m, contact_known, at_solved);
}
#endif

/* Body-frame feet for observers, worked out when asked (not every tick: the
 * control loop needs only the machine frame's), from what measure_feet
 * used: the IK's feet or the FK of the joints. */
void xgo_motion_feet_body(const xgo_motion_t *m, xgo_vec3_t out[XGO_LEG_COUNT])
{
    xgo_vec3_t feet_leg[XGO_LEG_COUNT];
    unsigned leg;
    /* without odometry measure_feet leaves the joints' half of the test to
     * this (an observer's) call */
    if (!m->feet_as_solved || (!XGO_WITH_ODOMETRY && !joints_as_solved(m))) {
        feet_of_joints(m, out);
        return;
    }
    /* The leg-frame feet solve_joints used: the same inputs, the same result. */
    xgo_body_ik_rotated(m->profile, &m->ik_cache.pose, m->ik_cache.rot_q30, m->ik_cache.feet,
                        feet_leg);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_leg_to_body(m->profile, (xgo_leg_t)leg, &feet_leg[leg], &out[leg]);
    }
}

/* ------------------------------------------------------------ publish */

/* Not the joints 0x50..0x5B nor the IMU's registers 0x62..0x68: a read
 * forms them from the servos' angles and the IMU's outputs (board.c,
 * read_registers), as nobody reads them most ticks. */
void xgo_motion_publish(const xgo_motion_t *m, xgo_regs_t *r)
{
    /* constant addresses: stores, not five calls every tick */
    xgo_regs_put(r, XGO_REG_MODE, m->mode);
    if (!xgo_battery_is_percent(&m->battery, xgo_regs_at(r, XGO_REG_BATTERY))) {
        xgo_regs_put(r, XGO_REG_BATTERY, xgo_battery_percent(&m->battery));
    }
    xgo_regs_put(r, XGO_REG_ACTION, m->action_id);
    xgo_regs_put(r, XGO_REG_PERFORM, m->perform);
    xgo_regs_put(r, XGO_REG_TURN_TO, xgo_heading_done(&m->heading));
    xgo_arm_publish(&m->arm, r);
}

/* The accelerometer and gyroscope see the body where the odometry and the
 * body pose put it, with the attitude the IMU reports. */
static XGO_OWN_FRAME void inertial_tick(xgo_motion_t *m)
{
    const int32_t att[3] = {m->imu.roll_mdeg, m->imu.pitch_mdeg, m->imu.yaw_mdeg};
#if XGO_WITH_INERTIAL
    /* Without a body yaw the IK's rotation holds the roll's and the pitch's
     * sin and cos as they are: R = Ry(pitch) Rx(roll) has cos p, -sin p at
     * (0, 0), (2, 0) and cos r, -sin r at (1, 1), (1, 2) (xgo_body_rotation;
     * test_inertial checks it). The IMU's angles are the pose's (no shove,
     * no ground tilt), so a body pitching or rolling (a periodic motion)
     * spares the IMU model's sincos. */
    const xgo_body_pose_t *c = &m->ik_cache.pose;
    if (m->ik_cache.valid && c->yaw_mdeg == 0) {
        const xgo_q30_t *rot = m->ik_cache.rot_q30;
        xgo_inertial_known_trig(&m->inertial, 0, att[0], c->roll_mdeg, -rot[XGO_ROT(1, 2)],
                                rot[XGO_ROT(1, 1)]);
        xgo_inertial_known_trig(&m->inertial, 1, att[1], c->pitch_mdeg, -rot[XGO_ROT(2, 0)],
                                rot[XGO_ROT(0, 0)]);
    }
#endif
    xgo_inertial_tick_body(&m->inertial, &m->odom, &m->pose, att);
}

/* Entering a mode from another: leg and servo modes start from home, and
 * whole unit goes on from wherever the robot was left (an action stopped
 * midway, leg or servo mode) by bringing the feet home first; an action
 * brings them home itself (start_action). Debug and calibration hold. */
static void enter_mode(xgo_motion_t *m, uint8_t was)
{
    switch (m->mode) {
    case XGO_MODE_LEG:
        m->leg_ready = 0;
        xgo_motion_begin_settle(m, was);
        break;
    case XGO_MODE_SERVO:
        m->servo_ready = 0;
        xgo_motion_begin_settle(m, was);
        break;
    case XGO_MODE_WHOLE_UNIT:
        xgo_motion_begin_settle(m, was);
        break;
    default:
        break;
    }
}

/* After the servos moved: the feet measured, the sensors, the battery, the
 * registers published. Out of line: its locals are not on the stack while
 * the tick goes deep (the reach search). */
static XGO_OWN_FRAME void sense(xgo_motion_t *m, xgo_regs_t *r, int contact_known, int at_solved,
                                int32_t yaw_rate, int busy, int pose_clamped)
{
    measure_feet(m, contact_known, at_solved);
    xgo_imu_tick(&m->imu, m->pose.roll_mdeg, m->pose.pitch_mdeg, m->pose.yaw_mdeg, yaw_rate);
    inertial_tick(m);
    xgo_arm_tick(&m->arm, r, &m->pose, &m->stand);
    if (pose_clamped || m->arm.out_of_reach) {
        m->reach_clamped_ticks++; /* the board holds the nearest pose it can, not the one asked */
    }
    xgo_battery_tick(&m->battery, busy);
    if (m->mode == XGO_MODE_ACTION && m->action_id == 0) {
        m->mode = m->group_mode;
    }
    xgo_motion_publish(m, r);
}

void xgo_motion_tick(xgo_motion_t *m, xgo_regs_t *r)
{
    const uint32_t clamped_before = m->clamped_pose_ticks;
    const int32_t *q = m->ik_cache.q_mdeg; /* the servos' targets */
    int32_t step = XGO_JOINT_STEP_MAX_MDEG;
    int32_t yaw_rate = 0;
    int busy = 0;
    int at_solved = -1; /* the joints are at the IK's angles: 1, 0, or -1 to compare */

    const uint8_t was = m->mode;
    int contact_known = 1;

    xgo_motion_take_writes(m, r);
    m->mode = m->action_id != 0 ? XGO_MODE_ACTION
              : m->calibration  ? XGO_MODE_CALIBRATION
                                : m->group_mode;
    if (m->mode != was) {
        enter_mode(m, was);
    }
    switch (m->mode) {
    case XGO_MODE_WHOLE_UNIT:
    case XGO_MODE_ACTION:
        busy = whole_unit_targets(m, r, &yaw_rate);
        break;
    case XGO_MODE_LEG:
        contact_known = leg_targets(m, r, &q);
        break;
    case XGO_MODE_SERVO:
        contact_known = servo_targets(m, r, &q, &step);
        break;
    default: /* debug, calibration: hold (each servo's target is its angle) */
        q = m->servos.angle_mdeg;
        contact_known = 0;
        break;
    }
    if (q != NULL) {
        const int at = xgo_servos_follow(&m->servos, q, step);
        if (q == m->ik_cache.q_mdeg) {
            at_solved = at; /* the joints are where the IK put them: no comparing them */
        }
    }
    sense(m, r, contact_known, at_solved, yaw_rate, busy, m->clamped_pose_ticks != clamped_before);
}
