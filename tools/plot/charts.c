/* charts.c - the gait diagram, joint angles, world path and foot
 * trajectories of xgo-plot (see charts.h). */
#include "charts.h"

#include <math.h>
#include <stdio.h>

#define MARGIN_L 70.0
#define MARGIN_R 30.0
#define GAIT_ROW 22.0
#define PI 3.14159265358979323846
/* Heights of the charts (they do not depend on the data). */
#define GAIT_HEIGHT (24 + XGO_LEG_COUNT * GAIT_ROW + 36)
#define JOINT_H 80.0
#define JOINT_ROW (JOINT_H + 44)
#define JOINTS_HEIGHT (44 + XGO_LEG_COUNT * JOINT_ROW + 10)
#define PATH_SIDE 440.0
#define PATH_HEIGHT (44 + PATH_SIDE + 50)

static const char *const k_leg_color[XGO_LEG_COUNT] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
static const char *const k_leg_name[XGO_LEG_COUNT] = {"1 LF", "2 RF", "3 RH", "4 LH"};
static const char *const k_joint_name[XGO_JOINT_COUNT] = {"knee (x1)", "hip (x2)", "abduction (x3)"};

/* Time axis over the whole record, in seconds. */
static void time_range(const xgo_rec_t *rec, xgo_area_t *a)
{
    a->x0 = rec->rows[0].t_ms / 1000.0;
    a->x1 = rec->rows[rec->n - 1].t_ms / 1000.0;
    if (a->x1 <= a->x0) {
        a->x1 = a->x0 + 1.0; /* one row: a one-second axis */
    }
}

/* One stance bar, from t0 to t1 (ms); data-* let a test check it. */
static void stance_bar(xgo_svg_t *s, const xgo_area_t *a, unsigned leg, double t0, double t1)
{
    double x0 = xgo_area_px(a, t0 / 1000.0), x1 = xgo_area_px(a, t1 / 1000.0);
    xgo_svg_raw(s,
                "<rect class=\"stance\" data-leg=\"%u\" data-t0-ms=\"%.3f\" data-t1-ms=\"%.3f\" "
                "x=\"%.3f\" y=\"%.2f\" width=\"%.3f\" height=\"%.2f\"/>\n",
                leg + 1u, t0, t1, x0, a->y + leg * GAIT_ROW + 3, x1 - x0, GAIT_ROW - 6);
}

/* Stance = from the first row with contact 1 to the first row after it
 * with contact 0 (or the last row): the contact holds until the next sample. */
static void gait_leg(xgo_svg_t *s, const xgo_area_t *a, const xgo_rec_t *rec, unsigned leg)
{
    size_t i;
    double start = 0;
    int on = 0;
    for (i = 0; i < rec->n; ++i) {
        int c = rec->rows[i].contact[leg];
        if (c && !on) {
            start = rec->rows[i].t_ms;
        } else if (!c && on) {
            stance_bar(s, a, leg, start, rec->rows[i].t_ms);
        }
        on = c;
    }
    if (on) {
        stance_bar(s, a, leg, start, rec->rows[rec->n - 1].t_ms);
    }
}

double xgo_chart_gait(xgo_svg_t *s, const xgo_rec_t *rec, double top)
{
    xgo_area_t a = {MARGIN_L, 0, XGO_PLOT_WIDTH - MARGIN_L - MARGIN_R, XGO_LEG_COUNT * GAIT_ROW,
                    0, 1, 0, XGO_LEG_COUNT};
    unsigned leg;
    a.y = top + 24;
    time_range(rec, &a);
    xgo_svg_text(s, MARGIN_L, top + 14, "heading", "start",
                 "Gait: stance (filled) and swing (empty) per leg, from contact1..4");
    xgo_svg_axes(s, &a, "time (s)", NULL, XGO_AXES_NO_Y);
    xgo_svg_raw(s, "<g id=\"gait\" data-x=\"%.3f\" data-w=\"%.3f\" data-t0-ms=\"%.3f\" "
                   "data-t1-ms=\"%.3f\">\n",
                a.x, a.w, a.x0 * 1000.0, a.x1 * 1000.0);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        xgo_svg_text(s, a.x - 6, a.y + leg * GAIT_ROW + GAIT_ROW / 2 + 4, "label", "end",
                     k_leg_name[leg]);
        gait_leg(s, &a, rec, leg);
    }
    xgo_svg_raw(s, "</g>\n");
    return GAIT_HEIGHT;
}

