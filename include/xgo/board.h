/*
 * xgo/board.h - the emulated driver board: wire in, registers, wire out,
 * control tick. This is the one object a host port (or a unit test) drives:
 *
 *   xgo_board_init(&b, &cfg);
 *   loop:
 *     xgo_board_receive(&b, bytes, n, now_ms);  // bytes from the host
 *     n = xgo_board_transmit(&b, out, sizeof out); // replies to send
 *     xgo_board_poll(&b, now_ms);                // parser silence timeout
 *     every 1/XGO_TICK_HZ s: xgo_board_tick(&b);
 *
 * Time is whatever the caller says it is (virtual in tests, a monotonic clock
 * in xgo-emu, a hardware timer on an MCU). The board never sends a frame that
 * was not asked for: only read requests, and a request to upgrade the
 * firmware (1 written to 0x05, answered XGO_UPGRADE_ANSWER), produce output.
 *
 * The public API is this header and what it includes (xgo/config.h options,
 * xgo/types.h values, xgo/profile.h models and numbering, xgo/protocol.h
 * frames and parser, xgo/regs.h the register map). xgo/board_state.h only
 * makes xgo_board_t complete so that the caller can own it: its fields are
 * private, read the board through the observers below. Emulator-only inputs
 * (ground tilt, battery, a shove) are in xgo/emulator.h, the port boundary
 * for firmware in xgo/port.h; the core's modules have private headers in
 * src/core.
 *
 * Return values: a call that can refuse its input returns why
 * (xgo_drop_reason_t; XGO_DROP_NONE, 0, means done); a call whose only
 * outcome is done or refused returns int 1 (done) or 0 (refused, nothing
 * changed); observers return the value or fill out-parameters.
 *
 * Checks: everything from the wire and every register value a host writes
 * is expected input - dropped, counted, traced or clamped, never asserted.
 * Caller bugs are XGO_ASSERT (xgo/config.h): a NULL board, bytes or buffer
 * with a non-zero length, a config with an unknown model or a battery over
 * 100 %, a joint index past 11; with the checks compiled out the documented
 * release behaviour applies (the battery clamped to 100, joint % 3).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_BOARD_H
#define XGO_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/board_state.h"
#include "xgo/config.h"
#include "xgo/profile.h"
#include "xgo/protocol.h"
#include "xgo/regs.h"
#include "xgo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The robot models (xgo_profile_get takes the same codes). */
typedef enum xgo_model_e {
    XGO_MODEL_MINI = 0,
    XGO_MODEL_LITE = 1,
    XGO_MODEL_MINI2 = 2 /* the Mini with the arm and claw (firmware 'W') */
} xgo_model_t;

typedef struct xgo_board_config_s {
    xgo_model_t model;
    uint32_t parser_timeout_ms; /* 0 = no silence timeout */
    uint8_t battery_pct;        /* initial battery level, 0..100 */
} xgo_board_config_t;

/* What a trace event is about. */
typedef enum xgo_trace_kind_e {
    XGO_TRACE_RX,   /* a frame from the host was accepted and applied (or answered) */
    XGO_TRACE_TX,   /* a reply frame was queued */
    XGO_TRACE_DROP  /* input was dropped: see reason, raw bytes / frame */
} xgo_trace_kind_t;

/* Who sent a write or request: the serial line, or a host-side program that
 * enters the same register-write path through xgo_board_write() (the live
 * view's page, a script through it, ...). Only for tracing. */
typedef enum xgo_source_e {
    XGO_SOURCE_WIRE = 0, /* bytes through xgo_board_receive() */
    XGO_SOURCE_VIEW = 1, /* the live view (xgo-emu --view) */
    XGO_SOURCE_CLI = 2   /* another local tool */
} xgo_source_t;

typedef struct xgo_trace_event_s {
    xgo_trace_kind_t kind;
    uint8_t source;            /* xgo_source_t of the frame (WIRE for parser drops) */
    xgo_drop_reason_t reason;  /* XGO_DROP_NONE unless kind == XGO_TRACE_DROP */
    const xgo_frame_t *frame;  /* the frame, when one was parsed (else NULL) */
    const uint8_t *raw;        /* for parser drops: the rejected bytes */
    size_t raw_len;
    uint8_t unmapped;          /* RX write: bytes for addresses the Mini lacks */
} xgo_trace_event_t;

typedef void (*xgo_trace_fn)(void *ctx, const xgo_trace_event_t *event);

/* An index into the transmit buffer: a byte when the buffer is no longer
 * (the firmware images': with the source below, 4 bytes of the board less). */
#if XGO_TX_BUFFER_SIZE <= 255u
typedef uint8_t xgo_tx_index_t;
#else
typedef uint16_t xgo_tx_index_t;
#endif

/* The register file first and the motion core right after it: the tick
 * works on both, and at the board's start (short offsets on a Cortex-M0)
 * it keeps fewer pointers in its frame, the deepest path's (nRF51
 * xgo_board_tick 80 -> 72 bytes, tools/mcu/fw_check.sh). */
