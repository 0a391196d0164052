/*
 * record.h - xgo-emu --record FILE.csv: the motion log. One CSV row per
 * control tick (or --record-hz rows a second) with the numbers of the view's
 * state object: time, mode, action, the 12 joints, the 4 feet, contacts,
 * body pose, world pose, IMU, battery, commanded and produced speed. The
 * header line names the columns (docs/view.md); xgo-plot reads the file.
 *
 * A service of the event loop (after_tick): rows go through a stdio buffer,
 * so recording costs a formatted line per row and a write per 64 KiB.
 */
#ifndef XGO_HOST_RECORD_H
#define XGO_HOST_RECORD_H

#include <stdio.h>

#include "loop.h"
#include "xgo/board.h"

typedef struct xgo_host_record_s {
    FILE *file;
    const char *path;
    const xgo_board_t *board;
    unsigned hz;        /* rows a second; XGO_TICK_HZ = every tick */
    unsigned acc;       /* row pacing: += hz per tick, a row at XGO_TICK_HZ */
    unsigned long rows;
    int failed;         /* a write failed: reported once, recording stopped */
    xgo_host_service_t service;
    char buffer[65536]; /* stdio buffer */
} xgo_host_record_t;

/* Creates (or truncates) path and writes the header line. hz: rows a
 * second, 0 = every tick. Returns 0, or -1 with a one-line message in err. */
int xgo_host_record_open(xgo_host_record_t *r, const char *path, unsigned hz,
                         const xgo_board_t *board, char *err, size_t err_size);

/* Writes a row now (the loop calls it after every tick, through r->service). */
void xgo_host_record_tick(void *ctx);

/* Flushes and closes; returns 0, or -1 (message on `out`) if any write
 * failed, now or earlier. */
int xgo_host_record_close(xgo_host_record_t *r, FILE *out);

#endif /* XGO_HOST_RECORD_H */
