/*
 * Turn in place to a heading (see heading.h).
 */
#include "heading.h"

#include "fixed.h"

void xgo_heading_init(xgo_heading_t *h)
{
    h->origin_mdeg = 0;
    h->target_mdeg = 0;
    h->state = XGO_HEADING_IDLE;
}

void xgo_heading_set_origin(xgo_heading_t *h, int32_t yaw_mdeg)
{
    h->origin_mdeg = xgo_wrap_mdeg(yaw_mdeg);
}

void xgo_heading_start(xgo_heading_t *h, int32_t heading_deg)
{
    /* an int16 of degrees is at most 91 turns: reduce before scaling */
    const int32_t turns_removed = heading_deg % 360;
    h->target_mdeg = xgo_wrap_mdeg(h->origin_mdeg + xgo_wrap_mdeg(turns_removed * 1000));
    h->state = XGO_HEADING_TURNING;
}

void xgo_heading_cancel(xgo_heading_t *h)
{
    h->state = XGO_HEADING_IDLE;
}

/* The rate that still stops at the target with the profile's deceleration. */
static int32_t profile_rate(int32_t error_mdeg)
{
    const uint32_t e = (uint32_t)(error_mdeg < 0 ? -error_mdeg : error_mdeg);
    uint32_t rate = xgo_isqrt64((uint64_t)2u * XGO_HEADING_DECEL_MDEG_S2 * e);
    if (rate > XGO_HEADING_RATE_MDEG_S) {
        rate = XGO_HEADING_RATE_MDEG_S;
    } else if (rate < XGO_HEADING_MIN_RATE_MDEG_S) {
        rate = XGO_HEADING_MIN_RATE_MDEG_S;
    }
    return error_mdeg < 0 ? -(int32_t)rate : (int32_t)rate;
}

int32_t xgo_heading_tick(xgo_heading_t *h, int32_t yaw_mdeg, int32_t produced_mdeg_s)
{
    const int32_t error = xgo_wrap_mdeg(h->target_mdeg - xgo_wrap_mdeg(yaw_mdeg));
    const int32_t abs_error = error < 0 ? -error : error;
    switch ((xgo_heading_state_t)h->state) {
    case XGO_HEADING_TURNING:
        if (abs_error > XGO_HEADING_STOP_MDEG) {
            return profile_rate(error);
        }
        h->state = XGO_HEADING_SETTLING;
        return 0;
    case XGO_HEADING_SETTLING:
        if (produced_mdeg_s == 0) {
            /* stopped: there, or (overshot, pushed) try again from here */
            h->state = abs_error <= XGO_HEADING_TOLERANCE_MDEG ? XGO_HEADING_IDLE
                                                               : XGO_HEADING_TURNING;
        }
        return 0;
    case XGO_HEADING_IDLE:
        break;
    }
    return 0;
}
