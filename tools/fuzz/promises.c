/* promises.c - the board's promises, checked (see promises.h). */
#include "promises.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "xgo/reg_units.h"

/* docs/motion.md, "Bounds": no joint moves more than 600 deg/s. */
#define FUZZ_JOINT_STEP_MAX_MDEG ((int32_t)(600000 / XGO_TICK_HZ))

void fuzz_check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_board: broken promise: %s\n", what);
        abort();
    }
}


/* ------------------------------------------------------ replies owed */

static void owe(fuzz_promises_t *p, uint8_t addr, uint8_t n)
{
    unsigned at = (p->owed_head + p->owed_len) % FUZZ_OWED_MAX;
    fuzz_check(p->owed_len < FUZZ_OWED_MAX, "more replies owed than any buffer holds");
    p->owed_addr[at] = addr;
    p->owed_n[at] = n;
    p->owed_len++;
}

/* The reply to the newest request was dropped (transmit buffer full). */
static void forgive_last(fuzz_promises_t *p)
{
    fuzz_check(p->owed_len > 0, "a reply dropped that nobody asked for");
    p->owed_len--;
}

static const uint8_t *newest_owed(const fuzz_promises_t *p, uint8_t *n)
{
    unsigned at;
    fuzz_check(p->owed_len > 0, "a reply queued that nobody asked for");
    at = (p->owed_head + p->owed_len - 1u) % FUZZ_OWED_MAX;
    *n = p->owed_n[at];
    return &p->owed_addr[at];
}

/* A reply being queued: it answers the newest request, with what the
 * board's read view shows right now (the upgrade request: its refusal). */
static void check_reply_content(fuzz_promises_t *p, const xgo_frame_t *f, int upgrade)
{
    uint8_t view[XGO_FRAME_MAX_DATA];
    uint8_t n;
    const uint8_t addr = *newest_owed(p, &n);
    fuzz_check(f->type == XGO_TYPE_READ_REPLY && f->addr == addr && f->len == n, "reply to what");
    if (upgrade) {
        fuzz_check(f->data[0] == XGO_UPGRADE_ANSWER, "upgrade answer");
        return;
    }
    fuzz_check(xgo_board_read(p->board, f->addr, f->len, view) == XGO_DROP_NONE, "read view");
    fuzz_check(memcmp(view, f->data, f->len) == 0, "reply differs from the board's read view");
}

/* ---------------------------------------------------- the trace hook */

static void delivered(fuzz_promises_t *p, const xgo_frame_t *f)
{
    p->frames++;
    p->frame_bytes += (size_t)f->len + XGO_FRAME_OVERHEAD;
}

static void observe_wire(fuzz_promises_t *p, const xgo_trace_event_t *ev)
{
    switch (ev->kind) {
    case XGO_TRACE_RX:
        delivered(p, ev->frame);
        p->upgrade_asked = ev->frame->type != XGO_TYPE_READ && xgo_frame_asks_upgrade(ev->frame);
        if (ev->frame->type == XGO_TYPE_READ) {
            owe(p, ev->frame->addr, ev->frame->data[0]);
        } else if (p->upgrade_asked) {
            owe(p, XGO_REG_UPGRADE, 1);
        }
        break;
    case XGO_TRACE_TX:
        check_reply_content(p, ev->frame, p->upgrade_asked);
        break;
    case XGO_TRACE_DROP:
        if (ev->reason == XGO_DROP_TX_OVERFLOW) {
            forgive_last(p);
        } else if (ev->frame != NULL) {
            delivered(p, ev->frame); /* parsed, then refused by the registers */
        }
        break;
    }
}

static void observe(void *ctx, const xgo_trace_event_t *ev)
{
    fuzz_promises_t *p = ctx;
    if (ev->kind == XGO_TRACE_DROP) {
        fuzz_check((unsigned)ev->reason < XGO_DROP_REASON_COUNT && ev->reason != XGO_DROP_NONE &&
                  strcmp(xgo_drop_reason_name(ev->reason), "unknown") != 0,
              "a drop without a reason the trace can name");
        p->drops[ev->reason]++;
    }
    if (ev->kind == XGO_TRACE_RX && ev->frame->type != XGO_TYPE_READ && ev->unmapped > 0) {
        p->unmapped_writes++;
    }
    if (ev->source != XGO_SOURCE_WIRE) {
        fuzz_check(ev->kind != XGO_TRACE_TX, "a reply to a write that did not come by wire");
        return;
    }
    observe_wire(p, ev);
}

