/*
 * xgo/emulator.h - inputs only an emulated board has: the world around the
 * robot, which a real board senses rather than is told (the ground's tilt,
 * the battery's charge, a shove). They sit on the emulator's side of the port
 * boundary: a host port that emulates the robot (xgo-emu, its live view,
 * tests) calls them; firmware on a real board has sensors instead and never
 * includes this header.
 *
 * Checks: values out of range are expected (a slider, a script) and clamped
 * as documented per call; none asserts.
 *
 * All take effect at the next xgo_board_tick(). Portable like the rest of the
 * core: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_EMULATOR_H
#define XGO_EMULATOR_H

#include <stdint.h>

#include "xgo/board.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Built without XGO_WITH_EMULATOR_INPUTS (xgo/config.h; the firmware
 * images) the tilt and the shove do nothing: the ground reads level and the
 * IMU gives the body's own attitude. */

/* The ground under the robot tilts by roll/pitch (the IMU reads the tilt;
 * self-stabilisation, 0x61 = 1, levels the body). Each is clamped to +-45
 * degrees: steeper is not ground a dog stands on (expected input). */
void xgo_board_set_ground_tilt(xgo_board_t *b, int32_t roll_mdeg, int32_t pitch_mdeg);

/* Ground tilt as set. */
void xgo_board_ground_tilt(const xgo_board_t *b, int32_t *roll_mdeg, int32_t *pitch_mdeg);

/* Battery charge now (0..100, larger values are 100); it drains from there. */
void xgo_board_set_battery(xgo_board_t *b, uint8_t pct);

/* A shove: the body tips by roll/pitch (each clamped to +-30 degrees, added
 * to a shove still ringing) and springs back as a damped oscillation
 * (docs/motion.md). */
void xgo_board_push(xgo_board_t *b, int32_t roll_mdeg, int32_t pitch_mdeg);

#ifdef __cplusplus
}
#endif

#endif /* XGO_EMULATOR_H */
