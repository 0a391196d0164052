/*
 * streams.c - the reply streams xgo-replay compares (see replay.h): bytes in
 * arrival order with the record each came in, and the frame a byte is part
 * of, found by the core's parser on the host side.
 */
#include <stdlib.h>
#include <string.h>

#include "replay.h"

static int xgo_replay_grow(void **p, size_t *cap, size_t need, size_t size)
{
    size_t n = *cap ? *cap : 1024;
    void *q;
    if (need <= *cap) {
        return 0;
    }
    while (n < need) {
        n *= 2;
    }
    q = realloc(*p, n * size);
    if (q == NULL) {
        return -1;
    }
    *p = q;
    *cap = n;
    return 0;
}

int xgo_replay_stream_add(xgo_replay_stream_t *s, const uint8_t *b, size_t n, unsigned long record,
                          uint64_t t_us, uint32_t tick)
{
    xgo_replay_chunk_t *c;
    if (n == 0) {
        return 0;
    }
    if (xgo_replay_grow((void **)&s->bytes, &s->cap, s->len + n, 1) != 0 ||
        xgo_replay_grow((void **)&s->chunks, &s->chunk_cap, s->chunk_count + 1, sizeof *s->chunks) != 0) {
        return -1;
    }
    c = &s->chunks[s->chunk_count++];
    c->start = s->len;
    c->record = record;
    c->t_us = t_us;
    c->tick = tick;
    memcpy(s->bytes + s->len, b, n);
    s->len += n;
    return 0;
}

void xgo_replay_stream_free(xgo_replay_stream_t *s)
{
    free(s->bytes);
    free(s->chunks);
    memset(s, 0, sizeof *s);
}

const xgo_replay_chunk_t *xgo_replay_stream_chunk(const xgo_replay_stream_t *s, size_t at)
{
    size_t lo = 0, hi = s->chunk_count;
    if (s->chunk_count == 0) {
        return NULL;
    }
    while (hi - lo > 1) { /* the last chunk starting at or before `at` */
        size_t mid = (lo + hi) / 2;
        if (s->chunks[mid].start <= at) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return &s->chunks[lo];
}

typedef struct xgo_replay_finder_s {
    size_t pos;   /* offset of the byte just fed */
    size_t at;    /* the byte looked for */
    size_t count; /* frames so far */
    int found;
    size_t number, start, len;
} xgo_replay_finder_t;

static void xgo_replay_on_frame(void *ctx, const xgo_frame_t *f)
{
    xgo_replay_finder_t *x = ctx;
    size_t len = (size_t)f->len + XGO_FRAME_OVERHEAD;
    size_t start = x->pos + 1 - len;
    x->count++;
    if (!x->found && x->at >= start && x->at <= x->pos) {
        x->found = 1;
        x->number = x->count;
        x->start = start;
        x->len = len;
    }
}

int xgo_replay_stream_frame(const xgo_replay_stream_t *s, size_t at, size_t *number, size_t *start,
                            size_t *len)
{
    xgo_parser_t p;
    xgo_parser_sink_t sink;
    xgo_replay_finder_t x;
    memset(&x, 0, sizeof x);
    memset(&sink, 0, sizeof sink);
    x.at = at;
    sink.on_frame = xgo_replay_on_frame;
    sink.ctx = &x;
    xgo_parser_init_side(&p, &sink, 0, XGO_PARSER_HOST);
    /* byte by byte: a frame ends at the byte that completes it */
    for (x.pos = 0; x.pos < s->len && !x.found && x.pos <= at + XGO_FRAME_MAX_LEN; x.pos++) {
        xgo_parser_feed(&p, s->bytes + x.pos, 1, 0);
    }
    if (!x.found) {
        *number = x.count + 1; /* the frame that would come next */
        return 0;
    }
    *number = x.number;
    *start = x.start;
    *len = x.len;
    return 1;
}
