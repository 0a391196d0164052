/*
 * cli.h - xgo-cli: talk to an XGO board (a real robot's serial port or
 * xgo-emu's pty) from the shell. What the command files share:
 *
 *   main.c      global options, command table, usage, exit codes
 *   link.c      the port: open, send a frame, wait for its reply (the
 *               core's encoder and a host-side parser), --capture
 *   regarg.c    REG (name, address) and VALUE (raw, physical, words) words
 *   show.c      one register as a line or a JSON object (units, meanings)
 *   cmd_*.c     one file per group of commands
 *
 * Exit codes: 0 ok, 1 no or bad reply (or a file that cannot be read),
 * 2 usage.
 */
#ifndef XGO_CLI_H
#define XGO_CLI_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "json_out.h"
#include "pcap.h"
#include "xgo/profile.h"
#include "xgo/protocol.h"
#include "xgo/regs.h"

#define XGO_CLI_OK 0
#define XGO_CLI_FAIL 1
#define XGO_CLI_USAGE 2

#define XGO_CLI_ERR_LEN 1024u

typedef struct xgo_cli_s {
    /* global options */
    const char *port;        /* -p, default $XGO_PORT */
    uint32_t baud;           /* --baud */
    long timeout_ms;         /* --timeout: wait for a reply */
    int json;                /* --json */
    const char *capture;     /* --capture FILE.pcap */
    const xgo_profile_t *profile; /* --profile, NULL = ask the board (0x02) */

    /* the open link */
    int fd;
    uint64_t t0_us;          /* monotonic time the port was opened */
    xgo_host_pcap_writer_t pcap;
    xgo_parser_t parser;     /* host side: the board's replies */
    uint8_t reply[XGO_FRAME_MAX_DATA];
    uint8_t reply_addr;
    uint8_t reply_len;
    int reply_ready;
    uint8_t seen[512];       /* bytes received for the current request */
    size_t seen_len;
    xgo_drop_reason_t last_drop; /* why the parser last dropped input */

    char err[XGO_CLI_ERR_LEN]; /* message of the last failure */
} xgo_cli_t;

/* A command: argv[0] is its name. Returns an exit code. */
typedef int (*xgo_cli_cmd_fn)(xgo_cli_t *cli, int argc, char **argv);

/* ---- main.c */
/* "xgo-cli: <message>" and the usage on stderr; returns XGO_CLI_USAGE. */
int xgo_cli_usage_error(const char *fmt, ...);
/* "xgo-cli: <cli->err>" on stderr (and {"ok":false,...} with --json);
 * returns XGO_CLI_FAIL. */
int xgo_cli_fail(xgo_cli_t *cli);

/* ---- link.c */
/* Opens cli->port (raw 8N1 at cli->baud) and the capture, if any. */
int xgo_cli_open(xgo_cli_t *cli);
void xgo_cli_close(xgo_cli_t *cli);
/* Sends n bytes as they are. */
int xgo_cli_send(xgo_cli_t *cli, const uint8_t *bytes, size_t n);
/* Reads n registers at addr into out (the reply's data). Returns 0, or -1
 * with cli->err naming the port, what was sent and what came back. */
int xgo_cli_read(xgo_cli_t *cli, uint8_t addr, uint8_t n, uint8_t *out);
/* Sends a write frame (the board never answers one). */
int xgo_cli_write(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n);
/* Collects whatever arrives within ms into buf (raw); returns the count. */
size_t xgo_cli_collect(xgo_cli_t *cli, uint8_t *buf, size_t cap, long ms);
/* The profile for unit conversions: --profile, else the board's 0x02. */
const xgo_profile_t *xgo_cli_profile(xgo_cli_t *cli);

/* ---- regarg.c */
/* The register row at addr for the board's model once it is known (--profile
 * or asked), else the Mini's (the Mini2 has other rows: the arm). */
const xgo_reg_desc_t *xgo_cli_reg(const xgo_cli_t *cli, uint8_t addr);
/* Its name, "-" when the model lacks addr. */
const char *xgo_cli_reg_name(const xgo_cli_t *cli, uint8_t addr);
/* REG: a register name of the core's table ("vx"), an address ("0x30",
 * "48"), or a name's unique part after '_' ("speed" -> servo_speed).
 * want_write narrows suffix matches to writable registers, unit (xgo_unit_t,
 * 0 = any) to registers with that kind of value. Returns 1 and *addr, or 0
 * with a message in err. */
int xgo_cli_parse_reg(const char *word, int want_write, int unit, uint8_t *addr, char *err,
                      size_t err_size);
/* A whole number in decimal or 0x-hex within lo..hi. */
int xgo_cli_parse_number(const char *word, long lo, long hi, long *out);
/* Hex bytes: each word one or more pairs ("55", "5500", "0x55"). Returns
 * the count, or -1 with a message in err. */
int xgo_cli_parse_hex(int argc, char **argv, uint8_t *out, size_t cap, char *err, size_t err_size);
/* VALUE for register addr -> bytes to write there (raw bytes "0xff" /
 * "255" / "0x8080", a physical value "12.5cm/s", "-10deg", "2.5s", a word
 * the register's values have ("walk"), or text for bt_name). Checks the
 * value against the register's valid set. Returns the byte count, or -1
 * with a message in err. */
int xgo_cli_parse_value(xgo_cli_t *cli, uint8_t addr, const char *value, uint8_t *out,
                        size_t cap, char *err, size_t err_size);
/* The xgo_unit_t a VALUE's suffix names (0 = raw / none). */
int xgo_cli_value_unit(const char *value);

/* ---- show.c */
/* The registers a read of n bytes at addr returned (data): one line each on
 * stdout, or with json != NULL one object each appended to the array being
 * written there. */
void xgo_cli_show_regs(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                       xgo_host_json_t *json);
/* The same for bytes written at addr (write views: 0x3F takes a heading). */
void xgo_cli_show_write(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                        xgo_host_json_t *json);
/* What the register at addr means, from a read of n bytes there: the
 * text of its line ("+25.00 cm/s", "-3.20 deg", "walk"), else its bytes. */
void xgo_cli_reg_text(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n, char *out,
                      size_t out_size);
/* The meaning of one byte of register addr: "+25.00 cm/s", "walk", "". */
void xgo_cli_meaning(xgo_cli_t *cli, uint8_t addr, uint8_t b, char *out, size_t out_size);
/* A value in base units (um, mdeg, ms ...) as text in the display unit:
 * "+25.00 cm/s" (sign: print '+' for positive values). */
void xgo_cli_format_value(int unit, int32_t value, int sign, char *out, size_t out_size);
/* A JSON document for --json: {"ok":true, ... ; xgo_cli_json_end prints it. */
xgo_host_json_t *xgo_cli_json_begin(xgo_cli_t *cli);
void xgo_cli_json_end(xgo_host_json_t *w);

/* ---- commands */
int xgo_cli_cmd_read(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_dump(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_watch(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_write(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_action(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_diag(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_raw(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_checksum(xgo_cli_t *cli, int argc, char **argv);
int xgo_cli_cmd_decode(xgo_cli_t *cli, int argc, char **argv);

#endif /* XGO_CLI_H */
