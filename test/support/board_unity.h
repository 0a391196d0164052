/*
 * board_unity.h - what the Unity suites that drive one board in process all
 * need, asserting as they go (hosted only: Unity and float): a register
 * write through the host path, a register read over the wire, the float32
 * a vendor library decodes from an attitude read. Built on board_io.h.
 */
#ifndef XGO_TEST_BOARD_UNITY_H
#define XGO_TEST_BOARD_UNITY_H

#include <stdint.h>

#include "board_io.h"

/* xgo_board_write of one byte; asserts it was applied. */
void xgo_test_wr(xgo_board_t *b, uint8_t addr, uint8_t value);

/* One register over the wire (a read frame); asserts a well-formed reply. */
uint8_t xgo_test_rd(xgo_board_t *b, uint8_t addr);

/* A 4-byte read at addr as float32 little-endian (what read_roll() and the
 * other float readers of the vendor library decode). */
float xgo_test_rd_float(xgo_board_t *b, uint8_t addr);

#endif /* XGO_TEST_BOARD_UNITY_H */
