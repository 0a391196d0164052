/* record.c - the xgo-emu --record CSV reader (see record.h). */
#include "record.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define XGO_REC_MAX_FIELDS 128u

/* The columns xgo-plot reads, in this order. */
enum {
    COL_T = 0,
    COL_JOINT = 1,
    COL_FOOT = COL_JOINT + XGO_REC_JOINTS,
    COL_CONTACT = COL_FOOT + XGO_LEG_COUNT * 3,
    COL_WORLD = COL_CONTACT + XGO_LEG_COUNT,
    COL_COUNT = COL_WORLD + 3
};

/* Header name of column c: "t_ms", "j11_deg" (servo ids from profile.h),
 * "foot1_x_mm", "contact1", "world_x_mm". */
static void column_name(unsigned c, char *out, size_t size)
{
    static const char *const world[3] = {"world_x_mm", "world_y_mm", "world_yaw_deg"};
    if (c == COL_T) {
        snprintf(out, size, "t_ms");
    } else if (c < COL_FOOT) {
        unsigned k = c - COL_JOINT;
        snprintf(out, size, "j%u_deg", XGO_SERVO_ID(k / XGO_JOINT_COUNT, k % XGO_JOINT_COUNT));
    } else if (c < COL_CONTACT) {
        unsigned k = c - COL_FOOT;
        snprintf(out, size, "foot%u_%c_mm", k / 3u + 1u, "xyz"[k % 3u]);
    } else if (c < COL_WORLD) {
        snprintf(out, size, "contact%u", c - COL_CONTACT + 1u);
    } else {
        snprintf(out, size, "%s", world[c - COL_WORLD]);
    }
}

typedef struct reader_s {
    const char *name;
    unsigned long line;
    char *err;
    size_t err_size;
    char *field[XGO_REC_MAX_FIELDS];
    const char *header[XGO_REC_MAX_FIELDS]; /* column names (the header line stays) */
    unsigned nfields;
    unsigned header_fields;
    unsigned col[COL_COUNT]; /* field index of each column */
} reader_t;

static int fail(reader_t *r, const char *what, const char *detail)
{
    snprintf(r->err, r->err_size, "%s:%lu: %s%s", r->name, r->line, what, detail ? detail : "");
    return -1;
}

/* Splits line (newline already removed) at commas, in place. */
static int split(reader_t *r, char *line)
{
    r->nfields = 0;
    for (;;) {
        char *comma = strchr(line, ',');
        if (r->nfields == XGO_REC_MAX_FIELDS) {
            return fail(r, "more than 128 fields", NULL);
        }
        r->field[r->nfields++] = line;
        if (comma == NULL) {
            return 0;
        }
        *comma = '\0';
        line = comma + 1;
    }
}

static int parse_header(reader_t *r, char *line)
{
    unsigned c, i;
    char want[32];
    if (split(r, line) != 0) {
        return -1;
    }
    r->header_fields = r->nfields;
    for (i = 0; i < r->nfields; ++i) {
        r->header[i] = r->field[i];
    }
    for (c = 0; c < COL_COUNT; ++c) {
        unsigned found = 0;
        column_name(c, want, sizeof want);
        for (i = 0; i < r->nfields; ++i) {
            if (strcmp(r->field[i], want) == 0) {
                r->col[c] = i;
                found++;
            }
        }
        if (found != 1) {
            char detail[80];
            snprintf(detail, sizeof detail, "'%s' (not an xgo-emu --record header?)", want);
            return fail(r, found ? "header repeats column " : "header has no column ", detail);
        }
    }
    return 0;
}

/* A whole field as a finite number: no blanks, no trailing characters. */
static int number(const char *text, double *out)
{
    char *end = NULL;
    if (text[0] == '\0' || text[0] == ' ' || text[0] == '\t') {
        return 0;
    }
    errno = 0;
    *out = strtod(text, &end);
    return errno == 0 && *end == '\0' && isfinite(*out);
}

/* Column c of a row whose fields all passed number(). */
static double value_of(const reader_t *r, unsigned c)
{
    return strtod(r->field[r->col[c]], NULL);
}

