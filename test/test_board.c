/*
 * The board end to end, bytes in -> bytes out, on virtual time: the spec's
 * examples byte-exact, several requests per write, rejections counted and
 * traced, vendor writes for other models, auto-clear, diagnostics over the
 * wire, transmit overflow.
 */
#include <math.h>
#include <string.h>

#include "board_io.h"
#include "fixed.h"           /* xgo_sin */
#include "motion_internal.h" /* xgo_motion_asked_pose */
#include "unity.h"
#include "xgo/board.h"
#include "xgo/emulator.h"
#include "xgo/profile.h"

static xgo_board_t board;

#define MAX_EVENTS 64
static xgo_trace_kind_t ev_kind[MAX_EVENTS];
static xgo_drop_reason_t ev_reason[MAX_EVENTS];
static uint8_t ev_unmapped[MAX_EVENTS];
static size_t n_events;

static void record(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    if (n_events < MAX_EVENTS) {
        ev_kind[n_events] = ev->kind;
        ev_reason[n_events] = ev->reason;
        ev_unmapped[n_events] = ev->unmapped;
    }
    n_events++;
}

void setUp(void)
{
    xgo_board_init(&board, NULL);
    n_events = 0;
    xgo_board_set_trace(&board, record, NULL);
}

void tearDown(void)
{
}

static const uint8_t k_spec_write[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
static const uint8_t k_spec_read[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
static const uint8_t k_spec_reply[] = {0x55, 0x00, 0x14, 0x12, 0x50, 0x80, 0x80, 0x80, 0x80,
                                       0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x89,
                                       0x00, 0xAA};

static void send(const uint8_t *bytes, size_t n)
{
    xgo_board_receive(&board, bytes, n, 0);
}

static void send_write(uint8_t addr, const uint8_t *data, size_t n)
{
    xgo_test_write(&board, addr, data, n, 0);
}

static void send_read(uint8_t addr, uint8_t count)
{
    xgo_test_request(&board, addr, count, 0);
}

/* Read `count` bytes at addr over the wire and check the reply's framing
 * (size, header, LEN, TYPE, ADDR, checksum, tail: test/support/board_io.h). */
static void wire_read(uint8_t addr, uint8_t count, uint8_t *out)
{
    const xgo_test_reply_t problem = xgo_test_read(&board, addr, count, 0, out);
    TEST_ASSERT_EQUAL_INT_MESSAGE(XGO_TEST_REPLY_OK, problem, xgo_test_reply_name(problem));
}

/* A register as the board holds it (xgo_board_read: no frame, no counting). */
static uint8_t reg(uint8_t addr)
{
    uint8_t v;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, addr, 1, &v));
    return v;
}

/* All 256 registers (reads starting at 0x00 and 0x80 see the flat image;
 * the diagnostic block is the counters as they are now). */
static void snapshot(uint8_t out[XGO_REG_COUNT])
{
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x00, 0x80, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x80, 0x80, out + 0x80));
}

static uint8_t wire_read1(uint8_t addr)
{
    uint8_t v;
    wire_read(addr, 1, &v);
    return v;
}

/* The spec's reply reads twelve 0x80: joints commanded to 0x80 in servo mode
 * (the spec's own write format) read back exactly that once they arrive. */
static void put_joints_at_0x80(void)
{
    uint8_t mid[12];
    unsigned i;
    memset(mid, 0x80, sizeof mid);
    send_write(0x50, mid, sizeof mid);
    for (i = 0; i < 2 * XGO_TICK_HZ; i++) {
        xgo_board_tick(&board);
    }
    n_events = 0;
}

static void test_spec_read_example_gets_the_spec_reply(void)
{
    uint8_t out[64];
    put_joints_at_0x80();
    send(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply, xgo_board_tx_pending(&board));
    TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply, xgo_board_transmit(&board, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, out, sizeof k_spec_reply);
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
}

static void test_spec_write_example_sets_vx_and_sends_nothing(void)
{
    send(k_spec_write, sizeof k_spec_write);
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
    TEST_ASSERT_EQUAL_HEX8(0xFF, reg(XGO_REG_VX));
    TEST_ASSERT_EQUAL_HEX8(0xFF, wire_read1(0x30));
}

