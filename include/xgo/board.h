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
 * was not asked for: only read requests produce output.
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_BOARD_H
#define XGO_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/config.h"
#include "xgo/motion.h"
#include "xgo/protocol.h"
#include "xgo/regs.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum xgo_model_e { XGO_MODEL_MINI = 0, XGO_MODEL_LITE = 1 } xgo_model_t;

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

typedef struct xgo_trace_event_s {
    xgo_trace_kind_t kind;
    xgo_drop_reason_t reason;  /* XGO_DROP_NONE unless kind == XGO_TRACE_DROP */
    const xgo_frame_t *frame;  /* the frame, when one was parsed (else NULL) */
    const uint8_t *raw;        /* for parser drops: the rejected bytes */
    size_t raw_len;
    uint8_t unmapped;          /* RX write: bytes for addresses the Mini lacks */
} xgo_trace_event_t;

typedef void (*xgo_trace_fn)(void *ctx, const xgo_trace_event_t *event);

typedef struct xgo_board_s {
    xgo_board_config_t config;
    xgo_parser_t parser;
    xgo_regs_t regs;
    uint8_t tx[XGO_TX_BUFFER_SIZE]; /* ring buffer of reply bytes */
    uint16_t tx_head;               /* index of the oldest byte */
    uint16_t tx_len;
    uint32_t tx_overflows;
    uint32_t ticks;
    xgo_motion_t motion;
    xgo_trace_fn trace;
    void *trace_ctx;
} xgo_board_t;

/* Fills cfg with the defaults: Mini, 20 ms parser timeout, battery 100 %. */
void xgo_board_default_config(xgo_board_config_t *cfg);

/* cfg may be NULL for the defaults. */
void xgo_board_init(xgo_board_t *b, const xgo_board_config_t *cfg);

/* Optional observer of every frame in and out and of every drop. */
void xgo_board_set_trace(xgo_board_t *b, xgo_trace_fn fn, void *ctx);

/* Bytes from the host that arrived at now_ms. Requests are applied and
 * answered at once (replies go to the transmit buffer). */
void xgo_board_receive(xgo_board_t *b, const uint8_t *bytes, size_t n, uint32_t now_ms);

/* Apply the parser's silence timeout at now_ms. */
void xgo_board_poll(xgo_board_t *b, uint32_t now_ms);

/* Move up to max queued reply bytes into out; returns how many. */
size_t xgo_board_transmit(xgo_board_t *b, uint8_t *out, size_t max);

/* Reply bytes waiting. */
size_t xgo_board_tx_pending(const xgo_board_t *b);

/* Advance one control period (1 / XGO_TICK_HZ s). */
void xgo_board_tick(xgo_board_t *b);

/* The ground under the robot tilts by roll/pitch (an emulator input: the
 * IMU reads the tilt; self-stabilisation, 0x61 = 1, levels the body). */
void xgo_board_set_ground_tilt(xgo_board_t *b, int32_t roll_mdeg, int32_t pitch_mdeg);

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