static int parse_row(reader_t *r, char *line, xgo_rec_row_t *row)
{
    unsigned i, c;
    double v;
    if (split(r, line) != 0) {
        return -1;
    }
    if (r->nfields != r->header_fields) {
        char detail[64];
        snprintf(detail, sizeof detail, "%u fields, the header has %u", r->nfields, r->header_fields);
        return fail(r, detail, NULL);
    }
    for (i = 0; i < r->nfields; ++i) { /* every field is a number, used or not */
        if (!number(r->field[i], &v)) {
            char detail[128];
            snprintf(detail, sizeof detail, "column %u (%.32s) is not a number: '%.40s'", i + 1u,
                     r->header[i], r->field[i]);
            return fail(r, detail, NULL);
        }
    }
    for (c = 0; c < COL_COUNT; ++c) {
        v = value_of(r, c);
        if (c == COL_T) {
            row->t_ms = v;
        } else if (c < COL_FOOT) {
            row->joint_deg[c - COL_JOINT] = (float)v;
        } else if (c < COL_CONTACT) {
            row->foot_mm[(c - COL_FOOT) / 3u][(c - COL_FOOT) % 3u] = (float)v;
        } else if (c < COL_WORLD) {
            if (v != 0.0 && v != 1.0) {
                return fail(r, "a contact column is neither 0 nor 1", NULL);
            }
            row->contact[c - COL_CONTACT] = (uint8_t)v;
        } else {
            row->world[c - COL_WORLD] = (float)v;
        }
    }
    return 0;
}

static int append(reader_t *r, xgo_rec_t *rec, const xgo_rec_row_t *row)
{
    if (rec->n > 0 && row->t_ms < rec->rows[rec->n - 1].t_ms) {
        return fail(r, "t_ms goes back in time", NULL);
    }
    if (rec->n == XGO_REC_MAX_ROWS) {
        return fail(r, "more than 2000000 rows: plot a part of it with --from/--to", NULL);
    }
    if (rec->n == rec->cap) {
        size_t cap = rec->cap ? 2u * rec->cap : 4096u;
        xgo_rec_row_t *rows = realloc(rec->rows, cap * sizeof *rows);
        if (rows == NULL) {
            return fail(r, "out of memory", NULL);
        }
        rec->rows = rows;
        rec->cap = cap;
    }
    rec->rows[rec->n++] = *row;
    return 0;
}

/* Reads one line into buf without its line end. 1: a line, 0: end of file,
 * -1: error (too long). */
static int read_line(reader_t *r, FILE *f, char *buf, size_t size)
{
    size_t len;
    if (fgets(buf, (int)size, f) == NULL) {
        return 0;
    }
    r->line++;
    len = strlen(buf);
    if (len > 0 && buf[len - 1] == '\n') {
        buf[--len] = '\0';
    } else if (!feof(f)) {
        return fail(r, "line longer than 4096 characters", NULL);
    }
    if (len > 0 && buf[len - 1] == '\r') {
        buf[--len] = '\0';
    }
    return 1;
}

static int load_rows(reader_t *r, FILE *f, double from_ms, double to_ms, xgo_rec_t *rec)
{
    char buf[XGO_REC_MAX_LINE + 1];
    unsigned long blank = 0;
    xgo_rec_row_t row;
    int got;
    while ((got = read_line(r, f, buf, sizeof buf)) == 1) {
        if (buf[0] == '\0') {
            blank = blank ? blank : r->line;
            continue;
        }
        if (blank) { /* only the end of the file may be blank */
            r->line = blank;
            return fail(r, "empty line", NULL);
        }
        if (parse_row(r, buf, &row) != 0) {
            return -1;
        }
        if (row.t_ms >= from_ms && row.t_ms <= to_ms && append(r, rec, &row) != 0) {
            return -1;
        }
    }
    if (got < 0 || ferror(f)) {
        return got < 0 ? -1 : fail(r, "read error", NULL);
    }
    if (rec->n == 0) {
        r->line = 0;
        snprintf(r->err, r->err_size, "%s: no data rows%s", r->name,
                 (from_ms > -HUGE_VAL || to_ms < HUGE_VAL) ? " between --from and --to" : "");
        return -1;
    }
    return 0;
}

int xgo_rec_load(FILE *f, const char *name, double from_ms, double to_ms, xgo_rec_t *rec,
                 char *err, size_t err_size)
{
    char buf[XGO_REC_MAX_LINE + 1];
    reader_t r;
    int got;
    memset(&r, 0, sizeof r);
    r.name = name;
    r.err = err;
    r.err_size = err_size;
    rec->rows = NULL;
    rec->n = rec->cap = 0;
    got = read_line(&r, f, buf, sizeof buf);
    if (got == 0) {
        snprintf(err, err_size, "%s: empty file (no header line)", name);
    }
    if (got != 1 || parse_header(&r, buf) != 0 || load_rows(&r, f, from_ms, to_ms, rec) != 0) {
        xgo_rec_free(rec);
        return -1;
    }
    return 0;
}

void xgo_rec_free(xgo_rec_t *rec)
{
    free(rec->rows);
    rec->rows = NULL;
    rec->n = rec->cap = 0;
}
