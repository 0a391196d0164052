/*
 * replay.h - xgo-replay's engine: a capture's host->board bytes into a fresh
 * board at their recorded ticks on virtual time, its replies compared with
 * the recorded ones byte for byte (docs/capture.md, docs/testing.md).
 *
 *   streams.c   the two reply streams (recorded, replayed), where each byte
 *               came from, the first difference, the frame around a byte
 *   replay.c    records -> board: settings note, ticks, feeding, hang-ups
 */
#ifndef XGO_REPLAY_H
#define XGO_REPLAY_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "pcap.h"
#include "record.h"
#include "trace.h"
#include "xgo/board.h"

/* A byte stream with where its bytes came from: one chunk per record. */
typedef struct xgo_replay_chunk_s {
    size_t start;          /* offset of its first byte in the stream */
    unsigned long record;  /* capture record number */
    uint64_t t_us;         /* since the capture's first record */
    uint32_t tick;         /* board tick */
} xgo_replay_chunk_t;

typedef struct xgo_replay_stream_s {
    uint8_t *bytes;
    size_t len, cap;
    xgo_replay_chunk_t *chunks;
    size_t chunk_count, chunk_cap;
} xgo_replay_stream_t;

/* ---- streams.c */
int xgo_replay_stream_add(xgo_replay_stream_t *s, const uint8_t *b, size_t n, unsigned long record,
                          uint64_t t_us, uint32_t tick);
void xgo_replay_stream_free(xgo_replay_stream_t *s);
/* The chunk byte `at` came in. */
const xgo_replay_chunk_t *xgo_replay_stream_chunk(const xgo_replay_stream_t *s, size_t at);
/* The reply frame around offset `at`: its number (1-based), start and
 * length; 0 when `at` is in no whole frame. */
int xgo_replay_stream_frame(const xgo_replay_stream_t *s, size_t at, size_t *number, size_t *start,
                            size_t *len);

/* ---- replay.c */
typedef struct xgo_replay_options_s {
    const char *capture;
    const char *record_path; /* --record */
    unsigned record_hz;
    int trace;               /* --trace */
    int profile;             /* -1: the capture's, else xgo_model_t */
    int battery;             /* -1: the capture's */
} xgo_replay_options_t;

typedef struct xgo_replay_s {
    xgo_replay_options_t opts;
    xgo_board_t board;
    int started;
    uint64_t origin_wall_us; /* the first record's time */
    uint32_t ticks;
    xgo_replay_stream_t recorded, replayed;
    size_t compared;         /* bytes equal so far */
    int differs;
    xgo_host_trace_t trace;
    xgo_host_record_t record;
    int recording;           /* record is open */
    unsigned long records;
    char err[1024];
} xgo_replay_t;

/* Runs the whole capture; returns 0 identical, 1 a difference or an
 * unreadable capture (message printed), -1 a file that cannot be written
 * (message in r->err). */
int xgo_replay_run(xgo_replay_t *r, FILE *out);

#endif /* XGO_REPLAY_H */
