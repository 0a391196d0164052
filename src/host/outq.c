/* outq.c - paced output queue (see outq.h). */
#include "outq.h"

#include <string.h>

void xgo_host_outq_init(xgo_host_outq_t *q)
{
    q->len = 0;
    q->seg_count = 0;
}

size_t xgo_host_outq_room(const xgo_host_outq_t *q)
{
    if (q->seg_count == XGO_HOST_OUTQ_SEGMENTS) {
        return 0;
    }
    return XGO_HOST_OUTQ_BYTES - q->len;
}

/* Does a push starting at start_us continue segment s without a gap? Then
 * it joins s: replies handed over a few bytes at a time (the device's
 * chunks) take one segment, not one each. Paced: it starts no later than
 * s's last byte leaves (1 us of rounding allowed). */
static int xgo_host_outq_continues(const xgo_host_segment_t *s, uint64_t start_us,
                                   uint32_t bytes_per_s)
{
    if (s->bytes_per_s != bytes_per_s) {
        return 0;
    }
    return bytes_per_s == 0 ||
           start_us <= s->start_us + (uint64_t)s->len * 1000000u / bytes_per_s + 1u;
}

void xgo_host_outq_push(xgo_host_outq_t *q, const uint8_t *bytes, size_t n, uint64_t start_us,
                        uint32_t bytes_per_s)
{
    xgo_host_segment_t *s;
    if (n == 0 || n > xgo_host_outq_room(q)) {
        return; /* callers check room first; refusing beats corrupting */
    }
    memcpy(q->bytes + q->len, bytes, n);
    q->len += n;
    if (q->seg_count > 0 &&
        xgo_host_outq_continues(&q->seg[q->seg_count - 1], start_us, bytes_per_s)) {
        q->seg[q->seg_count - 1].len += n;
        return;
    }
    s = &q->seg[q->seg_count++];
    s->len = n;
    s->sent = 0;
    s->start_us = start_us;
    s->bytes_per_s = bytes_per_s;
}

/* Bytes of segment s whose stop bit has gone out by now_us. */
static size_t xgo_host_segment_on_wire(const xgo_host_segment_t *s, uint64_t now_us)
{
    uint64_t n;
    if (s->bytes_per_s == 0) {
        return s->len;
    }
    if (now_us <= s->start_us) {
        return 0;
    }
    n = (now_us - s->start_us) * s->bytes_per_s / 1000000u;
    return n < s->len ? (size_t)n : s->len;
}

size_t xgo_host_outq_due(const xgo_host_outq_t *q, uint64_t now_us)
{
    size_t due = 0;
    size_t i;
    /* Later segments never start before earlier ones end, but summing over
     * all of them costs nothing and does not rely on that. */
    for (i = 0; i < q->seg_count; i++) {
        const xgo_host_segment_t *s = &q->seg[i];
        size_t on_wire = xgo_host_segment_on_wire(s, now_us);
        due += on_wire - s->sent;
        if (on_wire < s->len) {
            break; /* bytes behind a not-yet-due byte must wait for it */
        }
    }
    return due;
}

uint64_t xgo_host_outq_next_due_us(const xgo_host_outq_t *q)
{
    const xgo_host_segment_t *s;
    uint64_t k;
    if (q->seg_count == 0) {
        return UINT64_MAX;
    }
    s = &q->seg[0];
    if (s->bytes_per_s == 0) {
        return 0;
    }
    /* Byte index `sent` (0-based) is due at start + (sent + 1) / rate,
     * rounded up so that waking at this time finds it due. */
    k = (uint64_t)(s->sent + 1);
    return s->start_us + (k * 1000000u + s->bytes_per_s - 1) / s->bytes_per_s;
}

void xgo_host_outq_consume(xgo_host_outq_t *q, size_t n)
{
    if (n > q->len) {
        n = q->len;
    }
    memmove(q->bytes, q->bytes + n, q->len - n);
    q->len -= n;
    while (n > 0 && q->seg_count > 0) {
        xgo_host_segment_t *s = &q->seg[0];
        size_t left = s->len - s->sent;
        size_t take = n < left ? n : left;
        s->sent += take;
        n -= take;
        if (s->sent == s->len) {
            memmove(&q->seg[0], &q->seg[1], (q->seg_count - 1) * sizeof q->seg[0]);
            q->seg_count--;
        }
    }
}

size_t xgo_host_outq_clear(xgo_host_outq_t *q)
{
    size_t dropped = q->len;
    q->len = 0;
    q->seg_count = 0;
    return dropped;
}