/* Value v of row r for a time series: a joint angle. */
static double joint_at(const xgo_rec_row_t *r, unsigned k)
{
    return r->joint_deg[k];
}

/* A time series with at most two points per pixel column (the column's
 * minimum and maximum, in time order): the drawing looks the same, the file
 * stays small for long records. */
static void time_series(xgo_svg_t *s, const xgo_area_t *a, const xgo_rec_t *rec, unsigned k,
                        const char *color)
{
    size_t i, lo = 0, hi = 0;
    long column = -1;
    xgo_svg_poly_begin(s, "series", color);
    for (i = 0; i <= rec->n; ++i) {
        long c = i < rec->n ? (long)floor(xgo_area_px(a, rec->rows[i].t_ms / 1000.0)) : -2;
        if (c != column) {
            if (column != -1) { /* flush the finished column */
                size_t first = lo < hi ? lo : hi, second = lo < hi ? hi : lo;
                xgo_svg_poly_point(s, xgo_area_px(a, rec->rows[first].t_ms / 1000.0),
                                   xgo_area_py(a, joint_at(&rec->rows[first], k)));
                if (second != first) {
                    xgo_svg_poly_point(s, xgo_area_px(a, rec->rows[second].t_ms / 1000.0),
                                       xgo_area_py(a, joint_at(&rec->rows[second], k)));
                }
            }
            column = c;
            lo = hi = i;
        } else {
            lo = joint_at(&rec->rows[i], k) < joint_at(&rec->rows[lo], k) ? i : lo;
            hi = joint_at(&rec->rows[i], k) > joint_at(&rec->rows[hi], k) ? i : hi;
        }
    }
    xgo_svg_poly_end(s);
}

static void joint_cell(xgo_svg_t *s, const xgo_rec_t *rec, const xgo_profile_t *p, unsigned k,
                       const xgo_area_t *cell)
{
    xgo_area_t a = *cell;
    unsigned leg = k / XGO_JOINT_COUNT, joint = k % XGO_JOINT_COUNT;
    double lo = p->joint_mdeg[joint].lo / 1000.0, hi = p->joint_mdeg[joint].hi / 1000.0;
    char title[64];
    a.y0 = lo - 0.06 * (hi - lo);
    a.y1 = hi + 0.06 * (hi - lo);
    snprintf(title, sizeof title, "%u  leg %s, %s", XGO_SERVO_ID(leg, joint), k_leg_name[leg],
             k_joint_name[joint]);
    xgo_svg_text(s, a.x, a.y - 5, "label", "start", title);
    xgo_svg_axes(s, &a, leg == XGO_LEG_COUNT - 1 ? "time (s)" : NULL, NULL, 0);
    xgo_svg_line(s, a.x, xgo_area_py(&a, lo), a.x + a.w, xgo_area_py(&a, lo), "limit");
    xgo_svg_line(s, a.x, xgo_area_py(&a, hi), a.x + a.w, xgo_area_py(&a, hi), "limit");
    time_series(s, &a, rec, k, k_leg_color[leg]);
}

