/* tracer.c - frames of a byte stream as --trace lines (see tracer.h). */
#include "tracer.h"

#include <string.h>

#include "xgo/regs.h"

static void xgo_cli_tracer_emit(xgo_cli_tracer_t *t, const xgo_trace_event_t *ev)
{
    char line[4096];
    if (t->json == NULL) {
        xgo_host_trace_event(t->trace, ev);
        return;
    }
    xgo_host_trace_format(t->trace, ev, line, sizeof line);
    xgo_host_json_string(t->json, line);
}

/* Bytes of a write frame for addresses the board lacks (--trace says so). */
static uint8_t xgo_cli_unmapped(const xgo_frame_t *f)
{
    unsigned i, n = 0;
    if (f->type == XGO_TYPE_READ || f->type == XGO_TYPE_READ_REPLY) {
        return 0;
    }
    for (i = 0; i < f->len; i++) {
        n += xgo_reg_find((uint8_t)(f->addr + i)) == NULL;
    }
    return (uint8_t)n;
}

static void xgo_cli_tracer_on_frame(void *ctx, const xgo_frame_t *f)
{
    xgo_cli_tracer_t *t = ctx;
    xgo_trace_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = f->type == XGO_TYPE_READ_REPLY ? XGO_TRACE_TX : XGO_TRACE_RX;
    ev.source = XGO_SOURCE_WIRE;
    ev.reason = XGO_DROP_NONE;
    ev.frame = f;
    ev.unmapped = xgo_cli_unmapped(f);
    t->frames++;
    t->replies += f->type == XGO_TYPE_READ_REPLY;
    xgo_cli_tracer_emit(t, &ev);
}

static void xgo_cli_tracer_on_drop(void *ctx, xgo_drop_reason_t why, const uint8_t *b, size_t n)
{
    xgo_cli_tracer_t *t = ctx;
    xgo_trace_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = XGO_TRACE_DROP;
    ev.source = XGO_SOURCE_WIRE;
    ev.reason = why;
    ev.raw = b;
    ev.raw_len = n;
    t->drops++;
    xgo_cli_tracer_emit(t, &ev);
}

void xgo_cli_tracer_init(xgo_cli_tracer_t *t, xgo_parser_side_t side, xgo_host_trace_t *trace,
                         xgo_host_json_t *json)
{
    xgo_parser_sink_t sink;
    memset(t, 0, sizeof *t);
    t->trace = trace;
    t->json = json;
    sink.on_frame = xgo_cli_tracer_on_frame;
    sink.on_drop = xgo_cli_tracer_on_drop;
    sink.ctx = t;
    xgo_parser_init_side(&t->parser, &sink, XGO_PARSER_DEFAULT_TIMEOUT_MS, side);
}

void xgo_cli_tracer_feed(xgo_cli_tracer_t *t, const uint8_t *bytes, size_t n, uint64_t t_us)
{
    t->trace->now_us = t_us;
    xgo_parser_feed(&t->parser, bytes, n, (uint32_t)(t_us / 1000u));
}

void xgo_cli_tracer_finish(xgo_cli_tracer_t *t)
{
    /* as if the line went quiet: a partial frame times out */
    xgo_parser_poll(&t->parser, t->parser.last_rx_ms + XGO_PARSER_DEFAULT_TIMEOUT_MS + 1u);
    if (t->json == NULL) {
        xgo_host_trace_flush(t->trace);
    }
}
