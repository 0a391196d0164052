/*
 * Parser and encoder: exact bytes of the spec's examples, every rejection
 * class, resynchronisation after garbage, split-delivery equivalence and the
 * silence timeout. Time is virtual (ms passed in by the test).
 */
#include <stdlib.h>
#include <string.h>

#include "board_io.h" /* xgo_test_xorshift* */
#include "unity.h"
#include "xgo/protocol.h"

#define MAX_FRAMES 4096

typedef struct {
    uint8_t type, addr, len;
    uint8_t data[XGO_FRAME_MAX_DATA];
} seen_frame_t;

typedef struct {
    seen_frame_t frames[MAX_FRAMES];
    size_t n_frames;
    xgo_drop_reason_t drops[MAX_FRAMES]; /* rejections, not noise */
    size_t n_drops;
    size_t noise_bytes; /* reported as noise */
    uint8_t noise[16];  /* the first of them */
} recorder_t;

static recorder_t rec;
static xgo_parser_t parser;

static void on_frame(void *ctx, const xgo_frame_t *f)
{
    recorder_t *r = (recorder_t *)ctx;
    if (r->n_frames < MAX_FRAMES) {
        seen_frame_t *s = &r->frames[r->n_frames];
        s->type = f->type;
        s->addr = f->addr;
        s->len = f->len;
        memcpy(s->data, f->data, f->len);
    }
    r->n_frames++;
}

static void on_drop(void *ctx, xgo_drop_reason_t why, const uint8_t *bytes, size_t n)
{
    recorder_t *r = (recorder_t *)ctx;
    if (why == XGO_DROP_NOISE) {
        size_t i;
        for (i = 0; i < n && r->noise_bytes + i < sizeof r->noise; i++) {
            r->noise[r->noise_bytes + i] = bytes[i];
        }
        r->noise_bytes += n;
        return;
    }
    if (r->n_drops < MAX_FRAMES) {
        r->drops[r->n_drops] = why;
    }
    r->n_drops++;
}

static void init_parser(xgo_parser_t *p, recorder_t *r, uint32_t timeout_ms)
{
    xgo_parser_sink_t sink;
    memset(r, 0, sizeof *r);
    sink.on_frame = on_frame;
    sink.on_drop = on_drop;
    sink.ctx = r;
    xgo_parser_init(p, &sink, timeout_ms);
}

void setUp(void)
{
    init_parser(&parser, &rec, XGO_PARSER_DEFAULT_TIMEOUT_MS);
}

void tearDown(void)
{
}

static void feed(const uint8_t *bytes, size_t n)
{
    xgo_parser_feed(&parser, bytes, n, 0);
}

