/*
 * outq.h - reply bytes on their way to the host, each with the earliest
 * time it may leave.
 *
 * Without pacing every byte may leave at once. With --baud-pacing a burst of
 * bytes is scheduled as a segment: byte k of a segment starting at s may
 * leave at s + (k + 1) * 10 / baud seconds, i.e. when its stop bit would
 * have gone out on a real wire. The loop writes whatever is due; the host
 * thus sees replies trickle in at line speed, never early.
 *
 * Fixed capacity: when it is full the loop stops taking replies from the
 * board (and then stops reading requests), so a host that does not read
 * slows itself down instead of losing replies or blocking xgo-emu.
 */
#ifndef XGO_HOST_OUTQ_H
#define XGO_HOST_OUTQ_H

#include <stddef.h>
#include <stdint.h>

#define XGO_HOST_OUTQ_BYTES 16384u
#define XGO_HOST_OUTQ_SEGMENTS 64u

typedef struct xgo_host_segment_s {
    size_t len;           /* bytes in this segment */
    size_t sent;          /* of which already written */
    uint64_t start_us;    /* the line starts sending the first byte here */
    uint32_t bytes_per_s; /* 0: no pacing, all due now */
} xgo_host_segment_t;

typedef struct xgo_host_outq_s {
    uint8_t bytes[XGO_HOST_OUTQ_BYTES]; /* unsent bytes, oldest first */
    size_t len;
    xgo_host_segment_t seg[XGO_HOST_OUTQ_SEGMENTS];
    size_t seg_count;
} xgo_host_outq_t;

void xgo_host_outq_init(xgo_host_outq_t *q);

/* Room for more bytes (0 also when the segment table is full). */
size_t xgo_host_outq_room(const xgo_host_outq_t *q);

/* Appends n <= room bytes as one segment, or to the last one when they
 * follow it without a gap at the same rate; bytes_per_s 0 = unpaced. */
void xgo_host_outq_push(xgo_host_outq_t *q, const uint8_t *bytes, size_t n, uint64_t start_us,
                        uint32_t bytes_per_s);

/* Bytes at the front that may be written at now_us. */
size_t xgo_host_outq_due(const xgo_host_outq_t *q, uint64_t now_us);

/* Time at which the next unsent byte becomes due (now_us or earlier if it is
 * due already); UINT64_MAX when the queue is empty. */
uint64_t xgo_host_outq_next_due_us(const xgo_host_outq_t *q);

/* Drops the first n bytes (they were written). */
void xgo_host_outq_consume(xgo_host_outq_t *q, size_t n);

/* Drops everything (the host went away). Returns how many bytes. */
size_t xgo_host_outq_clear(xgo_host_outq_t *q);

#endif /* XGO_HOST_OUTQ_H */