static void test_two_requests_in_one_write_are_answered_in_order(void)
{
    uint8_t both[32], out[64];
    uint8_t f1[16], f2[16];
    const uint8_t c1 = 1, c2 = 2;
    size_t n1 = xgo_frame_encode(XGO_TYPE_READ, 0x01, &c1, 1, f1, sizeof f1);
    size_t n2 = xgo_frame_encode(XGO_TYPE_READ, 0x30, &c2, 1, f2, sizeof f2);
    memcpy(both, f1, n1);
    memcpy(both + n1, f2, n2);
    send(both, n1 + n2);
    TEST_ASSERT_EQUAL_UINT(9 + 10, xgo_board_transmit(&board, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0x01, out[4]);
    TEST_ASSERT_EQUAL_UINT8(100, out[5]); /* battery */
    TEST_ASSERT_EQUAL_HEX8(0x30, out[9 + 4]);
    TEST_ASSERT_EQUAL_HEX8(0x80, out[9 + 5]);
    TEST_ASSERT_EQUAL_HEX8(0x80, out[9 + 6]);
}

static void test_garbage_then_request_gets_its_reply(void)
{
    const uint8_t garbage[] = {0x00, 0xAA, 0x55, 0x13, 0x55, 0x00, 0x05, 0xFF, 0x12};
    uint8_t out[64];
    put_joints_at_0x80();
    send(garbage, sizeof garbage);
    send(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply, xgo_board_transmit(&board, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, out, sizeof k_spec_reply);
}

static void test_write_to_read_only_is_rejected_counted_and_traced(void)
{
    const uint8_t v = 50;
    uint32_t c[XGO_DIAG_COUNT];
    send_write(XGO_REG_BATTERY, &v, 1);
    TEST_ASSERT_EQUAL_UINT8(100, reg(XGO_REG_BATTERY));
    xgo_board_counters(&board, c);
    TEST_ASSERT_EQUAL_UINT32(1, c[XGO_DIAG_REJECTED_READ_ONLY]);
    TEST_ASSERT_EQUAL_UINT32(1, c[XGO_DIAG_FRAMES_OK]);
    TEST_ASSERT_EQUAL_UINT(1, n_events);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_DROP, ev_kind[0]);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, ev_reason[0]);
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
}

static void test_invalid_value_is_rejected_and_traced(void)
{
    const uint8_t pace = 3;
    send_write(XGO_REG_MOVE_MODE, &pace, 1);
    TEST_ASSERT_EQUAL_UINT8(0, reg(XGO_REG_MOVE_MODE));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, ev_reason[0]);
}

static void test_vendor_writes_for_other_models_do_no_harm(void)
{
    static const uint8_t others[] = {0x22, 0x23, 0x24, 0x5F, 0x70, 0x71, 0x72, 0x73, 0x74,
                                     0x75, 0x76, 0x77, 0xA1, 0xB0, 0xB1, 0xC0};
    const uint8_t servo_ctrl[2] = {0x08, 0x00};
    const uint8_t wheels[4] = {0x80, 0x80, 0x80, 0x80};
    uint32_t c[XGO_DIAG_COUNT];
    uint8_t before[256], after[256];
    size_t i;
    snapshot(before);
    for (i = 0; i < sizeof others; i++) {
        const uint8_t v = 0x08;
        send_write(others[i], &v, 1);
    }
    send_write(0xA1, servo_ctrl, sizeof servo_ctrl);
    send_write(0xB1, wheels, sizeof wheels);
    snapshot(after);
    /* every register, but the diagnostic block: it counts these writes */
    TEST_ASSERT_EQUAL_MEMORY(before, after, XGO_REG_DIAG);
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
    xgo_board_counters(&board, c);
    TEST_ASSERT_EQUAL_UINT32(sizeof others + 2, c[XGO_DIAG_IGNORED_UNMAPPED]);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_RX, ev_kind[0]);
    TEST_ASSERT_EQUAL_UINT8(1, ev_unmapped[0]);
    TEST_ASSERT_EQUAL_HEX8(0x00, wire_read1(0x71));
    TEST_ASSERT_EQUAL_HEX8(0x80, wire_read1(0x30)); /* still healthy */
}

static void test_auto_clear_registers_clear_on_the_next_tick(void)
{
    const uint8_t one = 1;
    send_write(XGO_REG_SET_ZERO, &one, 1);
    send_write(XGO_REG_STAND, &one, 1);
    TEST_ASSERT_EQUAL_HEX8(1, wire_read1(XGO_REG_SET_ZERO));
    TEST_ASSERT_EQUAL_HEX8(1, wire_read1(XGO_REG_STAND));
    xgo_board_tick(&board);
    TEST_ASSERT_EQUAL_HEX8(0, wire_read1(XGO_REG_SET_ZERO));
    TEST_ASSERT_EQUAL_HEX8(0, wire_read1(XGO_REG_STAND));
    TEST_ASSERT_EQUAL_UINT32(1, board.ticks);
}

static void test_plain_registers_do_not_clear_on_tick(void)
{
    const uint8_t walk = 1;
    send_write(XGO_REG_GAIT_TYPE, &walk, 1);
    xgo_board_tick(&board);
    xgo_board_tick(&board);
    TEST_ASSERT_EQUAL_HEX8(1, wire_read1(XGO_REG_GAIT_TYPE));
}