typedef struct xgo_board_s {
    xgo_regs_t regs;
    xgo_motion_t motion;
    xgo_board_config_t config;
    xgo_parser_t parser;
    uint8_t tx[XGO_TX_BUFFER_SIZE]; /* queue of reply bytes (board.c) */
    xgo_tx_index_t tx_head;         /* index of the oldest byte */
    xgo_tx_index_t tx_len;
    uint8_t source;                 /* xgo_source_t of the frame being handled */
    uint32_t tx_overflows;
    uint32_t framing_errors;        /* bytes the UART received with a bad stop bit */
    uint32_t ticks;
#if XGO_WITH_TRACE
    xgo_trace_fn trace;
    void *trace_ctx;
#endif
} xgo_board_t;

/* The answer (one byte at 0x05, TYPE 0x12) to an upgrade request from the
 * wire: not the 0x55 with which a real bootloader would take the firmware
 * image, so the vendor library reports the refusal at once and keeps its
 * port at 115200. */
#define XGO_UPGRADE_ANSWER 0x00u

/* 1 if f is a write frame that asks for a firmware upgrade (1 at 0x05): the
 * one write the board answers. */
int xgo_frame_asks_upgrade(const xgo_frame_t *f);

/* Fills cfg with the defaults: Mini, 20 ms parser timeout, battery 100 %. */
void xgo_board_default_config(xgo_board_config_t *cfg);

/* cfg may be NULL for the defaults. */
void xgo_board_init(xgo_board_t *b, const xgo_board_config_t *cfg);

/* Optional observer of every frame in and out and of every drop (does
 * nothing in a build without XGO_WITH_TRACE, xgo/config.h). */
void xgo_board_set_trace(xgo_board_t *b, xgo_trace_fn fn, void *ctx);

/* Bytes from the host that arrived at now_ms. Requests are applied and
 * answered at once (replies go to the transmit buffer). */
void xgo_board_receive(xgo_board_t *b, const uint8_t *bytes, size_t n, uint32_t now_ms);

/* The UART received n bytes with a framing error (stop bit 0: the host
 * sends at another speed, or noise). They never reach the parser; the port
 * (an MCU's UART interrupt, xgo-emu --uart-baud) drops them and counts them
 * here (diagnostic counter framing_errors). */
void xgo_board_framing_errors(xgo_board_t *b, uint32_t n);

/* Apply the parser's silence timeout at now_ms. */
void xgo_board_poll(xgo_board_t *b, uint32_t now_ms);

/* The host hung up (a host port saw the line go away): a partial frame it
 * left is dropped (reason XGO_DROP_HANGUP, traced, counted in
 * hangup_discards) instead of swallowing the next host's first request. Call
 * it after the departed host's last bytes were received. */
void xgo_board_hangup(xgo_board_t *b);

/* Move up to max queued reply bytes into out; returns how many. */
size_t xgo_board_transmit(xgo_board_t *b, uint8_t *out, size_t max);

/* Reply bytes waiting. */
size_t xgo_board_tx_pending(const xgo_board_t *b);

/* Advance one control period (1 / XGO_TICK_HZ s). */
void xgo_board_tick(xgo_board_t *b);

/* A register write from a host-side program (not the wire): exactly the
 * path of a write frame - validated whole, applied or rejected and counted,
 * traced with `source` - so a second controller (the live view) is no side
 * door. Frames through here do not count as frames_ok (the parser never saw
 * them). Returns XGO_DROP_NONE, or why nothing was written (n == 0,
 * n > XGO_FRAME_MAX_DATA or addr + n > 256 give XGO_DROP_BAD_RANGE, counted
 * as bad_range). */
xgo_drop_reason_t xgo_board_write(xgo_board_t *b, uint8_t source, uint8_t addr,
                                  const uint8_t *data, size_t n);

/* ---- Observers: what the board is doing, read-only, in physical units.
 * Frames: body frame = body axes, origin at the body centre, x forward,
 * y left, z up. Angles in millidegrees, lengths in micrometres. */

/* Registers addr..addr+n-1 as a host's read request for them would return
 * them (computed views included, the diagnostic block current), without a
 * frame: nothing is counted, traced or queued. Returns XGO_DROP_NONE, or
 * XGO_DROP_BAD_RANGE (out untouched) for n == 0, n > XGO_FRAME_MAX_DATA or
 * addr + n > 256. */
xgo_drop_reason_t xgo_board_read(const xgo_board_t *b, uint8_t addr, size_t n, uint8_t *out);

