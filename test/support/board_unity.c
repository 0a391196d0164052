/*
 * board_unity.c - asserting board helpers for the Unity suites (see
 * board_unity.h).
 */
#include "board_unity.h"

#include <string.h>

#include "unity.h"

void xgo_test_wr(xgo_board_t *b, uint8_t addr, uint8_t value)
{
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(b, XGO_SOURCE_CLI, addr, &value, 1));
}

uint8_t xgo_test_rd(xgo_board_t *b, uint8_t addr)
{
    uint8_t v;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(b, addr, 1, 0, &v));
    return v;
}

float xgo_test_rd_float(xgo_board_t *b, uint8_t addr)
{
    uint8_t raw[4];
    uint32_t u;
    float f;
    TEST_ASSERT_EQUAL_INT(XGO_TEST_REPLY_OK, xgo_test_read(b, addr, 4, 0, raw));
    u = (uint32_t)raw[0] | (uint32_t)raw[1] << 8 | (uint32_t)raw[2] << 16 | (uint32_t)raw[3] << 24;
    memcpy(&f, &u, sizeof f);
    return f;
}
