/*
 * cmd_raw.c - xgo-cli raw (exactly these bytes on the line, and what comes
 * back, decoded) and checksum (the sum a frame needs).
 */
#include <string.h>

#include "cli.h"
#include "tracer.h"

#define XGO_CLI_RAW_MAX 1024u
#define XGO_CLI_RAW_QUIET_MS 200L /* how long to listen when no reply is due */

/* Counts the read requests among bytes, by the board's own parser. */
static void xgo_cli_count_read(void *ctx, const xgo_frame_t *f)
{
    unsigned *reads = ctx;
    *reads += f->type == XGO_TYPE_READ;
}

static unsigned xgo_cli_reads_in(const uint8_t *b, size_t n)
{
    xgo_parser_t p;
    xgo_parser_sink_t sink;
    unsigned reads = 0;
    memset(&sink, 0, sizeof sink);
    sink.on_frame = xgo_cli_count_read;
    sink.ctx = &reads;
    xgo_parser_init(&p, &sink, 0);
    xgo_parser_feed(&p, b, n, 0);
    return reads;
}

/* LEN and SUM of the frame in b filled in; 0 when b is no frame shape. */
static int xgo_cli_fix_frame(uint8_t *b, size_t n)
{
    if (n < XGO_FRAME_OVERHEAD + 1u || n > XGO_FRAME_MAX_LEN || b[0] != XGO_FRAME_HEAD0 ||
        b[1] != XGO_FRAME_HEAD1 || b[n - 2] != XGO_FRAME_TAIL0 || b[n - 1] != XGO_FRAME_TAIL1) {
        return 0;
    }
    b[2] = (uint8_t)n;
    b[n - 3] = xgo_frame_checksum(b[2], b[3], b[4], b + 5, n - XGO_FRAME_OVERHEAD);
    return 1;
}

static void xgo_cli_print_hex(const char *label, const uint8_t *b, size_t n)
{
    size_t i;
    printf("%s", label);
    for (i = 0; i < n; i++) {
        printf(" %02X", b[i]);
    }
    printf("\n");
}

/* Waits for `reads` replies (or listens briefly if none is due) and shows
 * what came back as trace lines. Returns 0 when every reply came. */
static int xgo_cli_raw_answer(xgo_cli_t *cli, unsigned reads, const uint8_t *sent, size_t sent_n)
{
    static uint8_t got[4096];
    xgo_host_trace_t trace;
    xgo_cli_tracer_t tracer;
    xgo_host_json_t *json = NULL;
    size_t n = 0;
    uint64_t elapsed_ms = 0;
    long wait = reads > 0 ? cli->timeout_ms : (cli->timeout_ms < XGO_CLI_RAW_QUIET_MS ? cli->timeout_ms : XGO_CLI_RAW_QUIET_MS);
    xgo_host_trace_init(&trace, stdout, 0);
    if (cli->json) {
        json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "sent");
        xgo_host_json_hex(json, sent, sent_n);
        xgo_host_json_key(json, "frames");
        xgo_host_json_array_begin(json);
    } else {
        xgo_cli_print_hex("sent", sent, sent_n);
    }
    xgo_cli_tracer_init(&tracer, XGO_PARSER_HOST, &trace, json);
    /* listen in slices until every reply is there, or the wait is over */
    do {
        long slice = reads > 0 ? 20 : wait;
        size_t k = xgo_cli_collect(cli, got + n, sizeof got - n, slice);
        xgo_cli_tracer_feed(&tracer, got + n, k, elapsed_ms * 1000u);
        n += k;
        elapsed_ms += (uint64_t)slice;
    } while (tracer.replies < reads && (long)elapsed_ms < wait && n < sizeof got);
    xgo_cli_tracer_finish(&tracer);
    if (json != NULL) {
        xgo_host_json_array_end(json);
        xgo_host_json_key(json, "received");
        xgo_host_json_hex(json, got, n);
        xgo_cli_json_end(json);
    } else if (n == 0) {
        printf("received nothing\n");
    }
    if (tracer.replies < reads) {
        snprintf(cli->err, sizeof cli->err, "%lu of %u replies from %s within %ld ms (received %lu bytes)",
                 tracer.replies, reads, cli->port, cli->timeout_ms, (unsigned long)n);
        return -1;
    }
    return 0;
}

