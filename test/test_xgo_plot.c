/*
 * test_xgo_plot.c - xgo-plot end to end.
 *
 * The record is made here: a board (xgo/board.h) trots for 3 s and every
 * tick becomes a CSV row in the xgo-emu --record column order (docs/view.md).
 * xgo-plot (XGO_PLOT_PATH, run as a child) turns it into an SVG, which this
 * test parses with its own small XML checker: the file must be well formed,
 * and the gait diagram's stance bars must be exactly the contact intervals
 * of the rows written, placed and sized on the time axis. Bad input gets one
 * line on stderr and exit 1 (bad data) or 2 (misuse), and leaves no output.
 * Last, xgo-emu --record's own file of a trot (a host on the pty) is plotted.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "unity.h"
#include "xgo/board.h"

#ifndef XGO_PLOT_PATH
#error "XGO_PLOT_PATH must name the xgo-plot executable"
#endif
#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define PLOT_TIMEOUT_MS 10000
#define TROT_ROWS 2250u  /* 4.5 s at 500 rows/s */
#define MAX_BARS 64u

static char g_dir[64];
static char g_csv[128];
static char g_svg[128];
static xgo_test_emu_t g_child;

/* ------------------------------------------------------------ the record */

static unsigned char g_contacts[TROT_ROWS]; /* bit leg: stance, per row */
static double g_t_ms[TROT_ROWS];

static void write_header(FILE *f)
{
    unsigned leg, j;
    fputs("t_ms,mode,action", f);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (j = 0; j < XGO_JOINT_COUNT; ++j) {
            fprintf(f, ",j%u%u_deg", leg + 1u, j + 1u);
        }
    }
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        fprintf(f, ",foot%u_x_mm,foot%u_y_mm,foot%u_z_mm", leg + 1u, leg + 1u, leg + 1u);
    }
    fputs(",contact1,contact2,contact3,contact4,body_x_mm,body_y_mm,body_z_mm,body_roll_deg,"
          "body_pitch_deg,body_yaw_deg,world_x_mm,world_y_mm,world_yaw_deg,imu_roll_deg,"
          "imu_pitch_deg,imu_yaw_deg,battery_pct,cmd_vx_mm_s,cmd_vy_mm_s,cmd_vyaw_deg_s,"
          "act_vx_mm_s,act_vy_mm_s,act_vyaw_deg_s\n",
          f);
}

static void write_row(FILE *f, const xgo_board_t *b, unsigned row)
{
    int32_t q[XGO_SERVO_COUNT], rpy[3], cmd[3], act[3];
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t pose;
    xgo_world_pose_t world;
    unsigned k, contacts = xgo_board_contacts(b);
    xgo_board_joints_mdeg(b, q);
    xgo_board_feet_um(b, feet);
    xgo_board_body_pose(b, &pose);
    xgo_board_world_pose(b, &world);
    xgo_board_imu_mdeg(b, rpy);
    xgo_board_velocity(b, cmd, act);
    g_t_ms[row] = xgo_board_time_ms(b);
    g_contacts[row] = (unsigned char)contacts;
    fprintf(f, "%u,%u,%u", (unsigned)xgo_board_time_ms(b), xgo_board_mode(b), xgo_board_action(b));
    for (k = 0; k < XGO_SERVO_COUNT; ++k) {
        fprintf(f, ",%.3f", q[k] / 1000.0);
    }
    for (k = 0; k < XGO_LEG_COUNT; ++k) {
        fprintf(f, ",%.3f,%.3f,%.3f", feet[k].x / 1000.0, feet[k].y / 1000.0, feet[k].z / 1000.0);
    }
    for (k = 0; k < XGO_LEG_COUNT; ++k) {
        fprintf(f, ",%u", (contacts >> k) & 1u);
    }
    fprintf(f, ",%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%u", pose.x_um / 1000.0,
            pose.y_um / 1000.0, pose.z_um / 1000.0, pose.roll_mdeg / 1000.0,
            pose.pitch_mdeg / 1000.0, pose.yaw_mdeg / 1000.0, world.x_um / 1000.0,
            world.y_um / 1000.0, world.yaw_mdeg / 1000.0, rpy[0] / 1000.0, rpy[1] / 1000.0,
            rpy[2] / 1000.0, xgo_board_battery_pct(b));
    fprintf(f, ",%.1f,%.1f,%.2f,%.1f,%.1f,%.2f\n", cmd[0] / 1000.0, cmd[1] / 1000.0, cmd[2] / 1000.0,
            act[0] / 1000.0, act[1] / 1000.0, act[2] / 1000.0);
}

