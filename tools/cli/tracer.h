/*
 * tracer.h - bytes -> frames -> --trace lines, for xgo-cli raw and decode:
 * the core's parser on the chosen side, events formatted by the host's
 * trace formatter (src/host/trace.c), so offline decoding reads exactly like
 * xgo-emu --trace. With JSON, one object per line goes into an array.
 */
#ifndef XGO_CLI_TRACER_H
#define XGO_CLI_TRACER_H

#include <stdio.h>

#include "json_out.h"
#include "trace.h"
#include "xgo/protocol.h"

typedef struct xgo_cli_tracer_s {
    xgo_parser_t parser;
    xgo_host_trace_t *trace; /* shared by the tracers of one output */
    xgo_host_json_t *json;   /* NULL: lines on trace->out */
    unsigned long frames;
    unsigned long replies;
    unsigned long drops;
} xgo_cli_tracer_t;

void xgo_cli_tracer_init(xgo_cli_tracer_t *t, xgo_parser_side_t side, xgo_host_trace_t *trace,
                         xgo_host_json_t *json);

/* Bytes seen at t_us (the trace's clock). */
void xgo_cli_tracer_feed(xgo_cli_tracer_t *t, const uint8_t *bytes, size_t n, uint64_t t_us);

/* The end of the stream: a partial frame left over is reported. */
void xgo_cli_tracer_finish(xgo_cli_tracer_t *t);

#endif /* XGO_CLI_TRACER_H */
