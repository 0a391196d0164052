/*
 * record.c - the motion log (see record.h). Numbers are written as the view
 * writes them (json_out.h's fixed point: degrees with 2 decimals, mm and
 * mm/s with 1), so a CSV row and a state object of the same tick agree.
 */
#include "record.h"

#include <errno.h>
#include <string.h>

#include "json_out.h"

/* "t_ms,mode,action,j11_deg,...,act_vyaw_deg_s\n" (docs/view.md). */
static void xgo_host_record_header(FILE *f)
{
    static const char *const k_axes[3] = {"x", "y", "z"};
    unsigned leg, joint, axis;
    fputs("t_ms,mode,action", f);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        for (joint = 0; joint < XGO_JOINT_COUNT; joint++) {
            fprintf(f, ",j%u_deg", XGO_SERVO_ID(leg, joint));
        }
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        for (axis = 0; axis < 3; axis++) {
            fprintf(f, ",foot%u_%s_mm", leg + 1, k_axes[axis]);
        }
    }
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        fprintf(f, ",contact%u", leg + 1);
    }
    fputs(",body_x_mm,body_y_mm,body_z_mm,body_roll_deg,body_pitch_deg,body_yaw_deg"
          ",world_x_mm,world_y_mm,world_yaw_deg,imu_roll_deg,imu_pitch_deg,imu_yaw_deg"
          ",battery_pct,cmd_vx_mm_s,cmd_vy_mm_s,cmd_vyaw_deg_s"
          ",act_vx_mm_s,act_vy_mm_s,act_vyaw_deg_s\n",
          f);
}

/* ",12.34": value in thousandths with `decimals` kept. */
static void xgo_host_record_fixed(FILE *f, int32_t thousandths, unsigned decimals)
{
    char text[32];
    xgo_host_json_t w;
    xgo_host_json_init(&w, text, sizeof text);
    xgo_host_json_fixed(&w, thousandths, 3, decimals);
    fputc(',', f);
    fputs(text, f);
}

static void xgo_host_record_list(FILE *f, const int32_t *v, size_t n, unsigned decimals)
{
    size_t i;
    for (i = 0; i < n; i++) {
        xgo_host_record_fixed(f, v[i], decimals);
    }
}

static void xgo_host_record_row(FILE *f, const xgo_board_t *b)
{
    int32_t joints[XGO_SERVO_COUNT], feet[3 * XGO_LEG_COUNT], imu[3], cmd[3], act[3];
    int32_t pose[6], world[3];
    xgo_vec3_t foot[XGO_LEG_COUNT];
    xgo_body_pose_t body;
    xgo_world_pose_t w;
    uint8_t contacts = xgo_board_contacts(b);
    unsigned leg;

    xgo_board_joints_mdeg(b, joints);
    xgo_board_feet_um(b, foot);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        feet[3 * leg] = foot[leg].x;
        feet[3 * leg + 1] = foot[leg].y;
        feet[3 * leg + 2] = foot[leg].z;
    }
    xgo_board_body_pose(b, &body);
    xgo_board_world_pose(b, &w);
    xgo_board_imu_mdeg(b, imu);
    xgo_board_velocity(b, cmd, act);
    pose[0] = body.x_um;
    pose[1] = body.y_um;
    pose[2] = body.z_um;
    pose[3] = body.roll_mdeg;
    pose[4] = body.pitch_mdeg;
    pose[5] = body.yaw_mdeg;
    world[0] = w.x_um;
    world[1] = w.y_um;
    world[2] = w.yaw_mdeg;

    fprintf(f, "%lu,%u,%u", (unsigned long)xgo_board_time_ms(b), (unsigned)xgo_board_mode(b),
            (unsigned)xgo_board_action(b));
    xgo_host_record_list(f, joints, XGO_SERVO_COUNT, 2);
    xgo_host_record_list(f, feet, 3u * XGO_LEG_COUNT, 1);
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        fprintf(f, ",%u", (unsigned)((contacts >> leg) & 1u));
    }
    xgo_host_record_list(f, pose, 3, 1);
    xgo_host_record_list(f, pose + 3, 3, 2);
    xgo_host_record_list(f, world, 2, 1);
    xgo_host_record_list(f, world + 2, 1, 2);
    xgo_host_record_list(f, imu, 3, 2);
    fprintf(f, ",%u", (unsigned)xgo_board_battery_pct(b));
    xgo_host_record_list(f, cmd, 2, 1);
    xgo_host_record_list(f, cmd + 2, 1, 2);
    xgo_host_record_list(f, act, 2, 1);
    xgo_host_record_list(f, act + 2, 1, 2);
    fputc('\n', f);
}

int xgo_host_record_open(xgo_host_record_t *r, const char *path, unsigned hz,
                         const xgo_board_t *board, char *err, size_t err_size)
{
    memset(&r->service, 0, sizeof r->service);
    r->path = path;
    r->board = board;
    r->hz = hz == 0 || hz > XGO_TICK_HZ ? XGO_TICK_HZ : hz;
    r->acc = XGO_TICK_HZ - r->hz; /* the first tick writes a row */
    r->rows = 0;
    r->failed = 0;
    r->file = fopen(path, "w");
    if (r->file == NULL) {
        snprintf(err, err_size, "--record %s: %s", path, strerror(errno));
        return -1;
    }
    setvbuf(r->file, r->buffer, _IOFBF, sizeof r->buffer);
    xgo_host_record_header(r->file);
    r->service.after_tick = xgo_host_record_tick;
    r->service.ctx = r;
    return 0;
}

void xgo_host_record_tick(void *ctx)
{
    xgo_host_record_t *r = ctx;
    if (r->failed) {
        return;
    }
    r->acc += r->hz;
    if (r->acc < XGO_TICK_HZ) {
        return;
    }
    r->acc -= XGO_TICK_HZ;
    xgo_host_record_row(r->file, r->board);
    r->rows++;
    if (ferror(r->file)) {
        /* Disk full or gone: say so once and stop, rather than fail again
         * 500 times a second; the exit status reports it. */
        fprintf(stderr, "xgo-emu: --record %s: write failed (%s); recording stopped\n", r->path,
                strerror(errno));
        r->failed = 1;
    }
}

int xgo_host_record_close(xgo_host_record_t *r, FILE *out)
{
    int failed = r->failed;
    if (r->file == NULL) {
        return 0;
    }
    if (fclose(r->file) != 0 && !failed) {
        fprintf(out, "xgo-emu: --record %s: %s\n", r->path, strerror(errno));
        failed = 1;
    }
    r->file = NULL;
    return failed ? -1 : 0;
}
