/*
 * heading.h - turn in place to a heading: the controller behind register
 * 0x3F (the vendor library's move_to) and its origin, register 0x06.
 *
 * A heading command is relative to the origin: the yaw the IMU read when
 * 0x06 was last set to 1 (power-up and action 255 set it to 0, where the
 * IMU's yaw starts). The controller turns the robot in place by commanding
 * the gait's yaw rate, the shorter way round:
 *
 *   rate = min(XGO_HEADING_RATE_MDEG_S, sqrt(2 * XGO_HEADING_DECEL_MDEG_S2 * |error|))
 *
 * (never below XGO_HEADING_MIN_RATE_MDEG_S), i.e. full speed until the point
 * from which a constant deceleration stops it at the target; the gait's own
 * yaw ramp (250 deg/s^2) can follow that profile. Within
 * XGO_HEADING_STOP_MDEG of the target it commands zero; once the gait has
 * stopped turning the turn is done if the error is within
 * XGO_HEADING_TOLERANCE_MDEG, else it starts again from there.
 *
 * Checks: none; every input value is handled (expected input).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_HEADING_H
#define XGO_HEADING_H

#include <stdint.h>

#include "xgo/board_state.h" /* xgo_heading_t */

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_HEADING_RATE_MDEG_S 60000      /* the vendor library's turn_to default */
#define XGO_HEADING_DECEL_MDEG_S2 200000   /* below the gait's 250 deg/s^2 ramp */
#define XGO_HEADING_MIN_RATE_MDEG_S 5000   /* the last degrees take no ages */
#define XGO_HEADING_STOP_MDEG 250          /* command zero this close */
#define XGO_HEADING_TOLERANCE_MDEG 1000    /* done: within 1 degree */

typedef enum xgo_heading_state_e {
    XGO_HEADING_IDLE = 0,    /* done, cancelled or never asked */
    XGO_HEADING_TURNING = 1, /* commanding a rate toward the target */
    XGO_HEADING_SETTLING = 2 /* commanding zero, waiting for the gait to stop */
} xgo_heading_state_t;

/* Idle, origin 0. */
void xgo_heading_init(xgo_heading_t *h);

/* Register 0x06: the current IMU yaw becomes heading 0. */
void xgo_heading_set_origin(xgo_heading_t *h, int32_t yaw_mdeg);

/* Register 0x3F: turn to heading_deg relative to the origin (any int16;
 * wrapped into one turn). */
void xgo_heading_start(xgo_heading_t *h, int32_t heading_deg);

/* Stop turning (another motion command took over); the gait ramps down. */
void xgo_heading_cancel(xgo_heading_t *h);

/* 1 while a turn is under way (the caller then drives the gait with the
 * rate xgo_heading_tick returns and no translation). */
static inline int xgo_heading_active(const xgo_heading_t *h) /* inline: twice a tick */
{
    return h->state != XGO_HEADING_IDLE;
}

/* One tick: the IMU yaw now and the yaw rate the gait produced last tick
 * (mdeg/s). Returns the yaw rate to command (mdeg/s, counter-clockwise
 * positive); 0 when idle. */
int32_t xgo_heading_tick(xgo_heading_t *h, int32_t yaw_mdeg, int32_t produced_mdeg_s);

/* What register 0x3F reads: 1 when no turn is under way, 0 while turning. */
static inline uint8_t xgo_heading_done(const xgo_heading_t *h) /* inline: every tick */
{
    return h->state == XGO_HEADING_IDLE ? 1u : 0u;
}

#ifdef __cplusplus
}
#endif

#endif /* XGO_HEADING_H */
