/* svg.c - SVG output for xgo-plot (see svg.h). Numbers are written with
 * %.2f: hundredths of a pixel are below anything a viewer shows. */
#include "svg.h"

#include <math.h>
#include <stdarg.h>

void xgo_svg_begin(xgo_svg_t *s, FILE *f, double width, double height)
{
    s->f = f;
    s->points = 0;
    s->pending = 0;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%.0f\" "
               "height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" "
               "font-size=\"11\">\n",
            width, height, width, height);
    fprintf(f, "<style>\n"
               ".frame{fill:#fff;stroke:#888;stroke-width:1}\n"
               ".grid{stroke:#e4e4e4;stroke-width:1}\n"
               ".tick{fill:#555;font-size:10px}\n"
               ".label{fill:#333;font-size:11px}\n"
               ".title{fill:#111;font-size:15px;font-weight:bold}\n"
               ".heading{fill:#111;font-size:13px;font-weight:bold}\n"
               ".limit{stroke:#d33;stroke-width:1;stroke-dasharray:4 3}\n"
               ".series{fill:none;stroke-width:1.2}\n"
               ".stance{fill:#3a6ea5}\n"
               ".swing{fill:#f2f2f2}\n"
               ".mark{fill:#e07000;stroke:#fff;stroke-width:0.5}\n"
               "</style>\n"
               "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#fafafa\"/>\n",
            width, height);
}

void xgo_svg_end(xgo_svg_t *s)
{
    fprintf(s->f, "</svg>\n");
}

void xgo_svg_raw(xgo_svg_t *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(s->f, fmt, ap);
    va_end(ap);
}

static void escaped(FILE *f, const char *text)
{
    for (; *text; ++text) {
        switch (*text) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default:
            /* control characters are not allowed in XML 1.0 text */
            fputc((unsigned char)*text < 0x20 ? '?' : *text, f);
        }
    }
}

void xgo_svg_text(xgo_svg_t *s, double x, double y, const char *cls, const char *anchor,
                  const char *text)
{
    fprintf(s->f, "<text x=\"%.2f\" y=\"%.2f\" class=\"%s\" text-anchor=\"%s\">", x, y, cls, anchor);
    escaped(s->f, text);
    fputs("</text>\n", s->f);
}

void xgo_svg_line(xgo_svg_t *s, double x1, double y1, double x2, double y2, const char *cls)
{
    fprintf(s->f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" class=\"%s\"/>\n", x1, y1,
            x2, y2, cls);
}

void xgo_svg_poly_begin(xgo_svg_t *s, const char *cls, const char *color)
{
    fprintf(s->f, "<polyline class=\"%s\" stroke=\"%s\" points=\"", cls, color);
    s->points = 0;
    s->pending = 0;
}

static void poly_emit(xgo_svg_t *s, double x, double y)
{
    fprintf(s->f, "%s%.1f,%.1f", s->points ? " " : "", x, y);
    s->points++;
    if (s->points % 10u == 0) {
        fputc('\n', s->f);
    }
    s->last_x = x;
    s->last_y = y;
}

/* Points closer than XGO_SVG_MIN_STEP px to the last one written are held
 * back (the last of them is written when the line turns or ends): the line
 * looks the same and a long record does not make a huge file. */
void xgo_svg_poly_point(xgo_svg_t *s, double x, double y)
{
    if (s->points > 0 && fabs(x - s->last_x) < XGO_SVG_MIN_STEP &&
        fabs(y - s->last_y) < XGO_SVG_MIN_STEP) {
        s->pending = 1;
        s->pend_x = x;
        s->pend_y = y;
        return;
    }
    if (s->pending) {
        poly_emit(s, s->pend_x, s->pend_y);
        s->pending = 0;
    }
    poly_emit(s, x, y);
}

void xgo_svg_poly_end(xgo_svg_t *s)
{
    if (s->pending) {
        poly_emit(s, s->pend_x, s->pend_y);
    }
    fputs("\"/>\n", s->f);
    s->points = 0;
    s->pending = 0;
}

double xgo_area_px(const xgo_area_t *a, double x)
{
    return a->x + (x - a->x0) * a->w / (a->x1 - a->x0);
}

double xgo_area_py(const xgo_area_t *a, double y)
{
    return a->y + a->h - (y - a->y0) * a->h / (a->y1 - a->y0);
}

void xgo_area_equal_scale(xgo_area_t *a)
{
    double sx = (a->x1 - a->x0) / a->w, sy = (a->y1 - a->y0) / a->h; /* data per px */
    double k = sx > sy ? sx : sy;
    double cx = (a->x0 + a->x1) / 2, cy = (a->y0 + a->y1) / 2;
    a->x0 = cx - k * a->w / 2;
    a->x1 = cx + k * a->w / 2;
    a->y0 = cy - k * a->h / 2;
    a->y1 = cy + k * a->h / 2;
}

double xgo_nice_step(double range, int n)
{
    double raw = range / (n > 0 ? n : 1), p, m;
    if (!(raw > 0)) {
        return 1;
    }
    p = pow(10, floor(log10(raw)));
    m = raw / p;
    return p * (m < 1.5 ? 1 : (m < 3.5 ? 2 : (m < 7.5 ? 5 : 10)));
}

static void ticks(xgo_svg_t *s, const xgo_area_t *a, int vertical)
{
    double lo = vertical ? a->y0 : a->x0, hi = vertical ? a->y1 : a->x1;
    double step = xgo_nice_step(hi - lo, vertical ? (a->h > 120 ? 6 : 3) : (int)(a->w / 90) + 1);
    double v;
    char num[32];
    for (v = ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
        double q = fabs(v) < step * 1e-9 ? 0 : v; /* no "-0" */
        snprintf(num, sizeof num, "%g", q);
        if (vertical) {
            double y = xgo_area_py(a, q);
            xgo_svg_line(s, a->x, y, a->x + a->w, y, "grid");
            xgo_svg_text(s, a->x - 4, y + 3.5, "tick", "end", num);
        } else {
            double x = xgo_area_px(a, q);
            xgo_svg_line(s, x, a->y, x, a->y + a->h, "grid");
            xgo_svg_text(s, x, a->y + a->h + 12, "tick", "middle", num);
        }
    }
}

void xgo_svg_axes(xgo_svg_t *s, const xgo_area_t *a, const char *xlabel, const char *ylabel,
                  unsigned flags)
{
    fprintf(s->f, "<rect class=\"frame\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>\n",
            a->x, a->y, a->w, a->h);
    ticks(s, a, 0);
    if (!(flags & XGO_AXES_NO_Y)) {
        ticks(s, a, 1);
    }
    if (xlabel) {
        xgo_svg_text(s, a->x + a->w / 2, a->y + a->h + 26, "label", "middle", xlabel);
    }
    if (ylabel) {
        fprintf(s->f, "<text class=\"label\" text-anchor=\"middle\" transform=\"translate(%.2f %.2f) "
                      "rotate(-90)\">",
                a->x - 34, a->y + a->h / 2);
        escaped(s->f, ylabel);
        fputs("</text>\n", s->f);
    }
}
