/*
 * The board: parser -> register file -> replies, plus the control tick.
 */
#include "xgo/board.h"

#include <string.h>

#include "check.h"
#include "codec.h"
#include "motion.h"
#include "regfile.h"
#include "xgo/emulator.h"

/* Firmware string and version register 0x02 by xgo_model_t. The string's
 * first character selects the vendor library's parameter set ('M' Mini,
 * 'L' Lite, 'W' the Mini2 with its arm, xgomini2sw); the rest marks an
 * emulator. */
static const struct {
    const char *firmware;
    uint8_t version;
} k_models[] = {
    {"M-EMU-0.1", XGO_VERSION_MINI},
    {"L-EMU-0.1", XGO_VERSION_LITE},
    {"W-EMU-0.1", XGO_VERSION_MINI2},
};

#if XGO_WITH_NAMES
static const char *const k_diag_names[XGO_DIAG_COUNT] = {
#define DIAG_NAME_(id, name, member) #name,
    XGO_DIAG_LIST(DIAG_NAME_)
#undef DIAG_NAME_
};
#endif

const char *xgo_diag_name(xgo_diag_t which)
{
#if XGO_WITH_NAMES
    return (unsigned)which < XGO_DIAG_COUNT ? k_diag_names[which] : "unknown";
#else
    return (unsigned)which < XGO_DIAG_COUNT ? "" : "unknown";
#endif
}

void xgo_board_default_config(xgo_board_config_t *cfg)
{
    cfg->model = XGO_MODEL_MINI;
    cfg->parser_timeout_ms = XGO_PARSER_DEFAULT_TIMEOUT_MS;
    cfg->battery_pct = 100;
}

static void emit(xgo_board_t *b, xgo_trace_kind_t kind, xgo_drop_reason_t reason,
                 const xgo_frame_t *frame, const uint8_t *raw, size_t raw_len, uint8_t unmapped)
{
    xgo_trace_event_t ev;
    if (b->trace == NULL) {
        return;
    }
    ev.kind = kind;
    ev.source = b->source;
    ev.reason = reason;
    ev.frame = frame;
    ev.raw = raw;
    ev.raw_len = raw_len;
    ev.unmapped = unmapped;
    b->trace(b->trace_ctx, &ev);
}

/* Queue a whole frame or nothing: a truncated reply would desynchronise the
 * host's parser. */
static int tx_push(xgo_board_t *b, const uint8_t *bytes, size_t n)
{
    size_t i;
    if (n > XGO_TX_BUFFER_SIZE - (size_t)b->tx_len) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        b->tx[(b->tx_head + b->tx_len + i) % XGO_TX_BUFFER_SIZE] = bytes[i];
    }
    b->tx_len = (uint16_t)(b->tx_len + n);
    return 1;
}

size_t xgo_board_transmit(xgo_board_t *b, uint8_t *out, size_t max)
{
    size_t n = b->tx_len < max ? b->tx_len : max;
    size_t i;
    XGO_ASSERT(out != NULL || max == 0);
    for (i = 0; i < n; i++) {
        out[i] = b->tx[(b->tx_head + i) % XGO_TX_BUFFER_SIZE];
    }
    b->tx_head = (uint16_t)((b->tx_head + n) % XGO_TX_BUFFER_SIZE);
    b->tx_len = (uint16_t)(b->tx_len - n);
    return n;
}

size_t xgo_board_tx_pending(const xgo_board_t *b)
{
    return b->tx_len;
}

void xgo_board_counters(const xgo_board_t *b, uint32_t out[XGO_DIAG_COUNT])
{
#define DIAG_READ_(id, name, member) out[XGO_DIAG_##id] = b->member;
    XGO_DIAG_LIST(DIAG_READ_)
#undef DIAG_READ_
}

