/*
 * record.h - reading an `xgo-emu --record` CSV file (columns: docs/view.md)
 * for xgo-plot: the columns the plots need, found by name in the header, one
 * row per line. The whole file must be well formed: the first bad line stops
 * the load with a one-line message (file:line: what), nothing is guessed.
 */
#ifndef XGO_PLOT_RECORD_H
#define XGO_PLOT_RECORD_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "xgo/profile.h"

#define XGO_REC_JOINTS (XGO_LEG_COUNT * XGO_JOINT_COUNT)
#define XGO_REC_MAX_ROWS 2000000u /* 66 min at 500 rows/s; beyond: --from/--to */
#define XGO_REC_MAX_LINE 4096u    /* characters per line, newline included */

typedef struct xgo_rec_row_s {
    double t_ms;
    float joint_deg[XGO_REC_JOINTS];        /* register order 0x50..0x5B */
    float foot_mm[XGO_LEG_COUNT][3];        /* body frame, x fwd, y left, z up */
    float world[3];                         /* x_mm, y_mm, yaw_deg */
    uint8_t contact[XGO_LEG_COUNT];         /* 1 = stance */
} xgo_rec_row_t;

typedef struct xgo_rec_s {
    xgo_rec_row_t *rows; /* oldest first, t_ms never decreasing */
    size_t n;
    size_t cap;
} xgo_rec_t;

/* Keeps the rows with from_ms <= t_ms <= to_ms. Returns 0, or -1 with a
 * message "NAME:LINE: ..." in err (rec then holds nothing). */
int xgo_rec_load(FILE *f, const char *name, double from_ms, double to_ms, xgo_rec_t *rec,
                 char *err, size_t err_size);

void xgo_rec_free(xgo_rec_t *rec);

#endif /* XGO_PLOT_RECORD_H */