static const uint8_t k_spec_write[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
static const uint8_t k_spec_read[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
static const uint8_t k_spec_reply[] = {0x55, 0x00, 0x14, 0x12, 0x50, 0x80, 0x80, 0x80, 0x80,
                                       0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x89,
                                       0x00, 0xAA};

/* Reference checksum straight from the errata: ~(LEN+TYPE+ADDR+data) & 0xFF. */
static uint8_t ref_checksum(const uint8_t *frame)
{
    unsigned sum = 0;
    unsigned i;
    for (i = 2; i < (unsigned)frame[2] - 3u; i++) {
        sum += frame[i];
    }
    return (uint8_t)(255u - sum % 256u);
}

static void test_spec_write_example_is_one_write_frame(void)
{
    feed(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_WRITE, rec.frames[0].type);
    TEST_ASSERT_EQUAL_HEX8(0x30, rec.frames[0].addr);
    TEST_ASSERT_EQUAL_UINT8(1, rec.frames[0].len);
    TEST_ASSERT_EQUAL_HEX8(0xFF, rec.frames[0].data[0]);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.frames_ok);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_UINT(0, xgo_parser_pending(&parser));
}

static void test_spec_read_example_is_one_read_frame(void)
{
    feed(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ, rec.frames[0].type);
    TEST_ASSERT_EQUAL_HEX8(0x50, rec.frames[0].addr);
    TEST_ASSERT_EQUAL_UINT8(1, rec.frames[0].len);
    TEST_ASSERT_EQUAL_UINT8(12, rec.frames[0].data[0]);
}

static void test_checksum_matches_spec_examples(void)
{
    const uint8_t ff = 0xFF, twelve = 0x0C;
    TEST_ASSERT_EQUAL_HEX8(0xC7, xgo_frame_checksum(0x09, 0x00, 0x30, &ff, 1));
    TEST_ASSERT_EQUAL_HEX8(0x98, xgo_frame_checksum(0x09, 0x02, 0x50, &twelve, 1));
    TEST_ASSERT_EQUAL_HEX8(0x89, ref_checksum(k_spec_reply));
}

static void test_encode_reproduces_spec_reply_bytes(void)
{
    uint8_t data[12];
    uint8_t out[64];
    memset(data, 0x80, sizeof data);
    TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply,
                           xgo_frame_encode(XGO_TYPE_READ_REPLY, 0x50, data, 12, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, out, sizeof k_spec_reply);
}

static void test_encode_refuses_bad_sizes(void)
{
    uint8_t data[XGO_FRAME_MAX_DATA + 1];
    uint8_t out[300];
    memset(data, 1, sizeof data);
    memset(out, 0xEE, sizeof out);
    TEST_ASSERT_EQUAL_UINT(0, xgo_frame_encode(0, 0, data, 0, out, sizeof out));
    TEST_ASSERT_EQUAL_UINT(0, xgo_frame_encode(0, 0, data, XGO_FRAME_MAX_DATA + 1, out, sizeof out));
    TEST_ASSERT_EQUAL_UINT(0, xgo_frame_encode(0, 0, data, 10, out, 17));
    TEST_ASSERT_EQUAL_HEX8(0xEE, out[0]);
    TEST_ASSERT_EQUAL_UINT(255, xgo_frame_encode(0, 9, data, XGO_FRAME_MAX_DATA, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0xFF, out[2]);
}

static void test_legacy_write_type_is_accepted(void)
{
    uint8_t f[16];
    const uint8_t v = 0x42;
    size_t n = xgo_frame_encode(XGO_TYPE_WRITE_LEGACY, 0x31, &v, 1, f, sizeof f);
    feed(f, n);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_WRITE_LEGACY, rec.frames[0].type);
}

static void test_largest_write_is_accepted(void)
{
    uint8_t data[XGO_FRAME_MAX_DATA];
    uint8_t f[XGO_FRAME_MAX_LEN];
    size_t n;
    memset(data, 0x11, sizeof data);
    n = xgo_frame_encode(XGO_TYPE_WRITE, 0x09, data, sizeof data, f, sizeof f); /* 0x09+247 = 256 */
    feed(f, n);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT8(247, rec.frames[0].len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(data, rec.frames[0].data, 247);
}

/* Feed `bad`, then the spec write: the bad input is dropped with `why`, the
 * good frame still comes through. */
static void expect_rejected_then_recovered(const uint8_t *bad, size_t n, xgo_drop_reason_t why)
{
    feed(bad, n);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    feed(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(0x30, rec.frames[0].addr);
    TEST_ASSERT_GREATER_OR_EQUAL_UINT(1, rec.n_drops);
    TEST_ASSERT_EQUAL_INT(why, rec.drops[0]);
}

static void test_bad_checksum_rejected_and_counted(void)
{
    const uint8_t bad[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC6, 0x00, 0xAA};
    expect_rejected_then_recovered(bad, sizeof bad, XGO_DROP_BAD_CHECKSUM);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_checksum);
    TEST_ASSERT_EQUAL_UINT32(sizeof bad, parser.stats.bytes_discarded);
}

static void test_bad_tail_rejected_and_counted(void)
{
    const uint8_t bad[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAB};
    expect_rejected_then_recovered(bad, sizeof bad, XGO_DROP_BAD_TAIL);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_tail);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.bad_checksum);
}

