/*
 * Frame encoder and the resynchronising parser.
 *
 * The parser keeps every byte of the current candidate frame in buf[0..end).
 * buf[0..checked) has passed the checks that apply to its positions; bytes in
 * buf[checked..end) are waiting to be (re)examined. On any rejection the first
 * byte is discarded and everything after it is examined again from scratch, so
 * a header that hid inside a rejected candidate (after a false LEN, inside a
 * truncated frame, ...) is still found. Each rejection discards at least one
 * byte, which bounds the work per input byte by the frame size.
 */
#include "xgo/protocol.h"

#include <stddef.h> /* offsetof */
#include <string.h>

#include "check.h"
#include "compiler.h"

/* Positions inside a frame. */
enum { POS_HEAD0 = 0, POS_HEAD1 = 1, POS_LEN = 2, POS_TYPE = 3, POS_ADDR = 4, POS_DATA = 5 };

const char *xgo_drop_reason_name(xgo_drop_reason_t reason)
{
    switch (reason) {
    case XGO_DROP_NONE: return "none";
    case XGO_DROP_BAD_CHECKSUM: return "bad checksum";
    case XGO_DROP_BAD_TAIL: return "bad tail";
    case XGO_DROP_BAD_LENGTH: return "bad length";
    case XGO_DROP_BAD_TYPE: return "bad type";
    case XGO_DROP_BAD_RANGE: return "bad address range";
    case XGO_DROP_TIMEOUT: return "timeout";
    case XGO_DROP_READ_ONLY: return "read-only register";
    case XGO_DROP_BAD_VALUE: return "value not allowed";
    case XGO_DROP_TX_OVERFLOW: return "transmit buffer full";
    case XGO_DROP_HANGUP: return "hang-up";
    case XGO_DROP_NOISE: return "noise";
    case XGO_DROP_REASON_COUNT: break;
    }
    return "unknown";
}

uint8_t xgo_frame_checksum(uint8_t len, uint8_t type, uint8_t addr, const uint8_t *data, size_t n)
{
    uint32_t sum = (uint32_t)len + type + addr;
    size_t i;
    for (i = 0; i < n; i++) {
        sum += data[i];
    }
    return (uint8_t)~sum;
}

size_t xgo_frame_seal(uint8_t type, uint8_t addr, size_t n, uint8_t *out)
{
    const size_t total = n + XGO_FRAME_OVERHEAD;
    out[POS_HEAD0] = XGO_FRAME_HEAD0;
    out[POS_HEAD1] = XGO_FRAME_HEAD1;
    out[POS_LEN] = (uint8_t)total;
    out[POS_TYPE] = type;
    out[POS_ADDR] = addr;
    out[POS_DATA + n] = xgo_frame_checksum((uint8_t)total, type, addr, &out[POS_DATA], n);
    out[POS_DATA + n + 1] = XGO_FRAME_TAIL0;
    out[POS_DATA + n + 2] = XGO_FRAME_TAIL1;
    return total;
}

size_t xgo_frame_encode(uint8_t type, uint8_t addr, const uint8_t *data, size_t n,
                        uint8_t *out, size_t out_size)
{
    if (n == 0 || n > XGO_FRAME_MAX_DATA || out == NULL || out_size < n + XGO_FRAME_OVERHEAD) {
        return 0;
    }
    memcpy(&out[POS_DATA], data, n);
    return xgo_frame_seal(type, addr, n, out);
}

void xgo_parser_init_side(xgo_parser_t *p, const xgo_parser_sink_t *sink, uint32_t timeout_ms,
                          xgo_parser_side_t side)
{
    memset(p, 0, sizeof *p);
    if (sink != NULL) {
        p->sink = *sink;
    }
    p->timeout_ms = timeout_ms;
    p->side = (uint8_t)side;
}

void xgo_parser_init(xgo_parser_t *p, const xgo_parser_sink_t *sink, uint32_t timeout_ms)
{
    xgo_parser_init_side(p, sink, timeout_ms, XGO_PARSER_BOARD);
}

size_t xgo_parser_pending(const xgo_parser_t *p)
{
    return p->end;
}

/* Where the counter of each reason the parser drops for is in its stats
 * (all uint32_t), plus one; 0 for the reasons it never gives, so a reason
 * added without a row here is not counted (never counted as another). A
 * table is less flash than a switch. */
#define AT(member) (uint8_t)(offsetof(xgo_parser_stats_t, member) + 1u)
static const uint8_t k_drop_counter[XGO_DROP_REASON_COUNT] = {
    [XGO_DROP_BAD_CHECKSUM] = AT(bad_checksum),
    [XGO_DROP_BAD_TAIL] = AT(bad_tail),
    [XGO_DROP_BAD_LENGTH] = AT(bad_length),
    [XGO_DROP_BAD_TYPE] = AT(bad_type),
    [XGO_DROP_BAD_RANGE] = AT(bad_range),
    [XGO_DROP_TIMEOUT] = AT(timeouts),
    [XGO_DROP_HANGUP] = AT(hangup_discards),
};
#undef AT
typedef char stats_are_u32[sizeof(xgo_parser_stats_t) == 9u * sizeof(uint32_t) ? 1 : -1];