/* 0.2 s standing, 3 s trot at full speed forward, then stop. */
static void record_trot(const char *path)
{
    static xgo_board_t board;
    FILE *f = fopen(path, "w");
    unsigned row;
    uint8_t full = 0xFF, zero = 0x80;
    TEST_ASSERT_NOT_NULL(f);
    xgo_board_init(&board, NULL);
    write_header(f);
    for (row = 0; row < TROT_ROWS; ++row) {
        if (row == 100u) {
            TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_CLI, XGO_REG_VX, &full, 1));
        } else if (row == 1600u) {
            TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_CLI, XGO_REG_VX, &zero, 1));
        }
        xgo_board_tick(&board);
        write_row(f, &board, row);
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

/* ------------------------------------------------------------ XML */

/* What the checker saw: the gait group and the stance bars. */
typedef struct bar_s {
    unsigned leg;
    double x, w, t0, t1;
} bar_t;

typedef struct svg_facts_s {
    unsigned elements, polylines, limit_lines;
    int root_is_svg;
    double gait_x, gait_w, gait_t0, gait_t1;
    int have_gait;
    bar_t bars[XGO_LEG_COUNT][MAX_BARS];
    unsigned nbars[XGO_LEG_COUNT];
} svg_facts_t;

typedef struct xml_s {
    const char *p;
    const char *err; /* first problem found, NULL while well formed */
    char stack[32][32];
    unsigned depth;
} xml_t;

static int name_char(char c, int first)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' ||
           (!first && ((c >= '0' && c <= '9') || c == '-' || c == '.'));
}

/* Reads a name into out; 0 if there is none. */
static int xml_name(xml_t *x, char *out, size_t size)
{
    size_t n = 0;
    if (!name_char(*x->p, 1)) {
        return 0;
    }
    while (name_char(*x->p, 0)) {
        if (n + 1 < size) {
            out[n++] = *x->p;
        }
        x->p++;
    }
    out[n] = '\0';
    return 1;
}

/* An entity after '&': one of the five named ones or a character reference. */
static int xml_entity(const char *p)
{
    static const char *const names[] = {"amp;", "lt;", "gt;", "quot;", "apos;"};
    size_t i;
    for (i = 0; i < 5; ++i) {
        if (strncmp(p, names[i], strlen(names[i])) == 0) {
            return 1;
        }
    }
    if (*p++ != '#') {
        return 0;
    }
    if (*p == 'x') {
        p++;
    }
    if (*p == ';') {
        return 0;
    }
    while ((*p >= '0' && *p <= '9') || (*p >= 'a' && *p <= 'f') || (*p >= 'A' && *p <= 'F')) {
        p++;
    }
    return *p == ';';
}

static void xml_fail(xml_t *x, const char *why)
{
    if (x->err == NULL) {
        x->err = why;
    }
}

static void skip_space(xml_t *x)
{
    while (*x->p == ' ' || *x->p == '\n' || *x->p == '\t' || *x->p == '\r') {
        x->p++;
    }
}

