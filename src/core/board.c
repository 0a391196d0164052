/*
 * The board: parser -> register file -> replies, plus the control tick.
 */
#include "xgo/board.h"

#include <stddef.h> /* offsetof */
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
#if XGO_WITH_LITE || XGO_WITH_MINI2 /* no row without either model; with the Mini2 alone the
                                     * Lite's stays, keeping the Mini2's index (xgo_board_init) */
    {"L-EMU-0.1", XGO_VERSION_LITE},
#endif
#if XGO_WITH_MINI2
    {"W-EMU-0.1", XGO_VERSION_MINI2},
#endif
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

/* Whether someone observes the board (xgo_board_set_trace): never in a
 * build without the hook, where every event's forming compiles away. */
#if XGO_WITH_TRACE
#define TRACED(b) ((b)->trace != NULL)
#else
#define TRACED(b) 0
#endif

static void emit(xgo_board_t *b, xgo_trace_kind_t kind, xgo_drop_reason_t reason,
                 const xgo_frame_t *frame, const uint8_t *raw, size_t raw_len, uint8_t unmapped)
{
#if XGO_WITH_TRACE
    xgo_trace_event_t ev;
    if (!TRACED(b)) {
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
#else
    (void)b, (void)kind, (void)reason, (void)frame, (void)raw, (void)raw_len, (void)unmapped;
#endif
}

/* The transmit queue is linear: the bytes waiting are tx[tx_head ..
 * tx_head + tx_len). A reply is built in place at its end, so it needs room
 * in one piece: when the space after the waiting bytes is too short, they
 * move to the front first (rare: the device feeds input only when a whole
 * reply fits, and a drained queue starts at the front again). Whole frame
 * or nothing: a truncated reply would desynchronise the host's parser, so
 * NULL (and nothing changes) when the frame does not fit. */
static uint8_t *tx_reserve(xgo_board_t *b, size_t size)
{
    if (size > XGO_TX_BUFFER_SIZE - (size_t)b->tx_len) {
        return NULL;
    }
    if ((size_t)b->tx_head + b->tx_len + size > XGO_TX_BUFFER_SIZE) {
        memmove(b->tx, &b->tx[b->tx_head], b->tx_len);
        b->tx_head = 0;
    }
    return &b->tx[b->tx_head + b->tx_len];
}

size_t xgo_board_transmit(xgo_board_t *b, uint8_t *out, size_t max)
{
    const size_t n = b->tx_len < max ? b->tx_len : max;
    XGO_ASSERT(out != NULL || max == 0);
    if (n == 0) {
        return 0;
    }
    memcpy(out, &b->tx[b->tx_head], n);
    b->tx_len = (xgo_tx_index_t)(b->tx_len - n);
    b->tx_head = (xgo_tx_index_t)(b->tx_len == 0 ? 0u : b->tx_head + n);
    return n;
}

size_t xgo_board_tx_pending(const xgo_board_t *b)
{
    return b->tx_len;
}

/* Where counter i of the diagnostic block lives in the board
 * (XGO_DIAG_LIST): a table of offsets is a third of the flash a switch
 * over the members takes. Every counter is a uint32_t, and its offset fits
 * the table's type (checked below): 16 bits, unless a transmit buffer near
 * 64 KiB (xgo/config.h allows up to 65535) puts the counters behind it
 * further out. */
#if XGO_TX_BUFFER_SIZE > 60000u
typedef uint32_t diag_offset_t;
#else
typedef uint16_t diag_offset_t;
#endif
static const diag_offset_t k_diag_offset[XGO_DIAG_COUNT] = {
#define DIAG_OFFSET_(id, name, member) (diag_offset_t)offsetof(xgo_board_t, member),
    XGO_DIAG_LIST(DIAG_OFFSET_)
#undef DIAG_OFFSET_
};
#define DIAG_IS_U32_(id, name, member)                                                     \
    typedef char diag_##name##_is_u32[sizeof(((xgo_board_t *)0)->member) == 4u ? 1 : -1]; \
    typedef char diag_##name##_offset_fits[(diag_offset_t)offsetof(xgo_board_t, member) == \
                                                   offsetof(xgo_board_t, member)           \
                                               ? 1                                          \
                                               : -1];
XGO_DIAG_LIST(DIAG_IS_U32_)
#undef DIAG_IS_U32_

/* Counter i of the diagnostic block as it is now (i < XGO_DIAG_COUNT). */
static uint32_t diag_counter(const xgo_board_t *b, unsigned i)
{
    return *(const uint32_t *)(const void *)((const char *)b + k_diag_offset[i]);
}