static uint8_t count_unmapped(const xgo_regs_t *r, const xgo_frame_t *f)
{
    uint8_t n = 0;
    unsigned i;
    for (i = 0; i < f->len; i++) {
        if (xgo_regs_find(r, (uint8_t)(f->addr + i)) == NULL) {
            n++;
        }
    }
    return n;
}

/* Queue one reply frame (TYPE 0x12) whole, or count the overflow. */
static void send_reply(xgo_board_t *b, uint8_t addr, const uint8_t *data, size_t n)
{
    uint8_t frame_bytes[XGO_FRAME_MAX_LEN];
    xgo_frame_t reply;
    const size_t size = xgo_frame_encode(XGO_TYPE_READ_REPLY, addr, data, n, frame_bytes,
                                         sizeof frame_bytes);
    reply.type = XGO_TYPE_READ_REPLY;
    reply.addr = addr;
    reply.len = (uint8_t)n;
    reply.data = data;
    if (!tx_push(b, frame_bytes, size)) {
        b->tx_overflows++;
        emit(b, XGO_TRACE_DROP, XGO_DROP_TX_OVERFLOW, &reply, NULL, 0, 0);
        return;
    }
    emit(b, XGO_TRACE_TX, XGO_DROP_NONE, &reply, NULL, 0, 0);
}

int xgo_frame_asks_upgrade(const xgo_frame_t *f)
{
    const unsigned at = XGO_REG_UPGRADE - (unsigned)f->addr; /* wraps when addr > 0x05 */
    return f->type != XGO_TYPE_READ && at < f->len && f->data[at] == 1u;
}

static xgo_drop_reason_t handle_write(xgo_board_t *b, const xgo_frame_t *f)
{
    const uint8_t unmapped = count_unmapped(&b->regs, f);
    const xgo_drop_reason_t why = xgo_regs_write(&b->regs, f->addr, f->data, f->len);
    if (why != XGO_DROP_NONE) {
        emit(b, XGO_TRACE_DROP, why, f, NULL, 0, 0);
        return why;
    }
    emit(b, XGO_TRACE_RX, XGO_DROP_NONE, f, NULL, 0, unmapped);
    if (b->source == XGO_SOURCE_WIRE && xgo_frame_asks_upgrade(f)) {
        /* The host waits for an answer; an emulator has no bootloader to
         * hand over to, so it says no at once (docs/decisions.md). */
        static const uint8_t answer = XGO_UPGRADE_ANSWER;
        send_reply(b, XGO_REG_UPGRADE, &answer, 1);
    }
    return XGO_DROP_NONE;
}

static void handle_read(xgo_board_t *b, const xgo_frame_t *f)
{
    uint8_t data[XGO_FRAME_MAX_DATA];
    uint32_t counters[XGO_DIAG_COUNT];
    const size_t n = f->data[0];

    emit(b, XGO_TRACE_RX, XGO_DROP_NONE, f, NULL, 0, 0);
    xgo_board_counters(b, counters);
    xgo_regs_set_diag(&b->regs, counters);
    if (xgo_regs_read(&b->regs, f->addr, n, data) != XGO_DROP_NONE) {
        XGO_ASSERT(!"a read the parser accepted is in range"); /* ruled out */
        return;
    }
    send_reply(b, f->addr, data, n);
}

static void on_frame(void *ctx, const xgo_frame_t *f)
{
    xgo_board_t *b = (xgo_board_t *)ctx;
    if (f->type == XGO_TYPE_READ) {
        handle_read(b, f);
    } else {
        (void)handle_write(b, f);
    }
}

static void on_drop(void *ctx, xgo_drop_reason_t why, const uint8_t *bytes, size_t n)
{
    emit((xgo_board_t *)ctx, XGO_TRACE_DROP, why, NULL, bytes, n, 0);
}

