/*
 * cmd_read.c - xgo-cli read, dump, watch: registers from the board, decoded.
 */
#include <signal.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "clock.h"
#include "xgo/regs.h"

/* How many bytes a read of register addr takes by default: its width; the
 * computed views as the vendor library reads them (attitude as a 4-byte
 * float, the IMU block, the int16 angles). */
static unsigned xgo_cli_default_count(const xgo_cli_t *cli, uint8_t addr)
{
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    if (addr >= XGO_REG_IMU_ROLL && addr <= XGO_REG_IMU_YAW) {
        return 4;
    }
    if (addr == XGO_REG_IMU_BLOCK) {
        return XGO_IMU_BLOCK_LEN; /* read_imu() */
    }
    if (addr >= XGO_REG_IMU_ROLL16 && addr <= XGO_REG_IMU_YAW16) {
        return 2; /* read_imu_int16() */
    }
    if (d == NULL || d->addr != addr) {
        return 1;
    }
    return d->width;
}

/* Reads n at addr and shows the registers (text or into json). */
static int xgo_cli_read_show(xgo_cli_t *cli, uint8_t addr, unsigned n, xgo_host_json_t *json)
{
    uint8_t data[XGO_FRAME_MAX_DATA];
    if (xgo_cli_read(cli, addr, (uint8_t)n, data) != 0) {
        return -1;
    }
    /* the board's model names its registers (the Mini2's arm rows) and
     * scales them: asked once, after the board has answered at all */
    (void)xgo_cli_profile(cli);
    xgo_cli_show_regs(cli, addr, data, n, json);
    return 0;
}

static int xgo_cli_finish_json(xgo_cli_t *cli, xgo_host_json_t *json, int failed)
{
    if (failed) {
        return xgo_cli_fail(cli);
    }
    if (json != NULL) {
        xgo_host_json_array_end(json);
        xgo_cli_json_end(json);
    }
    return XGO_CLI_OK;
}

static xgo_host_json_t *xgo_cli_json_registers(xgo_cli_t *cli)
{
    xgo_host_json_t *json;
    if (!cli->json) {
        return NULL;
    }
    json = xgo_cli_json_begin(cli);
    xgo_host_json_key(json, "registers");
    xgo_host_json_array_begin(json);
    return json;
}

int xgo_cli_cmd_read(xgo_cli_t *cli, int argc, char **argv)
{
    uint8_t addr;
    long n;
    char err[256];
    if (argc < 2 || argc > 3) {
        return xgo_cli_usage_error("read needs REG|ADDR [N]");
    }
    if (!xgo_cli_parse_reg(argv[1], 0, 0, &addr, err, sizeof err)) {
        return xgo_cli_usage_error("%s", err);
    }
    n = (long)xgo_cli_default_count(cli, addr);
    if (argc == 3 && (!xgo_cli_parse_number(argv[2], 1, XGO_FRAME_MAX_DATA, &n) || addr + n > 256)) {
        return xgo_cli_usage_error("N must be 1..%u bytes and end by 0xFF, not '%s'",
                                   XGO_FRAME_MAX_DATA, argv[2]);
    }
    {
        xgo_host_json_t *json = xgo_cli_json_registers(cli);
        int failed = xgo_cli_read_show(cli, addr, (unsigned)n, json) != 0;
        return xgo_cli_finish_json(cli, json, failed);
    }
}

int xgo_cli_cmd_dump(xgo_cli_t *cli, int argc, char **argv)
{
    xgo_host_json_t *json;
    const xgo_profile_t *p;
    size_t i;
    (void)argv;
    if (argc != 1) {
        return xgo_cli_usage_error("dump takes no arguments");
    }
    p = xgo_cli_profile(cli); /* the rows of the board's model */
    json = xgo_cli_json_registers(cli);
    for (i = 0; i < xgo_reg_table_size(); i++) {
        uint8_t addr = xgo_reg_table_entry(i)->addr;
        if (!xgo_reg_for_model(xgo_reg_table_entry(i), p != NULL && p->arm != NULL)) {
            continue; /* the other model's row at that address (0x5D: stand / servo52) */
        }
        if (xgo_cli_read_show(cli, addr, xgo_cli_default_count(cli, addr), json) != 0) {
            return xgo_cli_finish_json(cli, json, 1);
        }
    }
    return xgo_cli_finish_json(cli, json, 0);
}

/* ---- watch */

static volatile sig_atomic_t xgo_cli_stop;

static void xgo_cli_on_sigint(int sig)
{
    (void)sig;
    xgo_cli_stop = 1;
}