static void test_diagnostic_block_over_the_wire_matches_counters(void)
{
    const uint8_t bad_sum[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0x00, 0x00, 0xAA};
    uint8_t diag[4 * XGO_DIAG_SLOTS];
    uint32_t c[XGO_DIAG_COUNT];
    size_t i;
    send(bad_sum, sizeof bad_sum);
    send(k_spec_write, sizeof k_spec_write);
    wire_read(0xC4, sizeof diag, diag); /* the whole block, docs/registers.md */
    xgo_board_counters(&board, c);
    /* The read itself was counted before the snapshot was taken. */
    TEST_ASSERT_EQUAL_UINT32(2, c[XGO_DIAG_FRAMES_OK]);
    TEST_ASSERT_EQUAL_UINT32(1, c[XGO_DIAG_BAD_CHECKSUM]);
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        const uint32_t v = (uint32_t)diag[4 * i] | (uint32_t)diag[4 * i + 1] << 8 |
                           (uint32_t)diag[4 * i + 2] << 16 | (uint32_t)diag[4 * i + 3] << 24;
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(c[i], v, xgo_diag_name((xgo_diag_t)i));
    }
    for (i = 4 * XGO_DIAG_COUNT; i < sizeof diag; i++) {
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(0, diag[i], "an unused slot of the diagnostic block");
    }
    TEST_ASSERT_EQUAL_STRING("frames_ok", xgo_diag_name(XGO_DIAG_FRAMES_OK));
    TEST_ASSERT_EQUAL_STRING("tx_overflow", xgo_diag_name(XGO_DIAG_TX_OVERFLOW));
    TEST_ASSERT_EQUAL_STRING("hangup_discards", xgo_diag_name(XGO_DIAG_HANGUP_DISCARDS));
    TEST_ASSERT_EQUAL_STRING("unknown", xgo_diag_name(XGO_DIAG_COUNT));
}

/* The block is formed from the counters when it is read (the register
 * image keeps no copy): uint32 little-endian in xgo_diag_t order, also in a
 * read that starts below it, and the traced reply is what the wire got. */
static uint8_t traced_reply[256];
static size_t traced_reply_len;

static void record_reply(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    if (ev->kind == XGO_TRACE_TX) {
        memcpy(traced_reply, ev->frame->data, ev->frame->len);
        traced_reply_len = ev->frame->len;
    }
}

static void test_diag_block_is_formed_on_read(void)
{
    uint8_t wire[0x100 - 0xB0];
    uint32_t c[XGO_DIAG_COUNT];
    size_t i;
    /* Distinct values with all four bytes set; frames_ok grows by the read. */
#define DIAG_SET_(id, name, member) board.member = 0x01020304u * (uint32_t)(XGO_DIAG_##id + 1);
    XGO_DIAG_LIST(DIAG_SET_)
#undef DIAG_SET_
    xgo_board_set_trace(&board, record_reply, NULL);
    wire_read(0xB0, sizeof wire, wire);
    xgo_board_counters(&board, c);
    TEST_ASSERT_EQUAL_HEX32(0x01020304u + 1u, c[XGO_DIAG_FRAMES_OK]);
    for (i = 0; i < 0xC4 - 0xB0; i++) {
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(0, wire[i], "unmapped below the block");
    }
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        const uint8_t *p = &wire[0xC4 - 0xB0 + 4 * i];
        const uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                           (uint32_t)p[3] << 24;
        TEST_ASSERT_EQUAL_HEX32_MESSAGE(c[i], v, xgo_diag_name((xgo_diag_t)i));
    }
    for (i = 0xC4 - 0xB0 + 4 * XGO_DIAG_COUNT; i < sizeof wire; i++) {
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(0, wire[i], "an unused slot of the diagnostic block");
    }
    TEST_ASSERT_EQUAL_UINT(sizeof wire, traced_reply_len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(wire, traced_reply, sizeof wire);
}

/* Replies are built in place at the end of the transmit queue, in one
 * piece: when the space after the bytes still waiting is too short, those
 * move to the front first, and the stream keeps its order. */
static void test_reply_after_waiting_bytes_keeps_the_stream(void)
{
    static uint8_t got[XGO_TX_BUFFER_SIZE + 108];
    const size_t reply = 100 + 8, k = XGO_TX_BUFFER_SIZE / reply, drained = XGO_TX_BUFFER_SIZE / 2;
    size_t i;
    for (i = 0; i < k; i++) {
        send_read(0x00, 100); /* below the diagnostic block: the same reply each time */
    }
    TEST_ASSERT_EQUAL_UINT(drained, xgo_board_transmit(&board, got, drained));
    send_read(0x00, 100); /* fits only after the waiting bytes moved */
    TEST_ASSERT_EQUAL_UINT((k + 1) * reply - drained, xgo_board_tx_pending(&board));
    TEST_ASSERT_EQUAL_UINT((k + 1) * reply - drained,
                           xgo_board_transmit(&board, got + drained, sizeof got - drained));
    for (i = 0; i <= k; i++) {
        TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK,
                              xgo_test_check_reply(&got[i * reply], reply, 0x00, 100));
        TEST_ASSERT_EQUAL_HEX8_ARRAY(&got[5], &got[i * reply + 5], 100);
    }
}

static void test_transmit_overflow_drops_whole_replies(void)
{
    uint8_t out[XGO_TX_BUFFER_SIZE + 256];
    const size_t reply = 247 + 8;
    const size_t fit = XGO_TX_BUFFER_SIZE / reply;
    size_t i, n;
    uint32_t c[XGO_DIAG_COUNT];
    for (i = 0; i < fit + 3; i++) {
        send_read(0x00, 247);
    }
    xgo_board_counters(&board, c);
    TEST_ASSERT_EQUAL_UINT32(3, c[XGO_DIAG_TX_OVERFLOW]);
    n = xgo_board_transmit(&board, out, sizeof out);
    TEST_ASSERT_EQUAL_UINT(fit * reply, n);
    for (i = 0; i < fit; i++) {
        TEST_ASSERT_EQUAL_HEX8(0x55, out[i * reply]);
        TEST_ASSERT_EQUAL_HEX8(0xAA, out[i * reply + reply - 1]);
    }
    /* Room again: the next request is answered. */
    TEST_ASSERT_EQUAL_UINT8(100, wire_read1(XGO_REG_BATTERY));
}

