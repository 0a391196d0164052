/*
 * cmd_decode.c - xgo-cli decode [FILE|-]: frames in a byte stream, offline,
 * as --trace lines. Input: a capture (pcap, both directions with their
 * times), hex text ("55 00 09 02 ...", "0x55,0x00", "5500 0902"), or raw
 * binary bytes. A plain stream may hold requests and replies alike.
 */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "pcap.h"
#include "tracer.h"

#define XGO_CLI_DECODE_MAX (16u << 20) /* bytes of a plain stream */

/* Hex text: only hex digits, "0x" prefixes, whitespace, ',' and ':'. */
static int xgo_cli_is_hex_text(const uint8_t *b, size_t n)
{
    size_t i, digits = 0;
    for (i = 0; i < n; i++) {
        int c = b[i];
        if (isxdigit(c)) {
            digits++;
        } else if (c == 'x' && i > 0 && b[i - 1] == '0') {
            digits--; /* the 0 of "0x" was no digit */
        } else if (!isspace(c) && c != ',' && c != ':') {
            return 0;
        }
    }
    return digits > 0;
}

/* Hex text -> bytes in place; -1 on an odd digit run. */
static long xgo_cli_hex_text(uint8_t *b, size_t n)
{
    size_t i = 0, out = 0;
    while (i < n) {
        size_t start;
        if (!isxdigit(b[i])) {
            i++;
            continue;
        }
        if (b[i] == '0' && i + 1 < n && b[i + 1] == 'x') {
            i += 2;
            continue;
        }
        start = i;
        while (i < n && isxdigit(b[i])) {
            i++;
        }
        if ((i - start) % 2 != 0) {
            return -1;
        }
        for (; start < i; start += 2) {
            char pair[3] = {(char)b[start], (char)b[start + 1], '\0'};
            b[out++] = (uint8_t)strtoul(pair, NULL, 16);
        }
    }
    return (long)out;
}

static void xgo_cli_note(xgo_host_trace_t *trace, xgo_host_json_t *json, const char *what,
                         const uint8_t *b, size_t n)
{
    char line[4600];
    size_t len, i;
    uint64_t t = trace->now_us - trace->origin_us;
    len = (size_t)snprintf(line, sizeof line, "%4lu.%06lu %s", (unsigned long)(t / 1000000u),
                           (unsigned long)(t % 1000000u), what);
    for (i = 0; i < n && len + 4 < sizeof line; i++) {
        if (what[0] == 'n') {
            len += (size_t)snprintf(line + len, sizeof line - len, "%c",
                                    (b[i] >= 0x20 && b[i] < 0x7F) ? b[i] : '.');
        } else {
            len += (size_t)snprintf(line + len, sizeof line - len, i ? " %02X" : " [%02X", b[i]);
        }
    }
    if (what[0] != 'n' && n > 0 && len + 2 < sizeof line) {
        snprintf(line + len, sizeof line - len, "]");
    }
    if (json != NULL) {
        xgo_host_json_string(json, line);
    } else {
        xgo_host_trace_flush(trace);
        printf("%s\n", line);
    }
}

/* A capture: host->board bytes through a board-side parser, replies
 * through a host-side one, each at its time since the first record. */
static int xgo_cli_decode_pcap(xgo_cli_t *cli, const char *path, xgo_host_trace_t *trace,
                               xgo_host_json_t *json, unsigned long *frames, unsigned long *drops)
{
    static xgo_host_pcap_reader_t reader;
    static xgo_cli_tracer_t board, host;
    xgo_host_pcap_record_t rec;
    uint64_t origin = 0;
    int r;
    if (xgo_host_pcap_open(&reader, path, cli->err, sizeof cli->err) != 0) {
        return -1;
    }
    xgo_cli_tracer_init(&board, XGO_PARSER_BOARD, trace, json);
    xgo_cli_tracer_init(&host, XGO_PARSER_HOST, trace, json);
    while ((r = xgo_host_pcap_next(&reader, &rec, cli->err, sizeof cli->err)) == 1) {
        uint64_t t;
        if (rec.number == 1) {
            origin = rec.wall_us;
        }
        t = rec.wall_us > origin ? rec.wall_us - origin : 0;
        trace->now_us = t;
        if (rec.dir == XGO_PCAP_HOST_TO_BOARD) {
            xgo_cli_tracer_feed(&board, rec.bytes, rec.n, t);
        } else if (rec.dir == XGO_PCAP_BOARD_TO_HOST) {
            xgo_cli_tracer_feed(&host, rec.bytes, rec.n, t);
        } else if (rec.dir == XGO_PCAP_HANGUP) {
            xgo_cli_note(trace, json, "hang-up (the board drops a partial frame)", rec.bytes, 0);
        } else {
            xgo_cli_note(trace, json, rec.dir == XGO_PCAP_NOTE ? "note " : "discarded (no host)",
                         rec.bytes, rec.n);
        }
    }
    xgo_cli_tracer_finish(&board);
    xgo_cli_tracer_finish(&host);
    xgo_host_pcap_close_reader(&reader);
    *frames = board.frames + host.frames;
    *drops = board.drops + host.drops;
    return r;
}