void xgo_board_init(xgo_board_t *b, const xgo_board_config_t *cfg)
{
    xgo_parser_sink_t sink;
    XGO_ASSERT(b != NULL);
    XGO_ASSERT(cfg == NULL || (cfg->model <= XGO_MODEL_MINI2 && cfg->battery_pct <= 100));
    memset(b, 0, sizeof *b);
    if (cfg != NULL) {
        b->config = *cfg;
    } else {
        xgo_board_default_config(&b->config);
    }
    if (b->config.battery_pct > 100) { /* release builds: the documented clamp */
        b->config.battery_pct = 100;
    }
    sink.on_frame = on_frame;
    sink.on_drop = on_drop;
    sink.ctx = b;
    xgo_parser_init(&b->parser, &sink, b->config.parser_timeout_ms);
    if ((unsigned)b->config.model >= sizeof k_models / sizeof k_models[0] ||
        !xgo_profile_built_in((unsigned)b->config.model)) { /* docs: xgo/config.h */
        b->config.model = XGO_MODEL_MINI;
    }
    xgo_regs_init(&b->regs, k_models[b->config.model].firmware, k_models[b->config.model].version);
    xgo_regs_set(&b->regs, XGO_REG_BATTERY, b->config.battery_pct);
    xgo_motion_init(&b->motion, xgo_profile_get((unsigned)b->config.model), b->config.battery_pct);
    xgo_motion_init_registers(&b->motion, &b->regs);
    xgo_motion_publish(&b->motion, &b->regs);
}

void xgo_board_set_trace(xgo_board_t *b, xgo_trace_fn fn, void *ctx)
{
    b->trace = fn;
    b->trace_ctx = ctx;
}

void xgo_board_receive(xgo_board_t *b, const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    XGO_ASSERT(bytes != NULL || n == 0);
    b->source = XGO_SOURCE_WIRE;
    xgo_parser_feed(&b->parser, bytes, n, now_ms);
}

xgo_drop_reason_t xgo_board_write(xgo_board_t *b, uint8_t source, uint8_t addr,
                                  const uint8_t *data, size_t n)
{
    xgo_frame_t f;
    xgo_drop_reason_t why;
    XGO_ASSERT(data != NULL || n == 0);
    f.type = XGO_TYPE_WRITE;
    f.addr = addr;
    f.len = (uint8_t)(n <= XGO_FRAME_MAX_DATA ? n : 0u);
    f.data = data;
    b->source = source;
    if (n == 0 || n > XGO_FRAME_MAX_DATA || (size_t)addr + n > XGO_REG_COUNT) {
        b->parser.stats.bad_range++;
        emit(b, XGO_TRACE_DROP, XGO_DROP_BAD_RANGE, n <= XGO_FRAME_MAX_DATA ? &f : NULL, NULL, 0,
             0);
        why = XGO_DROP_BAD_RANGE;
    } else {
        why = handle_write(b, &f);
    }
    b->source = XGO_SOURCE_WIRE;
    return why;
}

void xgo_board_framing_errors(xgo_board_t *b, uint32_t n)
{
    b->framing_errors += n;
}

void xgo_board_poll(xgo_board_t *b, uint32_t now_ms)
{
    xgo_parser_poll(&b->parser, now_ms);
}

void xgo_board_hangup(xgo_board_t *b)
{
    xgo_parser_hangup(&b->parser);
}

void xgo_board_tick(xgo_board_t *b)
{
    b->ticks++;
    xgo_motion_tick(&b->motion, &b->regs);
}

void xgo_board_set_ground_tilt(xgo_board_t *b, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    xgo_imu_set_ground_tilt(&b->motion.imu, roll_mdeg, pitch_mdeg);
}

void xgo_board_ground_tilt(const xgo_board_t *b, int32_t *roll_mdeg, int32_t *pitch_mdeg)
{
    *roll_mdeg = b->motion.imu.ground_roll_mdeg;
    *pitch_mdeg = b->motion.imu.ground_pitch_mdeg;
}

void xgo_board_set_battery(xgo_board_t *b, uint8_t pct)
{
    xgo_battery_init(&b->motion.battery, pct);
    xgo_regs_set(&b->regs, XGO_REG_BATTERY, xgo_battery_percent(&b->motion.battery));
}