static void test_partial_transmit_keeps_order_across_wrap(void)
{
    uint8_t out[8], got[64];
    size_t i, n, got_n;
    /* 100 replies of 20 bytes drained 7 at a time: the ring wraps twice. */
    put_joints_at_0x80();
    for (i = 0; i < 100; i++) {
        send_read(0x50, 12);
        got_n = 0;
        while ((n = xgo_board_transmit(&board, out, 7)) > 0) {
            TEST_ASSERT_LESS_OR_EQUAL_UINT(sizeof got, got_n + n);
            memcpy(got + got_n, out, n);
            got_n += n;
        }
        TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply, got_n);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, got, sizeof k_spec_reply);
    }
}

static void test_lite_profile_identity(void)
{
    xgo_board_config_t cfg;
    uint8_t fw[10];
    xgo_board_default_config(&cfg);
    cfg.model = XGO_MODEL_LITE;
    cfg.battery_pct = 37;
    xgo_board_init(&board, &cfg);
    TEST_ASSERT_EQUAL_HEX8(0x01, wire_read1(XGO_REG_VERSION));
    TEST_ASSERT_EQUAL_UINT8(37, wire_read1(XGO_REG_BATTERY));
    wire_read(0x07, 10, fw);
    TEST_ASSERT_EQUAL_HEX8('L', fw[0]);
}

static void test_mini_firmware_starts_with_M_and_is_ascii(void)
{
    uint8_t fw[10];
    size_t i;
    wire_read(0x07, 10, fw);
    TEST_ASSERT_EQUAL_HEX8('M', fw[0]);
    TEST_ASSERT_NOT_EQUAL('W', fw[1]); /* "MW" would select the mini2 SW parameters */
    for (i = 0; i < 10; i++) {
        TEST_ASSERT_TRUE(fw[i] == 0 || (fw[i] >= 0x20 && fw[i] < 0x7F));
    }
}

static void test_timeout_through_the_board(void)
{
    const uint8_t partial[] = {0x55, 0x00, 0x30, 0x00}; /* a write claiming 48 bytes */
    uint8_t out[64];
    put_joints_at_0x80();
    xgo_board_receive(&board, partial, sizeof partial, 10);
    xgo_board_receive(&board, k_spec_read, sizeof k_spec_read, 12);
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
    xgo_board_poll(&board, 12 + XGO_PARSER_DEFAULT_TIMEOUT_MS);
    TEST_ASSERT_EQUAL_UINT(sizeof k_spec_reply, xgo_board_transmit(&board, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(k_spec_reply, out, sizeof k_spec_reply);
}

static void test_read_requests_never_change_state(void)
{
    uint8_t before[256], after[256], out[256];
    unsigned a;
    snapshot(before);
    for (a = 0; a < 0xC4; a += 4) {
        wire_read((uint8_t)a, 4, out);
    }
    snapshot(after);
    TEST_ASSERT_EQUAL_MEMORY(before, after, 0xC4); /* all below the diagnostic block */
}

/* 1 at 0x05 (upgrade) is answered at once, one frame: 0x55 0x00, LEN 9,
 * TYPE 0x12, ADDR 0x05, one byte that is not the bootloader's 0x55, checksum
 * ~(0x09 + 0x12 + 0x05 + 0x00) = 0xDF, tail. */
static void test_upgrade_request_is_answered_at_once(void)
{
    static const uint8_t want[] = {0x55, 0x00, 0x09, 0x12, 0x05, 0x00, 0xDF, 0x00, 0xAA};
    const uint8_t one = 1, zero = 0;
    uint8_t out[32];
    send_write(0x05, &one, 1);
    TEST_ASSERT_EQUAL_UINT(sizeof want, xgo_board_transmit(&board, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want, out, sizeof want);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_TX, ev_kind[1]);
    /* 0 asks nothing; a write from the live view is no request of the host's */
    send_write(0x05, &zero, 1);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_VIEW, 0x05, &one, 1));
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board));
}

static void test_turn_command_reads_turning_until_the_tick_decides(void)
{
    const uint8_t zero_deg[2] = {0x00, 0x00};
    TEST_ASSERT_EQUAL_HEX8(1, wire_read1(0x3F)); /* nothing to do: done */
    send_write(0x3F, zero_deg, 2);
    TEST_ASSERT_EQUAL_HEX8(0, wire_read1(0x3F));
    xgo_test_ticks(&board, 2);
    TEST_ASSERT_EQUAL_HEX8(1, wire_read1(0x3F)); /* already there */
    TEST_ASSERT_EQUAL_HEX8(0x80, wire_read1(0x40));
}

