/*
 * IMU and battery models.
 */
#include "sensors.h"

#include <string.h>

#include "fixed.h" /* xgo_wrap_mdeg */
#include "wide.h"

#define FULL_UPCT 100000000u
#define UPCT_PER_PCT 1000000u

void xgo_battery_init(xgo_battery_t *b, uint8_t percent)
{
    b->charge_upct = (percent > 100 ? 100u : (uint32_t)percent) * UPCT_PER_PCT;
}

uint8_t xgo_battery_percent(const xgo_battery_t *b)
{
    const uint32_t c = b->charge_upct > FULL_UPCT ? FULL_UPCT : b->charge_upct;
    const uint32_t n = c + UPCT_PER_PCT - 1u;
    /* n / 10^6 as a multiply by ceil(2^50 / 10^6) on a core without a
     * divider (exact for every uint32 n, checked exhaustively): the board
     * publishes the percentage every tick */
    return (uint8_t)(XGO_CORE_NARROW_CPU ? (uint32_t)(xgo_umul_wide(n, 0x431BDE83u) >> 50)
                                         : n / UPCT_PER_PCT);
}

void xgo_imu_init(xgo_imu_t *imu)
{
    memset(imu, 0, sizeof *imu);
}

#if XGO_WITH_EMULATOR_INPUTS
void xgo_imu_set_ground_tilt(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    /* A ramp steeper than 45 degrees is not ground a dog stands on. */
    const int32_t lim = 45000;
    imu->ground_roll_mdeg = roll_mdeg < -lim ? -lim : (roll_mdeg > lim ? lim : roll_mdeg);
    imu->ground_pitch_mdeg = pitch_mdeg < -lim ? -lim : (pitch_mdeg > lim ? lim : pitch_mdeg);
}

/* The shove's spring per tick at 500 Hz, Q16: omega^2 dt^2 and 2 zeta omega
 * dt for 3 Hz and zeta 0.35 (docs/motion.md). */
#if XGO_TICK_HZ != 500u
#error "PUSH_SPRING_Q16 and PUSH_DAMPING_Q16 are per-tick constants for 500 Hz"
#endif
#define PUSH_SPRING_Q16 93
#define PUSH_DAMPING_Q16 1730
#define PUSH_MAX_MDEG 30000

static int32_t clamp_push(int32_t mdeg)
{
    return mdeg < -PUSH_MAX_MDEG ? -PUSH_MAX_MDEG : (mdeg > PUSH_MAX_MDEG ? PUSH_MAX_MDEG : mdeg);
}

void xgo_imu_push(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    const int32_t add[2] = {clamp_push(roll_mdeg), clamp_push(pitch_mdeg)};
    unsigned axis;
    for (axis = 0; axis < 2; axis++) {
        imu->push_q10[axis] = clamp_push((imu->push_q10[axis] >> 10) + add[axis]) * 1024;
    }
}

/* Semi-implicit Euler step of the damped spring (tilt in mdeg * 1024, rate
 * per tick in the same unit); the products need up to 36 bits. */
static void push_tick(xgo_imu_t *imu)
{
    unsigned axis;
    if ((imu->push_q10[0] | imu->push_q10[1] | imu->push_rate_q10[0] | imu->push_rate_q10[1]) == 0) {
        return; /* no shove ringing (nearly every tick): one test, not a loop */
    }
    for (axis = 0; axis < 2; axis++) {
        int32_t *x = &imu->push_q10[axis], *v = &imu->push_rate_q10[axis];
        if ((*x | *v) == 0) {
            continue;
        }
        *v -= (int32_t)((xgo_mul_wide(*x, PUSH_SPRING_Q16) + xgo_mul_wide(*v, PUSH_DAMPING_Q16)) >> 16);
        *x += *v;
        if (*x > -1024 && *x < 1024 && *v > -20 && *v < 20) {
            *x = 0; /* settled below a millidegree */
            *v = 0;
        }
    }
}

/* The tilt the emulator adds to the body's: the ground's and a shove's. */
static int32_t extra_roll(const xgo_imu_t *imu)
{
    return imu->ground_roll_mdeg + (imu->push_q10[0] >> 10);
}

static int32_t extra_pitch(const xgo_imu_t *imu)
{
    return imu->ground_pitch_mdeg + (imu->push_q10[1] >> 10);
}
#else /* a real board's IMU measures the world: nothing to add (xgo/config.h) */
void xgo_imu_set_ground_tilt(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    (void)imu;
    (void)roll_mdeg;
    (void)pitch_mdeg;
}

void xgo_imu_push(xgo_imu_t *imu, int32_t roll_mdeg, int32_t pitch_mdeg)
{
    (void)imu;
    (void)roll_mdeg;
    (void)pitch_mdeg;
}