/* A plain stream from path ("-": stdin): hex text or binary. */
static int xgo_cli_decode_stream(xgo_cli_t *cli, FILE *in, const char *path,
                                 xgo_host_trace_t *trace, xgo_host_json_t *json,
                                 unsigned long *frames, unsigned long *drops)
{
    static uint8_t buf[XGO_CLI_DECODE_MAX];
    static xgo_cli_tracer_t tracer;
    size_t n = fread(buf, 1, sizeof buf, in);
    long bytes = (long)n;
    if (ferror(in)) {
        snprintf(cli->err, sizeof cli->err, "cannot read %s", path);
        return -1;
    }
    if (n == sizeof buf && fgetc(in) != EOF) {
        snprintf(cli->err, sizeof cli->err, "%s is larger than %u MiB", path, XGO_CLI_DECODE_MAX >> 20);
        return -1;
    }
    if (xgo_cli_is_hex_text(buf, n) && (bytes = xgo_cli_hex_text(buf, n)) < 0) {
        snprintf(cli->err, sizeof cli->err, "%s: hex text with an odd number of digits in a run", path);
        return -1;
    }
    xgo_cli_tracer_init(&tracer, XGO_PARSER_ANY, trace, json);
    xgo_cli_tracer_feed(&tracer, buf, (size_t)bytes, 0);
    xgo_cli_tracer_finish(&tracer);
    *frames = tracer.frames;
    *drops = tracer.drops;
    return 0;
}

static int xgo_cli_decode_input(xgo_cli_t *cli, const char *path, xgo_host_trace_t *trace,
                                xgo_host_json_t *json, unsigned long *frames, unsigned long *drops)
{
    FILE *in = stdin;
    uint8_t head[4];
    size_t got;
    int rc;
    if (strcmp(path, "-") != 0) {
        in = fopen(path, "rb");
        if (in == NULL) {
            snprintf(cli->err, sizeof cli->err, "cannot open %s: %s", path, strerror(errno));
            return -1;
        }
        got = fread(head, 1, sizeof head, in);
        if (xgo_host_pcap_is_pcap(head, got)) {
            fclose(in);
            return xgo_cli_decode_pcap(cli, path, trace, json, frames, drops);
        }
        rewind(in);
    }
    rc = xgo_cli_decode_stream(cli, in, path, trace, json, frames, drops);
    if (in != stdin) {
        fclose(in);
    }
    return rc;
}

int xgo_cli_cmd_decode(xgo_cli_t *cli, int argc, char **argv)
{
    xgo_host_trace_t trace;
    xgo_host_json_t *json = NULL;
    unsigned long frames = 0, drops = 0;
    const char *path = argc > 1 ? argv[1] : "-";
    int rc;
    if (argc > 2) {
        return xgo_cli_usage_error("decode takes one FILE (or - for stdin)");
    }
    xgo_host_trace_init(&trace, stdout, 0);
    if (cli->json) {
        json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "lines");
        xgo_host_json_array_begin(json);
    }
    rc = xgo_cli_decode_input(cli, path, &trace, json, &frames, &drops);
    if (json != NULL && rc == 0) {
        xgo_host_json_array_end(json);
        xgo_host_json_key(json, "frames");
        xgo_host_json_uint(json, frames);
        xgo_host_json_key(json, "dropped");
        xgo_host_json_uint(json, drops);
        xgo_cli_json_end(json);
    }
    fflush(stdout);
    return rc == 0 ? XGO_CLI_OK : xgo_cli_fail(cli);
}