double xgo_chart_joints(xgo_svg_t *s, const xgo_rec_t *rec, const xgo_profile_t *p, double top)
{
    const double gap = 50, h = JOINT_H, row = JOINT_ROW;
    double w = (XGO_PLOT_WIDTH - MARGIN_L - MARGIN_R - 2 * gap) / 3;
    unsigned k;
    char heading[128];
    snprintf(heading, sizeof heading,
             "Joint angles (deg) over time, between the %s profile's limits (dashed)", p->name);
    xgo_svg_text(s, MARGIN_L, top + 14, "heading", "start", heading);
    for (k = 0; k < XGO_REC_JOINTS; ++k) {
        xgo_area_t cell = {0, 0, 0, 0, 0, 1, 0, 1};
        cell.x = MARGIN_L + (k % XGO_JOINT_COUNT) * (w + gap);
        cell.y = top + 44 + (k / XGO_JOINT_COUNT) * row;
        cell.w = w;
        cell.h = h;
        time_range(rec, &cell);
        joint_cell(s, rec, p, k, &cell);
    }
    return JOINTS_HEIGHT;
}

/* Data bounds of a point set, padded so a standing robot still gets an area. */
static void bounds(xgo_area_t *a, double x, double y, int first)
{
    if (first) {
        a->x0 = a->x1 = x;
        a->y0 = a->y1 = y;
    }
    a->x0 = x < a->x0 ? x : a->x0;
    a->x1 = x > a->x1 ? x : a->x1;
    a->y0 = y < a->y0 ? y : a->y0;
    a->y1 = y > a->y1 ? y : a->y1;
}

static void pad(xgo_area_t *a, double margin)
{
    a->x0 -= margin;
    a->x1 += margin;
    a->y0 -= margin;
    a->y1 += margin;
    xgo_area_equal_scale(a);
}

/* Every step-th row so a trajectory has at most about 1500 points (a
 * swing still gets 20 or more at 500 rows/s; the file stays small). */
static size_t stride(const xgo_rec_t *rec)
{
    return rec->n / 1500u + 1u;
}

/* Seconds between heading marks: 1, or more so there are at most 60. */
static double mark_every_s(const xgo_rec_t *rec)
{
    double span = rec->rows[rec->n - 1].t_ms - rec->rows[0].t_ms;
    return span > 60000 ? ceil(span / 60000.0) : 1.0;
}

static void heading_marks(xgo_svg_t *s, const xgo_area_t *a, const xgo_rec_t *rec)
{
    double every = 1000 * mark_every_s(rec), next = rec->rows[0].t_ms + every;
    size_t i;
    for (i = 0; i < rec->n; ++i) {
        const xgo_rec_row_t *r = &rec->rows[i];
        double x, y, yaw;
        if (r->t_ms < next) {
            continue;
        }
        next = r->t_ms + every;
        x = xgo_area_px(a, r->world[0]);
        y = xgo_area_py(a, r->world[1]);
        yaw = r->world[2] * PI / 180.0; /* CCW */
        { /* an arrowhead pointing along the heading (page y points down) */
            double cx = cos(yaw), sy = -sin(yaw);
            xgo_svg_raw(s, "<polygon class=\"mark\" points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\"/>\n",
                        x + 10 * cx, y + 10 * sy, x - 5 * cx - 5 * sy, y - 5 * sy + 5 * cx,
                        x - 5 * cx + 5 * sy, y - 5 * sy - 5 * cx);
        }
    }
}

static void path_chart(xgo_svg_t *s, const xgo_rec_t *rec, const xgo_area_t *box)
{
    xgo_area_t a = *box;
    size_t i, step = stride(rec);
    const xgo_rec_row_t *end = &rec->rows[rec->n - 1];
    for (i = 0; i < rec->n; ++i) {
        bounds(&a, rec->rows[i].world[0], rec->rows[i].world[1], i == 0);
    }
    pad(&a, 60);
    xgo_svg_axes(s, &a, "world x (mm)", "world y (mm)", 0);
    xgo_svg_poly_begin(s, "series", "#333");
    for (i = 0; i < rec->n; i += step) {
        xgo_svg_poly_point(s, xgo_area_px(&a, rec->rows[i].world[0]), xgo_area_py(&a, rec->rows[i].world[1]));
    }
    xgo_svg_poly_point(s, xgo_area_px(&a, end->world[0]), xgo_area_py(&a, end->world[1]));
    xgo_svg_poly_end(s);
    heading_marks(s, &a, rec);
    xgo_svg_raw(s, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"5\" fill=\"#2a2\"/>\n",
                xgo_area_px(&a, rec->rows[0].world[0]), xgo_area_py(&a, rec->rows[0].world[1]));
    xgo_svg_raw(s, "<rect x=\"%.2f\" y=\"%.2f\" width=\"9\" height=\"9\" fill=\"#c22\"/>\n",
                xgo_area_px(&a, end->world[0]) - 4.5, xgo_area_py(&a, end->world[1]) - 4.5);
}