/* Board time: control ticks since init, in ms. */
uint32_t xgo_board_time_ms(const xgo_board_t *b);
/* Register 0x00 (xgo_mode_t) and the running action (0x3E, 0 = none). */
uint8_t xgo_board_mode(const xgo_board_t *b);
uint8_t xgo_board_action(const xgo_board_t *b);
/* The twelve joints where they are now (register order 0x50..0x5B). */
void xgo_board_joints_mdeg(const xgo_board_t *b, int32_t out[XGO_SERVO_COUNT]);
/* Limits of joint 0..11 (the servo register's byte range). */
void xgo_board_joint_limits_mdeg(const xgo_board_t *b, unsigned joint, int32_t *lo, int32_t *hi);
/* The feet (legs LF, RF, RH, LH) in the body frame, from the actual joints. */
void xgo_board_feet_um(const xgo_board_t *b, xgo_vec3_t out[XGO_LEG_COUNT]);
/* Bit leg set: that foot is on the ground. */
uint8_t xgo_board_contacts(const xgo_board_t *b);
/* The body pose used this tick (machine frame: translation from the point
 * on the ground under the standing body; z = height of the hip axes). */
void xgo_board_body_pose(const xgo_board_t *b, xgo_body_pose_t *out);
/* Commanded (registers 0x30..0x32) and produced (the gait, after the ramp)
 * body velocity: vx, vy in um/s, yaw rate in mdeg/s. */
void xgo_board_velocity(const xgo_board_t *b, int32_t cmd[3], int32_t produced[3]);
/* What the IMU reports: roll, pitch, yaw. */
void xgo_board_imu_mdeg(const xgo_board_t *b, int32_t rpy[3]);
uint8_t xgo_board_battery_pct(const xgo_board_t *b);
/* Where the robot is on the floor (leg odometry): origin at the power-up
 * position, x forward at power-up, y left, yaw CCW. */
void xgo_board_world_pose(const xgo_board_t *b, xgo_world_pose_t *out);
/* Whole-unit ticks whose body pose is not the one the registers ask for,
 * because the legs could not hold that (docs/motion.md, "Poses the legs
 * cannot hold"). The diagnostic counter reach_clamped counts these ticks
 * and those where the Mini2's arm holds a clamped point. */
uint32_t xgo_board_clamped_pose_ticks(const xgo_board_t *b);

/* The gait generator (whole-unit mode): where it puts the feet, before the
 * body pose and the IK, and where it is in its cycle. */
typedef struct xgo_gait_status_s {
    xgo_vec3_t feet_um[XGO_LEG_COUNT]; /* machine frame relative to the body
                                          centre, z up, 0 on the ground */
    uint8_t contact;  /* bit leg: in stance */
    uint8_t walking;  /* 0: standing, four feet at their stance points */
    uint8_t type;     /* gait in use (register 0x09 values) */
    uint32_t phase;   /* master phase, 2^32 = one cycle */
} xgo_gait_status_t;
void xgo_board_gait(const xgo_board_t *b, xgo_gait_status_t *out);

/* The Mini2's arm as it is (profile.h has the angle conventions). */
typedef struct xgo_board_arm_s {
    int32_t joints_mdeg[XGO_ARM_JOINT_COUNT]; /* claw, elbow, shoulder: where they are */
    xgo_vec3_t shoulder_um; /* body frame (y = 0: the arm's plane) */
    xgo_vec3_t elbow_um;
    xgo_vec3_t claw_um;     /* the claw point */
    uint8_t out_of_reach;   /* the point it serves was out of reach (clamped) */
} xgo_board_arm_t;
/* 1 and *out filled on a model with the arm; 0 (out untouched) without. */
int xgo_board_arm(const xgo_board_t *b, xgo_board_arm_t *out);

/* Bytes of a frame the parser holds so far (0 between frames). */
size_t xgo_board_rx_pending(const xgo_board_t *b);

/* The board's non-volatile data (a real board keeps it in flash): the
 * Bluetooth name and the servo zero offsets. A host port saves it when
 * xgo_board_nv_changes() moves and restores it at start (xgo-emu --state). */
typedef struct xgo_board_nv_s {
    char bt_name[XGO_BT_NAME_LEN]; /* ASCII 0x20..0x7E, NUL padded */
    int32_t zero_offset_mdeg[XGO_SERVO_COUNT];
} xgo_board_nv_t;

void xgo_board_get_nv(const xgo_board_t *b, xgo_board_nv_t *nv);
/* Returns 1 and applies nv, or 0 (nothing changes) when the name is empty or
 * not printable ASCII or an offset is beyond +-360 degrees. */
int xgo_board_set_nv(xgo_board_t *b, const xgo_board_nv_t *nv);
/* Counts changes of the non-volatile data since init. */
uint32_t xgo_board_nv_changes(const xgo_board_t *b);

/* All counters in the order of the diagnostic block (see xgo_diag_t). */
void xgo_board_counters(const xgo_board_t *b, uint32_t out[XGO_DIAG_COUNT]);

/* Name of a diagnostic counter ("frames_ok", ...). */
const char *xgo_diag_name(xgo_diag_t which);

#ifdef __cplusplus
}
#endif

#endif /* XGO_BOARD_H */