/* ---- the joint registers 0x50..0x5B, formed on read ----
 * The board once stored them at power-up and at the end of every tick:
 * each joint's angle through the vendor's range map. joints_as_stored is
 * that store (in double, from the public observers), taken at those same
 * moments; every read until the next tick must give exactly it, whatever
 * was written in between. */
static uint8_t joints_as_stored[XGO_SERVO_COUNT];

static void store_joints(const xgo_profile_t *p)
{
    int32_t q[XGO_SERVO_COUNT];
    unsigned i;
    xgo_board_joints_mdeg(&board, q);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        const xgo_range_t *r = &p->joint_mdeg[i % XGO_JOINT_COUNT];
        joints_as_stored[i] = q[i] <= r->lo   ? 0u
                              : q[i] >= r->hi ? 255u
                                              : (uint8_t)floor(255.0 * ((double)q[i] - r->lo) /
                                                               ((double)r->hi - r->lo));
    }
}

/* Reads over the joints and past either end, every start from 0x40 to
 * 0x5C and several lengths: each gives the image's bytes (the joints as
 * stored) and writes no byte past its end; and one over the wire. */
static void check_joint_reads(void)
{
    static const uint8_t lens[] = {1, 2, 3, 4, 5, 12, 13, 16, 30};
    uint8_t image[XGO_REG_COUNT];
    uint8_t buf[32];
    unsigned start, k;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x00, XGO_FRAME_MAX_DATA, image));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, XGO_FRAME_MAX_DATA,
                                                        XGO_REG_COUNT - XGO_FRAME_MAX_DATA,
                                                        &image[XGO_FRAME_MAX_DATA]));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(joints_as_stored, &image[XGO_REG_SERVO11], XGO_SERVO_COUNT);
    for (start = 0x40; start <= 0x5C; start++) {
        for (k = 0; k < sizeof lens; k++) {
            memset(buf, 0xA5, sizeof buf);
            TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, (uint8_t)start, lens[k], buf));
            TEST_ASSERT_EQUAL_HEX8_ARRAY(&image[start], buf, lens[k]);
            TEST_ASSERT_EQUAL_HEX8(0xA5, buf[lens[k]]);
        }
    }
    wire_read(XGO_REG_SERVO11, XGO_SERVO_COUNT, buf);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(joints_as_stored, buf, XGO_SERVO_COUNT);
}

/* One random host write among those that move the joints or stop them:
 * servo commands (servo mode), unloading and loading, actions and the
 * reset, walking, the body pose, calibration, the servo speed, the arm. */
static void random_joint_write(uint32_t *seed, int arm)
{
    uint8_t data[XGO_SERVO_COUNT];
    const uint32_t r = xgo_test_xorshift32(seed);
    const uint8_t v = (uint8_t)(r >> 8);
    unsigned i;
    switch (r % 12u) {
    case 0: /* servo mode: a few commands, any byte */
    case 1:
        for (i = 0; i < XGO_SERVO_COUNT; i++) {
            data[i] = (uint8_t)(xgo_test_xorshift32(seed) >> 4);
        }
        i = (r >> 16) % XGO_SERVO_COUNT;
        send_write((uint8_t)(XGO_REG_SERVO11 + i), data, XGO_SERVO_COUNT - i);
        break;
    case 2: { /* all, one leg, loaded or not */
        static const uint8_t unload[] = {0x00, 0x01, 0x11, 0x12, 0x13, 0x14, 0x21, 0x22, 0x23, 0x24};
        xgo_test_write1(&board, XGO_REG_UNLOAD, unload[v % sizeof unload], 0);
        break;
    }
    case 3: /* an action now and then (they last seconds), else a stop */
        xgo_test_write1(&board, XGO_REG_ACTION,
                        v % 4u != 0    ? 0u
                        : v % 32u == 0 ? XGO_ACTION_RESET
                                       : (uint8_t)((v >> 2) % XGO_ACTION_LAST + 1u),
                        0);
        break;
    case 4:
        xgo_test_write1(&board, XGO_REG_VX, v, 0);
        break;
    case 5:
        xgo_test_write1(&board, XGO_REG_VYAW, v, 0);
        break;
    case 6:
        xgo_test_write1(&board, (uint8_t)(XGO_REG_BODY_X + v % 6u), (uint8_t)(r >> 16), 0);
        break;
    case 7:
        xgo_test_write1(&board, XGO_REG_CALIBRATION, v % 4u == 0, 0);
        break;
    case 8:
        xgo_test_write1(&board, XGO_REG_SERVO_SPEED, v, 0);
        break;
    case 9:
        xgo_test_write1(&board, XGO_REG_MOVE_MODE, v % 3u, 0);
        break;
    case 10: /* the Mini2's arm (0x5D, 0x5E, 0x71..); the others' stand */
        if (arm) {
            xgo_test_write1(&board, (uint8_t)(v & 1u ? XGO_REG_ARM_ELBOW : XGO_REG_CLAW),
                            (uint8_t)(r >> 16), 0);
        } else {
            xgo_test_write1(&board, XGO_REG_STAND, v & 1u, 0);
        }
        break;
    default: /* the feet (leg mode) */
        xgo_test_write1(&board, (uint8_t)(0x40u + v % 12u), (uint8_t)(r >> 16), 0);
        break;
    }
}