/* Feet in the body frame projected on axes u, v (0 x, 1 y, 2 z). */
static void feet_view(xgo_svg_t *s, const xgo_rec_t *rec, const xgo_area_t *box, unsigned u,
                      unsigned v, const char *xlabel, const char *ylabel)
{
    xgo_area_t a = *box;
    size_t i, step = stride(rec);
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (i = 0; i < rec->n; ++i) {
            bounds(&a, rec->rows[i].foot_mm[leg][u], rec->rows[i].foot_mm[leg][v], leg == 0 && i == 0);
        }
    }
    pad(&a, 10);
    xgo_svg_axes(s, &a, xlabel, ylabel, 0);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        xgo_svg_poly_begin(s, "series", k_leg_color[leg]);
        for (i = 0; i < rec->n; i += step) {
            xgo_svg_poly_point(s, xgo_area_px(&a, rec->rows[i].foot_mm[leg][u]),
                               xgo_area_py(&a, rec->rows[i].foot_mm[leg][v]));
        }
        xgo_svg_poly_end(s);
    }
}

static void feet_legend(xgo_svg_t *s, double x, double y)
{
    unsigned leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        xgo_svg_raw(s, "<rect x=\"%.2f\" y=\"%.2f\" width=\"14\" height=\"4\" fill=\"%s\"/>\n",
                    x + leg * 70.0, y - 4, k_leg_color[leg]);
        xgo_svg_text(s, x + leg * 70.0 + 18, y, "label", "start", k_leg_name[leg]);
    }
}

double xgo_charts_height(void)
{
    return GAIT_HEIGHT + JOINTS_HEIGHT + PATH_HEIGHT;
}

double xgo_chart_path_and_feet(xgo_svg_t *s, const xgo_rec_t *rec, double top)
{
    const double side = PATH_SIDE, half = (XGO_PLOT_WIDTH - MARGIN_R) - (MARGIN_L + side + 90);
    xgo_area_t path = {MARGIN_L, 0, side, side, 0, 1, 0, 1};
    xgo_area_t fx = {MARGIN_L + side + 90, 0, half, 180, 0, 1, 0, 1};
    xgo_area_t fy = fx;
    char heading[128];
    path.y = top + 44;
    fx.y = top + 44;
    fy.y = fx.y + fx.h + 80;
    xgo_svg_text(s, MARGIN_L, top + 14, "heading", "start", "World path from above");
    snprintf(heading, sizeof heading, "start: green dot, end: red square, heading every %g s",
             mark_every_s(rec));
    xgo_svg_text(s, MARGIN_L, top + 32, "label", "start", heading);
    path_chart(s, rec, &path);
    xgo_svg_text(s, fx.x, top + 14, "heading", "start", "Feet in the body frame");
    feet_legend(s, fx.x + 190, top + 14);
    xgo_svg_text(s, fx.x, fx.y - 5, "label", "start", "side view");
    feet_view(s, rec, &fx, 0, 2, "x forward (mm)", "z up (mm)");
    xgo_svg_text(s, fy.x, fy.y - 5, "label", "start", "top view");
    feet_view(s, rec, &fy, 0, 1, "x forward (mm)", "y left (mm)");
    return PATH_HEIGHT;
}
