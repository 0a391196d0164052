/*
 * view_state.c - the state object (see view_state.h; every field in
 * docs/view.md). Units on the wire: degrees with 2 decimals, millimetres
 * (and mm/s) with 1 decimal - the board's millidegrees and micrometres
 * rounded, so the page never has to know the core's fixed-point units.
 */
#include "view_state.h"

#include <string.h>

#include "xgo/emulator.h"

/* Names of the mode register's values (xgo_mode_t). */
const char *xgo_host_view_mode_name(uint8_t mode)
{
    static const char *const k_names[] = {"whole unit", "leg", "servo",
                                          "debug",      "action", "calibration"};
    return mode < sizeof k_names / sizeof k_names[0] ? k_names[mode] : "unknown";
}

static void xgo_host_view_deg(xgo_host_json_t *w, const char *key, int32_t mdeg)
{
    xgo_host_json_key(w, key);
    xgo_host_json_fixed(w, mdeg, 3, 2);
}

static void xgo_host_view_mm(xgo_host_json_t *w, const char *key, int32_t um)
{
    xgo_host_json_key(w, key);
    xgo_host_json_fixed(w, um, 3, 1);
}

void xgo_host_view_joint_limits(xgo_host_json_t *w, const xgo_board_t *b, unsigned decimals)
{
    unsigned i;
    xgo_host_json_key(w, "joint_limits_deg");
    xgo_host_json_array_begin(w);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        int32_t lo, hi;
        xgo_board_joint_limits_mdeg(b, i, &lo, &hi);
        xgo_host_json_array_begin(w);
        xgo_host_json_fixed(w, lo, 3, decimals);
        xgo_host_json_fixed(w, hi, 3, decimals);
        xgo_host_json_array_end(w);
    }
    xgo_host_json_array_end(w);
}

static void xgo_host_view_joints(xgo_host_json_t *w, const xgo_board_t *b)
{
    int32_t joints[XGO_SERVO_COUNT];
    unsigned i;
    xgo_board_joints_mdeg(b, joints);
    xgo_host_json_key(w, "joints_deg");
    xgo_host_json_array_begin(w);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        xgo_host_json_fixed(w, joints[i], 3, 2);
    }
    xgo_host_json_array_end(w);
    xgo_host_view_joint_limits(w, b, 2);
}

static void xgo_host_view_feet(xgo_host_json_t *w, const xgo_board_t *b)
{
    xgo_vec3_t feet[XGO_LEG_COUNT];
    uint8_t contacts = xgo_board_contacts(b);
    unsigned leg;
    xgo_board_feet_um(b, feet);
    xgo_host_json_key(w, "feet_mm");
    xgo_host_json_array_begin(w);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_host_json_array_begin(w);
        xgo_host_json_fixed(w, feet[leg].x, 3, 1);
        xgo_host_json_fixed(w, feet[leg].y, 3, 1);
        xgo_host_json_fixed(w, feet[leg].z, 3, 1);
        xgo_host_json_array_end(w);
    }
    xgo_host_json_array_end(w);
    xgo_host_json_key(w, "contacts");
    xgo_host_json_array_begin(w);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        xgo_host_json_uint(w, (contacts >> leg) & 1u);
    }
    xgo_host_json_array_end(w);
}

static void xgo_host_view_poses(xgo_host_json_t *w, const xgo_board_t *b)
{
    xgo_body_pose_t body;
    xgo_world_pose_t world;
    int32_t imu[3];
    xgo_board_body_pose(b, &body);
    xgo_board_world_pose(b, &world);
    xgo_board_imu_mdeg(b, imu);
    xgo_host_json_key(w, "body");
    xgo_host_json_object_begin(w);
    xgo_host_view_mm(w, "x_mm", body.x_um);
    xgo_host_view_mm(w, "y_mm", body.y_um);
    xgo_host_view_mm(w, "z_mm", body.z_um);
    xgo_host_view_deg(w, "roll_deg", body.roll_mdeg);
    xgo_host_view_deg(w, "pitch_deg", body.pitch_mdeg);
    xgo_host_view_deg(w, "yaw_deg", body.yaw_mdeg);
    xgo_host_json_object_end(w);
    xgo_host_json_key(w, "world");
    xgo_host_json_object_begin(w);
    xgo_host_view_mm(w, "x_mm", world.x_um);
    xgo_host_view_mm(w, "y_mm", world.y_um);
    xgo_host_view_deg(w, "yaw_deg", world.yaw_mdeg);
    xgo_host_json_object_end(w);
    xgo_host_json_key(w, "imu");
    xgo_host_json_object_begin(w);
    xgo_host_view_deg(w, "roll_deg", imu[0]);
    xgo_host_view_deg(w, "pitch_deg", imu[1]);
    xgo_host_view_deg(w, "yaw_deg", imu[2]);
    xgo_host_json_object_end(w);
}

