/*
 * clock.h - the host's monotonic time base. Everything time-related in
 * xgo-emu (control ticks, parser timestamps, baud pacing) reads this one
 * clock, so wall-clock jumps (NTP, suspend adjustments) never disturb it.
 */
#ifndef XGO_HOST_CLOCK_H
#define XGO_HOST_CLOCK_H

#include <stdint.h>

/* Microseconds on CLOCK_MONOTONIC (arbitrary origin, never goes back). */
uint64_t xgo_host_clock_us(void);

/* The board wants milliseconds in 32 bits; it handles the wrap itself. */
uint32_t xgo_host_clock_ms32(uint64_t now_us);

#endif /* XGO_HOST_CLOCK_H */