static void count_drop(xgo_parser_t *p, xgo_drop_reason_t reason)
{
    const unsigned at = k_drop_counter[reason];
    if (at != 0u) {
        (*(uint32_t *)(void *)((char *)&p->stats + (at - 1u)))++;
    }
}

/* The sink hears of n bytes dropped for a reason (one call in flash, not
 * four). */
static void report_drop(const xgo_parser_t *p, xgo_drop_reason_t reason, const uint8_t *bytes,
                        size_t n)
{
    if (p->sink.on_drop != NULL) {
        p->sink.on_drop(p->sink.ctx, reason, bytes, n);
    }
}

/* Remove the first n held bytes; they count as discarded unless delivered. */
static void consume(xgo_parser_t *p, size_t n)
{
    memmove(p->buf, p->buf + n, p->end - n);
    p->end = (uint8_t)(p->end - n);
    p->checked = 0;
}

/* The candidate in buf[0..checked) is rejected: report it, drop its first
 * byte and let the rest be examined again. */
static void reject(xgo_parser_t *p, xgo_drop_reason_t reason)
{
    count_drop(p, reason);
    report_drop(p, reason, p->buf, p->checked);
    p->stats.bytes_discarded++;
    consume(p, 1);
}

/* Bytes before any header: no frame was claimed. Reported (reason noise)
 * so a trace can show every byte that was thrown away. */
static void drop_noise(xgo_parser_t *p, size_t n)
{
    report_drop(p, XGO_DROP_NOISE, p->buf, n);
    p->stats.bytes_discarded += (uint32_t)n;
    consume(p, n);
}

/* A LEN byte the parser takes: at least one data byte, at most what its
 * buffer holds (xgo/config.h). unsigned: no warning when the limit is 255. */
static int length_valid(unsigned len)
{
    return len >= XGO_FRAME_OVERHEAD + 1u && len <= XGO_PARSER_FRAME_MAX;
}

static int type_valid(const xgo_parser_t *p, uint8_t type)
{
    const int request = type == XGO_TYPE_WRITE || type == XGO_TYPE_WRITE_LEGACY ||
                        type == XGO_TYPE_READ;
    const int reply = type == XGO_TYPE_READ_REPLY;
    switch (p->side) {
    case XGO_PARSER_HOST: return reply;
    case XGO_PARSER_ANY: return request || reply;
    default: return request;
    }
}

/* A complete, well-formed frame: checked for range, then delivered. */
static void complete(xgo_parser_t *p)
{
    const uint8_t len = p->buf[POS_LEN];
    const size_t n = (size_t)len - XGO_FRAME_OVERHEAD;
    xgo_frame_t frame;
    uint32_t span;

    if (p->buf[len - 2] != XGO_FRAME_TAIL0 || p->buf[len - 1] != XGO_FRAME_TAIL1) {
        reject(p, XGO_DROP_BAD_TAIL);
        return;
    }
    if (p->buf[len - 3] !=
        xgo_frame_checksum(len, p->buf[POS_TYPE], p->buf[POS_ADDR], &p->buf[POS_DATA], n)) {
        reject(p, XGO_DROP_BAD_CHECKSUM);
        return;
    }
    frame.type = p->buf[POS_TYPE];
    frame.addr = p->buf[POS_ADDR];
    frame.len = (uint8_t)n;
    frame.data = &p->buf[POS_DATA];

    /* A read asks for data[0] bytes; a write carries n. */
    span = (frame.type == XGO_TYPE_READ) ? frame.data[0] : (uint32_t)n;
    if (span == 0 || span > XGO_FRAME_MAX_DATA || (uint32_t)frame.addr + span > 256u) {
        /* Well-formed but meaningless: the whole frame goes, no rescan (its
         * checksum and tail prove the bytes belong together). */
        p->stats.bad_range++;
        report_drop(p, XGO_DROP_BAD_RANGE, p->buf, len);
        p->stats.bytes_discarded += len;
        consume(p, len);
        return;
    }
    p->stats.frames_ok++;
    if (p->sink.on_frame != NULL) {
        p->sink.on_frame(p->sink.ctx, &frame);
    }
    consume(p, len);
}

