/*
 * svg.h - the little SVG writer xgo-plot draws with: a document, text with
 * XML escaping, lines, rectangles, polylines, and plot areas that map data
 * to pixels with labelled axes. Plain SVG 1.1, no scripts, no external
 * references, so any browser or image viewer opens it.
 */
#ifndef XGO_PLOT_SVG_H
#define XGO_PLOT_SVG_H

#include <stddef.h>
#include <stdio.h>

#define XGO_SVG_MIN_STEP 1.0 /* px: polyline points closer than this are merged */

typedef struct xgo_svg_s {
    FILE *f;
    size_t points;          /* points written in the open polyline */
    double last_x, last_y;  /* the last of them */
    int pending;            /* a point held back (closer than XGO_SVG_MIN_STEP) */
    double pend_x, pend_y;
} xgo_svg_t;

/* A rectangle on the page (px) showing data x0..x1, y0..y1 (y up). */
typedef struct xgo_area_s {
    double x, y, w, h;
    double x0, x1, y0, y1;
} xgo_area_t;

void xgo_svg_begin(xgo_svg_t *s, FILE *f, double width, double height);
void xgo_svg_end(xgo_svg_t *s);

/* Markup as given (callers pass only literal tags and numbers). */
void xgo_svg_raw(xgo_svg_t *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* <text> at (x, y); anchor "start" | "middle" | "end"; text is escaped. */
void xgo_svg_text(xgo_svg_t *s, double x, double y, const char *cls, const char *anchor,
                  const char *text);
void xgo_svg_line(xgo_svg_t *s, double x1, double y1, double x2, double y2, const char *cls);

/* A polyline: begin, any number of points, end (fewer than 2: nothing). */
void xgo_svg_poly_begin(xgo_svg_t *s, const char *cls, const char *color);
void xgo_svg_poly_point(xgo_svg_t *s, double x, double y);
void xgo_svg_poly_end(xgo_svg_t *s);

/* Data -> page coordinates. */
double xgo_area_px(const xgo_area_t *a, double x);
double xgo_area_py(const xgo_area_t *a, double y);

/* Widens a's data ranges so one data unit is as long on both axes
 * (maps, trajectories), keeping the page rectangle. */
void xgo_area_equal_scale(xgo_area_t *a);

/* Frame, grid ticks with numbers, and axis labels (NULL: none). */
#define XGO_AXES_NO_Y 1u /* no ticks on the y axis */
void xgo_svg_axes(xgo_svg_t *s, const xgo_area_t *a, const char *xlabel, const char *ylabel,
                  unsigned flags);

/* A "nice" tick step (1, 2 or 5 times a power of ten) for about n ticks. */
double xgo_nice_step(double range, int n);

#endif /* XGO_PLOT_SVG_H */
