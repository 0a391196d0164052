/*
 * board_io.h - drive an xgo_board_t in process the way a host does over the
 * wire, for the tests, the benches and the MCU self test (tools/mcu), which
 * all share these helpers instead of keeping their own.
 *
 * Freestanding C99: no C library, no Unity, no OS (the MCU self test links it
 * bare metal). Nothing here asserts: results are return codes, the callers
 * assert on them (Unity) or exit with a code (MCU).
 */
#ifndef XGO_TEST_BOARD_IO_H
#define XGO_TEST_BOARD_IO_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/board.h"

/* A write frame of n data bytes at addr, fed to the board at now_ms. */
void xgo_test_write(xgo_board_t *b, uint8_t addr, const uint8_t *data, size_t n, uint32_t now_ms);
void xgo_test_write1(xgo_board_t *b, uint8_t addr, uint8_t value, uint32_t now_ms);

/* A read request for count bytes at addr, fed to the board at now_ms (the
 * reply waits in the board's transmit buffer). */
void xgo_test_request(xgo_board_t *b, uint8_t addr, uint8_t count, uint32_t now_ms);

/* What is wrong with a read reply, checked independently of the core's
 * encoder (the checksum is computed here): the first problem found. */
typedef enum xgo_test_reply_e {
    XGO_TEST_REPLY_OK = 0,
    XGO_TEST_REPLY_SIZE,     /* not count + 8 bytes */
    XGO_TEST_REPLY_HEADER,   /* not 0x55 0x00 */
    XGO_TEST_REPLY_LEN,      /* LEN byte not count + 8 */
    XGO_TEST_REPLY_TYPE,     /* TYPE not 0x12 */
    XGO_TEST_REPLY_ADDR,     /* ADDR not the one asked for */
    XGO_TEST_REPLY_CHECKSUM, /* SUM wrong */
    XGO_TEST_REPLY_TAIL      /* not 0x00 0xAA */
} xgo_test_reply_t;

xgo_test_reply_t xgo_test_check_reply(const uint8_t *reply, size_t n, uint8_t addr, uint8_t count);

/* "ok", "size", "header", ...: for assertion messages. */
const char *xgo_test_reply_name(xgo_test_reply_t problem);

/* Request count bytes at addr, drain the reply and check it; on
 * XGO_TEST_REPLY_OK its data is in data[0..count-1]. Anything else already
 * waiting in the transmit buffer counts as part of the reply. */
xgo_test_reply_t xgo_test_read(xgo_board_t *b, uint8_t addr, uint8_t count, uint32_t now_ms,
                               uint8_t *data);

/* n control ticks. */
void xgo_test_ticks(xgo_board_t *b, uint32_t n);

/* Deterministic generators (same numbers on every run and every target):
 * xorshift32 (13, 17, 5) and xorshift64 (13, 7, 17) returning bits 16..47.
 * The state is the caller's; it must not be 0. */
uint32_t xgo_test_xorshift32(uint32_t *state);
uint32_t xgo_test_xorshift64(uint64_t *state);

#endif /* XGO_TEST_BOARD_IO_H */