static void test_short_length_rejected(void)
{
    const uint8_t bad[] = {0x55, 0x00, 0x08, 0x00, 0x30, 0xC7, 0x00, 0xAA};
    expect_rejected_then_recovered(bad, sizeof bad, XGO_DROP_BAD_LENGTH);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_length);
}

static void test_read_with_wrong_length_rejected(void)
{
    /* A read request is exactly 9 bytes; LEN 10 with TYPE 0x02 is refused as
     * soon as TYPE arrives. */
    const uint8_t bad[] = {0x55, 0x00, 0x0A, 0x02, 0x50, 0x0C, 0x00, 0x97, 0x00, 0xAA};
    expect_rejected_then_recovered(bad, sizeof bad, XGO_DROP_BAD_LENGTH);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_length);
}

static void test_unknown_types_rejected(void)
{
    static const uint8_t types[] = {0x03, 0x10, 0x12, 0x55, 0xFF};
    size_t i;
    for (i = 0; i < sizeof types; i++) {
        uint8_t bad[9] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0x00, 0x00, 0xAA};
        bad[3] = types[i];
        bad[6] = ref_checksum(bad);
        setUp();
        expect_rejected_then_recovered(bad, sizeof bad, XGO_DROP_BAD_TYPE);
        TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_type);
    }
}

/* A host-side parser (xgo-cli) takes the board's replies and nothing else;
 * an offline one (xgo-cli decode) both directions. */
static void init_side(xgo_parser_side_t side)
{
    xgo_parser_sink_t sink;
    memset(&rec, 0, sizeof rec);
    sink.on_frame = on_frame;
    sink.on_drop = on_drop;
    sink.ctx = &rec;
    xgo_parser_init_side(&parser, &sink, XGO_PARSER_DEFAULT_TIMEOUT_MS, side);
}

static void test_host_side_parses_replies_only(void)
{
    init_side(XGO_PARSER_HOST);
    feed(k_spec_reply, sizeof k_spec_reply);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, rec.frames[0].type);
    TEST_ASSERT_EQUAL_HEX8(0x50, rec.frames[0].addr);
    TEST_ASSERT_EQUAL_UINT8(12, rec.frames[0].len);
    TEST_ASSERT_EACH_EQUAL_HEX8(0x80, rec.frames[0].data, 12);
    feed(k_spec_write, sizeof k_spec_write);
    feed(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT32(2, parser.stats.bad_type);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.frames_ok);
}

static void test_board_side_is_the_default(void)
{
    init_side(XGO_PARSER_BOARD);
    feed(k_spec_reply, sizeof k_spec_reply);
    feed(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_WRITE, rec.frames[0].type);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_type);
    TEST_ASSERT_EQUAL_UINT8(XGO_PARSER_BOARD, parser.side);
}

static void test_any_side_parses_both_directions(void)
{
    init_side(XGO_PARSER_ANY);
    feed(k_spec_read, sizeof k_spec_read);
    feed(k_spec_reply, sizeof k_spec_reply);
    feed(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(3, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ, rec.frames[0].type);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ_REPLY, rec.frames[1].type);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_WRITE, rec.frames[2].type);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.bad_type);
}

/* A reply whose data would run past 0xFF is as meaningless as such a write. */
static void test_host_side_reply_range_checked(void)
{
    uint8_t frame[16];
    static const uint8_t data[4] = {1, 2, 3, 4};
    size_t n = xgo_frame_encode(XGO_TYPE_READ_REPLY, 0xFE, data, sizeof data, frame, sizeof frame);
    init_side(XGO_PARSER_HOST);
    feed(frame, n);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_range);
}