/* Attribute value after '=': quoted, no '<', entities valid. Copies it. */
static void xml_value(xml_t *x, char *out, size_t size)
{
    char q = *x->p;
    size_t n = 0;
    if (q != '"' && q != '\'') {
        xml_fail(x, "unquoted attribute value");
        return;
    }
    for (x->p++; *x->p != q; x->p++) {
        if (*x->p == '\0' || *x->p == '<' || (*x->p == '&' && !xml_entity(x->p + 1))) {
            xml_fail(x, "bad character in an attribute value");
            return;
        }
        if (n + 1 < size) {
            out[n++] = *x->p;
        }
    }
    out[n] = '\0';
    x->p++;
}

static double attr_num(const char *v)
{
    return strtod(v, NULL);
}

/* Records the facts of one start tag (attribute names and values). */
static void note_attr(svg_facts_t *f, const char *tag, const char *cls, const char *name,
                      const char *value, bar_t *bar)
{
    if (strcmp(tag, "g") == 0 && strcmp(name, "data-x") == 0) {
        f->gait_x = attr_num(value), f->have_gait = 1;
    } else if (strcmp(tag, "g") == 0 && strcmp(name, "data-w") == 0) {
        f->gait_w = attr_num(value);
    } else if (strcmp(tag, "g") == 0 && strcmp(name, "data-t0-ms") == 0) {
        f->gait_t0 = attr_num(value);
    } else if (strcmp(tag, "g") == 0 && strcmp(name, "data-t1-ms") == 0) {
        f->gait_t1 = attr_num(value);
    } else if (strcmp(cls, "stance") == 0) {
        if (strcmp(name, "data-leg") == 0) {
            bar->leg = (unsigned)atoi(value);
        } else if (strcmp(name, "x") == 0) {
            bar->x = attr_num(value);
        } else if (strcmp(name, "width") == 0) {
            bar->w = attr_num(value);
        } else if (strcmp(name, "data-t0-ms") == 0) {
            bar->t0 = attr_num(value);
        } else if (strcmp(name, "data-t1-ms") == 0) {
            bar->t1 = attr_num(value);
        }
    }
}

static void note_element(svg_facts_t *f, const char *tag, const char *cls, const bar_t *bar)
{
    f->elements++;
    f->polylines += strcmp(tag, "polyline") == 0;
    f->limit_lines += strcmp(tag, "line") == 0 && strcmp(cls, "limit") == 0;
    if (strcmp(cls, "stance") == 0 && bar->leg >= 1 && bar->leg <= XGO_LEG_COUNT &&
        f->nbars[bar->leg - 1] < MAX_BARS) {
        f->bars[bar->leg - 1][f->nbars[bar->leg - 1]++] = *bar;
    }
}

/* A start tag after '<': name, attributes (no repeats), then '>' or '/>'. */
static void xml_start_tag(xml_t *x, svg_facts_t *f)
{
    char tag[32], names[24][32], value[256], cls[32] = "";
    unsigned n = 0, i;
    bar_t bar = {0, 0, 0, 0, 0};
    if (!xml_name(x, tag, sizeof tag)) {
        xml_fail(x, "'<' without a tag name");
        return;
    }
    if (x->depth == 0) {
        f->root_is_svg = strcmp(tag, "svg") == 0 && f->elements == 0;
    }
    for (skip_space(x); x->err == NULL && xml_name(x, names[n % 24], sizeof names[0]); skip_space(x)) {
        for (i = 0; i < n && i < 24; ++i) {
            if (strcmp(names[i], names[n % 24]) == 0) {
                xml_fail(x, "repeated attribute");
            }
        }
        skip_space(x);
        if (*x->p++ != '=') {
            xml_fail(x, "attribute without '='");
            return;
        }
        skip_space(x);
        xml_value(x, value, sizeof value);
        if (strcmp(names[n % 24], "class") == 0) {
            snprintf(cls, sizeof cls, "%.31s", value);
        }
        note_attr(f, tag, cls, names[n % 24], value, &bar);
        n++;
    }
    note_element(f, tag, cls, &bar);
    if (x->p[0] == '/' && x->p[1] == '>') {
        x->p += 2;
    } else if (*x->p == '>') {
        x->p++;
        if (x->depth == 32) {
            xml_fail(x, "nesting too deep");
            return;
        }
        snprintf(x->stack[x->depth++], sizeof x->stack[0], "%s", tag);
    } else {
        xml_fail(x, "start tag not closed");
    }
}