static void test_joint_reads_give_the_bytes_a_tick_stored(void)
{
    static const xgo_model_t models[] = {XGO_MODEL_MINI, XGO_MODEL_LITE, XGO_MODEL_MINI2};
    unsigned m, t;
    uint32_t seed = 0x2545F491u;
    for (m = 0; m < sizeof models / sizeof models[0]; m++) {
        xgo_board_config_t cfg;
        const xgo_profile_t *p = xgo_profile_get((unsigned)models[m]);
        xgo_board_default_config(&cfg);
        cfg.model = models[m];
        xgo_board_init(&board, &cfg);
        store_joints(p); /* power-up */
        check_joint_reads();
        for (t = 0; t < 6000; t++) {
            if (xgo_test_xorshift32(&seed) % 25u == 0) {
                random_joint_write(&seed, models[m] == XGO_MODEL_MINI2);
                check_joint_reads(); /* written, not yet ticked */
            }
            xgo_board_tick(&board);
            store_joints(p);
            if (t % 16u == 0) {
                check_joint_reads();
            }
        }
    }
}

static int32_t clamp_range(int32_t v, const xgo_range_t *r)
{
    return v < r->lo ? r->lo : (v > r->hi ? r->hi : v);
}

static int32_t *pose_axis(xgo_body_pose_t *p, unsigned axis) /* axes roll pitch yaw x y z */
{
    int32_t *f[6];
    f[0] = &p->roll_mdeg, f[1] = &p->pitch_mdeg, f[2] = &p->yaw_mdeg;
    f[3] = &p->x_um, f[4] = &p->y_um, f[5] = &p->z_um;
    return f[axis];
}

/* The pose the registers ask for (on a host laid out with vector moves),
 * for every mix of periodic axes and random values, against docs/motion.md
 * written out: a static axis its value, a periodic one its phase advanced
 * by its step and the sinusoid around the range's middle (base: the
 * middle, spread: the amplitude); roll and pitch within their ranges. */
static void test_the_asked_pose_is_each_axis_static_or_periodic(void)
{
    xgo_motion_t *m = &board.motion;
    const xgo_profile_t *p;
    uint32_t seed = 0x9E3779B9u;
    unsigned n, axis;
    xgo_board_init(&board, NULL);
    p = m->profile;
    for (n = 0; n < 20000; n++) {
        xgo_body_pose_t pose, base, spread, want_pose, want_base, want_spread;
        uint32_t phase[6];
        m->decoded.valid = 1;
        m->decoded.periodic = (uint8_t)(n % 64u);
        m->stab_mdeg[0] = m->stab_mdeg[1] = 0;
        for (axis = 0; axis < 6; axis++) {
            const xgo_range_t *range = axis < 3 ? &p->body_mdeg[axis] : &p->body_um[axis - 3];
            const int periodic = (m->decoded.periodic >> axis) & 1u;
            m->decoded.body[axis] = (int32_t)(xgo_test_xorshift32(&seed) % 400001u) - 200000;
            m->periodic_phase[axis] = periodic ? xgo_test_xorshift32(&seed) : 0u;
            phase[axis] = m->periodic_phase[axis] + (uint32_t)m->decoded.body[axis];
            if (periodic) {
                const int32_t mid = (range->lo + range->hi) / 2, amp = (range->hi - range->lo) / 4;
                *pose_axis(&want_pose, axis) =
                    mid + (int32_t)(((int64_t)amp * xgo_sin(phase[axis]) + (1 << 29)) >> 30);
                *pose_axis(&want_base, axis) = mid;
                *pose_axis(&want_spread, axis) = amp;
            } else {
                *pose_axis(&want_pose, axis) = *pose_axis(&want_base, axis) = m->decoded.body[axis];
                *pose_axis(&want_spread, axis) = 0;
            }
        }
        want_pose.roll_mdeg = clamp_range(want_pose.roll_mdeg, &p->body_mdeg[0]);
        want_pose.pitch_mdeg = clamp_range(want_pose.pitch_mdeg, &p->body_mdeg[1]);
        want_base.roll_mdeg = clamp_range(want_base.roll_mdeg, &p->body_mdeg[0]);
        want_base.pitch_mdeg = clamp_range(want_base.pitch_mdeg, &p->body_mdeg[1]);
        xgo_motion_asked_pose(m, &board.regs, &pose, &base, &spread);
        TEST_ASSERT_EQUAL_MEMORY(&want_pose, &pose, sizeof pose);
        TEST_ASSERT_EQUAL_MEMORY(&want_base, &base, sizeof base);
        TEST_ASSERT_EQUAL_MEMORY(&want_spread, &spread, sizeof spread);
        for (axis = 0; axis < 6; axis++) {
            TEST_ASSERT_EQUAL_UINT32((m->decoded.periodic >> axis) & 1u ? phase[axis] : 0u, m->periodic_phase[axis]);
        }
    }
}