/* {"vx_mm_s":..,"vy_mm_s":..,"vyaw_deg_s":..} from um/s, um/s, mdeg/s. */
static void xgo_host_view_velocity(xgo_host_json_t *w, const char *key, const int32_t v[3])
{
    xgo_host_json_key(w, key);
    xgo_host_json_object_begin(w);
    xgo_host_view_mm(w, "vx_mm_s", v[0]);
    xgo_host_view_mm(w, "vy_mm_s", v[1]);
    xgo_host_view_deg(w, "vyaw_deg_s", v[2]);
    xgo_host_json_object_end(w);
}

static void xgo_host_view_speed_and_inputs(xgo_host_json_t *w, const xgo_board_t *b)
{
    int32_t cmd[3], produced[3];
    int32_t roll, pitch;
    xgo_board_velocity(b, cmd, produced);
    xgo_board_ground_tilt(b, &roll, &pitch);
    xgo_host_json_key(w, "battery_pct");
    xgo_host_json_uint(w, xgo_board_battery_pct(b));
    xgo_host_json_key(w, "speed");
    xgo_host_json_object_begin(w);
    xgo_host_view_velocity(w, "cmd", cmd);
    xgo_host_view_velocity(w, "actual", produced);
    xgo_host_json_object_end(w);
    xgo_host_json_key(w, "inputs");
    xgo_host_json_object_begin(w);
    xgo_host_view_deg(w, "ground_roll_deg", roll);
    xgo_host_view_deg(w, "ground_pitch_deg", pitch);
    xgo_host_json_object_end(w);
}

static void xgo_host_view_counters_and_regs(xgo_host_json_t *w, const xgo_board_t *b)
{
    uint32_t counters[XGO_DIAG_COUNT];
    uint8_t regs[XGO_REG_COUNT];
    unsigned i;
    xgo_board_counters(b, counters);
    xgo_host_json_key(w, "counters");
    xgo_host_json_object_begin(w);
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        xgo_host_json_key(w, xgo_diag_name((xgo_diag_t)i));
        xgo_host_json_uint(w, counters[i]);
    }
    xgo_host_json_object_end(w);
    /* The whole map in the two reads a host needs for it (at most
     * XGO_FRAME_MAX_DATA bytes each), starting at 0x00. */
    (void)xgo_board_read(b, 0x00, XGO_FRAME_MAX_DATA, regs);
    (void)xgo_board_read(b, XGO_FRAME_MAX_DATA, XGO_REG_COUNT - XGO_FRAME_MAX_DATA,
                         regs + XGO_FRAME_MAX_DATA);
    xgo_host_json_key(w, "regs");
    xgo_host_json_hex(w, regs, sizeof regs);
}

static void xgo_host_view_point(xgo_host_json_t *w, const char *key, const xgo_vec3_t *p)
{
    xgo_host_json_key(w, key);
    xgo_host_json_array_begin(w);
    xgo_host_json_fixed(w, p->x, 3, 1);
    xgo_host_json_fixed(w, p->y, 3, 1);
    xgo_host_json_fixed(w, p->z, 3, 1);
    xgo_host_json_array_end(w);
}

/* The Mini2's arm (null on a model without one): servo angles and the
 * shoulder, elbow and claw points in the body frame. */
static void xgo_host_view_arm(xgo_host_json_t *w, const xgo_board_t *b)
{
    xgo_board_arm_t arm;
    unsigned i;
    xgo_host_json_key(w, "arm");
    if (!xgo_board_arm(b, &arm)) {
        xgo_host_json_null(w);
        return;
    }
    xgo_host_json_object_begin(w);
    xgo_host_json_key(w, "joints_deg");
    xgo_host_json_array_begin(w);
    for (i = 0; i < XGO_ARM_JOINT_COUNT; i++) {
        xgo_host_json_fixed(w, arm.joints_mdeg[i], 3, 2);
    }
    xgo_host_json_array_end(w);
    xgo_host_view_point(w, "shoulder_mm", &arm.shoulder_um);
    xgo_host_view_point(w, "elbow_mm", &arm.elbow_um);
    xgo_host_view_point(w, "claw_mm", &arm.claw_um);
    xgo_host_json_key(w, "out_of_reach");
    xgo_host_json_bool(w, arm.out_of_reach);
    xgo_host_json_object_end(w);
}

