/*
 * options.c - table-driven parsing of xgo-emu's command line.
 *
 * Each row names an option, its argument (if any), a help line and the
 * function that applies it. Both "--opt VALUE" and "--opt=VALUE" work.
 * A bad value is misuse just like an unknown option: the caller prints one
 * line plus the usage and exits 2.
 */
#include "options.h"

#include "uart_model.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "net.h"

typedef enum xgo_host_apply_e {
    XGO_HOST_APPLY_OK = 0,
    XGO_HOST_APPLY_BAD_VALUE, /* message already written to err */
    XGO_HOST_APPLY_HELP,
    XGO_HOST_APPLY_VERSION
} xgo_host_apply_t;

typedef xgo_host_apply_t (*xgo_host_apply_fn)(xgo_host_options_t *opts, const char *value,
                                               char *err, size_t err_size);

typedef struct xgo_host_option_s {
    const char *name;     /* long name without "--" */
    char short_name;      /* single-letter alias, 0 for none */
    const char *arg_name; /* shown in usage; NULL: the option takes no value */
    const char *help;     /* one line, or lines split by '\n' */
    xgo_host_apply_fn apply;
} xgo_host_option_t;

/* Parses a whole decimal string within lo..hi. */
static int xgo_host_parse_ulong(const char *text, unsigned long lo, unsigned long hi,
                                unsigned long *out)
{
    char *end = NULL;
    unsigned long v;
    if (text[0] < '0' || text[0] > '9') {
        return 0; /* rejects "", "-1", " 5", "+5": strtoul would accept some */
    }
    errno = 0;
    v = strtoul(text, &end, 10);
    if (errno != 0 || *end != '\0' || v < lo || v > hi) {
        return 0;
    }
    *out = v;
    return 1;
}

