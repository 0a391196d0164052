/*
 * board_io.c - the in-process wire helpers (see board_io.h). Frames are built
 * with the core's encoder (what a host library would send); replies are
 * checked byte by byte here, without it.
 */
#include "board_io.h"

void xgo_test_write(xgo_board_t *b, uint8_t addr, const uint8_t *data, size_t n, uint32_t now_ms)
{
    uint8_t frame[XGO_FRAME_MAX_LEN];
    xgo_board_receive(b, frame, xgo_frame_encode(XGO_TYPE_WRITE, addr, data, n, frame, sizeof frame),
                      now_ms);
}

void xgo_test_write1(xgo_board_t *b, uint8_t addr, uint8_t value, uint32_t now_ms)
{
    xgo_test_write(b, addr, &value, 1, now_ms);
}

void xgo_test_request(xgo_board_t *b, uint8_t addr, uint8_t count, uint32_t now_ms)
{
    uint8_t frame[XGO_READ_REQUEST_LEN];
    xgo_board_receive(b, frame, xgo_frame_encode(XGO_TYPE_READ, addr, &count, 1, frame, sizeof frame),
                      now_ms);
}

xgo_test_reply_t xgo_test_check_reply(const uint8_t *reply, size_t n, uint8_t addr, uint8_t count)
{
    uint32_t sum;
    size_t i;
    if (n != (size_t)count + 8u) {
        return XGO_TEST_REPLY_SIZE;
    }
    if (reply[0] != 0x55u || reply[1] != 0x00u) {
        return XGO_TEST_REPLY_HEADER;
    }
    if (reply[2] != (uint8_t)(count + 8u)) {
        return XGO_TEST_REPLY_LEN;
    }
    if (reply[3] != 0x12u) {
        return XGO_TEST_REPLY_TYPE;
    }
    if (reply[4] != addr) {
        return XGO_TEST_REPLY_ADDR;
    }
    sum = (uint32_t)reply[2] + reply[3] + reply[4];
    for (i = 0; i < count; i++) {
        sum += reply[5 + i];
    }
    if (reply[5 + count] != (uint8_t)~sum) {
        return XGO_TEST_REPLY_CHECKSUM;
    }
    if (reply[6 + count] != 0x00u || reply[7 + count] != 0xAAu) {
        return XGO_TEST_REPLY_TAIL;
    }
    return XGO_TEST_REPLY_OK;
}

const char *xgo_test_reply_name(xgo_test_reply_t problem)
{
    static const char *const names[] = {"ok", "size", "header", "len", "type", "addr", "checksum",
                                        "tail"};
    return (unsigned)problem < sizeof names / sizeof names[0] ? names[problem] : "?";
}

xgo_test_reply_t xgo_test_read(xgo_board_t *b, uint8_t addr, uint8_t count, uint32_t now_ms,
                               uint8_t *data)
{
    uint8_t reply[XGO_FRAME_MAX_LEN + 1]; /* one more: a longer reply shows */
    size_t n, i;
    xgo_test_reply_t problem;
    xgo_test_request(b, addr, count, now_ms);
    n = xgo_board_transmit(b, reply, sizeof reply);
    problem = xgo_test_check_reply(reply, n, addr, count);
    if (problem == XGO_TEST_REPLY_OK) {
        for (i = 0; i < count; i++) {
            data[i] = reply[5 + i];
        }
    }
    return problem;
}

void xgo_test_ticks(xgo_board_t *b, uint32_t n)
{
    while (n-- > 0) {
        xgo_board_tick(b);
    }
}

uint32_t xgo_test_xorshift32(uint32_t *state)
{
    uint32_t s = *state;
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    *state = s;
    return s;
}

uint32_t xgo_test_xorshift64(uint64_t *state)
{
    uint64_t s = *state;
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    *state = s;
    return (uint32_t)(s >> 16);
}