void xgo_board_push(xgo_board_t *b, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    xgo_imu_push(&b->motion.imu, roll_mdeg, pitch_mdeg);
}

/* ------------------------------------------------------------ observers */

#if (1000 % XGO_TICK_HZ) != 0
#error "xgo_board_time_ms assumes a whole number of ms per tick"
#endif

xgo_drop_reason_t xgo_board_read(const xgo_board_t *b, uint8_t addr, size_t n, uint8_t *out)
{
    uint32_t counters[XGO_DIAG_COUNT];
    xgo_drop_reason_t why;
    size_t i;
    XGO_ASSERT(out != NULL);
    why = xgo_regs_read(&b->regs, addr, n, out);
    if (why != XGO_DROP_NONE) {
        return why;
    }
    /* The block in regs is refreshed only by a read frame: overlay the
     * counters as they are now (uint32 little-endian, as on the wire). */
    xgo_board_counters(b, counters);
    for (i = 0; i < 4u * XGO_DIAG_COUNT; i++) {
        const size_t reg = XGO_REG_DIAG + i;
        if (reg >= addr && reg < (size_t)addr + n) {
            out[reg - addr] = (uint8_t)(counters[i / 4u] >> (8u * (i % 4u)));
        }
    }
    return XGO_DROP_NONE;
}

uint32_t xgo_board_time_ms(const xgo_board_t *b)
{
    return b->ticks * (1000u / XGO_TICK_HZ);
}

uint8_t xgo_board_mode(const xgo_board_t *b)
{
    return b->motion.mode;
}

uint8_t xgo_board_action(const xgo_board_t *b)
{
    return b->motion.action_id;
}

void xgo_board_joints_mdeg(const xgo_board_t *b, int32_t out[XGO_SERVO_COUNT])
{
    memcpy(out, b->motion.servos.angle_mdeg, sizeof b->motion.servos.angle_mdeg);
}

void xgo_board_joint_limits_mdeg(const xgo_board_t *b, unsigned joint, int32_t *lo, int32_t *hi)
{
    const xgo_range_t *r = &b->motion.profile->joint_mdeg[joint % XGO_JOINT_COUNT];
    XGO_ASSERT(joint < XGO_SERVO_COUNT);
    *lo = r->lo;
    *hi = r->hi;
}

void xgo_board_feet_um(const xgo_board_t *b, xgo_vec3_t out[XGO_LEG_COUNT])
{
    xgo_motion_feet_body(&b->motion, out);
}

uint8_t xgo_board_contacts(const xgo_board_t *b)
{
    return b->motion.contact;
}

void xgo_board_body_pose(const xgo_board_t *b, xgo_body_pose_t *out)
{
    *out = b->motion.pose;
}

void xgo_board_velocity(const xgo_board_t *b, int32_t cmd[3], int32_t produced[3])
{
    static const uint8_t regs[3] = {XGO_REG_VX, XGO_REG_VY, XGO_REG_VYAW};
    static const int32_t limits[3] = {XGO_VX_MAX_UM_S, XGO_VY_MAX_UM_S, XGO_VYAW_MAX_MDEG_S};
    const int gait = b->motion.mode == XGO_MODE_WHOLE_UNIT;
    unsigned i;
    for (i = 0; i < 3; i++) {
        cmd[i] = gait ? xgo_signed_byte_to_value(xgo_regs_get(&b->regs, regs[i]), limits[i]) : 0;
    }
    produced[0] = gait ? b->motion.gait.vx_um_s : 0;
    produced[1] = gait ? b->motion.gait.vy_um_s : 0;
    produced[2] = gait ? b->motion.gait.vyaw_mdeg_s : 0;
}

void xgo_board_imu_mdeg(const xgo_board_t *b, int32_t rpy[3])
{
    rpy[0] = b->motion.imu.roll_mdeg;
    rpy[1] = b->motion.imu.pitch_mdeg;
    rpy[2] = b->motion.imu.yaw_mdeg;
}