static void expect_range_rejected(uint8_t type, uint8_t addr, const uint8_t *data, size_t n)
{
    uint8_t f[XGO_FRAME_MAX_LEN];
    size_t size = xgo_frame_encode(type, addr, data, n, f, sizeof f);
    setUp();
    expect_rejected_then_recovered(f, size, XGO_DROP_BAD_RANGE);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.bad_range);
    /* A well-formed frame is dropped whole: nothing was rescanned. */
    TEST_ASSERT_EQUAL_UINT(1, rec.n_drops);
    TEST_ASSERT_EQUAL_UINT32(size, parser.stats.bytes_discarded);
}

static void test_address_ranges_past_ff_rejected(void)
{
    uint8_t data[XGO_FRAME_MAX_DATA];
    uint8_t count;
    memset(data, 0, sizeof data);
    expect_range_rejected(XGO_TYPE_WRITE, 0xFF, data, 2);
    expect_range_rejected(XGO_TYPE_WRITE, 0x0A, data, XGO_FRAME_MAX_DATA);
    count = 0;
    expect_range_rejected(XGO_TYPE_READ, 0x50, &count, 1);
    count = 248;
    expect_range_rejected(XGO_TYPE_READ, 0x00, &count, 1);
    count = 0x20;
    expect_range_rejected(XGO_TYPE_READ, 0xF0, &count, 1);
}

static void test_read_up_to_last_address_is_accepted(void)
{
    uint8_t f[16];
    const uint8_t count = 0x10;
    size_t n = xgo_frame_encode(XGO_TYPE_READ, 0xF0, &count, 1, f, sizeof f);
    feed(f, n);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
}

static void test_header_inside_false_length_is_found_after_silence(void)
{
    /* A stray header claims 0x40 bytes; the real frame sits inside it and
     * the stream then goes quiet. The timeout rescans and finds it. */
    const uint8_t stray[] = {0x55, 0x00, 0x40, 0x00, 0x00};
    xgo_parser_feed(&parser, stray, sizeof stray, 100);
    xgo_parser_feed(&parser, k_spec_read, sizeof k_spec_read, 101);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    xgo_parser_poll(&parser, 101 + XGO_PARSER_DEFAULT_TIMEOUT_MS - 1);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    xgo_parser_poll(&parser, 101 + XGO_PARSER_DEFAULT_TIMEOUT_MS);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(0x50, rec.frames[0].addr);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.timeouts);
    TEST_ASSERT_EQUAL_UINT32(sizeof stray, parser.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_UINT(0, xgo_parser_pending(&parser));
}

static void test_truncated_frame_then_request_after_silence(void)
{
    /* Noise leaves a partial frame; the host's next request comes 500 ms
     * later and must be answered (the partial frame is abandoned first). */
    const uint8_t partial[] = {0x55, 0x00, 0x09, 0x00, 0x30};
    xgo_parser_feed(&parser, partial, sizeof partial, 1000);
    xgo_parser_feed(&parser, k_spec_read, sizeof k_spec_read, 1500);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ, rec.frames[0].type);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.timeouts);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_TIMEOUT, rec.drops[0]);
}

static void test_slow_bytes_within_timeout_still_form_a_frame(void)
{
    size_t i;
    for (i = 0; i < sizeof k_spec_write; i++) {
        xgo_parser_feed(&parser, &k_spec_write[i], 1, (uint32_t)(i * (XGO_PARSER_DEFAULT_TIMEOUT_MS - 1)));
        xgo_parser_poll(&parser, (uint32_t)(i * (XGO_PARSER_DEFAULT_TIMEOUT_MS - 1)));
    }
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.timeouts);
}

static void test_timeout_zero_disables_it(void)
{
    const uint8_t partial[] = {0x55, 0x00, 0x09, 0x00};
    init_parser(&parser, &rec, 0);
    xgo_parser_feed(&parser, partial, sizeof partial, 0);
    xgo_parser_poll(&parser, 1000000);
    TEST_ASSERT_EQUAL_UINT(4, xgo_parser_pending(&parser));
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.timeouts);
}

