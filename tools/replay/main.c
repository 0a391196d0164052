/*
 * main.c - xgo-replay FILE.pcap: a capture's host->board bytes into a fresh
 * board on virtual time, every reply compared with the recorded one (see
 * replay.h, docs/capture.md). Exit 0 identical, 1 a difference (reported
 * with its time, record and frame) or an unreadable capture, 2 usage.
 */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "meaning.h"
#include "replay.h"

#define XGO_REPLAY_VERSION "0.1.0"

static void xgo_replay_usage(FILE *out)
{
    fputs("usage: xgo-replay [options] FILE.pcap\n"
          "Feeds the host->board bytes of a capture (xgo-emu --capture, xgo-cli --capture)\n"
          "into a fresh board at their recorded ticks, on virtual time, and compares every\n"
          "reply with the recorded one byte for byte.\n"
          "\n"
          "options:\n"
          "  --record FILE.csv   the replayed board's motion log (xgo-emu --record's columns)\n"
          "  --record-hz N       rows a second, 1..500 (default: every tick)\n"
          "  --trace             the replayed board's frames on stderr (xgo-emu --trace format)\n"
          "  --profile M         mini, lite or mini2 instead of the capture's settings note\n"
          "  --battery PCT       initial battery 0..100 instead of the capture's\n"
          "  -h, --help          this help;  --version  the version\n"
          "\n"
          "exit status: 0 identical, 1 a difference (first one reported with its time,\n"
          "record and frame) or an unreadable capture, 2 usage. See docs/capture.md.\n",
          out);
}

static int xgo_replay_usage_error(const char *fmt, ...)
{
    va_list ap;
    fputs("xgo-replay: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    xgo_replay_usage(stderr);
    return 2;
}

static int xgo_replay_number(const char *text, long lo, long hi, long *out)
{
    char *end = NULL;
    long v;
    if (text == NULL || text[0] < '0' || text[0] > '9') {
        return 0;
    }
    v = strtol(text, &end, 10);
    if (*end != '\0' || v < lo || v > hi) {
        return 0;
    }
    *out = v;
    return 1;
}

/* One option at argv[*i] (with its value); 0, 1 (help/version done) or 2. */
static int xgo_replay_option(xgo_replay_options_t *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    long n;
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0 || strcmp(a, "--version") == 0) {
        if (a[2] == 'v') {
            printf("xgo-replay %s\n", XGO_REPLAY_VERSION);
        } else {
            xgo_replay_usage(stdout);
        }
        return 1;
    }
    if (strcmp(a, "--trace") == 0) {
        o->trace = 1;
        return 0;
    }
    if (v == NULL) {
        return xgo_replay_usage_error(strncmp(a, "--", 2) == 0 ? "%s needs a value or is unknown"
                                                               : "unknown option '%s'", a);
    }
    (*i)++;
    if (strcmp(a, "--record") == 0) {
        o->record_path = v;
    } else if (strcmp(a, "--record-hz") == 0 && xgo_replay_number(v, 1, XGO_TICK_HZ, &n)) {
        o->record_hz = (unsigned)n;
    } else if (strcmp(a, "--battery") == 0 && xgo_replay_number(v, 0, 100, &n)) {
        o->battery = (int)n;
    } else if (strcmp(a, "--profile") == 0 && xgo_host_model_by_name(v) >= 0) {
        o->profile = xgo_host_model_by_name(v);
    } else {
        return xgo_replay_usage_error("bad option '%s %s'", a, v);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static xgo_replay_t r; /* large: the board, the streams */
    int i, rc;
    memset(&r, 0, sizeof r);
    r.opts.profile = -1;
    r.opts.battery = -1;
    for (i = 1; i < argc; i++) {
        if (argv[i][0] == '-' && argv[i][1] != '\0') {
            int o = xgo_replay_option(&r.opts, argc, argv, &i);
            if (o != 0) {
                return o == 1 ? 0 : o;
            }
        } else if (r.opts.capture == NULL) {
            r.opts.capture = argv[i];
        } else {
            return xgo_replay_usage_error("one capture only, not also '%s'", argv[i]);
        }
    }
    if (r.opts.capture == NULL) {
        return xgo_replay_usage_error("no capture given");
    }
    if (r.opts.record_hz != 0 && r.opts.record_path == NULL) {
        return xgo_replay_usage_error("--record-hz needs --record");
    }
    rc = xgo_replay_run(&r, stderr);
    if (rc < 0) {
        fprintf(stderr, "xgo-replay: %s\n", r.err);
        rc = 1;
    }
    xgo_replay_stream_free(&r.recorded);
    xgo_replay_stream_free(&r.replayed);
    return rc;
}
