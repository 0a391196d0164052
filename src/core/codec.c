/*
 * codec.c - the register file's byte encodings (see codec.h).
 */
#include "codec.h"

#include "wide.h" /* XGO_CORE_NARROW_CPU */
#include "check.h"
#include "fixed.h"
#include "xgo/regs.h"

/* ------------------------------------------------------------ range map, joints, feet, body */

/* Every range the codec maps spans less than XGO_RANGE_SPAN_LIMIT units
 * (test_profile checks the profiles' ranges, the rest are constants here):
 * then b * span, 255 * offset and (2b + 1) * span fit 32 bits and no 64-bit
 * division is ever needed (none may run in a tick: docs/mcu.md). */
static uint32_t span_of(const xgo_range_t *r)
{
    XGO_ASSERT(r->hi > r->lo && (uint32_t)(r->hi - r->lo) < XGO_RANGE_SPAN_LIMIT);
    return (uint32_t)r->hi - (uint32_t)r->lo;
}

/* num / span for 0 < num < 255 * span: a byte. */
static uint8_t byte_quotient(uint32_t num, uint32_t span)
{
    if (XGO_CORE_NARROW_CPU) {
        /* The quotient is below 255: eight steps of restoring division give
         * it exactly, with no divide call on cores without a divider
         * (Cortex-M0; with one, the plain division is cheaper). */
        uint32_t den = span << 7;
        uint32_t q = 0;
        int i;
        for (i = 0; i < 8; ++i) {
            q <<= 1;
            if (num >= den) {
                num -= den;
                q |= 1u;
            }
            den >>= 1;
        }
        return (uint8_t)q;
    }
    return (uint8_t)(num / span);
}

uint8_t xgo_range_to_byte(const xgo_range_t *r, int32_t v)
{
    if (r->hi <= r->lo || v <= r->lo) {
        return 0u;
    }
    if (v >= r->hi) {
        return 255u;
    }
    /* 0 < num < 255 * span < 2^31 */
    return byte_quotient(255u * ((uint32_t)v - (uint32_t)r->lo), span_of(r));
}

/* n / 255; on a core without a divider as a multiply by ceil(2^39 / 255)
 * (exact for every uint32 n, checked exhaustively): the board decodes a few
 * registers every tick. */
static uint32_t div255(uint32_t n)
{
    return XGO_CORE_NARROW_CPU ? (uint32_t)(xgo_umul_wide(n, 0x80808081u) >> 39) : n / 255u;
}

int32_t xgo_byte_to_range(const xgo_range_t *r, uint8_t b)
{
    if (r->hi <= r->lo) {
        return r->lo;
    }
    /* ceil(b * span / 255): rounding up (by less than one unit) makes
     * encode(decode(b)) == b for every byte whenever span >= 255 units. */
    return (int32_t)((uint32_t)r->lo + div255((uint32_t)b * span_of(r) + 254u));
}

int32_t xgo_byte_to_range_mid(const xgo_range_t *r, uint8_t b)
{
    if (r->hi <= r->lo || b == 0xFFu) {
        return r->hi <= r->lo ? r->lo : r->hi;
    }
    /* (2b + 1) * span + 255 < 511 * 2^23 + 255 < 2^32 */
    return (int32_t)((uint32_t)r->lo + ((2u * b + 1u) * span_of(r) + 255u) / 510u);
}

int32_t xgo_servo_byte_to_range_mid(const xgo_range_t *r, uint8_t b)
{
    if (r->hi <= r->lo || b == 0u || b == 0xFFu) {
        return (r->hi <= r->lo || b == 0u) ? r->lo : r->hi;
    }
    return (int32_t)((uint32_t)r->lo + ((2u * b - 1u) * span_of(r) + 254u) / 508u);
}

uint8_t xgo_joint_to_byte(const xgo_profile_t *p, xgo_joint_t joint, int32_t mdeg)
{
    return xgo_range_to_byte(&p->joint_mdeg[joint], mdeg);
}

int32_t xgo_byte_to_joint(const xgo_profile_t *p, xgo_joint_t joint, uint8_t b)
{
    return xgo_byte_to_range(&p->joint_mdeg[joint], b);
}

uint8_t xgo_foot_to_byte(const xgo_profile_t *p, xgo_axis_t axis, int32_t um)
{
    return xgo_range_to_byte(&p->foot_um[axis], um);
}

int32_t xgo_byte_to_foot(const xgo_profile_t *p, xgo_axis_t axis, uint8_t b)
{
    return xgo_byte_to_range(&p->foot_um[axis], b);
}