/* ------------------------------------------- the host's side of the line */

static void host_frame(void *ctx, const xgo_frame_t *f)
{
    fuzz_promises_t *p = ctx;
    fuzz_check(p->owed_len > 0, "an unasked-for reply");
    fuzz_check(f->type == XGO_TYPE_READ_REPLY, "reply type");
    fuzz_check(f->addr == p->owed_addr[p->owed_head] && f->len == p->owed_n[p->owed_head],
          "replies out of order");
    p->owed_head = (p->owed_head + 1u) % FUZZ_OWED_MAX;
    p->owed_len--;
    p->host_frames++;
}

static void host_drop(void *ctx, xgo_drop_reason_t why, const uint8_t *bytes, size_t n)
{
    (void)ctx;
    (void)why;
    (void)bytes;
    (void)n;
    fuzz_check(0, "output a host cannot parse");
}

void fuzz_promises_init(fuzz_promises_t *p, xgo_board_t *b, const xgo_profile_t *profile)
{
    xgo_parser_sink_t sink;
    memset(p, 0, sizeof *p);
    p->board = b;
    p->profile = profile;
    sink.on_frame = host_frame;
    sink.on_drop = host_drop;
    sink.ctx = p;
    xgo_parser_init_side(&p->host, &sink, 0, XGO_PARSER_HOST);
    xgo_board_set_trace(b, observe, p);
    fuzz_promises_rebase_joints(p);
}

void fuzz_promises_fed(fuzz_promises_t *p, size_t n)
{
    p->wire_bytes += n;
}

/* ------------------------------------------------ read-only registers */

/* Every read-only register but the counters, as a host would read it. */
static size_t read_only_view(const xgo_board_t *b, uint8_t *out)
{
    size_t i, at = 0;
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        if (d->access == XGO_ACCESS_R && d->addr != XGO_REG_DIAG) {
            fuzz_check(xgo_board_read(b, d->addr, d->width, out + at) == XGO_DROP_NONE, "read view");
            at += d->width;
        }
    }
    return at;
}

void fuzz_promises_before_write(fuzz_promises_t *p)
{
    (void)read_only_view(p->board, p->read_only);
}

void fuzz_promises_after_write(fuzz_promises_t *p)
{
    uint8_t now[XGO_REG_COUNT];
    size_t n = read_only_view(p->board, now);
    fuzz_check(memcmp(now, p->read_only, n) == 0, "a host write changed a read-only register");
}

void fuzz_promises_units(const fuzz_promises_t *p, uint8_t addr, const uint8_t *data, size_t n)
{
    size_t i;
    for (i = 0; i < n && (size_t)addr + i < XGO_REG_COUNT; i++) {
        const uint8_t a = (uint8_t)(addr + i);
        int32_t value, back, lo, hi;
        uint8_t byte;
        if (!xgo_reg_byte_to_value(p->profile, a, data[i], &value)) {
            fuzz_check(xgo_reg_unit(a) == XGO_UNIT_NONE, "a unit without a value");
            continue;
        }
        fuzz_check(xgo_reg_value_range(p->profile, a, &lo, &hi) && lo <= hi, "unit range");
        fuzz_check((value >= lo && value <= hi) || value == 0, "a byte's value outside its range");
        fuzz_check(xgo_reg_value_to_byte(p->profile, a, value, &byte) == XGO_REG_VALUE_OK,
              "a byte's own value refused");
        fuzz_check(xgo_reg_byte_to_value(p->profile, a, byte, &back) && back == value,
              "value -> byte -> value is not the identity");
    }
}

/* ------------------------------------------------------------ joints */

/* Joint angles are reported from the servos' zeros: when calibration
 * records new zeros they jump without anything moving, so that tick's steps
 * are not checked. */