typedef struct xgo_cli_watch_s {
    uint8_t addr[32];
    size_t count;
    long hz;
    long samples; /* 0 = until Ctrl-C */
} xgo_cli_watch_t;

static int xgo_cli_watch_args(int argc, char **argv, xgo_cli_watch_t *w)
{
    int i;
    char err[256];
    w->count = 0;
    w->hz = 5;
    w->samples = 0;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--hz") == 0 || strcmp(argv[i], "--count") == 0) {
            long *dst = argv[i][2] == 'h' ? &w->hz : &w->samples;
            long hi = argv[i][2] == 'h' ? 100 : 1000000000L;
            if (i + 1 >= argc || !xgo_cli_parse_number(argv[i + 1], 1, hi, dst)) {
                return xgo_cli_usage_error("%s needs a number 1..%ld", argv[i], hi);
            }
            i++;
            continue;
        }
        if (w->count == sizeof w->addr) {
            return xgo_cli_usage_error("watch takes at most %u registers", (unsigned)sizeof w->addr);
        }
        if (!xgo_cli_parse_reg(argv[i], 0, 0, &w->addr[w->count], err, sizeof err)) {
            return xgo_cli_usage_error("%s", err);
        }
        w->count++;
    }
    if (w->count == 0) {
        return xgo_cli_usage_error("watch needs at least one REG");
    }
    return 0;
}

/* One row: time, then each register's meaning (or raw bytes). */
static int xgo_cli_watch_row(xgo_cli_t *cli, const xgo_cli_watch_t *w, uint64_t t_us)
{
    size_t i;
    xgo_host_json_t *json = NULL;
    if (cli->json) {
        json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "t_ms");
        xgo_host_json_uint(json, t_us / 1000u);
        xgo_host_json_key(json, "registers");
        xgo_host_json_array_begin(json);
    } else {
        printf("%10.3f", (double)t_us / 1e6);
    }
    for (i = 0; i < w->count; i++) {
        uint8_t data[XGO_FRAME_MAX_DATA];
        unsigned n = xgo_cli_default_count(cli, w->addr[i]);
        if (xgo_cli_read(cli, w->addr[i], (uint8_t)n, data) != 0) {
            if (!cli->json) {
                printf("\n");
            }
            return -1;
        }
        if (json != NULL) {
            xgo_cli_show_regs(cli, w->addr[i], data, n, json);
        } else {
            char text[128];
            xgo_cli_reg_text(cli, w->addr[i], data, n, text, sizeof text);
            printf("  %16s", text);
        }
    }
    if (json != NULL) {
        xgo_host_json_array_end(json);
        xgo_cli_json_end(json);
    } else {
        printf("\n");
    }
    fflush(stdout);
    return 0;
}

static void xgo_cli_sleep_until(uint64_t t_us)
{
    uint64_t now = xgo_host_clock_us();
    if (t_us > now) {
        struct timespec ts;
        ts.tv_sec = (time_t)((t_us - now) / 1000000u);
        ts.tv_nsec = (long)((t_us - now) % 1000000u) * 1000L;
        nanosleep(&ts, NULL); /* a signal ends it early: the loop checks */
    }
}

int xgo_cli_cmd_watch(xgo_cli_t *cli, int argc, char **argv)
{
    xgo_cli_watch_t w;
    uint64_t start, next;
    long done = 0;
    size_t i;
    int rc = xgo_cli_watch_args(argc, argv, &w);
    if (rc != 0) {
        return rc;
    }
    if (xgo_cli_open(cli) != 0) {
        return xgo_cli_fail(cli);
    }
    signal(SIGINT, xgo_cli_on_sigint);
    signal(SIGTERM, xgo_cli_on_sigint);
    if (xgo_cli_profile(cli) == NULL) { /* the columns' names are the model's */
        return xgo_cli_fail(cli);
    }
    if (!cli->json) {
        printf("%10s", "time_s");
        for (i = 0; i < w.count; i++) {
            printf("  %16s", xgo_cli_reg_name(cli, w.addr[i]));
        }
        printf("\n");
    }
    start = next = xgo_host_clock_us();
    while (!xgo_cli_stop && (w.samples == 0 || done < w.samples)) {
        if (xgo_cli_watch_row(cli, &w, xgo_host_clock_us() - start) != 0) {
            return xgo_cli_fail(cli);
        }
        done++;
        next += 1000000u / (uint64_t)w.hz;
        if (w.samples == 0 || done < w.samples) {
            xgo_cli_sleep_until(next);
        }
    }
    return XGO_CLI_OK;
}
