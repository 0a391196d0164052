/*
 * trace.h - --trace output: one line per frame on stderr, e.g.
 *
 *     0.512034 rx write 0x30 vx n=1 [FF] vx=FF(+100%)
 *     0.530112 rx read 0x50 servo11 n=12
 *     0.530112 tx reply 0x50 servo11 n=12 [80 80 80 80 80 80 80 80 80 80 80 80]
 *     0.611870 drop bad checksum [55 00 09 02 50 0C 99 00 AA]
 *     0.700201 drop read-only register: write 0x01 battery n=1 [05]
 *     0.750003 rx write 0x90 - n=1 [01] ignored (not on the Mini)
 *
 * The first column is seconds since xgo-emu started (monotonic clock, microseconds);
 * the drop reason is xgo_drop_reason_name().
 */
#ifndef XGO_HOST_TRACE_H
#define XGO_HOST_TRACE_H

#include <stdint.h>
#include <stdio.h>

#include "xgo/board.h"

typedef struct xgo_host_trace_s {
    FILE *out;
    uint64_t origin_us; /* time 0 of the first column */
    uint64_t now_us;    /* the loop updates this before feeding the board */
} xgo_host_trace_t;

void xgo_host_trace_init(xgo_host_trace_t *t, FILE *out, uint64_t origin_us);

/* Formats one event into line (always NUL-terminated, no newline). */
void xgo_host_trace_format(const xgo_host_trace_t *t, const xgo_trace_event_t *ev, char *line,
                           size_t line_size);

/* xgo_trace_fn for xgo_board_set_trace(); ctx is an xgo_host_trace_t. */
void xgo_host_trace_event(void *ctx, const xgo_trace_event_t *ev);

#endif /* XGO_HOST_TRACE_H */
