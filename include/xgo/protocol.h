/*
 * xgo/protocol.h - the XGO serial frame: constants, encoder and an
 * incremental, self-resynchronising parser.
 *
 * Wire format (spec + errata in docs/protocol.md):
 *
 *   0x55 0x00 | LEN | TYPE | ADDR | DATA[n] | SUM | 0x00 0xAA
 *
 *   LEN = n + 8 (every byte of the frame), SUM = ~(LEN + TYPE + ADDR + DATA...).
 *   Host -> board: TYPE 0x00 write (0x01 from older hosts), 0x02 read with one
 *   data byte, the byte count. Board -> host: TYPE 0x12 read reply.
 *
 * The parser never trusts its input: every frame is validated whole before the
 * sink sees it, and after any rejection the bytes already consumed are
 * rescanned for the next header, so a good frame hiding behind garbage is
 * still found. Bad input is expected, so it is counted, never asserted.
 *
 * Checks: bytes are expected input, all of them (counted, never asserted);
 * a NULL buffer with a non-zero length is a caller bug (XGO_ASSERT,
 * xgo/config.h). xgo_frame_encode refuses what no frame can hold (returns 0).
 *
 * Portable: no OS calls, no heap, no globals; all state is in xgo_parser_t.
 */
#ifndef XGO_PROTOCOL_H
#define XGO_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/config.h" /* XGO_PARSER_DEFAULT_TIMEOUT_MS, XGO_PARSER_FRAME_MAX */

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_FRAME_HEAD0 0x55u
#define XGO_FRAME_HEAD1 0x00u
#define XGO_FRAME_TAIL0 0x00u
#define XGO_FRAME_TAIL1 0xAAu

/* header(2) + LEN + TYPE + ADDR + SUM + tail(2) */
#define XGO_FRAME_OVERHEAD 8u
#define XGO_FRAME_DATA_POS 5u /* the first data byte: 55 00 LEN TYPE ADDR DATA... */
#define XGO_FRAME_MAX_LEN 255u
#define XGO_FRAME_MAX_DATA (XGO_FRAME_MAX_LEN - XGO_FRAME_OVERHEAD) /* 247 */
#define XGO_READ_REQUEST_LEN 9u

#define XGO_TYPE_WRITE 0x00u
#define XGO_TYPE_WRITE_LEGACY 0x01u /* older vendor libraries and the ROS driver */
#define XGO_TYPE_READ 0x02u
#define XGO_TYPE_READ_REPLY 0x12u

/* A validated frame. `data` points into the parser's buffer or into the bytes
 * being fed (a whole frame is delivered from there, uncopied) and is valid
 * only during the sink callback. For a read request data[0] is the byte
 * count. */
typedef struct xgo_frame_s {
    uint8_t type;
    uint8_t addr;
    uint8_t len;         /* number of data bytes, 1..247 */
    const uint8_t *data;
} xgo_frame_t;

/* Why input was dropped. The first group is the parser's; the rest are
 * decided later (register file, board) but share one enum for tracing. */
typedef enum xgo_drop_reason_e {
    XGO_DROP_NONE = 0,
    XGO_DROP_BAD_CHECKSUM,
    XGO_DROP_BAD_TAIL,
    XGO_DROP_BAD_LENGTH,
    XGO_DROP_BAD_TYPE,
    XGO_DROP_BAD_RANGE,   /* ADDR + n > 256, or read count 0 or > 247 */
    XGO_DROP_TIMEOUT,     /* partial frame abandoned after silence */
    XGO_DROP_READ_ONLY,   /* write touches a read-only register */
    XGO_DROP_BAD_VALUE,   /* write value outside the register's valid set */
    XGO_DROP_TX_OVERFLOW, /* reply did not fit the transmit buffer */
    XGO_DROP_HANGUP,      /* partial frame of a host that hung up */
    XGO_DROP_NOISE,       /* bytes skipped while looking for a 55 00 header (no counter
                           * of its own: they are in bytes_discarded) */
    XGO_DROP_REASON_COUNT
} xgo_drop_reason_t;

/* Short lower-case name ("bad checksum", ...). Never NULL. */
const char *xgo_drop_reason_name(xgo_drop_reason_t reason);

