/*
 * main.c - xgo-cli's command line: global options, then a command and its
 * words (see cli.h and docs/xgo-cli.md).
 */
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "json_out.h"
#include "meaning.h"
#include "serial.h"
#include "xgo/board.h"

#define XGO_CLI_VERSION "0.1.0"
#define XGO_CLI_DEFAULT_TIMEOUT_MS 1000 /* the vendor library waits 1 s for a reply */

typedef struct xgo_cli_cmd_s {
    const char *name;
    const char *args;
    const char *help;
    xgo_cli_cmd_fn fn;
    int needs_port;
} xgo_cli_cmd_t;

static const xgo_cli_cmd_t xgo_cli_cmds[] = {
    {"read", "REG|ADDR [N]", "read N bytes (default: the register's width), decoded", xgo_cli_cmd_read, 1},
    {"dump", "", "every register, one line each", xgo_cli_cmd_dump, 1},
    {"write", "REG=VALUE...", "write by name or address: raw (vx=0xff), physical\n"
                              "(vx=12.5cm/s, body_roll=-10deg, period_x=2.5s) or a word\n"
                              "(gait_type=walk); out-of-range values are refused",
     xgo_cli_cmd_write, 1},
    {"watch", "REG... [--hz N] [--count N]", "a live table until Ctrl-C (default 5 Hz)", xgo_cli_cmd_watch, 1},
    {"action", "NAME|N [--wait]", "start a preset action; --wait for its duration", xgo_cli_cmd_action, 1},
    {"diag", "", "the board's parser counters (diagnostic block 0xC4..)", xgo_cli_cmd_diag, 1},
    {"raw", "[--fix] HEX...", "send exactly these bytes, show what comes back;\n"
                              "--fix fills in LEN and the checksum",
     xgo_cli_cmd_raw, 1},
    {"checksum", "HEX...", "the checksum of TYPE ADDR DATA... or of a whole frame", xgo_cli_cmd_checksum, 0},
    {"decode", "[FILE|-]", "frames in a hex or binary byte stream or a capture,\n"
                           "offline, in the --trace format",
     xgo_cli_cmd_decode, 0},
};

#define XGO_CLI_CMD_COUNT (sizeof xgo_cli_cmds / sizeof xgo_cli_cmds[0])

static void xgo_cli_print_help_lines(FILE *out, const char *help)
{
    const char *nl;
    while ((nl = strchr(help, '\n')) != NULL) {
        fprintf(out, "%.*s\n%37s", (int)(nl - help), help, "");
        help = nl + 1;
    }
    fprintf(out, "%s\n", help);
}

static void xgo_cli_usage(FILE *out)
{
    size_t i;
    fputs("usage: xgo-cli [options] COMMAND [ARGS...]\n"
          "Talks to an XGO board (a robot's serial port or xgo-emu's pty) in raw 8N1.\n"
          "\n"
          "options:\n"
          "  -p, --port PORT   serial port (default: $XGO_PORT)\n"
          "      --baud N      line speed (default 115200)\n"
          "      --timeout MS  wait this long for a reply (default 1000)\n"
          "      --json        one JSON object on stdout per command\n"
          "      --capture F   record every byte sent and received in F (pcap)\n"
          "      --profile M   mini, lite or mini2 for unit conversions (default: ask the board)\n"
          "  -h, --help        this help;  --version  the version\n"
          "\n"
          "commands:\n",
          out);
    for (i = 0; i < XGO_CLI_CMD_COUNT; i++) {
        char left[48];
        snprintf(left, sizeof left, "%s %s", xgo_cli_cmds[i].name, xgo_cli_cmds[i].args);
        fprintf(out, "  %-34s ", left);
        xgo_cli_print_help_lines(out, xgo_cli_cmds[i].help);
    }
    fputs("\n"
          "exit status: 0 ok, 1 no or bad reply (or an unreadable file), 2 usage.\n"
          "See docs/xgo-cli.md.\n",
          out);
}

int xgo_cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    fputs("xgo-cli: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    xgo_cli_usage(stderr);
    return XGO_CLI_USAGE;
}

int xgo_cli_fail(xgo_cli_t *cli)
{
    fprintf(stderr, "xgo-cli: %s\n", cli->err);
    if (cli->json) {
        char buf[XGO_CLI_ERR_LEN * 2];
        xgo_host_json_t w;
        xgo_host_json_init(&w, buf, sizeof buf);
        xgo_host_json_object_begin(&w);
        xgo_host_json_key(&w, "ok");
        xgo_host_json_bool(&w, 0);
        xgo_host_json_key(&w, "error");
        xgo_host_json_string(&w, cli->err);
        xgo_host_json_object_end(&w);
        printf("%s\n", buf);
    }
    return XGO_CLI_FAIL;
}