void xgo_joints_to_bytes(const xgo_profile_t *p, const int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT],
                         uint8_t out[XGO_LEG_COUNT * XGO_JOINT_COUNT])
{
    int leg, j;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (j = 0; j < XGO_JOINT_COUNT; ++j) {
            out[leg * XGO_JOINT_COUNT + j] = xgo_range_to_byte(&p->joint_mdeg[j], q_mdeg[leg][j]);
        }
    }
}

void xgo_bytes_to_joints(const xgo_profile_t *p, const uint8_t in[XGO_LEG_COUNT * XGO_JOINT_COUNT],
                         int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT])
{
    int leg, j;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (j = 0; j < XGO_JOINT_COUNT; ++j) {
            q_mdeg[leg][j] = xgo_byte_to_range(&p->joint_mdeg[j], in[leg * XGO_JOINT_COUNT + j]);
        }
    }
}

void xgo_feet_to_bytes(const xgo_profile_t *p, const xgo_vec3_t feet_leg_um[XGO_LEG_COUNT],
                       uint8_t out[XGO_LEG_COUNT * XGO_AXIS_COUNT])
{
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        out[leg * 3 + 0] = xgo_range_to_byte(&p->foot_um[XGO_AXIS_X], feet_leg_um[leg].x);
        out[leg * 3 + 1] = xgo_range_to_byte(&p->foot_um[XGO_AXIS_Y], feet_leg_um[leg].y);
        out[leg * 3 + 2] = xgo_range_to_byte(&p->foot_um[XGO_AXIS_Z], feet_leg_um[leg].z);
    }
}

void xgo_bytes_to_feet(const xgo_profile_t *p, const uint8_t in[XGO_LEG_COUNT * XGO_AXIS_COUNT],
                       xgo_vec3_t feet_leg_um[XGO_LEG_COUNT])
{
    int leg;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        feet_leg_um[leg].x = xgo_byte_to_range(&p->foot_um[XGO_AXIS_X], in[leg * 3 + 0]);
        feet_leg_um[leg].y = xgo_byte_to_range(&p->foot_um[XGO_AXIS_Y], in[leg * 3 + 1]);
        feet_leg_um[leg].z = xgo_byte_to_range(&p->foot_um[XGO_AXIS_Z], in[leg * 3 + 2]);
    }
}

void xgo_body_pose_to_bytes(const xgo_profile_t *p, const xgo_body_pose_t *pose, uint8_t out[6])
{
    out[0] = xgo_range_to_byte(&p->body_um[XGO_AXIS_X], pose->x_um);
    out[1] = xgo_range_to_byte(&p->body_um[XGO_AXIS_Y], pose->y_um);
    out[2] = xgo_range_to_byte(&p->body_um[XGO_AXIS_Z], pose->z_um);
    out[3] = xgo_range_to_byte(&p->body_mdeg[0], pose->roll_mdeg);
    out[4] = xgo_range_to_byte(&p->body_mdeg[1], pose->pitch_mdeg);
    out[5] = xgo_range_to_byte(&p->body_mdeg[2], pose->yaw_mdeg);
}

void xgo_bytes_to_body_pose(const xgo_profile_t *p, const uint8_t in[6], xgo_body_pose_t *pose)
{
    pose->x_um = xgo_byte_to_range(&p->body_um[XGO_AXIS_X], in[0]);
    pose->y_um = xgo_byte_to_range(&p->body_um[XGO_AXIS_Y], in[1]);
    pose->z_um = xgo_byte_to_range(&p->body_um[XGO_AXIS_Z], in[2]);
    pose->roll_mdeg = xgo_byte_to_range(&p->body_mdeg[0], in[3]);
    pose->pitch_mdeg = xgo_byte_to_range(&p->body_mdeg[1], in[4]);
    pose->yaw_mdeg = xgo_byte_to_range(&p->body_mdeg[2], in[5]);
}

int32_t xgo_signed_byte_to_value(uint8_t b, int32_t limit)
{
    xgo_range_t r;
    if (b == 0x7Fu || b == 0x80u) {
        return 0;
    }
    r.lo = -limit;
    r.hi = limit;
    return xgo_byte_to_range(&r, b);
}

/* ------------------------------------------------------------ attitude */

/* n / 180000 for n <= 180000 * 128 + 90000. Cores without a divider (three
 * attitude bytes a tick): the estimate (n >> 7) * 11931 / 2^24 (product <
 * 2^32) is within one of the quotient, one compare puts it right (checked
 * for every n in range). */
static uint32_t div180000(uint32_t n)
{
    uint32_t q;
    if (!XGO_CORE_NARROW_CPU) {
        return n / 180000u;
    }
    q = ((n >> 7) * 11931u) >> 24;
    if (q * 180000u > n) {
        q--;
    } else if ((q + 1u) * 180000u <= n) {
        q++;
    }
    return q;
}