typedef struct xgo_parser_stats_s {
    uint32_t frames_ok;
    uint32_t bad_checksum;
    uint32_t bad_tail;
    uint32_t bad_length;
    uint32_t bad_type;
    uint32_t bad_range;
    uint32_t bytes_discarded; /* every byte not delivered inside an accepted frame */
    uint32_t timeouts;
    uint32_t hangup_discards; /* partial frames dropped because their host hung up */
} xgo_parser_stats_t;

/* Callbacks; any may be NULL. `on_drop` sees the bytes of the rejected
 * candidate (for a timeout or a hang-up: all bytes that were pending; for
 * noise: the bytes skipped before a possible header - after a rejection,
 * the rest of the candidate is searched again and may be skipped so). */
typedef struct xgo_parser_sink_s {
    void (*on_frame)(void *ctx, const xgo_frame_t *frame);
    void (*on_drop)(void *ctx, xgo_drop_reason_t reason, const uint8_t *bytes, size_t n);
    void *ctx;
} xgo_parser_sink_t;

/* Which frames a parser takes: the board parses the host's requests (TYPE
 * 0x00, 0x01, 0x02), a host-side tool the board's replies (TYPE 0x12), an
 * offline decoder of a mixed byte stream both. Other types are bad types. */
typedef enum xgo_parser_side_e {
    XGO_PARSER_BOARD = 0,
    XGO_PARSER_HOST = 1,
    XGO_PARSER_ANY = 2
} xgo_parser_side_t;

typedef struct xgo_parser_s {
    uint8_t buf[XGO_PARSER_FRAME_MAX]; /* the candidate frame (xgo/config.h) */
    uint8_t end;         /* bytes held (never more than a LEN byte: <= 255) */
    uint8_t checked;     /* prefix of buf already validated as a frame candidate */
    uint8_t side;        /* xgo_parser_side_t */
    uint32_t last_rx_ms; /* time of the last byte fed */
    uint32_t timeout_ms; /* 0 disables the silence timeout */
    xgo_parser_sink_t sink;
    xgo_parser_stats_t stats;
} xgo_parser_t;

/* A parser on the board's side (host requests). */
void xgo_parser_init(xgo_parser_t *p, const xgo_parser_sink_t *sink, uint32_t timeout_ms);
/* The same on the given side (xgo-cli parses replies with XGO_PARSER_HOST). */
void xgo_parser_init_side(xgo_parser_t *p, const xgo_parser_sink_t *sink, uint32_t timeout_ms,
                          xgo_parser_side_t side);

/* Feed bytes that arrived at time now_ms (any clock in ms, wrap-safe). First
 * applies the silence timeout relative to the previous byte. */
void xgo_parser_feed(xgo_parser_t *p, const uint8_t *bytes, size_t n, uint32_t now_ms);

/* Apply the silence timeout without new bytes (call periodically). */
void xgo_parser_poll(xgo_parser_t *p, uint32_t now_ms);

/* The host hung up (the line went away): a partial frame it left will never
 * complete and must not prefix the next host's bytes. Dropped as on a
 * timeout (a whole frame hiding inside is still delivered), reason
 * XGO_DROP_HANGUP, counted in hangup_discards. Nothing happens when no
 * partial frame is held. */
void xgo_parser_hangup(xgo_parser_t *p);

/* Bytes currently held as a partial frame. */
size_t xgo_parser_pending(const xgo_parser_t *p);

/* Checksum over LEN, TYPE, ADDR and data, as the wire carries it. */
uint8_t xgo_frame_checksum(uint8_t len, uint8_t type, uint8_t addr, const uint8_t *data, size_t n);

/* Encode one frame into out. Returns the frame size (n + 8), or 0 when n is 0,
 * n > 247 or out_size is too small (nothing written then). */
size_t xgo_frame_encode(uint8_t type, uint8_t addr, const uint8_t *data, size_t n,
                        uint8_t *out, size_t out_size);

/* Completes a frame in place whose n data bytes (1..247) the caller already
 * put at out + XGO_FRAME_DATA_POS: header, checksum and tail around them.
 * Returns the frame size, n + 8. The board builds its replies so, straight
 * in its transmit buffer (no frame-sized buffer on the stack). */
size_t xgo_frame_seal(uint8_t type, uint8_t addr, size_t n, uint8_t *out);

#ifdef __cplusplus
}
#endif

#endif /* XGO_PROTOCOL_H */
