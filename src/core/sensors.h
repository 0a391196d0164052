/*
 * sensors.h - the board's emulated IMU and battery.
 *
 * IMU: roll and pitch are the body's attitude relative to the ground plus the
 * ground's own tilt (an emulator input: a ramp under the robot), composed by
 * addition (exact for a tilt about one axis, a small-angle approximation for
 * both at once; docs/motion.md). Yaw integrates the body's turning rate and
 * is reported in [-180, 180) degrees.
 *
 * Battery: a charge counter in micro-percent that drains at a constant rate,
 * faster while walking (rates in docs/motion.md). The register shows the
 * charge in whole percent, rounded up, so a full battery reads 100 until
 * one percent has gone.
 *
 * Checks: none assert; a battery level over 100 is clamped (the board
 * asserts on it in its config, xgo/board.h), tilts and shoves are clamped.
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_SENSORS_H
#define XGO_SENSORS_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_battery_t, xgo_imu_t */
#include "xgo/config.h"      /* XGO_TICK_HZ */

#ifdef __cplusplus
extern "C" {
#endif

/* Drain per control tick, micro-percent, rounded: 100 % lasts 120 min idle
 * and 60 min walking (at 500 Hz: 1e8 / 3.6e6 = 27.8 -> 28, 55.6 -> 56). */
#define XGO_BATTERY_UPCT_PER_TICK_(minutes)                                                    \
    ((100000000u + (minutes)*60u * XGO_TICK_HZ / 2u) / ((minutes)*60u * XGO_TICK_HZ))
#define XGO_BATTERY_IDLE_UPCT_PER_TICK XGO_BATTERY_UPCT_PER_TICK_(120u)
#define XGO_BATTERY_WALK_UPCT_PER_TICK XGO_BATTERY_UPCT_PER_TICK_(60u)

void xgo_battery_init(xgo_battery_t *b, uint8_t percent);
/* One tick's drain (inline: every tick, three instructions' worth). */
static inline void xgo_battery_tick(xgo_battery_t *b, int walking)
{
    const uint32_t drain = walking ? XGO_BATTERY_WALK_UPCT_PER_TICK : XGO_BATTERY_IDLE_UPCT_PER_TICK;
    b->charge_upct = b->charge_upct > drain ? b->charge_upct - drain : 0u;
}
uint8_t xgo_battery_percent(const xgo_battery_t *b);

/* 1: percent == xgo_battery_percent(b), by three compares: percent <= 100
 * and the charge c in ((percent - 1) 10^6, percent 10^6] micro-percent
 * (c + 10^6 is formed only for c <= 10^8: no overflow). 0 otherwise, and
 * for a charge beyond full (never: xgo_battery_init caps it), so the caller
 * works the percentage out. The board publishes it every tick and it
 * changes once a percent: a byte already right is not worked out again. */
static inline int xgo_battery_is_percent(const xgo_battery_t *b, uint8_t percent)
{
    const uint32_t c = b->charge_upct, at = (uint32_t)percent * 1000000u;
    return percent <= 100u && c <= at && at < c + 1000000u;
}

void xgo_imu_init(xgo_imu_t *imu);
void xgo_imu_set_ground_tilt(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg);
/* A shove (an emulator input): the body is tipped by roll/pitch (mdeg, each
 * clamped to +-30 degrees, added to any shove still ringing) and springs back
 * as a damped oscillation (3 Hz, damping ratio 0.35: below 1 % of the tip
 * from 0.65 s on, settled to 0 within 1.5 s; test_sensors). The IMU reads it; self-stabilisation (0x61) reacts to it. */
void xgo_imu_push(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg);

/* Zero the integrated yaw (action 255 does this, like a power-up). */
void xgo_imu_reset_yaw(xgo_imu_t *imu);

/* One tick (1 / XGO_TICK_HZ s): body attitude relative to the ground (mdeg)
 * and the body's yaw rate (mdeg/s). */
void xgo_imu_tick(xgo_imu_t *imu, int32_t body_roll_mdeg, int32_t body_pitch_mdeg,
                  int32_t body_yaw_mdeg, int32_t yaw_rate_mdeg_s);

#ifdef __cplusplus
}
#endif

#endif /* XGO_SENSORS_H */