uint8_t xgo_board_battery_pct(const xgo_board_t *b)
{
    return xgo_battery_percent(&b->motion.battery);
}

int xgo_board_arm(const xgo_board_t *b, xgo_board_arm_t *out)
{
    const xgo_arm_t *a = &b->motion.arm;
    int32_t ex, ez, cx, cz;
    if (a->geo == NULL) {
        return 0;
    }
    memcpy(out->joints_mdeg, a->q_mdeg, sizeof out->joints_mdeg);
    xgo_arm_points(a->geo, a->q_mdeg, &ex, &ez, &cx, &cz);
    out->shoulder_um.x = a->geo->shoulder_x_um;
    out->shoulder_um.y = 0;
    out->shoulder_um.z = a->geo->shoulder_z_um;
    out->elbow_um = out->shoulder_um;
    out->elbow_um.x += ex;
    out->elbow_um.z += ez;
    out->claw_um = out->shoulder_um;
    out->claw_um.x += cx;
    out->claw_um.z += cz;
    out->out_of_reach = a->out_of_reach;
    return 1;
}

uint32_t xgo_board_clamped_pose_ticks(const xgo_board_t *b)
{
    return b->motion.clamped_pose_ticks;
}

void xgo_board_world_pose(const xgo_board_t *b, xgo_world_pose_t *out)
{
    xgo_odometry_pose(&b->motion.odom, out);
}

void xgo_board_gait(const xgo_board_t *b, xgo_gait_status_t *out)
{
    const xgo_gait_t *g = &b->motion.gait;
    unsigned leg;
    out->contact = 0;
    for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
        out->feet_um[leg] = g->foot_um[leg];
        out->contact |= (uint8_t)((g->contact[leg] != 0) << leg);
    }
    out->walking = (uint8_t)!xgo_gait_is_standing(g);
    out->type = g->type;
    out->phase = g->phase;
}

size_t xgo_board_rx_pending(const xgo_board_t *b)
{
    return xgo_parser_pending(&b->parser);
}

void xgo_board_get_nv(const xgo_board_t *b, xgo_board_nv_t *nv)
{
    unsigned i;
    for (i = 0; i < XGO_BT_NAME_LEN; i++) {
        nv->bt_name[i] = (char)xgo_regs_get(&b->regs, (uint8_t)(XGO_REG_BT_NAME + i));
    }
    memcpy(nv->zero_offset_mdeg, b->motion.servos.zero_offset_mdeg, sizeof nv->zero_offset_mdeg);
}

int xgo_board_set_nv(xgo_board_t *b, const xgo_board_nv_t *nv)
{
    unsigned i, len = 0;
    for (i = 0; i < XGO_BT_NAME_LEN && nv->bt_name[i] != '\0'; i++) {
        const unsigned char c = (unsigned char)nv->bt_name[i];
        if (c < 0x20 || c > 0x7E) {
            return 0;
        }
        len++;
    }
    for (; i < XGO_BT_NAME_LEN; i++) {
        if (nv->bt_name[i] != '\0') {
            return 0; /* printable after the end of the name */
        }
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        if (nv->zero_offset_mdeg[i] < -360000 || nv->zero_offset_mdeg[i] > 360000) {
            return 0;
        }
    }
    if (len == 0) {
        return 0;
    }
    for (i = 0; i < XGO_BT_NAME_LEN; i++) {
        xgo_regs_set(&b->regs, (uint8_t)(XGO_REG_BT_NAME + i), (uint8_t)nv->bt_name[i]);
    }
    memcpy(b->motion.servos.zero_offset_mdeg, nv->zero_offset_mdeg,
           sizeof b->motion.servos.zero_offset_mdeg);
    return 1;
}

uint32_t xgo_board_nv_changes(const xgo_board_t *b)
{
    return b->motion.nv_changes;
}