void xgo_host_view_state_open(xgo_host_json_t *w, const xgo_board_t *b, uint64_t seq,
                              int host_connected, const char *model)
{
    uint8_t action = xgo_board_action(b);
    const char *action_name = action != 0 ? xgo_action_name(action) : "";
    xgo_host_json_object_begin(w);
    xgo_host_json_key(w, "seq");
    xgo_host_json_uint(w, seq);
    xgo_host_json_key(w, "t_ms");
    xgo_host_json_uint(w, xgo_board_time_ms(b));
    xgo_host_json_key(w, "model");
    xgo_host_json_string(w, model);
    xgo_host_json_key(w, "mode");
    xgo_host_json_uint(w, xgo_board_mode(b));
    xgo_host_json_key(w, "mode_name");
    xgo_host_json_string(w, xgo_host_view_mode_name(xgo_board_mode(b)));
    xgo_host_json_key(w, "action");
    xgo_host_json_object_begin(w);
    xgo_host_json_key(w, "id");
    xgo_host_json_uint(w, action);
    xgo_host_json_key(w, "name");
    xgo_host_json_string(w, action_name != NULL ? action_name : "");
    xgo_host_json_object_end(w);
    xgo_host_view_joints(w, b);
    xgo_host_view_feet(w, b);
    xgo_host_view_poses(w, b);
    xgo_host_view_arm(w, b);
    xgo_host_view_speed_and_inputs(w, b);
    xgo_host_json_key(w, "host_connected");
    xgo_host_json_bool(w, host_connected);
    xgo_host_view_counters_and_regs(w, b);
}

/* ------------------------------------------------------------ frames */

uint64_t xgo_host_view_state_first_cursor(const xgo_host_view_frames_t *f)
{
    uint64_t oldest = xgo_host_view_frames_oldest(f);
    uint64_t recent = f->next_seq > XGO_HOST_VIEW_FRAMES_PER_EVENT
                          ? f->next_seq - XGO_HOST_VIEW_FRAMES_PER_EVENT
                          : 0;
    return recent > oldest ? recent : oldest;
}

/* The event's object, rendered once into its cache slot. */
static void xgo_host_view_frame_render(xgo_host_view_frame_t *e)
{
    char text[XGO_HOST_VIEW_FRAME_TEXT];
    xgo_host_json_t w;
    xgo_host_view_frame_text(e, text);
    xgo_host_json_init(&w, e->json, sizeof e->json);
    xgo_host_json_object_begin(&w);
    xgo_host_json_key(&w, "t_ms");
    xgo_host_json_uint(&w, e->t_ms);
    xgo_host_json_key(&w, "kind");
    xgo_host_json_string(&w, xgo_host_view_frame_kind_name(e->kind));
    xgo_host_json_key(&w, "source");
    xgo_host_json_string(&w, xgo_host_view_frame_source_name(e->source));
    xgo_host_json_key(&w, "addr");
    if (e->has_frame) {
        xgo_host_json_uint(&w, e->frame_addr);
    } else {
        xgo_host_json_null(&w); /* a parser drop: no frame, only bytes */
    }
    xgo_host_json_key(&w, "n");
    /* A read request's n is its count; otherwise the bytes it carried. */
    xgo_host_json_uint(&w, !e->has_frame                     ? e->noise_n
                           : e->frame_type == XGO_TYPE_READ ? e->frame_data[0]
                                                            : e->frame_len);
    xgo_host_json_key(&w, "text");
    xgo_host_json_string(&w, text);
    xgo_host_json_object_end(&w);
    if (!xgo_host_json_ok(&w)) {
        /* Cannot happen with our sizes; an empty object keeps the list valid. */
        memcpy(e->json, "{}", 3);
        w.len = 2;
    }
    e->json_len = (uint16_t)w.len;
}

unsigned xgo_host_view_state_render(xgo_host_view_frames_t *f, unsigned budget)
{
    uint64_t seq = xgo_host_view_state_first_cursor(f);
    unsigned done = 0;
    for (; seq < f->next_seq && done < budget; seq++) {
        xgo_host_view_frame_t *e = xgo_host_view_frames_get(f, seq);
        if (e->json_len == 0) {
            xgo_host_view_frame_render(e);
            done++;
        }
    }
    return done;
}

void xgo_host_view_state_close(xgo_host_json_t *w, xgo_host_view_frames_t *f, uint64_t *cursor)
{
    uint64_t oldest = xgo_host_view_frames_oldest(f);
    uint64_t first = *cursor > oldest ? *cursor : oldest;
    uint64_t omitted = first - *cursor;
    uint64_t seq;
    if (f->next_seq - first > XGO_HOST_VIEW_FRAMES_PER_EVENT) {
        omitted += f->next_seq - first - XGO_HOST_VIEW_FRAMES_PER_EVENT;
        first = f->next_seq - XGO_HOST_VIEW_FRAMES_PER_EVENT; /* the newest are kept */
    }
    xgo_host_json_key(w, "frames");
    xgo_host_json_array_begin(w);
    for (seq = first; seq < f->next_seq; seq++) {
        xgo_host_view_frame_t *e = xgo_host_view_frames_get(f, seq);
        if (e->json_len == 0) {
            xgo_host_view_frame_render(e);
        }
        xgo_host_json_value_text(w, e->json, e->json_len);
    }
    xgo_host_json_array_end(w);
    xgo_host_json_key(w, "frames_omitted");
    xgo_host_json_uint(w, omitted);
    xgo_host_json_object_end(w);
    *cursor = f->next_seq;
}