static void xml_end_tag(xml_t *x)
{
    char tag[32];
    if (!xml_name(x, tag, sizeof tag) || x->depth == 0 || strcmp(tag, x->stack[x->depth - 1]) != 0) {
        xml_fail(x, "end tag does not match the open element");
        return;
    }
    x->depth--;
    skip_space(x);
    if (*x->p++ != '>') {
        xml_fail(x, "end tag not closed");
    }
}

/* Markup after '<': declaration, comment, end tag or start tag. */
static void xml_markup(xml_t *x, svg_facts_t *f)
{
    const char *end;
    if (*x->p == '?' || strncmp(x->p, "!--", 3) == 0) {
        end = strstr(x->p, *x->p == '?' ? "?>" : "-->");
        if (end == NULL) {
            xml_fail(x, "unterminated declaration or comment");
            return;
        }
        x->p = end + (*x->p == '?' ? 2 : 3);
    } else if (*x->p == '/') {
        x->p++;
        xml_end_tag(x);
    } else {
        xml_start_tag(x, f);
    }
}

/* Well formed: one root element, every tag closed in order, text with valid
 * entities only, no content after the root. */
static const char *xml_check(const char *doc, svg_facts_t *f)
{
    xml_t x;
    int root_done = 0;
    memset(&x, 0, sizeof x);
    memset(f, 0, sizeof *f);
    for (x.p = doc; *x.p != '\0' && x.err == NULL;) {
        if (*x.p == '<') {
            x.p++;
            if (root_done && x.p[0] != '!' && x.p[0] != '?') {
                xml_fail(&x, "content after the root element");
            }
            xml_markup(&x, f);
            root_done = root_done || (f->elements > 0 && x.depth == 0);
        } else if (*x.p == '&' && !xml_entity(x.p + 1)) {
            xml_fail(&x, "bad entity in text");
        } else if (x.depth == 0 && !(*x.p == ' ' || *x.p == '\n' || *x.p == '\r' || *x.p == '\t')) {
            xml_fail(&x, "text outside the root element");
        } else {
            x.p++;
        }
    }
    if (x.err == NULL && (x.depth != 0 || f->elements == 0)) {
        xml_fail(&x, "document ends inside an element (or is empty)");
    }
    return x.err;
}

/* ------------------------------------------------------------ helpers */

static char g_doc[4 * 1024 * 1024];