/* ---- the IMU registers 0x62..0x68, formed on read ----
 * The board once stored the IMU's angles (bytes at 0x62..0x64, the angles
 * themselves for the views) and the accelerometer and gyroscope (the block
 * at 0x65) at power-up and at the end of every tick. imu_as_stored is that
 * store, from the public observers (the model's outputs from its struct),
 * encoded here in double; every read until the next tick must give exactly
 * it: the flat bytes in any window, and the views a read starting at 0x62..
 * 0x68 gets (float32 LE degrees from four bytes, the block, big-endian
 * centidegrees). */
static struct {
    int32_t mdeg[3];
    uint8_t byte[3];
    int16_t accel[3], gyro[3];
} imu_as_stored;

static void store_imu(void)
{
    unsigned i;
    xgo_board_imu_mdeg(&board, imu_as_stored.mdeg);
    for (i = 0; i < 3; i++) {
        /* 1 LSB = 1406.25 mdeg, half away from zero (never a tie: 8 m is
         * even, 5625 (2k + 1) odd), clamped */
        const double q = (double)imu_as_stored.mdeg[i] / 1406.25;
        const double k = 128.0 + (q >= 0 ? floor(q + 0.5) : -floor(-q + 0.5));
        imu_as_stored.byte[i] = (uint8_t)(k < 0 ? 0 : (k > 255 ? 255 : k));
#if XGO_WITH_INERTIAL
        imu_as_stored.accel[i] = board.motion.inertial.accel[i];
        imu_as_stored.gyro[i] = board.motion.inertial.gyro[i];
#else
        imu_as_stored.accel[i] = imu_as_stored.gyro[i] = 0;
#endif
    }
}

static void put_le(uint8_t *out, uint32_t v, unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        out[i] = (uint8_t)(v >> (8u * i));
    }
}

static uint32_t deg_float_bits(int32_t mdeg)
{
    const float f = (float)((double)mdeg / 1000.0);
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    return bits;
}

/* The bytes a read of len at start gives: the image's, and at its start
 * the view of that address, if any (xgo/regs.h). */
static void imu_expected(const uint8_t image[XGO_REG_COUNT], unsigned start, unsigned len,
                         uint8_t *want)
{
    uint8_t view[XGO_IMU_BLOCK_LEN];
    unsigned i, vlen = 0;
    memcpy(want, &image[start], len);
    if (start >= XGO_REG_IMU_ROLL && start <= XGO_REG_IMU_YAW && len >= 4) {
        put_le(view, deg_float_bits(imu_as_stored.mdeg[start - XGO_REG_IMU_ROLL]), 4);
        vlen = 4;
    } else if (start == XGO_REG_IMU_BLOCK) {
        for (i = 0; i < 3; i++) {
            put_le(&view[2 * i], (uint16_t)imu_as_stored.accel[i], 2);
            put_le(&view[6 + 2 * i], (uint16_t)imu_as_stored.gyro[i], 2);
            put_le(&view[12 + 4 * i], deg_float_bits(imu_as_stored.mdeg[i]), 4);
        }
        vlen = XGO_IMU_BLOCK_LEN;
    } else if (start >= XGO_REG_IMU_ROLL16 && start <= XGO_REG_IMU_YAW16) {
        const double c = (double)imu_as_stored.mdeg[start - XGO_REG_IMU_ROLL16] / 10.0;
        const uint16_t v = (uint16_t)(int16_t)(c >= 0 ? floor(c + 0.5) : -floor(-c + 0.5));
        view[0] = (uint8_t)(v >> 8);
        view[1] = (uint8_t)v;
        vlen = 2;
    }
    for (i = 0; i < len && i < vlen; i++) {
        want[i] = view[i];
    }
}

/* Every start from 0x50 to 0x80 and several lengths over the IMU's
 * registers and past them: each read gives the bytes as stored and writes
 * no byte past its end; and over the wire, the yaw's float and the block. */
static void check_imu_reads(void)
{
    static const uint8_t lens[] = {1, 2, 3, 4, 5, 6, 8, 19, 24, 25, 40};
    uint8_t image[XGO_REG_COUNT];
    uint8_t buf[48], want[48];
    unsigned start, k;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x00, XGO_FRAME_MAX_DATA, image));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, XGO_FRAME_MAX_DATA,
                                                        XGO_REG_COUNT - XGO_FRAME_MAX_DATA,
                                                        &image[XGO_FRAME_MAX_DATA]));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(imu_as_stored.byte, &image[XGO_REG_IMU_ROLL], 3);
    for (start = 0x50; start <= 0x80; start++) {
        for (k = 0; k < sizeof lens; k++) {
            memset(buf, 0xA5, sizeof buf);
            imu_expected(image, start, lens[k], want);
            TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, (uint8_t)start, lens[k], buf));
            TEST_ASSERT_EQUAL_HEX8_ARRAY(want, buf, lens[k]);
            TEST_ASSERT_EQUAL_HEX8(0xA5, buf[lens[k]]);
        }
    }
    wire_read(XGO_REG_IMU_YAW, 4, buf);
    imu_expected(image, XGO_REG_IMU_YAW, 4, want);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want, buf, 4);
    wire_read(XGO_REG_IMU_BLOCK, XGO_IMU_BLOCK_LEN, buf);
    imu_expected(image, XGO_REG_IMU_BLOCK, XGO_IMU_BLOCK_LEN, want);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want, buf, XGO_IMU_BLOCK_LEN);
}