/* A hang-up ends a partial frame even with the timeout off: dropped with
 * its own reason and counter, a whole frame inside it still delivered. With
 * nothing pending it does nothing. */
static void test_hangup_drops_the_partial_frame(void)
{
    const uint8_t stray[] = {0x55, 0x00, 0x40, 0x00, 0x00};
    init_parser(&parser, &rec, 0);
    xgo_parser_hangup(&parser);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_drops);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.hangup_discards);
    feed(stray, sizeof stray);
    feed(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    xgo_parser_hangup(&parser);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_drops);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_HANGUP, rec.drops[0]);
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.hangup_discards);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.timeouts);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(0x50, rec.frames[0].addr);
    TEST_ASSERT_EQUAL_UINT32(sizeof stray, parser.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_UINT(0, xgo_parser_pending(&parser));
    TEST_ASSERT_EQUAL_STRING("hang-up", xgo_drop_reason_name(XGO_DROP_HANGUP));
}

static void test_timeout_survives_clock_wrap(void)
{
    const uint8_t partial[] = {0x55, 0x00, 0x09};
    xgo_parser_feed(&parser, partial, sizeof partial, 0xFFFFFFF0u);
    xgo_parser_poll(&parser, 0x00000002u); /* 18 ms later */
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.timeouts);
    xgo_parser_poll(&parser, 0x00000004u); /* 20 ms later */
    TEST_ASSERT_EQUAL_UINT32(1, parser.stats.timeouts);
}