#define push_tick(imu) ((void)(imu))
#define extra_roll(imu) 0
#define extra_pitch(imu) 0
#endif

void xgo_imu_reset_yaw(xgo_imu_t *imu)
{
    imu->yaw_acc = 0;
}

/* a + b wrapped into [-180000, 180000): the sum of int32 angles, clamped to
 * int32 first (angles beyond +-2147483 degrees are no angles a tick makes),
 * so no 64-bit remainder is needed. Inline: a sum already an angle (the
 * common case) makes no call. The sum is formed in 32 bits: one of the two
 * is small (under 2^20: the tilt a ramp and a shove add, or the integrated
 * yaw), so a sum that overflowed lies near -2^31 or 2^31, never in the
 * range nor a turn from it, and takes the exact path; no 64-bit value
 * either. On a 64-bit host a sum within a turn of the range (the
 * integrated yaw, at most one turn, plus a body's yaw: a robot that turned
 * half a turn or more, about half the ticks of one that keeps turning) is
 * wrapped here too, without the calls (x86-64: their saved registers and
 * about 20 instructions); on an MCU that would cost flash for a tick that
 * is no worst case. */
XGO_ALWAYS_INLINE int32_t wrap_sum(int32_t a, int32_t b)
{
    const int32_t s = (int32_t)((uint32_t)a + (uint32_t)b);
    if ((uint32_t)s + 180000u < 360000u) {
        return s;
    }
#if XGO_CORE_DIV64_NATIVE
    if ((uint32_t)s - 180000u < 360000u) { /* [180000, 540000) */
        return s - 360000;
    }
    if ((uint32_t)s + 540000u < 360000u) { /* [-540000, -180000) */
        return s + 360000;
    }
#endif
    return xgo_wrap_mdeg(xgo_sat32((int64_t)a + b));
}

/* yaw_acc wraps at one turn: 360 degrees in mdeg * XGO_TICK_HZ. */
#define YAW_TURN ((int64_t)360000 * (int64_t)XGO_TICK_HZ)
#if XGO_TICK_HZ > 2900
#error "xgo_imu_tick keeps two turns of yaw_acc (mdeg * XGO_TICK_HZ) in an int32"
#endif

/* a32 / XGO_TICK_HZ (truncated), |a32| < 2^30. On a core without a
 * divider as a multiply by ceil(2^32 / 500) and one correction (the
 * estimate is the quotient or one more: u * 0.408 / 2^32 < 1 / 500), not a
 * library division every tick. */
static int32_t yaw_acc_mdeg(int32_t a32)
{
#if XGO_TICK_HZ == 500u
    if (XGO_CORE_NARROW_CPU) {
        const uint32_t u = a32 < 0 ? 0u - (uint32_t)a32 : (uint32_t)a32;
        uint32_t q = (uint32_t)(xgo_umul_wide(u, 8589935u) >> 32);
        q -= q * 500u > u ? 1u : 0u;
        return a32 < 0 ? -(int32_t)q : (int32_t)q;
    }
#endif
    return a32 / (int32_t)XGO_TICK_HZ;
}

void xgo_imu_tick(xgo_imu_t *imu, int32_t body_roll_mdeg, int32_t body_pitch_mdeg,
                  int32_t body_yaw_mdeg, int32_t yaw_rate_mdeg_s)
{
    /* yaw_acc counts mdeg * XGO_TICK_HZ, so adding the rate each tick
     * integrates exactly; it wraps at one turn. All in 32 bits: |yaw_acc| <
     * turn, so |a32| < 2 turn < 2^30, and one subtraction does what % does
     * (truncating, sign of acc). A rate of a turn per tick or more (180,000
     * deg/s at 500 Hz) is clamped just below it. */
    const int32_t t32 = (int32_t)YAW_TURN;
    const int32_t rate = yaw_rate_mdeg_s >= t32 ? t32 - 1
                                                : (yaw_rate_mdeg_s <= -t32 ? 1 - t32 : yaw_rate_mdeg_s);
    int32_t a32 = imu->yaw_acc + rate;
    int32_t acc;
    if (a32 >= t32) {
        a32 -= t32;
    } else if (a32 <= -t32) {
        a32 += t32;
    }
    imu->yaw_acc = a32;
    acc = yaw_acc_mdeg(a32);
    push_tick(imu);
    imu->roll_mdeg = wrap_sum(body_roll_mdeg, extra_roll(imu));
    imu->pitch_mdeg = wrap_sum(body_pitch_mdeg, extra_pitch(imu));
    imu->yaw_mdeg = wrap_sum(acc, body_yaw_mdeg);
}