static long read_file(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "rb");
    size_t n;
    if (f == NULL) {
        return -1;
    }
    n = fread(buf, 1, size - 1, f);
    fclose(f);
    buf[n] = '\0';
    return (long)n;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT((unsigned)strlen(text), (unsigned)fwrite(text, 1, strlen(text), f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

/* Runs xgo-plot with args (NULL-terminated); returns its exit code. */
static int run_plot(const char *const *args)
{
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_child, XGO_PLOT_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, xgo_test_emu_wait(&g_child, PLOT_TIMEOUT_MS), "xgo-plot hangs");
    TEST_ASSERT_TRUE(WIFEXITED(g_child.status));
    return WEXITSTATUS(g_child.status);
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

void setUp(void)
{
    const char *tmp = getenv("TMPDIR");
    /* markup characters in the path: the title quoting it must escape them */
    snprintf(g_dir, sizeof g_dir, "%.40s/xgo-plot &<\"'>-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    TEST_ASSERT_NOT_NULL(mkdtemp(g_dir));
    snprintf(g_csv, sizeof g_csv, "%s/rec.csv", g_dir);
    snprintf(g_svg, sizeof g_svg, "%s/out.svg", g_dir);
    xgo_test_emu_init(&g_child);
}

void tearDown(void)
{
    char tmp[160];
    xgo_test_emu_kill(&g_child);
    snprintf(tmp, sizeof tmp, "%s.tmp", g_svg);
    remove(g_csv);
    remove(g_svg);
    remove(tmp);
    rmdir(g_dir);
}

/* ------------------------------------------------------------ tests */

/* The bars of one leg, computed here from the rows written: stance from the
 * first row with the contact to the first row without it (or the last). */
static unsigned expected_bars(unsigned leg, double t0[], double t1[])
{
    unsigned row, n = 0;
    int on = 0;
    for (row = 0; row < TROT_ROWS; ++row) {
        int c = (g_contacts[row] >> leg) & 1;
        if (c && !on && n < MAX_BARS) {
            t0[n] = g_t_ms[row];
        } else if (!c && on) {
            t1[n++] = g_t_ms[row];
        }
        on = c;
    }
    if (on) {
        t1[n++] = g_t_ms[TROT_ROWS - 1];
    }
    return n;
}

static void check_leg_bars(const svg_facts_t *f, unsigned leg)
{
    double t0[MAX_BARS], t1[MAX_BARS], scale = f->gait_w / (f->gait_t1 - f->gait_t0);
    unsigned n = expected_bars(leg, t0, t1), i;
    TEST_ASSERT_GREATER_OR_EQUAL_UINT_MESSAGE(6, n, "a 3 s trot has at least 6 stance phases per leg");
    TEST_ASSERT_EQUAL_UINT_MESSAGE(n, f->nbars[leg], "one stance bar per contact interval");
    for (i = 0; i < n; ++i) {
        const bar_t *b = &f->bars[leg][i];
        TEST_ASSERT_DOUBLE_WITHIN(0.0005, t0[i], b->t0);
        TEST_ASSERT_DOUBLE_WITHIN(0.0005, t1[i], b->t1);
        TEST_ASSERT_DOUBLE_WITHIN(0.002, f->gait_x + (t0[i] - f->gait_t0) * scale, b->x);
        TEST_ASSERT_DOUBLE_WITHIN(0.002, (t1[i] - t0[i]) * scale, b->w);
    }
}

static void test_trot_record_gives_well_formed_svg_with_the_stance_bars(void)
{
    const char *args[] = {g_csv, "-o", g_svg, NULL};
    svg_facts_t f;
    const char *err;
    unsigned leg;
    record_trot(g_csv);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run_plot(args), g_child.err);
    TEST_ASSERT_EQUAL_STRING("", g_child.err);
    TEST_ASSERT_GREATER_THAN_INT(1000, (int)read_file(g_svg, g_doc, sizeof g_doc));
    err = xml_check(g_doc, &f);
    TEST_ASSERT_NULL_MESSAGE(err, err);
    TEST_ASSERT_TRUE(f.root_is_svg);
    TEST_ASSERT_TRUE(f.have_gait);
    TEST_ASSERT_DOUBLE_WITHIN(0.0005, g_t_ms[0], f.gait_t0);
    TEST_ASSERT_DOUBLE_WITHIN(0.0005, g_t_ms[TROT_ROWS - 1], f.gait_t1);
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        check_leg_bars(&f, leg);
    }
    /* 12 joint series + the path + 4 feet in 2 views; 2 limit lines per joint */
    TEST_ASSERT_EQUAL_UINT(12u + 1u + 8u, f.polylines);
    TEST_ASSERT_EQUAL_UINT(24u, f.limit_lines);
}

/* A trot moves diagonal legs together: legs 1 and 3 (LF, RH) share their
 * bars, as do 2 and 4, and the two pairs differ. */
static void test_trot_diagonal_pairs_share_bars(void)
{
    const char *args[] = {g_csv, "-o", g_svg, NULL};
    svg_facts_t f;
    unsigned i;
    record_trot(g_csv);
    TEST_ASSERT_EQUAL_INT(0, run_plot(args));
    TEST_ASSERT_GREATER_THAN_INT(0, (int)read_file(g_svg, g_doc, sizeof g_doc));
    TEST_ASSERT_NULL(xml_check(g_doc, &f));
    TEST_ASSERT_EQUAL_UINT(f.nbars[0], f.nbars[2]);
    TEST_ASSERT_EQUAL_UINT(f.nbars[1], f.nbars[3]);
    for (i = 0; i < f.nbars[0]; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(0.0005, f.bars[0][i].t0, f.bars[2][i].t0);
    }
    TEST_ASSERT_TRUE(f.bars[0][1].t0 != f.bars[1][1].t0);
}

/* One line on stderr starting "xgo-plot: " and containing want; no output. */
static void expect_failure(const char *const *args, int code, const char *want)
{
    char tmp[160];
    TEST_ASSERT_EQUAL_INT_MESSAGE(code, run_plot(args), g_child.err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(g_child.err, "xgo-plot: ", 10), g_child.err);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_child.err, want), g_child.err);
    if (code == 1) {
        TEST_ASSERT_NOT_NULL(strchr(g_child.err, '\n'));
        TEST_ASSERT_EQUAL_STRING_MESSAGE("", strchr(g_child.err, '\n') + 1, "one line only");
    } else {
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_child.err, "\nusage: xgo-plot FILE.csv -o OUT.svg"), g_child.err);
    }
    snprintf(tmp, sizeof tmp, "%s.tmp", g_svg);
    TEST_ASSERT_FALSE(file_exists(g_svg));
    TEST_ASSERT_FALSE(file_exists(tmp));
}

