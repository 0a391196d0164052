/* view_frames.c - recent trace events for the view (see view_frames.h). */
#include "view_frames.h"

#include <string.h>

void xgo_host_view_frames_init(xgo_host_view_frames_t *f, const xgo_board_t *board,
                               xgo_host_trace_t *trace_out)
{
    f->next_seq = 0;
    f->board = board;
    f->trace_out = trace_out;
}

/* Copies what the event points at: the pointers die with the callback. */
static void xgo_host_view_frames_copy(xgo_host_view_frame_t *e, const xgo_trace_event_t *ev)
{
    e->kind = (uint8_t)ev->kind;
    e->source = ev->source;
    e->reason = (uint8_t)ev->reason;
    e->unmapped = ev->unmapped;
    e->has_frame = ev->frame != NULL;
    e->frame_len = 0;
    if (ev->frame != NULL) {
        size_t n = ev->frame->type == XGO_TYPE_READ ? 1u : ev->frame->len;
        e->frame_type = ev->frame->type;
        e->frame_addr = ev->frame->addr;
        e->frame_len = ev->frame->len;
        memcpy(e->frame_data, ev->frame->data, n < sizeof e->frame_data ? n : sizeof e->frame_data);
    }
    e->raw_len = 0;
    if (ev->raw != NULL) {
        e->raw_len = (uint16_t)(ev->raw_len < sizeof e->raw ? ev->raw_len : sizeof e->raw);
        memcpy(e->raw, ev->raw, e->raw_len);
    }
    e->json_len = 0;
}

static int xgo_host_view_is_noise(uint8_t kind, uint8_t reason)
{
    return kind == XGO_TRACE_DROP && reason == XGO_DROP_NOISE;
}

/* More noise onto an unsent noise entry: the count grows, the first bytes
 * stay (they are what the line shows). */
static int xgo_host_view_frames_fold(xgo_host_view_frames_t *f, const xgo_trace_event_t *ev)
{
    xgo_host_view_frame_t *last;
    size_t room, take;
    if (f->next_seq == 0 || !xgo_host_view_is_noise((uint8_t)ev->kind, (uint8_t)ev->reason)) {
        return 0;
    }
    last = &f->ring[(f->next_seq - 1) % XGO_HOST_VIEW_FRAME_RING];
    if (!xgo_host_view_is_noise(last->kind, last->reason) || last->json_len != 0) {
        return 0;
    }
    room = sizeof last->raw - last->raw_len;
    take = ev->raw_len < room ? ev->raw_len : room;
    memcpy(last->raw + last->raw_len, ev->raw, take);
    last->raw_len = (uint16_t)(last->raw_len + take);
    last->noise_n += (uint32_t)ev->raw_len;
    return 1;
}

void xgo_host_view_frames_event(void *ctx, const xgo_trace_event_t *ev)
{
    xgo_host_view_frames_t *f = ctx;
    xgo_host_view_frame_t *e = &f->ring[f->next_seq % XGO_HOST_VIEW_FRAME_RING];
    if (f->trace_out != NULL) {
        xgo_host_trace_event(f->trace_out, ev);
    }
    if (xgo_host_view_frames_fold(f, ev)) {
        return;
    }
    e->t_ms = xgo_board_time_ms(f->board);
    xgo_host_view_frames_copy(e, ev);
    e->noise_n = (uint32_t)ev->raw_len;
    f->next_seq++;
}

uint64_t xgo_host_view_frames_oldest(const xgo_host_view_frames_t *f)
{
    return f->next_seq > XGO_HOST_VIEW_FRAME_RING ? f->next_seq - XGO_HOST_VIEW_FRAME_RING : 0;
}

void xgo_host_view_frame_text(const xgo_host_view_frame_t *e, char *text)
{
    static const char k_more[] = "...";
    char line[4096]; /* a 255-byte frame in hex plus its decoding */
    xgo_trace_event_t ev;
    xgo_frame_t frame;
    xgo_host_trace_t clock; /* the time column is cut off below */
    const char *p = line;
    size_t n;

    memset(&ev, 0, sizeof ev);
    ev.kind = (xgo_trace_kind_t)e->kind;
    ev.source = e->source;
    ev.reason = (xgo_drop_reason_t)e->reason;
    ev.unmapped = e->unmapped;
    if (e->has_frame) {
        frame.type = e->frame_type;
        frame.addr = e->frame_addr;
        frame.len = e->frame_len;
        frame.data = e->frame_data;
        ev.frame = &frame;
    }
    ev.raw = e->raw_len > 0 ? e->raw : NULL;
    /* noise: the whole run's count; the formatter shows the first bytes */
    ev.raw_len = xgo_host_view_is_noise(e->kind, e->reason) ? e->noise_n : e->raw_len;
    xgo_host_trace_init(&clock, NULL, 0);
    xgo_host_trace_format(&clock, &ev, line, sizeof line);
    /* "   1.234567 rx write ..." -> "write ..." (time and kind are fields) */
    p += strspn(p, " ");
    p += strcspn(p, " ");
    p += strspn(p, " ");
    p += strcspn(p, " ");
    p += strspn(p, " ");
    n = strlen(p);
    if (n >= XGO_HOST_VIEW_FRAME_TEXT) {
        n = XGO_HOST_VIEW_FRAME_TEXT - sizeof k_more;
        memcpy(text + n, k_more, sizeof k_more);
    } else {
        text[n] = '\0';
    }
    memcpy(text, p, n);
}

xgo_host_view_frame_t *xgo_host_view_frames_get(xgo_host_view_frames_t *f, uint64_t seq)
{
    return &f->ring[seq % XGO_HOST_VIEW_FRAME_RING];
}

const char *xgo_host_view_frame_kind_name(uint8_t kind)
{
    switch (kind) {
    case XGO_TRACE_RX:
        return "rx";
    case XGO_TRACE_TX:
        return "tx";
    default:
        return "drop";
    }
}

const char *xgo_host_view_frame_source_name(uint8_t source)
{
    switch (source) {
    case XGO_SOURCE_VIEW:
        return "view";
    case XGO_SOURCE_CLI:
        return "cli";
    default:
        return "wire";
    }
}