static void test_header_bytes_repeated_do_not_hide_frame(void)
{
    /* 55 55 00 ..., 55 00 55 00 ...: the parser must not lose the real one. */
    const uint8_t junk1[] = {0x55, 0x55, 0x55};
    const uint8_t junk2[] = {0x55, 0x00, 0x55, 0x00};
    feed(junk1, sizeof junk1);
    feed(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    feed(junk2, sizeof junk2);
    feed(k_spec_read, sizeof k_spec_read);
    /* junk2 made a candidate with LEN 0x55 that swallowed the request: it
     * only fails once 0x55 bytes have arrived, or on silence. */
    xgo_parser_poll(&parser, XGO_PARSER_DEFAULT_TIMEOUT_MS);
    TEST_ASSERT_EQUAL_UINT(2, rec.n_frames);
    TEST_ASSERT_EQUAL_HEX8(XGO_TYPE_READ, rec.frames[1].type);
}

/* --- randomized and split-delivery properties -------------------------- */

static uint32_t rng_state;
static uint32_t rng(void)
{
    /* deterministic, fixed seed per test */
    return xgo_test_xorshift32(&rng_state);
}

#define STREAM_MAX 200000
static uint8_t stream[STREAM_MAX];
static seen_frame_t expected[MAX_FRAMES];

/* Builds garbage + valid frames; returns the stream length. */
static size_t build_stream(size_t n_frames, int with_garbage)
{
    size_t len = 0, i;
    for (i = 0; i < n_frames; i++) {
        seen_frame_t *e = &expected[i];
        size_t g, k;
        if (with_garbage) {
            /* Garbage biased towards header, tail and small LEN bytes. */
            size_t n_garbage = rng() % 40;
            for (g = 0; g < n_garbage; g++) {
                static const uint8_t nasty[] = {0x55, 0x00, 0xAA, 0x09, 0x02, 0x12, 0xFF};
                uint32_t r = rng();
                stream[len++] = (r & 1) ? nasty[(r >> 1) % sizeof nasty] : (uint8_t)(r >> 8);
            }
        }
        e->type = (rng() % 3 == 0) ? XGO_TYPE_READ : (uint8_t)(rng() % 2);
        if (e->type == XGO_TYPE_READ) {
            e->len = 1;
            e->data[0] = (uint8_t)(1 + rng() % 40);
            e->addr = (uint8_t)(rng() % (257u - e->data[0]));
        } else {
            e->len = (uint8_t)(1 + rng() % 30);
            e->addr = (uint8_t)(rng() % (257u - e->len));
            for (k = 0; k < e->len; k++) {
                e->data[k] = (uint8_t)rng();
            }
        }
        len += xgo_frame_encode(e->type, e->addr, e->data, e->len, &stream[len], STREAM_MAX - len);
    }
    return len;
}

static void assert_frames_equal(const seen_frame_t *want, size_t n)
{
    size_t i;
    TEST_ASSERT_EQUAL_UINT(n, rec.n_frames);
    for (i = 0; i < n; i++) {
        TEST_ASSERT_EQUAL_HEX8(want[i].type, rec.frames[i].type);
        TEST_ASSERT_EQUAL_HEX8(want[i].addr, rec.frames[i].addr);
        TEST_ASSERT_EQUAL_UINT8(want[i].len, rec.frames[i].len);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(want[i].data, rec.frames[i].data, want[i].len);
    }
}

static void test_random_garbage_never_hides_valid_frames(void)
{
    const size_t n_frames = 3000;
    size_t len, accepted_bytes = 0, i;
    rng_state = 0x12345678u;
    len = build_stream(n_frames, 1);
    feed(stream, len);
    /* A false header near the end may still be waiting: let it time out. */
    xgo_parser_poll(&parser, 1000);
    assert_frames_equal(expected, n_frames);
    for (i = 0; i < n_frames; i++) {
        accepted_bytes += expected[i].len + XGO_FRAME_OVERHEAD;
    }
    /* Every byte is accounted for: delivered, discarded or still pending. */
    TEST_ASSERT_EQUAL_UINT32(len, accepted_bytes + parser.stats.bytes_discarded +
                                      xgo_parser_pending(&parser));
    TEST_ASSERT_GREATER_THAN_UINT32(0, parser.stats.bad_length + parser.stats.bad_type +
                                           parser.stats.bad_tail + parser.stats.bad_checksum);
}

static void test_split_delivery_gives_identical_results(void)
{
    recorder_t whole_rec;
    xgo_parser_t whole;
    size_t len, pos;
    rng_state = 0xCAFEF00Du;
    len = build_stream(500, 1);

    init_parser(&whole, &whole_rec, XGO_PARSER_DEFAULT_TIMEOUT_MS);
    xgo_parser_feed(&whole, stream, len, 0);
    memcpy(expected, whole_rec.frames, sizeof(seen_frame_t) * whole_rec.n_frames);

    /* byte by byte */
    for (pos = 0; pos < len; pos++) {
        xgo_parser_feed(&parser, &stream[pos], 1, 0);
    }
    assert_frames_equal(expected, whole_rec.n_frames);
    TEST_ASSERT_EQUAL_MEMORY(&whole.stats, &parser.stats, sizeof parser.stats);

    /* random splits */
    setUp();
    pos = 0;
    while (pos < len) {
        size_t chunk = 1 + rng() % 300;
        if (chunk > len - pos) {
            chunk = len - pos;
        }
        xgo_parser_feed(&parser, &stream[pos], chunk, 0);
        pos += chunk;
    }
    assert_frames_equal(expected, whole_rec.n_frames);
    TEST_ASSERT_EQUAL_MEMORY(&whole.stats, &parser.stats, sizeof parser.stats);
    TEST_ASSERT_EQUAL_UINT(xgo_parser_pending(&whole), xgo_parser_pending(&parser));
}

static void test_pure_noise_is_bounded_and_counted(void)
{
    size_t i;
    rng_state = 0xBADC0DEu;
    for (i = 0; i < 100000; i++) {
        stream[i] = (uint8_t)rng();
    }
    feed(stream, 100000);
    TEST_ASSERT_LESS_THAN_UINT(XGO_FRAME_MAX_LEN, xgo_parser_pending(&parser));
    /* With this seed no frame hides in the noise: every byte is discarded
     * or still pending, and the held bytes never exceed one frame. */
    TEST_ASSERT_EQUAL_UINT(0, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT32(100000, parser.stats.bytes_discarded + xgo_parser_pending(&parser));
    /* Every byte skipped while hunting was reported as noise; the rest of
     * bytes_discarded is one byte per rejected candidate. */
    TEST_ASSERT_EQUAL_UINT32(parser.stats.bytes_discarded,
                             rec.noise_bytes + parser.stats.bad_checksum + parser.stats.bad_tail +
                                 parser.stats.bad_length + parser.stats.bad_type);
    TEST_ASSERT_EQUAL_UINT32(0, parser.stats.bad_range);
}

/* Bytes before a header are reported as noise, exactly those. */
static void test_noise_is_reported_with_its_bytes(void)
{
    const uint8_t noise[] = {'h', 'i', 0x0D, 0x0A, 0x55, 0x13};
    feed(noise, sizeof noise);
    feed(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(1, rec.n_frames);
    TEST_ASSERT_EQUAL_UINT(0, rec.n_drops);
    TEST_ASSERT_EQUAL_UINT(sizeof noise, rec.noise_bytes);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(noise, rec.noise, sizeof noise);
    TEST_ASSERT_EQUAL_UINT32(sizeof noise, parser.stats.bytes_discarded);
    TEST_ASSERT_EQUAL_STRING("noise", xgo_drop_reason_name(XGO_DROP_NOISE));
}

static void test_drop_reason_names(void)
{
    int r;
    for (r = 0; r < XGO_DROP_REASON_COUNT; r++) {
        TEST_ASSERT_NOT_NULL(xgo_drop_reason_name((xgo_drop_reason_t)r));
    }
    TEST_ASSERT_EQUAL_STRING("bad checksum", xgo_drop_reason_name(XGO_DROP_BAD_CHECKSUM));
    TEST_ASSERT_EQUAL_STRING("unknown", xgo_drop_reason_name(XGO_DROP_REASON_COUNT));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_spec_write_example_is_one_write_frame);
    RUN_TEST(test_spec_read_example_is_one_read_frame);
    RUN_TEST(test_checksum_matches_spec_examples);
    RUN_TEST(test_encode_reproduces_spec_reply_bytes);
    RUN_TEST(test_encode_refuses_bad_sizes);
    RUN_TEST(test_legacy_write_type_is_accepted);
    RUN_TEST(test_largest_write_is_accepted);
    RUN_TEST(test_bad_checksum_rejected_and_counted);
    RUN_TEST(test_bad_tail_rejected_and_counted);
    RUN_TEST(test_short_length_rejected);
    RUN_TEST(test_read_with_wrong_length_rejected);
    RUN_TEST(test_unknown_types_rejected);
    RUN_TEST(test_address_ranges_past_ff_rejected);
    RUN_TEST(test_read_up_to_last_address_is_accepted);
    RUN_TEST(test_header_inside_false_length_is_found_after_silence);
    RUN_TEST(test_truncated_frame_then_request_after_silence);
    RUN_TEST(test_slow_bytes_within_timeout_still_form_a_frame);
    RUN_TEST(test_timeout_zero_disables_it);
    RUN_TEST(test_timeout_survives_clock_wrap);
    RUN_TEST(test_hangup_drops_the_partial_frame);
    RUN_TEST(test_noise_is_reported_with_its_bytes);
    RUN_TEST(test_header_bytes_repeated_do_not_hide_frame);
    RUN_TEST(test_random_garbage_never_hides_valid_frames);
    RUN_TEST(test_split_delivery_gives_identical_results);
    RUN_TEST(test_pure_noise_is_bounded_and_counted);
    RUN_TEST(test_drop_reason_names);
    RUN_TEST(test_host_side_parses_replies_only);
    RUN_TEST(test_board_side_is_the_default);
    RUN_TEST(test_any_side_parses_both_directions);
    RUN_TEST(test_host_side_reply_range_checked);
    return UNITY_END();
}
