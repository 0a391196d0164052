/*
 * view_frames.h - the recent frames for the view: every trace event of the
 * board (frames in and out, drops, writes from the page) kept in a ring,
 * decoded into a --trace line only when a view client is sent it.
 *
 * Noise (bytes without a header, reported a run at a time) is folded into
 * the newest entry while that is noise nobody has been sent yet, as
 * --trace folds it into one line: a flood of garbage takes a few entries,
 * not the whole ring, and the frames around it stay visible.
 *
 * Installed as the board's trace function; it passes every event on to the
 * --trace output too (when that is on), so one board has two observers.
 * Recording an event costs a copy of its bytes, nothing more: the pty's
 * replies are never delayed by decoding for the view. Each entry has room
 * for its rendering as a JSON object (view_state.c fills it once, every
 * client then copies it).
 */
#ifndef XGO_HOST_VIEW_FRAMES_H
#define XGO_HOST_VIEW_FRAMES_H

#include <stddef.h>
#include <stdint.h>

#include "trace.h"
#include "xgo/board.h"

/* Events held; older ones are overwritten (and counted as omitted by a
 * client that had not been sent them yet). */
#define XGO_HOST_VIEW_FRAME_RING 256u
/* Longest decoded line kept for the view, NUL included; longer ones end
 * in "...". */
#define XGO_HOST_VIEW_FRAME_TEXT 512u
/* Room for an entry's JSON object: the text (escaped quotes at most
 * double a few characters) plus the other fields. */
#define XGO_HOST_VIEW_FRAME_JSON 768u

typedef struct xgo_host_view_frame_s {
    uint32_t t_ms;   /* board time (xgo_board_time_ms) when it happened */
    uint8_t kind;    /* xgo_trace_kind_t */
    uint8_t source;  /* XGO_SOURCE_* */
    uint8_t reason;  /* xgo_drop_reason_t */
    uint8_t unmapped;
    uint8_t has_frame;
    uint8_t frame_type;
    uint8_t frame_addr;
    uint8_t frame_len;
    uint8_t frame_data[XGO_FRAME_MAX_DATA];
    uint16_t raw_len;  /* bytes kept in raw */
    uint8_t raw[XGO_FRAME_MAX_LEN];
    uint32_t noise_n;  /* a noise drop: all the bytes folded into it */
    uint16_t json_len; /* 0 until the JSON object below is rendered */
    char json[XGO_HOST_VIEW_FRAME_JSON];
} xgo_host_view_frame_t;

typedef struct xgo_host_view_frames_s {
    xgo_host_view_frame_t ring[XGO_HOST_VIEW_FRAME_RING];
    uint64_t next_seq;               /* sequence number of the next event */
    const xgo_board_t *board;        /* for the time stamp */
    xgo_host_trace_t *trace_out;     /* --trace output, NULL when off */
} xgo_host_view_frames_t;

/* trace_out: events are passed on to it (NULL: --trace is off). */
void xgo_host_view_frames_init(xgo_host_view_frames_t *f, const xgo_board_t *board,
                               xgo_host_trace_t *trace_out);

/* xgo_trace_fn: install with xgo_board_set_trace(board, this, f). */
void xgo_host_view_frames_event(void *ctx, const xgo_trace_event_t *ev);

/* Sequence numbers still held: [oldest, f->next_seq). */
uint64_t xgo_host_view_frames_oldest(const xgo_host_view_frames_t *f);

/* The event with sequence number seq (must be held). */
xgo_host_view_frame_t *xgo_host_view_frames_get(xgo_host_view_frames_t *f, uint64_t seq);

/* Its --trace line without the time column and the rx/tx/drop word,
 * decoded by the --trace formatter into text (at most
 * XGO_HOST_VIEW_FRAME_TEXT bytes; a longer line ends in "..."). */
void xgo_host_view_frame_text(const xgo_host_view_frame_t *e, char *text);

/* "rx", "tx", "drop" and "wire", "view", "cli". */
const char *xgo_host_view_frame_kind_name(uint8_t kind);
const char *xgo_host_view_frame_source_name(uint8_t source);

#endif /* XGO_HOST_VIEW_FRAMES_H */