/* Examine held bytes until all are checked or a frame completes. */
static void scan(xgo_parser_t *p)
{
    while (p->checked < p->end) {
        const uint8_t pos = p->checked;
        const uint8_t byte = p->buf[pos];
        p->checked++;
        switch (pos) {
        case POS_HEAD0:
            if (byte != XGO_FRAME_HEAD0) {
                /* Hunting: skip to the next possible header in one move. */
                size_t skip = 1;
                while (skip < p->end && p->buf[skip] != XGO_FRAME_HEAD0) {
                    skip++;
                }
                drop_noise(p, skip);
            }
            break;
        case POS_HEAD1:
            if (byte != XGO_FRAME_HEAD1) {
                /* Not a header after all: no frame was claimed, just noise. */
                drop_noise(p, 1);
            }
            break;
        case POS_LEN:
            if (!length_valid(byte)) {
                reject(p, XGO_DROP_BAD_LENGTH);
            }
            break;
        case POS_TYPE:
            if (!type_valid(p, byte)) {
                reject(p, XGO_DROP_BAD_TYPE);
            } else if (byte == XGO_TYPE_READ && p->buf[POS_LEN] != XGO_READ_REQUEST_LEN) {
                reject(p, XGO_DROP_BAD_LENGTH);
            }
            break;
        default:
            if (p->checked == p->buf[POS_LEN]) {
                complete(p);
            }
            break;
        }
    }
}

/* The partial frame will never complete (silence, hang-up), but a whole
 * frame may hide inside it. Drop its first byte and rescan until nothing is
 * left pending. */
static void abandon(xgo_parser_t *p, xgo_drop_reason_t reason)
{
    count_drop(p, reason);
    report_drop(p, reason, p->buf, p->end);
    while (p->end > 0) {
        p->stats.bytes_discarded++;
        consume(p, 1);
        scan(p);
    }
}

void xgo_parser_poll(xgo_parser_t *p, uint32_t now_ms)
{
    if (p->end == 0 || p->timeout_ms == 0 || (uint32_t)(now_ms - p->last_rx_ms) < p->timeout_ms) {
        return;
    }
    abandon(p, XGO_DROP_TIMEOUT);
}

void xgo_parser_hangup(xgo_parser_t *p)
{
    if (p->end > 0) {
        abandon(p, XGO_DROP_HANGUP);
    }
}

/* The fast path: a whole, valid, in-range frame starting at in[0] (its
 * last byte within avail) is delivered from there; returns its length, else
 * 0 and nothing happened. It makes exactly the checks of scan() and
 * complete(), so a frame it accepts is one the byte-by-byte path would
 * deliver the same way; everything else (noise, a bad or cut-off candidate)
 * goes that path, with its rejections, rescans and counters. Kept out of
 * line: inlined, it makes the byte-at-a-time path (an MCU's RX interrupt
 * feeding single bytes) pay for its registers on every call. */
XGO_OWN_FRAME static size_t take_whole_frame(xgo_parser_t *p, const uint8_t *in, size_t avail)
{
    const size_t len = in[POS_LEN];
    const size_t n = len - XGO_FRAME_OVERHEAD;
    const uint8_t type = in[POS_TYPE];
    xgo_frame_t frame;
    uint32_t span;
    if (in[POS_HEAD1] != XGO_FRAME_HEAD1 || !length_valid(len) || len > avail ||
        !type_valid(p, type) || (type == XGO_TYPE_READ && len != XGO_READ_REQUEST_LEN) ||
        in[len - 2] != XGO_FRAME_TAIL0 || in[len - 1] != XGO_FRAME_TAIL1 ||
        in[len - 3] != xgo_frame_checksum((uint8_t)len, type, in[POS_ADDR], &in[POS_DATA], n)) {
        return 0;
    }
    span = (type == XGO_TYPE_READ) ? in[POS_DATA] : (uint32_t)n;
    if (span == 0 || span > XGO_FRAME_MAX_DATA || (uint32_t)in[POS_ADDR] + span > 256u) {
        return 0;
    }
    frame.type = type;
    frame.addr = in[POS_ADDR];
    frame.len = (uint8_t)n;
    frame.data = &in[POS_DATA];
    p->stats.frames_ok++;
    if (p->sink.on_frame != NULL) {
        p->sink.on_frame(p->sink.ctx, &frame);
    }
    return len;
}

void xgo_parser_feed(xgo_parser_t *p, const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    size_t i = 0;
    XGO_ASSERT(bytes != NULL || n == 0);
    if (n == 0) {
        return;
    }
    xgo_parser_poll(p, now_ms);
    while (i < n) {
        /* With nothing held, a whole frame in the input is delivered from
         * there: no copy, no per-byte state machine. */
        if (p->end == 0 && n - i >= XGO_READ_REQUEST_LEN && bytes[i] == XGO_FRAME_HEAD0) {
            const size_t len = take_whole_frame(p, &bytes[i], n - i);
            if (len > 0) {
                i += len;
                continue;
            }
        }
        /* Room is guaranteed: after scan() the held bytes are a strict prefix
         * of a candidate frame, so end < its LEN <= XGO_PARSER_FRAME_MAX. */
        p->buf[p->end++] = bytes[i++];
        scan(p);
    }
    p->last_rx_ms = now_ms;
}
