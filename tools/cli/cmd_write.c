/*
 * cmd_write.c - xgo-cli write REG=VALUE...: every pair is checked (name,
 * access, valid set, range) before the first byte is sent; then the frames
 * go out and a read of the mode register confirms the board took them (it
 * answers in order, and never answers a write itself).
 */
#include <string.h>

#include "cli.h"
#include "xgo/regs.h"

#define XGO_CLI_MAX_WRITES 64

typedef struct xgo_cli_write_s {
    uint8_t addr;
    uint8_t n;
    uint8_t data[XGO_FRAME_MAX_DATA];
} xgo_cli_write_t;

/* "REG=VALUE" -> one write; returns 0 or a usage exit code. */
static int xgo_cli_parse_pair(xgo_cli_t *cli, const char *arg, xgo_cli_write_t *w)
{
    char reg[64], err[512];
    const char *eq = strchr(arg, '=');
    int n;
    if (eq == NULL || eq == arg || (size_t)(eq - arg) >= sizeof reg) {
        return xgo_cli_usage_error("write needs REG=VALUE, not '%s'", arg);
    }
    memcpy(reg, arg, (size_t)(eq - arg));
    reg[eq - arg] = '\0';
    if (!xgo_cli_parse_reg(reg, 1, xgo_cli_value_unit(eq + 1), &w->addr, err, sizeof err)) {
        return xgo_cli_usage_error("%s", err);
    }
    n = xgo_cli_parse_value(cli, w->addr, eq + 1, w->data, sizeof w->data, err, sizeof err);
    if (n < 0) {
        /* a board that could not tell its model is a failed exchange */
        if (strstr(err, "needed to know the model") != NULL) {
            snprintf(cli->err, sizeof cli->err, "%s", err);
            return xgo_cli_fail(cli);
        }
        return xgo_cli_usage_error("%s", err);
    }
    w->n = (uint8_t)n;
    return 0;
}

int xgo_cli_cmd_write(xgo_cli_t *cli, int argc, char **argv)
{
    static xgo_cli_write_t writes[XGO_CLI_MAX_WRITES];
    xgo_host_json_t *json = NULL;
    uint8_t mode;
    int i;
    if (argc < 2 || argc - 1 > XGO_CLI_MAX_WRITES) {
        return xgo_cli_usage_error("write needs 1..%d REG=VALUE", XGO_CLI_MAX_WRITES);
    }
    for (i = 1; i < argc; i++) {
        int rc = xgo_cli_parse_pair(cli, argv[i], &writes[i - 1]);
        if (rc != 0) {
            return rc;
        }
    }
    for (i = 0; i < argc - 1; i++) {
        if (xgo_cli_write(cli, writes[i].addr, writes[i].data, writes[i].n) != 0) {
            return xgo_cli_fail(cli);
        }
    }
    if (xgo_cli_read(cli, XGO_REG_MODE, 1, &mode) != 0) {
        return xgo_cli_fail(cli);
    }
    if (cli->json) {
        json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "written");
        xgo_host_json_array_begin(json);
    }
    for (i = 0; i < argc - 1; i++) {
        xgo_cli_show_write(cli, writes[i].addr, writes[i].data, writes[i].n, json);
    }
    if (json != NULL) {
        xgo_host_json_array_end(json);
        xgo_cli_json_end(json);
    }
    return XGO_CLI_OK;
}