int xgo_cli_cmd_raw(xgo_cli_t *cli, int argc, char **argv)
{
    uint8_t bytes[XGO_CLI_RAW_MAX];
    char err[256];
    int fix = 0, n;
    if (argc > 1 && strcmp(argv[1], "--fix") == 0) {
        fix = 1;
        argc--;
        argv++;
    }
    if (argc < 2) {
        return xgo_cli_usage_error("raw needs HEX bytes");
    }
    n = xgo_cli_parse_hex(argc - 1, argv + 1, bytes, sizeof bytes, err, sizeof err);
    if (n < 0) {
        return xgo_cli_usage_error("%s", err);
    }
    if (fix && !xgo_cli_fix_frame(bytes, (size_t)n)) {
        return xgo_cli_usage_error("--fix needs one whole frame: 55 00 LEN TYPE ADDR DATA... SUM 00 AA "
                                   "(LEN and SUM may be anything, e.g. 00)");
    }
    if (xgo_cli_open(cli) != 0 || xgo_cli_send(cli, bytes, (size_t)n) != 0 ||
        xgo_cli_raw_answer(cli, xgo_cli_reads_in(bytes, (size_t)n), bytes, (size_t)n) != 0) {
        return xgo_cli_fail(cli);
    }
    return XGO_CLI_OK;
}

int xgo_cli_cmd_checksum(xgo_cli_t *cli, int argc, char **argv)
{
    uint8_t b[XGO_CLI_RAW_MAX];
    uint8_t frame[XGO_FRAME_MAX_LEN];
    char err[256];
    size_t len;
    int n = xgo_cli_parse_hex(argc - 1, argv + 1, b, sizeof b, err, sizeof err);
    int whole, was_ok = 1;
    if (n < 0) {
        return xgo_cli_usage_error("%s", err);
    }
    whole = n >= 9 && b[0] == XGO_FRAME_HEAD0 && b[1] == XGO_FRAME_HEAD1 &&
            b[n - 2] == XGO_FRAME_TAIL0 && b[n - 1] == XGO_FRAME_TAIL1;
    if (whole) {
        uint8_t given_len = b[2], given_sum = b[n - 3];
        memcpy(frame, b, (size_t)n);
        (void)xgo_cli_fix_frame(frame, (size_t)n);
        len = (size_t)n;
        was_ok = given_len == frame[2] && given_sum == frame[n - 3];
    } else if (n >= 3) {
        len = xgo_frame_encode(b[0], b[1], b + 2, (size_t)n - 2, frame, sizeof frame);
    } else {
        len = 0;
    }
    if (len == 0) {
        return xgo_cli_usage_error("checksum needs TYPE ADDR DATA... (1..247 data bytes) or a whole "
                                   "frame 55 00 LEN TYPE ADDR DATA... SUM 00 AA");
    }
    if (cli->json) {
        xgo_host_json_t *json = xgo_cli_json_begin(cli);
        xgo_host_json_key(json, "checksum");
        xgo_host_json_uint(json, frame[len - 3]);
        xgo_host_json_key(json, "frame");
        xgo_host_json_hex(json, frame, len);
        if (whole) {
            xgo_host_json_key(json, "given_frame_ok");
            xgo_host_json_bool(json, was_ok);
        }
        xgo_cli_json_end(json);
        return XGO_CLI_OK;
    }
    printf("checksum 0x%02X", frame[len - 3]);
    if (whole && !was_ok) {
        printf(" (the frame given has LEN 0x%02X and SUM 0x%02X: wrong)", b[2], b[n - 3]);
    } else if (whole) {
        printf(" (the frame given is right)");
    }
    printf("\n");
    xgo_cli_print_hex("frame", frame, len);
    return XGO_CLI_OK;
}