static void test_misuse_exits_2_with_usage(void)
{
    const char *none[] = {NULL};
    const char *no_out[] = {g_csv, NULL};
    const char *unknown[] = {g_csv, "-o", g_svg, "--frobnicate", "1", NULL};
    const char *profile[] = {g_csv, "-o", g_svg, "--profile", "maxi", NULL};
    const char *from[] = {g_csv, "-o", g_svg, "--from", "2s", NULL};
    const char *two[] = {g_csv, g_csv, "-o", g_svg, NULL};
    const char *dangling[] = {g_csv, "-o", NULL};
    write_file(g_csv, "t_ms\n1\n");
    expect_failure(none, 2, "no input file");
    expect_failure(no_out, 2, "no output");
    expect_failure(unknown, 2, "unknown option --frobnicate");
    expect_failure(profile, 2, "--profile must be mini or lite, not maxi");
    expect_failure(from, 2, "--from needs seconds, not 2s");
    expect_failure(two, 2, "more than one input file");
    expect_failure(dangling, 2, "-o needs a value");
}

/* The trot record with field `col` (1 = t_ms) of data row `row` (1 = the
 * first) replaced by text. */
static void corrupt_record(unsigned row, unsigned col, const char *text)
{
    FILE *f;
    char *p = g_doc, *end;
    unsigned i;
    record_trot(g_csv);
    TEST_ASSERT_GREATER_THAN_INT(0, (int)read_file(g_csv, g_doc, sizeof g_doc));
    for (i = 0; i < row; ++i) {
        p = strchr(p, '\n') + 1;
    }
    for (i = 1; i < col; ++i) {
        p = strchr(p, ',') + 1;
    }
    end = p + strcspn(p, ",\n");
    f = fopen(g_csv, "wb");
    TEST_ASSERT_NOT_NULL(f);
    fwrite(g_doc, 1, (size_t)(p - g_doc), f);
    fputs(text, f);
    fputs(end, f);
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

static void test_bad_data_exits_1_with_one_line(void)
{
    const char *args[] = {g_csv, "-o", g_svg, NULL};
    const char *missing[] = {"/nonexistent/rec.csv", "-o", g_svg, NULL};
    expect_failure(missing, 1, "cannot open /nonexistent/rec.csv: No such file or directory");
    write_file(g_csv, "");
    expect_failure(args, 1, "rec.csv: empty file (no header line)");
    write_file(g_csv, "time,a,b\n1,2,3\n");
    expect_failure(args, 1, "rec.csv:1: header has no column 't_ms'");
    corrupt_record(7, 2, "abc");
    expect_failure(args, 1, "rec.csv:8: column 2 (mode) is not a number: 'abc'");
    corrupt_record(3, 4, "1e999");
    expect_failure(args, 1, "rec.csv:4: column 4 (j11_deg) is not a number: '1e999'");
    corrupt_record(9, 2, "");
    expect_failure(args, 1, "rec.csv:10: column 2 (mode) is not a number: ''");
    corrupt_record(5, 2, "0,0");
    expect_failure(args, 1, "rec.csv:6: 51 fields, the header has 50");
    corrupt_record(11, 28, "2");
    expect_failure(args, 1, "rec.csv:12: a contact column is neither 0 nor 1");
    corrupt_record(20, 1, "0");
    expect_failure(args, 1, "rec.csv:21: t_ms goes back in time");
}

static void test_blank_line_and_empty_window_exit_1(void)
{
    const char *args[] = {g_csv, "-o", g_svg, NULL};
    const char *window[] = {g_csv, "-o", g_svg, "--from", "100", NULL};
    const char *tail_blank[] = {g_csv, "-o", g_svg, "--to", "1", NULL};
    FILE *f;
    unsigned i;
    record_trot(g_csv);
    f = fopen(g_csv, "ab");
    TEST_ASSERT_NOT_NULL(f);
    fputs("\n\n", f); /* blank lines at the end are fine ... */
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run_plot(tail_blank), g_child.err);
    remove(g_svg);
    f = fopen(g_csv, "ab");
    TEST_ASSERT_NOT_NULL(f);
    fputs("5000", f); /* ... but not before more data */
    for (i = 1; i < 50; ++i) {
        fputs(",0", f);
    }
    fputs("\n", f);
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    expect_failure(args, 1, "rec.csv:2252: empty line");
    record_trot(g_csv);
    expect_failure(window, 1, "rec.csv: no data rows between --from and --to");
}