/* Random writes as the joints' test makes (walking turns the yaw, the body
 * pose and actions roll and pitch it, the reset and the modes), the body
 * pose's angles at any value, and the emulator's shove and ground tilt
 * between ticks (the model's inputs: the angles move on the next tick). */
static void random_imu_write(uint32_t *seed, int arm)
{
    const uint32_t r = xgo_test_xorshift32(seed);
    switch (r % 4u) {
    case 0:
        xgo_board_push(&board, (int32_t)(r >> 8) % 40000 - 20000, (int32_t)(r >> 12) % 40000 - 20000);
        break;
    case 1:
        xgo_board_set_ground_tilt(&board, (int32_t)(r >> 4) % 100000 - 50000,
                                  (int32_t)(r >> 10) % 100000 - 50000);
        break;
    case 2:
        xgo_test_write1(&board, (uint8_t)(XGO_REG_BODY_ROLL + (r >> 8) % 3u), (uint8_t)(r >> 16), 0);
        break;
    default:
        random_joint_write(seed, arm);
        break;
    }
}

static void test_imu_reads_give_the_bytes_a_tick_stored(void)
{
    static const xgo_model_t models[] = {XGO_MODEL_MINI, XGO_MODEL_LITE, XGO_MODEL_MINI2};
    unsigned m, t;
    uint32_t seed = 0x9E3779B9u;
    for (m = 0; m < sizeof models / sizeof models[0]; m++) {
        xgo_board_config_t cfg;
        xgo_board_default_config(&cfg);
        cfg.model = models[m];
        xgo_board_init(&board, &cfg);
        store_imu(); /* power-up */
        check_imu_reads();
        for (t = 0; t < 6000; t++) {
            if (xgo_test_xorshift32(&seed) % 20u == 0) {
                random_imu_write(&seed, models[m] == XGO_MODEL_MINI2);
                check_imu_reads(); /* written, not yet ticked */
            }
            xgo_board_tick(&board);
            store_imu();
            if (t % 16u == 0) {
                check_imu_reads();
            }
        }
    }
}

/* A periodic motion turned off and on again starts over from its phase 0,
 * as it did the first time (the phase of an axis without one is 0). */
static void test_a_periodic_motion_turned_on_again_starts_over(void)
{
    static xgo_board_t again;
    xgo_board_init(&board, NULL);
    xgo_board_init(&again, NULL);
    xgo_test_write1(&board, XGO_REG_PERIOD_ROLL, 0x30, 0);
    xgo_test_ticks(&board, 300);
    xgo_test_write1(&board, XGO_REG_PERIOD_ROLL, 0, 0);
    xgo_test_ticks(&board, 1);
    TEST_ASSERT_EQUAL_UINT32(0, board.motion.periodic_phase[0]);
    xgo_test_write1(&board, XGO_REG_PERIOD_ROLL, 0x30, 0);
    xgo_test_write1(&again, XGO_REG_PERIOD_ROLL, 0x30, 0);
    xgo_test_ticks(&board, 1);
    xgo_test_ticks(&again, 1);
    TEST_ASSERT_EQUAL_UINT32(again.motion.periodic_phase[0], board.motion.periodic_phase[0]);
    TEST_ASSERT_NOT_EQUAL(0, board.motion.periodic_phase[0]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_spec_read_example_gets_the_spec_reply);
    RUN_TEST(test_spec_write_example_sets_vx_and_sends_nothing);
    RUN_TEST(test_two_requests_in_one_write_are_answered_in_order);
    RUN_TEST(test_garbage_then_request_gets_its_reply);
    RUN_TEST(test_write_to_read_only_is_rejected_counted_and_traced);
    RUN_TEST(test_invalid_value_is_rejected_and_traced);
    RUN_TEST(test_vendor_writes_for_other_models_do_no_harm);
    RUN_TEST(test_auto_clear_registers_clear_on_the_next_tick);
    RUN_TEST(test_plain_registers_do_not_clear_on_tick);
    RUN_TEST(test_diagnostic_block_over_the_wire_matches_counters);
    RUN_TEST(test_diag_block_is_formed_on_read);
    RUN_TEST(test_reply_after_waiting_bytes_keeps_the_stream);
    RUN_TEST(test_transmit_overflow_drops_whole_replies);
    RUN_TEST(test_partial_transmit_keeps_order_across_wrap);
    RUN_TEST(test_lite_profile_identity);
    RUN_TEST(test_mini_firmware_starts_with_M_and_is_ascii);
    RUN_TEST(test_timeout_through_the_board);
    RUN_TEST(test_read_requests_never_change_state);
    RUN_TEST(test_upgrade_request_is_answered_at_once);
    RUN_TEST(test_turn_command_reads_turning_until_the_tick_decides);
    RUN_TEST(test_joint_reads_give_the_bytes_a_tick_stored);
    RUN_TEST(test_the_asked_pose_is_each_axis_static_or_periodic);
    RUN_TEST(test_a_periodic_motion_turned_on_again_starts_over);
    RUN_TEST(test_imu_reads_give_the_bytes_a_tick_stored);
    return UNITY_END();
}