/* Applies one global option at argv[*i]; returns 0, 1 for --help/--version
 * handled (exit 0), or XGO_CLI_USAGE. */
static int xgo_cli_global_option(xgo_cli_t *cli, int argc, char **argv, int *i)
{
    const char *o = argv[*i];
    const char *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    long n;
    if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
        xgo_cli_usage(stdout);
        return 1;
    }
    if (strcmp(o, "--version") == 0) {
        printf("xgo-cli %s\n", XGO_CLI_VERSION);
        return 1;
    }
    if (strcmp(o, "--json") == 0) {
        cli->json = 1;
        return 0;
    }
    if (strcmp(o, "-p") != 0 && strcmp(o, "--port") != 0 && strcmp(o, "--baud") != 0 &&
        strcmp(o, "--timeout") != 0 && strcmp(o, "--capture") != 0 && strcmp(o, "--profile") != 0) {
        return xgo_cli_usage_error("unknown option '%s'", o);
    }
    if (v == NULL) {
        return xgo_cli_usage_error("%s needs a value", o);
    }
    (*i)++;
    if (o[1] == 'p' || strcmp(o, "--port") == 0) {
        cli->port = v;
    } else if (strcmp(o, "--baud") == 0) {
        speed_t code;
        if (!xgo_cli_parse_number(v, 1, 4000000, &n) || !xgo_host_serial_speed_code((uint32_t)n, &code)) {
            return xgo_cli_usage_error("--baud must be a standard line speed (e.g. 115200), not '%s'", v);
        }
        cli->baud = (uint32_t)n;
    } else if (strcmp(o, "--timeout") == 0) {
        if (!xgo_cli_parse_number(v, 1, 600000, &n)) {
            return xgo_cli_usage_error("--timeout must be 1..600000 ms, not '%s'", v);
        }
        cli->timeout_ms = n;
    } else if (strcmp(o, "--capture") == 0) {
        cli->capture = v;
    } else if (xgo_host_model_by_name(v) >= 0) {
        cli->profile = xgo_profile_get((unsigned)xgo_host_model_by_name(v));
    } else {
        return xgo_cli_usage_error("--profile must be mini, lite or mini2, not '%s'", v);
    }
    return 0;
}

static const xgo_cli_cmd_t *xgo_cli_find_cmd(const char *name)
{
    size_t i;
    for (i = 0; i < XGO_CLI_CMD_COUNT; i++) {
        if (strcmp(xgo_cli_cmds[i].name, name) == 0) {
            return &xgo_cli_cmds[i];
        }
    }
    return NULL;
}

static int xgo_cli_run(xgo_cli_t *cli, const xgo_cli_cmd_t *cmd, int argc, char **argv)
{
    int rc;
    if (cmd->needs_port) {
        if (cli->port == NULL || cli->port[0] == '\0') {
            return xgo_cli_usage_error("no port: give -p PORT or set XGO_PORT");
        }
    }
    rc = cmd->fn(cli, argc, argv);
    xgo_cli_close(cli);
    return rc;
}

int main(int argc, char **argv)
{
    static xgo_cli_t cli; /* static: large (parser, buffers) */
    const xgo_cli_cmd_t *cmd;
    int i;

    memset(&cli, 0, sizeof cli);
    cli.fd = -1;
    cli.pcap.fd = -1;
    cli.port = getenv("XGO_PORT");
    cli.baud = XGO_HOST_DEFAULT_BAUD;
    cli.timeout_ms = XGO_CLI_DEFAULT_TIMEOUT_MS;
    signal(SIGPIPE, SIG_IGN);

    for (i = 1; i < argc && argv[i][0] == '-' && argv[i][1] != '\0'; i++) {
        int r = xgo_cli_global_option(&cli, argc, argv, &i);
        if (r == 1) {
            return XGO_CLI_OK;
        }
        if (r != 0) {
            return r;
        }
    }
    if (i >= argc) {
        return xgo_cli_usage_error("no command");
    }
    cmd = xgo_cli_find_cmd(argv[i]);
    if (cmd == NULL) {
        return xgo_cli_usage_error("unknown command '%s'", argv[i]);
    }
    return xgo_cli_run(&cli, cmd, argc - i, argv + i);
}
