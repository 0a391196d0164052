/*
 * link.c - xgo-cli's side of the serial line (see cli.h): frames out with
 * the core's encoder, replies in through the core's parser on the host side,
 * every byte into the --capture file as it passes.
 */
#include <errno.h>
#include <poll.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "clock.h"
#include "serial.h"
#include "trace.h"
#include "xgo/regs.h"

#define XGO_CLI_VERSION_NOTE "xgo-cli 0.1.0"

static void xgo_cli_on_reply(void *ctx, const xgo_frame_t *f)
{
    xgo_cli_t *cli = ctx;
    if (cli->reply_ready) {
        return; /* the first reply answers the request; later ones are noise */
    }
    memcpy(cli->reply, f->data, f->len);
    cli->reply_addr = f->addr;
    cli->reply_len = f->len;
    cli->reply_ready = 1;
}

static void xgo_cli_on_drop(void *ctx, xgo_drop_reason_t why, const uint8_t *bytes, size_t n)
{
    xgo_cli_t *cli = ctx;
    (void)bytes;
    (void)n;
    cli->last_drop = why;
}

static uint32_t xgo_cli_ms(const xgo_cli_t *cli)
{
    return (uint32_t)((xgo_host_clock_us() - cli->t0_us) / 1000u);
}

static int xgo_cli_open_capture(xgo_cli_t *cli)
{
    char note[512];
    if (xgo_host_pcap_create(&cli->pcap, cli->capture, cli->t0_us, cli->err, sizeof cli->err) != 0) {
        return -1;
    }
    snprintf(note, sizeof note, "%s port=%s baud=%lu", XGO_CLI_VERSION_NOTE, cli->port,
             (unsigned long)cli->baud);
    return xgo_host_pcap_note(&cli->pcap, cli->t0_us, note);
}

int xgo_cli_open(xgo_cli_t *cli)
{
    xgo_parser_sink_t sink;
    if (cli->fd >= 0) {
        return 0;
    }
    cli->fd = xgo_host_serial_open(cli->port, cli->baud, cli->err, sizeof cli->err);
    if (cli->fd < 0) {
        return -1;
    }
    cli->t0_us = xgo_host_clock_us();
    sink.on_frame = xgo_cli_on_reply;
    sink.on_drop = xgo_cli_on_drop;
    sink.ctx = cli;
    xgo_parser_init_side(&cli->parser, &sink, XGO_PARSER_DEFAULT_TIMEOUT_MS, XGO_PARSER_HOST);
    if (cli->capture != NULL && xgo_cli_open_capture(cli) != 0) {
        close(cli->fd);
        cli->fd = -1;
        return -1;
    }
    return 0;
}

void xgo_cli_close(xgo_cli_t *cli)
{
    if (cli->fd >= 0) {
        close(cli->fd);
        cli->fd = -1;
    }
    xgo_host_pcap_close(&cli->pcap);
}

static void xgo_cli_capture(xgo_cli_t *cli, xgo_pcap_dir_t dir, const uint8_t *b, size_t n)
{
    if (cli->capture != NULL) {
        (void)xgo_host_pcap_write(&cli->pcap, xgo_host_clock_us(), dir, XGO_PCAP_TICK_UNKNOWN, b, n);
    }
}

int xgo_cli_send(xgo_cli_t *cli, const uint8_t *bytes, size_t n)
{
    uint64_t deadline = xgo_host_clock_us() + (uint64_t)cli->timeout_ms * 1000u;
    size_t done = 0;
    while (done < n) {
        ssize_t k = write(cli->fd, bytes + done, n - done);
        if (k > 0) {
            xgo_cli_capture(cli, XGO_PCAP_HOST_TO_BOARD, bytes + done, (size_t)k);
            done += (size_t)k;
            continue;
        }
        if (k < 0 && errno != EAGAIN && errno != EINTR) {
            snprintf(cli->err, sizeof cli->err, "cannot write to %s: %s", cli->port, strerror(errno));
            return -1;
        }
        if (xgo_host_clock_us() >= deadline) {
            snprintf(cli->err, sizeof cli->err, "%s takes no bytes: %lu of %lu sent in %ld ms",
                     cli->port, (unsigned long)done, (unsigned long)n, cli->timeout_ms);
            return -1;
        }
        {
            struct pollfd p;
            p.fd = cli->fd;
            p.events = POLLOUT;
            (void)poll(&p, 1, 10);
        }
    }
    return 0;
}

/* Reads what is there (waiting up to wait_ms for the first byte) into the
 * parser and cli->seen. Returns bytes read, 0 on timeout, -1 when the port
 * is gone (message in err). */
