/*
 * host_test.c - a host project's unit test against the xgo core, in
 * process and on virtual time: the bytes a host program would send go into
 * the board, the board's replies come back, nothing waits in real time.
 *
 * Here: put servo 11 (left front knee) at -20 degrees through its register,
 * let the board run 1 s of control ticks, read the register back over the
 * protocol and check the joint arrived. Only public headers (include/xgo).
 */
#include <stdio.h>
#include <stdlib.h>

#include "xgo/board.h"
#include "xgo/reg_units.h"

#define SERVO11 0x50
#define TARGET_MDEG (-20000)

static int failures;

static void check(int ok, const char *what)
{
    printf("%s: %s\n", ok ? "PASS" : "FAIL", what);
    failures += !ok;
}

int main(void)
{
    static xgo_board_t board; /* the caller owns the board's state */
    uint8_t frame[XGO_FRAME_MAX_LEN], reply[XGO_FRAME_MAX_LEN], byte, count = 1;
    size_t n, i;
    int32_t mdeg;

    xgo_board_init(&board, NULL); /* a Mini with the defaults */

    /* the byte the board decodes nearest to -20 deg, written as a host would */
    check(xgo_reg_value_to_byte(NULL, SERVO11, TARGET_MDEG, &byte) == XGO_REG_VALUE_OK,
          "-20 deg is in servo 11's range");
    n = xgo_frame_encode(XGO_TYPE_WRITE, SERVO11, &byte, 1, frame, sizeof frame);
    xgo_board_receive(&board, frame, n, 0);
    check(xgo_board_transmit(&board, reply, sizeof reply) == 0, "a write is not answered");

    for (i = 0; i < XGO_TICK_HZ; i++) { /* one second of control ticks */
        xgo_board_tick(&board);
    }

    /* read the joint back over the protocol: 55 00 09 02 50 01 SUM 00 AA */
    n = xgo_frame_encode(XGO_TYPE_READ, SERVO11, &count, 1, frame, sizeof frame);
    xgo_board_receive(&board, frame, n, 1000);
    n = xgo_board_transmit(&board, reply, sizeof reply);
    check(n == 9 && reply[0] == 0x55 && reply[3] == XGO_TYPE_READ_REPLY && reply[4] == SERVO11,
          "the read is answered with one reply frame");
    check(n == 9 && reply[6] == xgo_frame_checksum(reply[2], reply[3], reply[4], &reply[5], 1),
          "the reply's checksum is right");
    check(xgo_reg_byte_to_value(NULL, SERVO11, reply[5], &mdeg) && labs((long)(mdeg - TARGET_MDEG)) <= 510,
          "servo 11 reads -20 deg within one register step (0.51 deg)");
    printf("servo 11 at %ld mdeg after %lu ms\n", (long)mdeg, (unsigned long)xgo_board_time_ms(&board));
    return failures == 0 ? 0 : 1;
}