void fuzz_promises_after_tick(fuzz_promises_t *p)
{
    int32_t now[XGO_SERVO_COUNT];
    xgo_board_nv_t nv;
    int new_zeros;
    unsigned j;
    xgo_board_joints_mdeg(p->board, now);
    xgo_board_get_nv(p->board, &nv);
    new_zeros = memcmp(nv.zero_offset_mdeg, p->zeros, sizeof p->zeros) != 0;
    memcpy(p->zeros, nv.zero_offset_mdeg, sizeof p->zeros);
    for (j = 0; j < XGO_SERVO_COUNT; j++) {
        int32_t lo, hi;
        const int32_t step = now[j] - p->joints[j];
        xgo_board_joint_limits_mdeg(p->board, j, &lo, &hi);
        fuzz_check(new_zeros ||
                  (step <= FUZZ_JOINT_STEP_MAX_MDEG && step >= -FUZZ_JOINT_STEP_MAX_MDEG),
              "a joint moved more than its step per tick");
        fuzz_check(now[j] >= lo && now[j] <= hi, "a joint left its limits");
        p->joints[j] = now[j];
    }
}

void fuzz_promises_rebase_joints(fuzz_promises_t *p)
{
    xgo_board_nv_t nv;
    xgo_board_joints_mdeg(p->board, p->joints);
    xgo_board_get_nv(p->board, &nv);
    memcpy(p->zeros, nv.zero_offset_mdeg, sizeof p->zeros);
}

/* ------------------------------------------------------------ output */

/* Walks the output independently of the parser: whole frames only. */
static void check_frames(const uint8_t *out, size_t n)
{
    size_t pos = 0;
    while (pos < n) {
        size_t len, k;
        fuzz_check(n - pos >= XGO_FRAME_OVERHEAD + 1u, "truncated reply");
        len = out[pos + 2];
        fuzz_check(out[pos] == XGO_FRAME_HEAD0 && out[pos + 1] == XGO_FRAME_HEAD1, "reply header");
        fuzz_check(len >= XGO_FRAME_OVERHEAD + 1u && pos + len <= n, "reply length");
        fuzz_check(out[pos + 3] == XGO_TYPE_READ_REPLY, "reply type");
        k = len - XGO_FRAME_OVERHEAD;
        fuzz_check(out[pos + 5 + k] == xgo_frame_checksum((uint8_t)len, out[pos + 3], out[pos + 4],
                                                     &out[pos + 5], k),
              "reply checksum");
        fuzz_check(out[pos + len - 2] == XGO_FRAME_TAIL0 && out[pos + len - 1] == XGO_FRAME_TAIL1,
              "reply tail");
        pos += len;
    }
}

/* What the observers say agrees with the registers and stays in range. */
static void check_observers(const xgo_board_t *b, const xgo_profile_t *profile)
{
    unsigned i;
    uint8_t regs[XGO_REG_IMU_YAW + 1];
    int32_t rpy[3], cmd[3], produced[3];
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t body;
    xgo_world_pose_t world;
    xgo_gait_status_t gait;
    uint8_t action = xgo_board_action(b);
    fuzz_check(xgo_board_read(b, 0x00, sizeof regs, regs) == XGO_DROP_NONE, "read view");
    fuzz_check(xgo_board_mode(b) == regs[XGO_REG_MODE] && regs[XGO_REG_MODE] <= XGO_MODE_CALIBRATION,
          "mode");
    fuzz_check(xgo_board_battery_pct(b) == regs[XGO_REG_BATTERY] && regs[XGO_REG_BATTERY] <= 100,
          "battery");
    fuzz_check(action == 0 || xgo_action_name(action) != NULL, "an action without a table");
    xgo_board_imu_mdeg(b, rpy);
    for (i = 0; i < 3; i++) { /* the one-byte view: nearest, 1 LSB = 180/128 deg */
        const uint8_t a = (uint8_t)(XGO_REG_IMU_ROLL + i);
        int32_t lo, hi, v;
        fuzz_check(xgo_reg_value_range(profile, a, &lo, &hi) &&
                  xgo_reg_byte_to_value(profile, a, regs[a], &v),
              "attitude unit");
        if (rpy[i] >= lo && rpy[i] <= hi) {
            fuzz_check(v - rpy[i] <= 704 && rpy[i] - v <= 704, "IMU registers differ from the IMU");
        }
    }
    xgo_board_world_pose(b, &world);
    fuzz_check(world.yaw_mdeg >= -180000 && world.yaw_mdeg <= 180000, "world yaw");
    fuzz_check(xgo_board_contacts(b) <= 0x0Fu, "contacts");
    xgo_board_gait(b, &gait);
    fuzz_check(gait.contact <= 0x0Fu && gait.type <= 3u, "gait status");
    xgo_board_feet_um(b, feet);
    xgo_board_body_pose(b, &body);
    xgo_board_velocity(b, cmd, produced);
    (void)xgo_board_time_ms(b);
}