static int xgo_cli_receive(xgo_cli_t *cli, long wait_ms)
{
    uint8_t buf[512];
    struct pollfd p;
    ssize_t k;
    p.fd = cli->fd;
    p.events = POLLIN;
    p.revents = 0;
    if (poll(&p, 1, (int)wait_ms) <= 0) {
        return 0;
    }
    k = read(cli->fd, buf, sizeof buf);
    if (k < 0 && (errno == EAGAIN || errno == EINTR)) {
        return 0;
    }
    if (k <= 0) {
        snprintf(cli->err, sizeof cli->err, "%s closed (%s)", cli->port,
                 k == 0 ? "end of file" : strerror(errno));
        return -1;
    }
    xgo_cli_capture(cli, XGO_PCAP_BOARD_TO_HOST, buf, (size_t)k);
    if (cli->seen_len < sizeof cli->seen) {
        size_t room = sizeof cli->seen - cli->seen_len;
        size_t take = (size_t)k < room ? (size_t)k : room;
        memcpy(cli->seen + cli->seen_len, buf, take);
        cli->seen_len += take;
    }
    xgo_parser_feed(&cli->parser, buf, (size_t)k, xgo_cli_ms(cli));
    return (int)k;
}

/* "55 00 09 ..." of up to 64 bytes into out. */
static void xgo_cli_hex(const uint8_t *b, size_t n, char *out, size_t out_size)
{
    size_t i, len = 0;
    out[0] = '\0';
    for (i = 0; i < n && len + 4 < out_size; i++) {
        if (i == 64) {
            snprintf(out + len, out_size - len, " ...");
            return;
        }
        len += (size_t)snprintf(out + len, out_size - len, i ? " %02X" : "%02X", b[i]);
    }
}

static void xgo_cli_reply_error(xgo_cli_t *cli, const char *what, const uint8_t *req, size_t n)
{
    char sent[256], got[256];
    xgo_cli_hex(req, n, sent, sizeof sent);
    if (cli->seen_len == 0) {
        snprintf(cli->err, sizeof cli->err, "no reply from %s within %ld ms to %s (sent %s)",
                 cli->port, cli->timeout_ms, what, sent);
        return;
    }
    xgo_cli_hex(cli->seen, cli->seen_len, got, sizeof got);
    if (cli->reply_ready) {
        snprintf(cli->err, sizeof cli->err,
                 "bad reply from %s to %s (sent %s): received %s, a reply for 0x%02X n=%u", cli->port,
                 what, sent, got, cli->reply_addr, (unsigned)cli->reply_len);
    } else {
        snprintf(cli->err, sizeof cli->err, "bad reply from %s to %s (sent %s): received %s (%s)",
                 cli->port, what, sent, got,
                 cli->last_drop != XGO_DROP_NONE ? xgo_drop_reason_name(cli->last_drop)
                                                 : "no whole frame");
    }
}

int xgo_cli_read(xgo_cli_t *cli, uint8_t addr, uint8_t n, uint8_t *out)
{
    uint8_t req[XGO_READ_REQUEST_LEN];
    uint64_t deadline;
    char what[64];
    if (xgo_cli_open(cli) != 0) {
        return -1;
    }
    (void)xgo_frame_encode(XGO_TYPE_READ, addr, &n, 1, req, sizeof req);
    cli->reply_ready = 0;
    cli->seen_len = 0;
    cli->last_drop = XGO_DROP_NONE;
    if (xgo_cli_send(cli, req, sizeof req) != 0) {
        return -1;
    }
    deadline = xgo_host_clock_us() + (uint64_t)cli->timeout_ms * 1000u;
    while (!cli->reply_ready) {
        uint64_t now = xgo_host_clock_us();
        if (now >= deadline) {
            break;
        }
        if (xgo_cli_receive(cli, (long)((deadline - now + 999u) / 1000u)) < 0) {
            return -1;
        }
    }
    snprintf(what, sizeof what, "read 0x%02X %s n=%u", addr, xgo_cli_reg_name(cli, addr), (unsigned)n);
    if (!cli->reply_ready || cli->reply_addr != addr || cli->reply_len != n) {
        xgo_cli_reply_error(cli, what, req, sizeof req);
        return -1;
    }
    memcpy(out, cli->reply, n);
    return 0;
}

int xgo_cli_write(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n)
{
    uint8_t frame[XGO_FRAME_MAX_LEN];
    size_t len = xgo_frame_encode(XGO_TYPE_WRITE, addr, data, n, frame, sizeof frame);
    if (len == 0) {
        snprintf(cli->err, sizeof cli->err, "%lu bytes do not fit one frame", (unsigned long)n);
        return -1;
    }
    if (xgo_cli_open(cli) != 0) {
        return -1;
    }
    return xgo_cli_send(cli, frame, len);
}

size_t xgo_cli_collect(xgo_cli_t *cli, uint8_t *buf, size_t cap, long ms)
{
    uint64_t deadline = xgo_host_clock_us() + (uint64_t)ms * 1000u;
    cli->seen_len = 0;
    for (;;) {
        uint64_t now = xgo_host_clock_us();
        if (now >= deadline || xgo_cli_receive(cli, (long)((deadline - now + 999u) / 1000u)) < 0) {
            break;
        }
    }
    if (cli->seen_len < cap) {
        cap = cli->seen_len;
    }
    memcpy(buf, cli->seen, cap);
    return cap;
}

const xgo_profile_t *xgo_cli_profile(xgo_cli_t *cli)
{
    uint8_t version;
    if (cli->profile != NULL) {
        return cli->profile;
    }
    if (xgo_cli_read(cli, XGO_REG_VERSION, 1, &version) != 0) {
        return NULL;
    }
    cli->profile = xgo_profile_get(xgo_version_profile(version));
    return cli->profile;
}
