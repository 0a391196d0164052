/*
 * xgo-plot - pictures of a motion record (xgo-emu --record FILE.csv):
 *
 *   xgo-plot FILE.csv -o OUT.svg [--profile mini|lite] [--from S] [--to S]
 *
 * One SVG page: the gait diagram, the 12 joint angles against their limits
 * (the core's profile), the world path from above and the feet in the body
 * frame (docs/view.md, "xgo-plot"). Exit 0 done, 1 bad or unreadable data
 * (one line on stderr: file:line: what), 2 misuse (one line and the usage).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "charts.h"
#include "record.h"
#include "svg.h"
#include "xgo/profile.h"

typedef struct plot_options_s {
    const char *in;
    const char *out;
    const xgo_profile_t *profile;
    double from_ms, to_ms;
} plot_options_t;

static const char k_usage[] =
    "usage: xgo-plot FILE.csv -o OUT.svg [--profile mini|lite] [--from S] [--to S]\n"
    "  FILE.csv          a record written by xgo-emu --record\n"
    "  -o, --output OUT  the SVG to write (- for stdout)\n"
    "  --profile MODEL   joint limits of mini (default) or lite\n"
    "  --from S, --to S  plot only rows with S <= t <= S (seconds)\n"
    "  -h, --help        this text\n";

static int misuse(const char *what, const char *arg)
{
    fprintf(stderr, "xgo-plot: %s%s\n%s", what, arg ? arg : "", k_usage);
    return 2;
}

/* A whole decimal number of seconds, as ms. */
static int parse_seconds(const char *text, double *ms)
{
    char *end = NULL;
    double v;
    errno = 0;
    v = strtod(text, &end);
    if (text[0] == '\0' || errno != 0 || *end != '\0' || !isfinite(v)) {
        return 0;
    }
    *ms = v * 1000.0;
    return 1;
}

/* Returns -1 to go on, else the exit code. */
static int option(plot_options_t *o, const char *opt, const char *value)
{
    if (strcmp(opt, "-o") == 0 || strcmp(opt, "--output") == 0) {
        o->out = value;
        return value[0] ? -1 : misuse("-o needs a file name", NULL);
    }
    if (strcmp(opt, "--profile") == 0) {
        o->profile = strcmp(value, "mini") == 0 ? xgo_profile_mini()
                     : strcmp(value, "lite") == 0 ? xgo_profile_lite() : NULL;
        return o->profile ? -1 : misuse("--profile must be mini or lite, not ", value);
    }
    if (strcmp(opt, "--from") == 0) {
        return parse_seconds(value, &o->from_ms) ? -1 : misuse("--from needs seconds, not ", value);
    }
    if (strcmp(opt, "--to") == 0) {
        return parse_seconds(value, &o->to_ms) ? -1 : misuse("--to needs seconds, not ", value);
    }
    return misuse("unknown option ", opt);
}

static int parse_args(int argc, char **argv, plot_options_t *o)
{
    int i, rc;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(k_usage, stdout);
            return 0;
        }
        if (a[0] == '-' && a[1] != '\0') {
            if (i + 1 == argc) {
                return misuse(a, strcmp(a, "-o") && strcmp(a, "--output") && strcmp(a, "--profile") &&
                                         strcmp(a, "--from") && strcmp(a, "--to")
                                     ? ": unknown option" : " needs a value");
            }
            if ((rc = option(o, a, argv[++i])) >= 0) {
                return rc;
            }
        } else if (o->in == NULL) {
            o->in = a;
        } else {
            return misuse("more than one input file: ", a);
        }
    }
    if (o->in == NULL || o->out == NULL) {
        return misuse(o->in ? "no output: give -o OUT.svg" : "no input file", NULL);
    }
    return o->from_ms <= o->to_ms ? -1 : misuse("--from is after --to", NULL);
}

static void draw(FILE *f, const xgo_rec_t *rec, const plot_options_t *o)
{
    xgo_svg_t s;
    char title[512];
    double top = 50;
    double seconds = (rec->rows[rec->n - 1].t_ms - rec->rows[0].t_ms) / 1000.0;
    xgo_svg_begin(&s, f, XGO_PLOT_WIDTH, top + xgo_charts_height());
    snprintf(title, sizeof title, "%.300s: %.2f s, %lu rows (t = %.3f .. %.3f s), joint limits: %s",
             o->in, seconds, (unsigned long)rec->n, rec->rows[0].t_ms / 1000.0,
             rec->rows[rec->n - 1].t_ms / 1000.0, o->profile->name);
    xgo_svg_text(&s, 20, 30, "title", "start", title);
    top += xgo_chart_gait(&s, rec, top);
    top += xgo_chart_joints(&s, rec, o->profile, top);
    xgo_chart_path_and_feet(&s, rec, top);
    xgo_svg_end(&s);
}

/* Writes OUT through OUT.tmp and a rename, so a failed run leaves no half
 * picture under the real name. */
static int write_svg(const xgo_rec_t *rec, const plot_options_t *o)
{
    char tmp[4096];
    FILE *f;
    int ok;
    if (strcmp(o->out, "-") == 0) {
        draw(stdout, rec, o);
        return fflush(stdout) == 0 ? 0 : (fprintf(stderr, "xgo-plot: write error on stdout\n"), 1);
    }
    if (snprintf(tmp, sizeof tmp, "%s.tmp", o->out) >= (int)sizeof tmp || (f = fopen(tmp, "w")) == NULL) {
        fprintf(stderr, "xgo-plot: cannot write %s: %s\n", o->out, strerror(errno));
        return 1;
    }
    draw(f, rec, o);
    ok = !ferror(f);
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, o->out) != 0) {
        fprintf(stderr, "xgo-plot: cannot write %s: %s\n", o->out, strerror(errno));
        remove(tmp);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    plot_options_t o = {NULL, NULL, NULL, -HUGE_VAL, HUGE_VAL};
    xgo_rec_t rec;
    char err[256];
    FILE *in;
    int rc;
    o.profile = xgo_profile_mini();
    if ((rc = parse_args(argc, argv, &o)) >= 0) {
        return rc;
    }
    if ((in = fopen(o.in, "r")) == NULL) {
        fprintf(stderr, "xgo-plot: cannot open %s: %s\n", o.in, strerror(errno));
        return 1;
    }
    rc = xgo_rec_load(in, o.in, o.from_ms, o.to_ms, &rec, err, sizeof err);
    fclose(in);
    if (rc != 0) {
        fprintf(stderr, "xgo-plot: %s\n", err);
        return 1;
    }
    rc = write_svg(&rec, &o);
    xgo_rec_free(&rec);
    return rc;
}