/* The real thing: xgo-emu --record while a host on its pty makes the dog
 * trot, then xgo-plot on that file (the two programs agree on the columns). */
static void test_xgo_emu_record_plots(void)
{
    const char *emu_args[] = {"--record", g_csv, "--record-hz", "100", NULL};
    const char *args[] = {g_csv, "-o", g_svg, NULL};
    xgo_test_emu_t emu;
    uint8_t full = 0xFF;
    svg_facts_t f;
    unsigned leg;
    int fd;
    xgo_test_emu_init(&emu);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&emu, XGO_EMU_PATH, emu_args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&emu, 5000));
    fd = xgo_test_port_open_like_pyserial(emu.pty, B115200);
    TEST_ASSERT_TRUE(fd >= 0);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_write_regs(fd, 0x30, &full, 1, 1000)); /* vx: trot */
    usleep(2000000);
    close(fd);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, xgo_test_emu_stop(&emu, SIGTERM, 5000), emu.err);
    xgo_test_emu_reset(&emu);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, run_plot(args), g_child.err);
    TEST_ASSERT_GREATER_THAN_INT(0, (int)read_file(g_svg, g_doc, sizeof g_doc));
    TEST_ASSERT_NULL(xml_check(g_doc, &f));
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) { /* standing, then a few steps */
        TEST_ASSERT_GREATER_OR_EQUAL_UINT_MESSAGE(3, f.nbars[leg], "stance bars of a recorded trot");
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_trot_record_gives_well_formed_svg_with_the_stance_bars);
    RUN_TEST(test_trot_diagonal_pairs_share_bars);
    RUN_TEST(test_misuse_exits_2_with_usage);
    RUN_TEST(test_bad_data_exits_1_with_one_line);
    RUN_TEST(test_blank_line_and_empty_window_exit_1);
    RUN_TEST(test_xgo_emu_record_plots);
    return UNITY_END();
}