/* Each drop reason's counter, and the traced drops it counts. */
static const struct {
    xgo_diag_t diag;
    xgo_drop_reason_t reason;
} k_counted[] = {
    {XGO_DIAG_BAD_CHECKSUM, XGO_DROP_BAD_CHECKSUM},  {XGO_DIAG_BAD_TAIL, XGO_DROP_BAD_TAIL},
    {XGO_DIAG_BAD_LENGTH, XGO_DROP_BAD_LENGTH},      {XGO_DIAG_BAD_TYPE, XGO_DROP_BAD_TYPE},
    {XGO_DIAG_BAD_RANGE, XGO_DROP_BAD_RANGE},        {XGO_DIAG_TIMEOUTS, XGO_DROP_TIMEOUT},
    {XGO_DIAG_REJECTED_READ_ONLY, XGO_DROP_READ_ONLY}, {XGO_DIAG_REJECTED_VALUE, XGO_DROP_BAD_VALUE},
    {XGO_DIAG_TX_OVERFLOW, XGO_DROP_TX_OVERFLOW},    {XGO_DIAG_HANGUP_DISCARDS, XGO_DROP_HANGUP},
};

static void check_counters(fuzz_promises_t *p)
{
    uint32_t c[XGO_DIAG_COUNT];
    size_t i, accounted;
    xgo_board_counters(p->board, c);
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        fuzz_check(c[i] >= p->counters[i], "a counter went back");
        fuzz_check(strcmp(xgo_diag_name((xgo_diag_t)i), "unknown") != 0, "a counter without a name");
    }
    memcpy(p->counters, c, sizeof c);
    for (i = 0; i < sizeof k_counted / sizeof k_counted[0]; i++) {
        fuzz_check(c[k_counted[i].diag] == p->drops[k_counted[i].reason],
              "a drop counted but not traced, or traced but not counted");
    }
    fuzz_check(c[XGO_DIAG_IGNORED_UNMAPPED] == p->unmapped_writes, "ignored_unmapped");
    fuzz_check(c[XGO_DIAG_FRAMES_OK] == p->frames, "frames_ok is not the frames delivered");
    accounted = p->frame_bytes + c[XGO_DIAG_BYTES_DISCARDED] + xgo_board_rx_pending(p->board);
    fuzz_check(accounted == p->wire_bytes && xgo_board_rx_pending(p->board) < XGO_FRAME_MAX_LEN,
          "bytes fed != delivered + discarded + pending");
}

void fuzz_promises_drain(fuzz_promises_t *p, const uint8_t *out, size_t n, uint32_t now_ms)
{
    fuzz_check(xgo_board_tx_pending(p->board) == 0, "replies left behind");
    check_frames(out, n);
    xgo_parser_feed(&p->host, out, n, now_ms);
    fuzz_check(xgo_parser_pending(&p->host) == 0, "a reply cut short");
    check_observers(p->board, p->profile);
    check_counters(p);
}

void fuzz_promises_finish(fuzz_promises_t *p)
{
    uint32_t c[XGO_DIAG_COUNT];
    xgo_board_counters(p->board, c);
    fuzz_check(xgo_board_rx_pending(p->board) == 0 &&
              p->wire_bytes == p->frame_bytes + c[XGO_DIAG_BYTES_DISCARDED],
          "after a hang-up, bytes fed != delivered + discarded");
    fuzz_check(p->owed_len == 0, "a reply owed never came");
}