void xgo_board_counters(const xgo_board_t *b, uint32_t out[XGO_DIAG_COUNT])
{
    unsigned i;
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        out[i] = diag_counter(b, i);
    }
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

/* The reply (TYPE 0x12) whose n data bytes are in place in the frame
 * tx_reserve gave: completed, queued and traced. */
static void reply_queued(xgo_board_t *b, uint8_t *frame, uint8_t addr, size_t n)
{
    xgo_frame_t reply;
    b->tx_len = (xgo_tx_index_t)(b->tx_len + xgo_frame_seal(XGO_TYPE_READ_REPLY, addr, n, frame));
    reply.type = XGO_TYPE_READ_REPLY;
    reply.addr = addr;
    reply.len = (uint8_t)n;
    reply.data = &frame[XGO_FRAME_DATA_POS];
    emit(b, XGO_TRACE_TX, XGO_DROP_NONE, &reply, NULL, 0, 0);
}

/* A reply that did not fit: dropped whole, counted, traced with the data it
 * would have carried (data may be NULL when nobody traces). */
static void reply_lost(xgo_board_t *b, uint8_t addr, const uint8_t *data, size_t n)
{
    xgo_frame_t reply;
    b->tx_overflows++;
    reply.type = XGO_TYPE_READ_REPLY;
    reply.addr = addr;
    reply.len = (uint8_t)n;
    reply.data = data;
    emit(b, XGO_TRACE_DROP, XGO_DROP_TX_OVERFLOW, &reply, NULL, 0, 0);
}

/* The joint registers 0x50..0x5B inside a read of n bytes at addr: each
 * joint where it is now, in its profile range. Only a tick moves the
 * servos, so this is what the tick would have stored after moving them;
 * formed here, the tick pays nothing for bytes a host reads now and then. */
static void read_joints(const xgo_board_t *b, uint8_t addr, size_t n, uint8_t *out)
{
    const xgo_profile_t *p = b->motion.profile;
    const int32_t *q = b->motion.servos.angle_mdeg;
    unsigned i, j;
    if ((size_t)addr + n <= XGO_REG_SERVO11 || addr > XGO_REG_SERVO43) {
        return; /* most reads: status, attitude, the block */
    }
    for (i = 0; i < XGO_SERVO_COUNT; i += XGO_JOINT_COUNT) {
        for (j = 0; j < XGO_JOINT_COUNT; j++) {
            /* wraps above n for a register before addr: one compare */
            const size_t at = (size_t)(XGO_REG_SERVO11 + i + j) - addr;
            if (at < n) {
                out[at] = xgo_range_to_byte(&p->joint_mdeg[j], q[i + j]);
            }
        }
    }
}

/* The IMU's outputs as the last tick left them (xgo_board_init's too):
 * only a tick changes them, so they are what the tick would have stored in
 * the IMU's registers; a read forms those from them. */
static void imu_outputs(const xgo_motion_t *m, xgo_regs_imu_t *imu)
{
#if XGO_WITH_INERTIAL
    unsigned i;
    for (i = 0; i < 3; i++) {
        imu->accel[i] = m->inertial.accel[i];
        imu->gyro[i] = m->inertial.gyro[i];
    }
#endif
    imu->attitude_mdeg[0] = m->imu.roll_mdeg;
    imu->attitude_mdeg[1] = m->imu.pitch_mdeg;
    imu->attitude_mdeg[2] = m->imu.yaw_mdeg;
}

/* Registers as a host read returns them: the register file's image and
 * views with the IMU's registers formed from its outputs (imu_outputs), the
 * joints (read_joints) and the diagnostic block formed from the counters as
 * they are now (uint32 little-endian): the register image keeps no copy of
 * any. The caller checked the range (xgo_regs_read's rule). */
static void read_registers(const xgo_board_t *b, uint8_t addr, size_t n, uint8_t *out)
{
    const size_t end = (size_t)addr + n;
    size_t reg = addr > XGO_REG_DIAG ? (size_t)addr : (size_t)XGO_REG_DIAG;
    xgo_regs_imu_t imu;
    imu_outputs(&b->motion, &imu);
    xgo_regs_read_imu(&b->regs, &imu, addr, n, out);
    read_joints(b, addr, n, out);
    for (; reg < end && reg < XGO_REG_DIAG + 4u * XGO_DIAG_COUNT; reg++) {
        const unsigned i = (unsigned)(reg - XGO_REG_DIAG);
        out[reg - addr] = (uint8_t)(diag_counter(b, i / 4u) >> (8u * (i % 4u)));
    }
}

