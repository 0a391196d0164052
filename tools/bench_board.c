/*
 * Control-tick cost: the whole board (register decoding, gait, body pose,
 * body + leg IK, servos, IMU, battery, publishing) while trotting with a body
 * pose and a periodic motion, as a host would command it.
 *
 * Instructions per tick (exact, repeatable):
 *   valgrind --tool=callgrind --toggle-collect=xgo_board_tick \
 *       --callgrind-out-file=/dev/null ./build/bench_board 10000
 *   (Collected / 11000: the 1000 warm-up ticks are counted too); the wall-clock ticks per second printed below are
 *   for information on this machine.
 *
 * Usage: bench_board [ticks] (default 200000)
 */
#include <stdio.h>
#include <stdlib.h>

#include "board_io.h"
#include "test_clock.h"
#include "xgo/board.h"

/* Wall-clock seconds (test/support/test_clock.h). */
static double now_s(void)
{
    return xgo_test_now_us_f() * 1e-6;
}

int main(int argc, char **argv)
{
    static xgo_board_t board;
    xgo_gait_status_t gait;
    const long n = argc > 1 ? atol(argv[1]) : 200000L;
    long i;
    double t0, dt;

    if (n < 1) {
        fprintf(stderr, "usage: bench_board [ticks>=1]\n");
        return 2;
    }
    xgo_board_init(&board, NULL);
    xgo_test_write1(&board, XGO_REG_VX, 0xE0, 0);        /* forward ~19 cm/s */
    xgo_test_write1(&board, XGO_REG_VYAW, 0xA0, 0);      /* turning ~25 deg/s */
    xgo_test_write1(&board, XGO_REG_BODY_ROLL, 0xA0, 0); /* body pose on top */
    xgo_test_write1(&board, XGO_REG_BODY_Z, 0x60, 0);
    xgo_test_write1(&board, XGO_REG_PERIOD_PITCH, 0x40, 0);
    /* Warm up past the velocity ramp so every measured tick is trotting. */
    xgo_test_ticks(&board, 1000);
    t0 = now_s();
    for (i = 0; i < n; i++) {
        xgo_board_tick(&board);
    }
    dt = now_s() - t0;
    printf("bench_board: %ld ticks trotting with body pose: %.0f ticks/s, %.2f us/tick "
           "(wall clock); %.1f%% of one core at %u Hz\n",
           n, (double)n / dt, dt / (double)n * 1e6, 100.0 * XGO_TICK_HZ * dt / (double)n,
           XGO_TICK_HZ);
    xgo_board_gait(&board, &gait);
    return gait.walking ? 0 : 1;
}