static xgo_host_apply_t xgo_host_apply_link(xgo_host_options_t *opts, const char *value,
                                             char *err, size_t err_size)
{
    if (value[0] == '\0') {
        snprintf(err, err_size, "--link needs a non-empty PATH");
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->link_path = value;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_trace(xgo_host_options_t *opts, const char *value,
                                              char *err, size_t err_size)
{
    (void)value;
    (void)err;
    (void)err_size;
    opts->trace = 1;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_baud_pacing(xgo_host_options_t *opts, const char *value,
                                                    char *err, size_t err_size)
{
    (void)value;
    (void)err;
    (void)err_size;
    opts->baud_pacing = 1;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_uart_baud(xgo_host_options_t *opts, const char *value,
                                                  char *err, size_t err_size)
{
    unsigned long baud;
    if (!xgo_host_parse_ulong(value, XGO_HOST_UART_MIN_BAUD, XGO_HOST_UART_MAX_BAUD, &baud)) {
        snprintf(err, err_size, "--uart-baud must be a whole number %u..%u, not '%s'",
                 XGO_HOST_UART_MIN_BAUD, XGO_HOST_UART_MAX_BAUD, value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->uart_baud = (uint32_t)baud;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_profile(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    if (strcmp(value, "mini") == 0) {
        opts->board.model = XGO_MODEL_MINI;
    } else if (strcmp(value, "lite") == 0) {
        opts->board.model = XGO_MODEL_LITE;
    } else if (strcmp(value, "mini2") == 0) {
        opts->board.model = XGO_MODEL_MINI2;
    } else {
        snprintf(err, err_size, "--profile must be mini, lite or mini2, not '%s'", value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_battery(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    unsigned long pct;
    if (!xgo_host_parse_ulong(value, 0, 100, &pct)) {
        snprintf(err, err_size, "--battery must be a whole number 0..100, not '%s'", value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->board.battery_pct = (uint8_t)pct;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_timeout(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    unsigned long ms;
    /* An hour is far beyond any sensible silence timeout; the cap keeps
     * typos like an extra zero-run from looking valid. */
    if (!xgo_host_parse_ulong(value, 0, 3600000ul, &ms)) {
        snprintf(err, err_size, "--timeout-ms must be a whole number of ms 0..3600000, not '%s'",
                 value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->board.parser_timeout_ms = (uint32_t)ms;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_state(xgo_host_options_t *opts, const char *value,
                                              char *err, size_t err_size)
{
    if (value[0] == '\0') {
        snprintf(err, err_size, "--state needs a non-empty FILE");
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->state_path = value;
    return XGO_HOST_APPLY_OK;
}

/* Largest ground tilt in mdeg: steeper is no ground a dog stands on (the
 * core clamps there too). */
#define XGO_HOST_MAX_TILT_MDEG 45000L

/* Parses degrees "[+-]D[.D...]" into mdeg, rounded to nearest (ties away
 * from zero), without floating point: exact, and no locale, "nan" or "1e3"
 * surprises from strtod. *text is advanced past the number. */
static int xgo_host_parse_mdeg(const char **text, long *mdeg)
{
    const char *p = *text;
    long v = 0;
    int neg = (*p == '-');
    if (*p == '-' || *p == '+') {
        p++;
    }
    if (*p < '0' || *p > '9') {
        return 0;
    }
    for (; *p >= '0' && *p <= '9'; p++) {
        v = v * 10 + (*p - '0');
        if (v > XGO_HOST_MAX_TILT_MDEG) {
            return 0; /* whole degrees: far out of range, and no overflow */
        }
    }
    v *= 1000;
    if (*p == '.') {
        static const long k_place_mdeg[3] = {100, 10, 1};
        int place = 0;
        if (p[1] < '0' || p[1] > '9') {
            return 0;
        }
        for (p++; *p >= '0' && *p <= '9'; p++, place++) {
            if (place < 3) {
                v += (*p - '0') * k_place_mdeg[place];
            } else if (place == 3 && *p >= '5') {
                v++; /* the 4th decimal rounds; later ones cannot change that */
            }
        }
    }
    *mdeg = neg ? -v : v;
    *text = p;
    return 1;
}

static xgo_host_apply_t xgo_host_apply_ground_tilt(xgo_host_options_t *opts, const char *value,
                                                    char *err, size_t err_size)
{
    const char *p = value;
    long roll = 0;
    long pitch = 0;
    if (!xgo_host_parse_mdeg(&p, &roll) || *p++ != ',' || !xgo_host_parse_mdeg(&p, &pitch) ||
        *p != '\0' || roll < -XGO_HOST_MAX_TILT_MDEG || roll > XGO_HOST_MAX_TILT_MDEG ||
        pitch < -XGO_HOST_MAX_TILT_MDEG || pitch > XGO_HOST_MAX_TILT_MDEG) {
        snprintf(err, err_size,
                 "--ground-tilt must be ROLL,PITCH in degrees within -45..45 (e.g. 5,-2.5), "
                 "not '%s'",
                 value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->ground_roll_mdeg = (int32_t)roll;
    opts->ground_pitch_mdeg = (int32_t)pitch;
    return XGO_HOST_APPLY_OK;
}

/* --view, --tcp: [HOST:]PORT (net.h: HOST 127.0.0.1 unless given). */
static xgo_host_apply_t xgo_host_apply_endpoint(const char *option, const char *value,
                                                 uint32_t *addr, unsigned *port, int *given,
                                                 char *err, size_t err_size)
{
    char why[128];
    if (!xgo_host_net_parse_endpoint(value, addr, port, why, sizeof why)) {
        snprintf(err, err_size, "--%s %s, not '%s'", option, why, value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    *given = 1;
    return XGO_HOST_APPLY_OK;
}

static xgo_host_apply_t xgo_host_apply_view(xgo_host_options_t *opts, const char *value,
                                             char *err, size_t err_size)
{
    return xgo_host_apply_endpoint("view", value, &opts->view_addr, &opts->view_port, &opts->view,
                                   err, err_size);
}

/* The serial line over TCP (tcp_bridge.c). */
static xgo_host_apply_t xgo_host_apply_tcp(xgo_host_options_t *opts, const char *value,
                                            char *err, size_t err_size)
{
    return xgo_host_apply_endpoint("tcp", value, &opts->tcp_addr, &opts->tcp_port, &opts->tcp,
                                   err, err_size);
}

/* --capture FILE.pcap (capture.c). */
static xgo_host_apply_t xgo_host_apply_capture(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    if (value[0] == '\0') {
        snprintf(err, err_size, "--capture needs a non-empty FILE");
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->capture_path = value;
    return XGO_HOST_APPLY_OK;
}

/* Whole number lo..hi into *out, or misuse naming the option. */
static xgo_host_apply_t xgo_host_apply_rate(const char *option, const char *value,
                                             unsigned long lo, unsigned long hi, unsigned *out,
                                             char *err, size_t err_size)
{
    unsigned long n;
    if (!xgo_host_parse_ulong(value, lo, hi, &n)) {
        snprintf(err, err_size, "--%s must be a whole number %lu..%lu, not '%s'", option, lo, hi,
                 value);
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    *out = (unsigned)n;
    return XGO_HOST_APPLY_OK;
}

/* Events a second: at most one per control tick. */
static xgo_host_apply_t xgo_host_apply_view_hz(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    return xgo_host_apply_rate("view-hz", value, 1, XGO_TICK_HZ, &opts->view_hz, err, err_size);
}

static xgo_host_apply_t xgo_host_apply_record(xgo_host_options_t *opts, const char *value,
                                               char *err, size_t err_size)
{
    if (value[0] == '\0') {
        snprintf(err, err_size, "--record needs a non-empty FILE");
        return XGO_HOST_APPLY_BAD_VALUE;
    }
    opts->record_path = value;
    return XGO_HOST_APPLY_OK;
}

/* Rows a second: at most one per control tick. */
static xgo_host_apply_t xgo_host_apply_record_hz(xgo_host_options_t *opts, const char *value,
                                                  char *err, size_t err_size)
{
    return xgo_host_apply_rate("record-hz", value, 1, XGO_TICK_HZ, &opts->record_hz, err,
                               err_size);
}

static xgo_host_apply_t xgo_host_apply_help(xgo_host_options_t *opts, const char *value,
                                             char *err, size_t err_size)
{
    (void)opts;
    (void)value;
    (void)err;
    (void)err_size;
    return XGO_HOST_APPLY_HELP;
}

static xgo_host_apply_t xgo_host_apply_version(xgo_host_options_t *opts, const char *value,
                                                char *err, size_t err_size)
{
    (void)opts;
    (void)value;
    (void)err;
    (void)err_size;
    return XGO_HOST_APPLY_VERSION;
}

static const xgo_host_option_t xgo_host_option_table[] = {
    {"link", 0, "PATH",
     "keep a symlink PATH -> the pty; replaces only a stale pty link\n"
     "(one into the pty directory whose pty is gone); anything else\n"
     "at PATH is refused (exit 1)",
     xgo_host_apply_link},
    {"trace", 0, NULL, "print one line per frame in, out or dropped on stderr", xgo_host_apply_trace},
    {"baud-pacing", 0, NULL, "delay replies by their wire time at the speed the host set",
     xgo_host_apply_baud_pacing},
    {"uart-baud", 0, "N",
     "the board's UART runs at N baud (the robot: 115200): a host port set\n"
     "to another speed gets garbled bytes and no answer, framing errors counted",
     xgo_host_apply_uart_baud},
    {"profile", 0, "MODEL", "board model: mini (default), lite or mini2 (with the arm)", xgo_host_apply_profile},
    {"battery", 0, "PCT", "initial battery level 0..100 (default 100)", xgo_host_apply_battery},
    {"timeout-ms", 0, "N", "abandon a partial frame after N ms of silence, 0 = never (default 20)",
     xgo_host_apply_timeout},
    {"state", 0, "FILE", "keep the Bluetooth name and zero offsets in FILE across runs",
     xgo_host_apply_state},
    {"ground-tilt", 0, "R,P", "ground tilted R deg in roll, P deg in pitch (e.g. 5,-2.5; max 45)",
     xgo_host_apply_ground_tilt},
    {"view", 0, "[HOST:]PORT", "serve the live view on http://HOST:PORT/ (HOST 127.0.0.1)",
     xgo_host_apply_view},
    {"view-hz", 0, "N", "live view events a second, 1..500 (default 30)", xgo_host_apply_view_hz},
    {"record", 0, "FILE", "write the motion log to FILE (CSV, one row per tick)",
     xgo_host_apply_record},
    {"record-hz", 0, "N", "motion log rows a second instead, 1..500", xgo_host_apply_record_hz},
    {"tcp", 0, "[HOST:]PORT",
     "the serial line over TCP too, one client at a time (HOST\n"
     "127.0.0.1, PORT 0 = any free port; pyserial socket://)",
     xgo_host_apply_tcp},
    {"capture", 0, "FILE", "record every byte of the line in FILE (pcap, docs/capture.md)",
     xgo_host_apply_capture},
    {"help", 'h', NULL, "show this help and exit", xgo_host_apply_help},
    {"version", 0, NULL, "show the version and exit", xgo_host_apply_version},
};

#define XGO_HOST_OPTION_COUNT (sizeof xgo_host_option_table / sizeof xgo_host_option_table[0])

/* Finds the row for "--name", "--name=value" or "-x"; *inline_value gets the
 * part after '=' (or NULL). */
static const xgo_host_option_t *xgo_host_option_lookup(const char *word, const char **inline_value)
{
    size_t i;
    *inline_value = NULL;
    if (word[0] == '-' && word[1] != '-' && word[1] != '\0' && word[2] == '\0') {
        for (i = 0; i < XGO_HOST_OPTION_COUNT; i++) {
            if (xgo_host_option_table[i].short_name == word[1]) {
                return &xgo_host_option_table[i];
            }
        }
        return NULL;
    }
    if (word[0] != '-' || word[1] != '-') {
        return NULL;
    }
    word += 2;
    for (i = 0; i < XGO_HOST_OPTION_COUNT; i++) {
        const char *name = xgo_host_option_table[i].name;
        size_t len = strlen(name);
        if (strncmp(word, name, len) != 0) {
            continue;
        }
        if (word[len] == '\0') {
            return &xgo_host_option_table[i];
        }
        if (word[len] == '=') {
            *inline_value = word + len + 1;
            return &xgo_host_option_table[i];
        }
    }
    return NULL;
}

/* Options that only make sense together. */
static xgo_host_parse_result_t xgo_host_options_check(xgo_host_options_t *opts, char *error,
                                                      size_t error_size)
{
    if (opts->view_hz != 0 && !opts->view) {
        snprintf(error, error_size, "--view-hz needs --view");
        return XGO_HOST_PARSE_ERROR;
    }
    if (opts->record_hz != 0 && opts->record_path == NULL) {
        snprintf(error, error_size, "--record-hz needs --record");
        return XGO_HOST_PARSE_ERROR;
    }
    if (opts->view_hz == 0) {
        opts->view_hz = 30u;
    }
    return XGO_HOST_PARSE_RUN;
}

xgo_host_parse_result_t xgo_host_options_parse(xgo_host_options_t *opts, int argc, char **argv,
                                               char *error, size_t error_size)
{
    int i;
    memset(opts, 0, sizeof *opts);
    xgo_board_default_config(&opts->board);
    opts->view_addr = 0x7F000001ul; /* 127.0.0.1 */
    opts->tcp_addr = 0x7F000001ul;

    for (i = 1; i < argc; i++) {
        const char *word = argv[i];
        const char *value = NULL;
        const xgo_host_option_t *opt = xgo_host_option_lookup(word, &value);
        xgo_host_apply_t applied;

        if (opt == NULL) {
            if (word[0] == '-') {
                snprintf(error, error_size, "unknown option '%s'", word);
            } else {
                snprintf(error, error_size, "unexpected argument '%s'", word);
            }
            return XGO_HOST_PARSE_ERROR;
        }
        if (opt->arg_name != NULL && value == NULL) {
            if (i + 1 >= argc) {
                snprintf(error, error_size, "--%s needs a value (%s)", opt->name, opt->arg_name);
                return XGO_HOST_PARSE_ERROR;
            }
            value = argv[++i];
        } else if (opt->arg_name == NULL && value != NULL) {
            snprintf(error, error_size, "--%s takes no value", opt->name);
            return XGO_HOST_PARSE_ERROR;
        }

        applied = opt->apply(opts, value, error, error_size);
        switch (applied) {
        case XGO_HOST_APPLY_OK:
            break;
        case XGO_HOST_APPLY_BAD_VALUE:
            return XGO_HOST_PARSE_ERROR;
        case XGO_HOST_APPLY_HELP:
            return XGO_HOST_PARSE_HELP;
        case XGO_HOST_APPLY_VERSION:
            return XGO_HOST_PARSE_VERSION;
        }
    }
    return xgo_host_options_check(opts, error, error_size);
}

/* A help text; lines after the first (split at '\n') are indented under
 * it. */
static void xgo_host_options_print_help(FILE *out, const char *help)
{
    const char *nl;
    while ((nl = strchr(help, '\n')) != NULL) {
        fprintf(out, "%.*s\n%25s", (int)(nl - help), help, "");
        help = nl + 1;
    }
    fprintf(out, "%s\n", help);
}

void xgo_host_options_usage(FILE *out)
{
    size_t i;
    fputs("usage: xgo-emu [options]\n"
          "Emulates the XGO-Mini driver board on a pseudo-terminal: prints the pty\n"
          "path as the first line on stdout, then serves the serial protocol until\n"
          "SIGINT or SIGTERM.\n"
          "\n"
          "options:\n",
          out);
    for (i = 0; i < XGO_HOST_OPTION_COUNT; i++) {
        const xgo_host_option_t *opt = &xgo_host_option_table[i];
        char left[48];
        if (opt->short_name != 0) {
            snprintf(left, sizeof left, "-%c, --%s%s%s", opt->short_name, opt->name,
                     opt->arg_name ? " " : "", opt->arg_name ? opt->arg_name : "");
        } else {
            snprintf(left, sizeof left, "    --%s%s%s", opt->name, opt->arg_name ? " " : "",
                     opt->arg_name ? opt->arg_name : "");
        }
        fprintf(out, "  %-22s ", left);
        xgo_host_options_print_help(out, opt->help);
    }
    fputs("\n"
          "exit status: 0 after SIGINT/SIGTERM, 1 on a runtime error, 2 on misuse.\n"
          "Counters are printed on stderr at exit. See docs/xgo-emu.md.\n",
          out);
}