/* A read whose reply did not fit: its data exists only for a trace, in a
 * frame of its own (off the answered reply's path, which needs no buffer). */
XGO_OWN_FRAME static void read_lost(xgo_board_t *b, uint8_t addr, size_t n)
{
    uint8_t data[XGO_FRAME_MAX_DATA];
    if (!TRACED(b)) {
        reply_lost(b, addr, NULL, n);
        return;
    }
    read_registers(b, addr, n, data);
    reply_lost(b, addr, data, n);
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
        uint8_t *frame = tx_reserve(b, 1u + XGO_FRAME_OVERHEAD);
        if (frame == NULL) {
            reply_lost(b, XGO_REG_UPGRADE, &answer, 1);
        } else {
            frame[XGO_FRAME_DATA_POS] = answer;
            reply_queued(b, frame, XGO_REG_UPGRADE, 1);
        }
    }
    return XGO_DROP_NONE;
}

/* The reply is read straight into the transmit buffer: no copy of it on
 * the stack, whose deepest path this was (docs/mcu.md "Sizes"). The parser
 * accepted the range (a read it passes is in range). */
static void handle_read(xgo_board_t *b, const xgo_frame_t *f)
{
    const size_t n = f->data[0];
    uint8_t *frame;
    emit(b, XGO_TRACE_RX, XGO_DROP_NONE, f, NULL, 0, 0);
    frame = tx_reserve(b, n + XGO_FRAME_OVERHEAD);
    if (frame == NULL) {
        read_lost(b, f->addr, n);
        return;
    }
    read_registers(b, f->addr, n, &frame[XGO_FRAME_DATA_POS]);
    reply_queued(b, frame, f->addr, n);
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
    xgo_regs_put(&b->regs, XGO_REG_BATTERY, b->config.battery_pct);
    xgo_motion_init(&b->motion, xgo_profile_get((unsigned)b->config.model), b->config.battery_pct);
    xgo_motion_init_registers(&b->motion, &b->regs);
    xgo_motion_publish(&b->motion, &b->regs);
}

void xgo_board_set_trace(xgo_board_t *b, xgo_trace_fn fn, void *ctx)
{
#if XGO_WITH_TRACE
    b->trace = fn;
    b->trace_ctx = ctx;
#else
    (void)b, (void)fn, (void)ctx;
#endif
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
#if XGO_WITH_EMULATOR_INPUTS
    *roll_mdeg = b->motion.imu.ground_roll_mdeg;
    *pitch_mdeg = b->motion.imu.ground_pitch_mdeg;
#else
    (void)b;
    *roll_mdeg = 0; /* level: the input is compiled out (xgo/config.h) */
    *pitch_mdeg = 0;
#endif
}

void xgo_board_set_battery(xgo_board_t *b, uint8_t pct)
{
    xgo_battery_init(&b->motion.battery, pct);
    xgo_regs_put(&b->regs, XGO_REG_BATTERY, xgo_battery_percent(&b->motion.battery));
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
    XGO_ASSERT(out != NULL);
    if (n == 0 || n > XGO_FRAME_MAX_DATA || (size_t)addr + n > XGO_REG_COUNT) {
        return XGO_DROP_BAD_RANGE; /* xgo_regs_read's rule; out untouched */
    }
    read_registers(b, addr, n, out);
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

/* The name's registers are stored in one piece (no gap of the image cuts
 * them, checked here): copied at once. */
#define BT_NAME_SLOT XGO_REGS_SLOT(XGO_REG_BT_NAME)
typedef char bt_name_in_one_piece[XGO_REGS_SLOT(XGO_REG_BT_NAME + XGO_BT_NAME_LEN - 1u) ==
                                          BT_NAME_SLOT + XGO_BT_NAME_LEN - 1u
                                      ? 1
                                      : -1];

void xgo_board_get_nv(const xgo_board_t *b, xgo_board_nv_t *nv)
{
    memcpy(nv->bt_name, &b->regs.mem[BT_NAME_SLOT], XGO_BT_NAME_LEN);
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
    memcpy(&b->regs.mem[BT_NAME_SLOT], nv->bt_name, XGO_BT_NAME_LEN);
    memcpy(b->motion.servos.zero_offset_mdeg, nv->zero_offset_mdeg,
           sizeof b->motion.servos.zero_offset_mdeg);
    return 1;
}

uint32_t xgo_board_nv_changes(const xgo_board_t *b)
{
    return b->motion.nv_changes;
}
