/*
 * cmd_action.c - xgo-cli action (a preset action by name or number, waiting
 * the vendor's duration) and diag (the board's parser counters).
 */
#include <ctype.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "clock.h"
#include "xgo/board.h"
#include "xgo/regs.h"

/* "lie down" == "lie_down" == "Lie-Down". */
static int xgo_cli_action_named(const char *name, const char *word)
{
    for (; *name != '\0' && *word != '\0'; name++, word++) {
        char w = (*word == '_' || *word == '-') ? ' ' : (char)tolower((unsigned char)*word);
        if (*name != w) {
            return 0;
        }
    }
    return *name == *word;
}

/* NAME or N -> id (0 stops the running action). */
static int xgo_cli_action_id(const char *word, uint8_t *id)
{
    long n;
    unsigned i;
    if (xgo_cli_parse_number(word, 0, 255, &n)) {
        if (n != 0 && xgo_action_name((uint8_t)n) == NULL) {
            return 0;
        }
        *id = (uint8_t)n;
        return 1;
    }
    for (i = 1; i < 256; i++) {
        const char *name = xgo_action_name((uint8_t)i);
        if (name != NULL && xgo_cli_action_named(name, word)) {
            *id = (uint8_t)i;
            return 1;
        }
    }
    return 0;
}

static void xgo_cli_sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    while (nanosleep(&ts, &ts) != 0) {
    }
}

/* Waits the action's duration, then until 0x3E reads 0 (the action ended),
 * for at most one more second (the board may run a little behind). */
static int xgo_cli_action_wait(xgo_cli_t *cli, uint8_t id, long duration_ms)
{
    uint64_t give_up;
    uint8_t running = id;
    xgo_cli_sleep_ms(duration_ms);
    give_up = xgo_host_clock_us() + 1000000u;
    while (running != 0) {
        if (xgo_cli_read(cli, XGO_REG_ACTION, 1, &running) != 0) {
            return -1;
        }
        if (running != 0 && xgo_host_clock_us() > give_up) {
            snprintf(cli->err, sizeof cli->err,
                     "action %u still running 1 s after its %ld ms (0x3E reads %u)", id, duration_ms,
                     running);
            return -1;
        }
        if (running != 0) {
            xgo_cli_sleep_ms(20);
        }
    }
    return 0;
}

int xgo_cli_cmd_action(xgo_cli_t *cli, int argc, char **argv)
{
    uint8_t id = 0;
    int wait = 0, i;
    const char *word = NULL;
    long duration_ms;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--wait") == 0) {
            wait = 1;
        } else if (word == NULL) {
            word = argv[i];
        } else {
            return xgo_cli_usage_error("action takes one NAME|N, not also '%s'", argv[i]);
        }
    }
    if (word == NULL || !xgo_cli_action_id(word, &id)) {
        return xgo_cli_usage_error("action needs a preset: 1..%u, %u or a name such as 'lie down'%s%s",
                                   XGO_ACTION_LAST, XGO_ACTION_RESET, word ? ", not " : "",
                                   word ? word : "");
    }
    duration_ms = (long)(xgo_action_duration_ticks(id) * 1000u / XGO_TICK_HZ);
    if (xgo_cli_write(cli, XGO_REG_ACTION, &id, 1) != 0 || (wait && xgo_cli_action_wait(cli, id, duration_ms) != 0)) {
        return xgo_cli_fail(cli);
    }
    if (!wait) {
        uint8_t mode; /* the board answers in order: it has the write */
        if (xgo_cli_read(cli, XGO_REG_MODE, 1, &mode) != 0) {
            return xgo_cli_fail(cli);
        }
    }
    if (cli->json) {
        xgo_host_json_t *json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "action");
        xgo_host_json_uint(json, id);
        xgo_host_json_key(json, "name");
        xgo_host_json_string(json, id == 0 ? "stop" : xgo_action_name(id));
        xgo_host_json_key(json, "duration_ms");
        xgo_host_json_uint(json, (uint64_t)duration_ms);
        xgo_host_json_key(json, "done");
        xgo_host_json_bool(json, wait);
        xgo_cli_json_end(json);
    } else if (id == 0) {
        printf("action stopped\n");
    } else {
        printf("action %u %s: %ld.%03ld s%s\n", id, xgo_action_name(id), duration_ms / 1000,
               duration_ms % 1000, wait ? ", done" : "");
    }
    return XGO_CLI_OK;
}

int xgo_cli_cmd_diag(xgo_cli_t *cli, int argc, char **argv)
{
    uint8_t data[XGO_DIAG_SLOTS * 4u];
    uint32_t frames_ok;
    (void)argv;
    if (argc != 1) {
        return xgo_cli_usage_error("diag takes no arguments");
    }
    if (xgo_cli_read(cli, XGO_REG_DIAG, (uint8_t)sizeof data, data) != 0) {
        char why[XGO_CLI_ERR_LEN];
        snprintf(why, sizeof why, "%s", cli->err);
        snprintf(cli->err, sizeof cli->err,
                 "%s has no diagnostic block, as on a real robot's board (%.700s)", cli->port, why);
        return xgo_cli_fail(cli);
    }
    /* This very read was a frame the board accepted: a board that keeps
     * counters there counts it, so frames_ok cannot read 0. */
    frames_ok = (uint32_t)data[0] | (uint32_t)data[1] << 8 | (uint32_t)data[2] << 16 |
                (uint32_t)data[3] << 24;
    if (frames_ok == 0) {
        snprintf(cli->err, sizeof cli->err,
                 "%s has no diagnostic block, as on a real robot's board (0xC4.. reads frames_ok 0 "
                 "although this read was a frame)",
                 cli->port);
        return xgo_cli_fail(cli);
    }
    if (cli->json) {
        xgo_host_json_t *json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "registers");
        xgo_host_json_array_begin(json);
        xgo_cli_show_regs(cli, XGO_REG_DIAG, data, sizeof data, json);
        xgo_host_json_array_end(json);
        xgo_cli_json_end(json);
    } else {
        xgo_cli_show_regs(cli, XGO_REG_DIAG, data, sizeof data, NULL);
    }
    return XGO_CLI_OK;
}