uint8_t xgo_angle_to_byte(int32_t mdeg)
{
    /* 1 LSB = 180/128 deg = 1406.25 mdeg; round half away from zero.
     * +-180 degrees already give 256 and 0 (clamped below), so clamping the
     * angle there first changes nothing and keeps mdeg * 128 within 2^25:
     * 32-bit arithmetic. The quotient truncates toward zero, as C's. */
    int32_t m = mdeg > 180000 ? 180000 : (mdeg < -180000 ? -180000 : mdeg);
    /* one division on |m| (one copy of div180000, inline), the sign after */
    const uint32_t u = (uint32_t)(m < 0 ? -m : m);
    const int32_t d = (int32_t)div180000(u * 128u + 90000u);
    int32_t q = m < 0 ? -d : d;
    q += 128;
    if (q < 0) {
        q = 0;
    } else if (q > 255) {
        q = 255;
    }
    return (uint8_t)q;
}

uint32_t xgo_mdeg_to_float32_bits(int32_t mdeg)
{
    /* value = m / 1000 with m = |mdeg|. Find e with 2^23 <= m*2^s/1000 < 2^24,
     * then round the 24-bit significand to nearest, ties to even. */
    uint32_t sign = mdeg < 0 ? 0x80000000u : 0u;
    uint64_t m = mdeg < 0 ? (uint64_t)(-(int64_t)mdeg) : (uint64_t)mdeg;
    int shift = 0; /* significand = m * 2^shift / 1000 */
    uint64_t num, q, rem;
    int32_t exponent;

    if (m == 0) {
        return sign;
    }
    /* Normalise num = m << shift into [2^23 * 1000, 2^24 * 1000). As
     * 1 <= m <= 2^31 < 2^24 * 1000, shift is 0..33 and num < 2^44. */
    num = m;
    while (num < (uint64_t)1000u << 23) {
        num <<= 1;
        shift++;
    }
    /* num / 1000 in two 32-bit steps (no 64-bit division helper: about
     * 750 bytes of flash on a Cortex-M): num < 2^44, so its top part
     * num >> 22 < 2^22 and the remainder's next part (r << 22 | low 22
     * bits) < 1000 * 2^22 < 2^32. */
    {
        const uint32_t top = (uint32_t)(num >> 22);
        const uint32_t low = ((top % 1000u) << 22) | ((uint32_t)num & 0x3FFFFFu);
        q = ((uint64_t)(top / 1000u) << 22) | (low / 1000u);
        rem = low % 1000u;
    }
    if (rem > 500u || (rem == 500u && (q & 1u) != 0)) {
        q++;
        if (q == (uint64_t)1u << 24) {
            q >>= 1;
            shift--;
        }
    }
    exponent = 127 + 23 - shift;
    return sign | ((uint32_t)exponent << 23) | ((uint32_t)q & 0x7FFFFFu);
}

int16_t xgo_mdeg_to_centideg(int32_t mdeg)
{
    const int32_t limit = 327674; /* beyond it the rounded value leaves int16 */
    const int32_t m = mdeg > limit ? limit : (mdeg < -limit ? -limit : mdeg);
    return (int16_t)((m >= 0 ? m + 5 : m - 5) / 10);
}

/* ------------------------------------------------------------ motion commands */

int32_t xgo_period_byte_to_ms(uint8_t b)
{
    static const xgo_range_t period_ms = {XGO_PERIOD_MIN_MS, XGO_PERIOD_MAX_MS};
    return xgo_byte_to_range(&period_ms, b);
}

int32_t xgo_mark_time_byte_to_um(const xgo_profile_t *p, uint8_t b)
{
    const xgo_range_t *r = &p->mark_time_um;
    if (b == 0) {
        return 0;
    }
    /* b * span / 255 rounded to nearest (span < 2^23: 32 bits suffice) */
    return (int32_t)((uint32_t)r->lo + ((uint32_t)b * span_of(r) + 127u) / 255u);
}

int32_t xgo_servo_speed_byte_to_mdeg_s(uint8_t b)
{
    static const xgo_range_t speed = {XGO_SERVO_SPEED_MIN_MDEG_S, XGO_SERVO_SPEED_MAX_MDEG_S};
    return xgo_byte_to_range(&speed, b);
}

/* ------------------------------------------------------------ unload */

int xgo_unload_decode(uint8_t value, xgo_unload_t *out)
{
    if (value == 0x00u || value == 0x01u) {
        out->load = value == 0x00u;
        out->leg = XGO_UNLOAD_ALL_LEGS;
        return 1;
    }
    if ((value >= 0x11u && value <= 0x14u) || (value >= 0x21u && value <= 0x24u)) {
        out->load = value >= 0x21u;
        out->leg = (uint8_t)((value & 0x0Fu) - 1u);
        return 1;
    }
    return 0;
}
