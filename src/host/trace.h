/*
 * trace.h - --trace output: one line per frame on stderr, e.g.
 *
 *     0.512034 rx write 0x30 vx n=1 [FF] vx=FF(+100%)
 *     0.530112 rx read 0x50 servo11 n=12
 *     0.530112 tx reply 0x50 servo11 n=12 [80 80 80 80 80 80 80 80 80 80 80 80]
 *     0.611870 drop bad checksum [55 00 09 02 50 0C 99 00 AA]
 *     0.700201 drop read-only register: write 0x01 battery n=1 [05]
 *     0.750003 rx write 0x90 - n=1 [01] ignored (not on the Mini)
 *     0.801544 drop noise n=86 [68 65 6C 6C 6F 2C 20 74 68 69 73 20 69 73 20 61 ...]
 *
 * The first column is seconds since xgo-emu started (monotonic clock, microseconds);
 * the drop reason is xgo_drop_reason_name().
 *
 * Noise (bytes before any 55 00 header) comes from the board in runs as
 * small as one byte; it is folded into "drop noise" lines, at most one per
 * XGO_HOST_TRACE_NOISE_US (a flood must not drown stderr), each with the
 * number of bytes it covers and the first of them.
 */
#ifndef XGO_HOST_TRACE_H
#define XGO_HOST_TRACE_H

#include <stdint.h>
#include <stdio.h>

#include "xgo/board.h"

#define XGO_HOST_TRACE_NOISE_US 10000u /* at most one noise line per 10 ms */
#define XGO_HOST_TRACE_NOISE_SHOWN 16u /* bytes of it shown */

typedef struct xgo_host_trace_s {
    FILE *out;
    uint64_t origin_us; /* time 0 of the first column */
    uint64_t now_us;    /* the loop updates this before feeding the board */
    /* noise folded but not printed yet */
    uint32_t noise_bytes;
    uint8_t noise_head[XGO_HOST_TRACE_NOISE_SHOWN];
    uint64_t noise_since_us; /* when its first byte came */
    uint64_t noise_line_us;  /* when the last noise line was printed */
    int noise_printed;       /* a noise line was printed before */
    int arm;                 /* the board is a Mini2: name its registers (0x5D servo52) */
} xgo_host_trace_t;

void xgo_host_trace_init(xgo_host_trace_t *t, FILE *out, uint64_t origin_us);

/* Formats one event into line (always NUL-terminated, no newline). */
void xgo_host_trace_format(const xgo_host_trace_t *t, const xgo_trace_event_t *ev, char *line,
                           size_t line_size);

/* xgo_trace_fn for xgo_board_set_trace(); ctx is an xgo_host_trace_t. Noise
 * is folded (printed by xgo_host_trace_tick, or before the next other line). */
void xgo_host_trace_event(void *ctx, const xgo_trace_event_t *ev);

/* Prints the folded noise if XGO_HOST_TRACE_NOISE_US have passed since the
 * last noise line; the loop calls it every turn. */
void xgo_host_trace_tick(xgo_host_trace_t *t, uint64_t now_us);

/* Prints the folded noise now (at exit). */
void xgo_host_trace_flush(xgo_host_trace_t *t);

#endif /* XGO_HOST_TRACE_H */
