/*
 * Accelerometer and gyroscope model (see inertial.h).
 */
#include "inertial.h"

#include <string.h>

#include "xgo/config.h"
#include "wide.h"

#if XGO_WITH_INERTIAL /* else accelerometer and gyroscope read 0 (inertial.h) */

/* Second difference of a position in 1/256 um per tick^2 -> acceleration in
 * LSB * 256: * XGO_TICK_HZ^2 / 256 (um/s^2) * 16384 * 256 / g, as a Q16
 * multiplier (2.74e7 at 500 Hz). */
#define ACCEL_Q16                                                                                 \
    ((int32_t)(((uint64_t)XGO_TICK_HZ * XGO_TICK_HZ * XGO_ACCEL_LSB_PER_G * 65536u +              \
                XGO_GRAVITY_UM_S2 / 2u) /                                                         \
               XGO_GRAVITY_UM_S2))
/* Angle change in mdeg per tick -> LSB * 256: * XGO_TICK_HZ (mdeg/s) * 16.4 /
 * 1000 * 256, as a Q16 multiplier. */
#define GYRO_Q16                                                                                  \
    ((int32_t)(((uint64_t)XGO_TICK_HZ * XGO_GYRO_LSB_PER_10_DEG_S * 256u * 65536u + 5000u) /     \
               10000u))
/* 1 g in LSB * 256: 2^22 */
#define ONE_G_Q8 (XGO_ACCEL_LSB_PER_G * 256)
/* xgo_inertial_tick_sc turns products by exactly 1 g into shifts */
typedef char xgo_one_g_is_2_to_the_22[ONE_G_Q8 == (1 << 22) ? 1 : -1];
/* Second differences beyond this (about 100 g at 500 Hz) saturate anyway. */
#define D2_LIMIT_Q8 (1 << 20)

static int32_t clamp32(int64_t v, int32_t lim)
{
    return v > lim ? lim : (v < -lim ? -lim : (int32_t)v);
}

/* clamp32 of a second difference. On a narrow core, where each 64-bit
 * compare is a few instructions, the value's fitting 32 bits (nearly
 * always: 8 m per tick^2) is one compare, and then it is clamped in 32
 * bits: the same value. */
static int32_t clamp_d2(int64_t v)
{
#if XGO_CORE_NARROW_CPU
    const int32_t lo = (int32_t)(uint32_t)(uint64_t)v;
    if ((int64_t)lo == v) {
        return lo > D2_LIMIT_Q8 ? D2_LIMIT_Q8 : (lo < -D2_LIMIT_Q8 ? -D2_LIMIT_Q8 : lo);
    }
#endif
    return clamp32(v, D2_LIMIT_Q8);
}

static int16_t to_lsb(int32_t q8)
{
    const int32_t v = (q8 >= 0 ? q8 + 128 : q8 - 127) >> 8;
    return (int16_t)(v > 32767 ? 32767 : (v < -32768 ? -32768 : v));
}

/* a * q30 value, result in the unit of a: (a c + 2^29) >> 30.
 * On a core without a widening multiply (XGO_CORE_NARROW_CPU) a small a
 * (|a| < 2^20: every rate, a walk's horizontal accelerations) takes three
 * 32-bit products with c's 10-bit pieces (xgo_mul_round_pieces10, wide.h;
 * |c >> 20| <= 2^10 for a Q30 factor): exact, so the same result as the
 * 64-bit product (tools/mcu/run.sh compares). The range tests here
 * are (a >> k) == (a >> 31), i.e. -2^k <= a < 2^k: two shifts, no
 * constants to load on the M0. */
XGO_ALWAYS_INLINE int32_t mul_q30(int32_t a, xgo_q30_t c) /* inline: 18 calls a tick */
{
#if XGO_CORE_NARROW_CPU
    if ((a >> 20) == (a >> 31)) {
        return xgo_mul_round_pieces10(a, c, 30u); /* |c >> 20| <= 2^10 */
    }
#endif
    return (int32_t)((xgo_mul_wide(a, c) + (1 << 29)) >> 30);
}

/* mul_q30 for the body rates' factors, angle changes per tick (tens of
 * mdeg while walking, turning, pitching). On a narrow core, for |a| < 2^14,
 * from c's 16-bit pieces, c = ch 2^16 + cl (|ch| <= 2^14, 0 <= cl < 2^16),
 * |a cl| + 2^29 < 2^31 and
 *   floor((a c + 2^29) / 2^30) = floor((a ch + floor((a cl + 2^29) / 2^16)) / 2^14):
 * exact, two MULS instead of three; larger a take mul_q30. */
XGO_ALWAYS_INLINE int32_t mul_q30_rate(int32_t a, xgo_q30_t c) /* inline: 6 calls a tick */
{
#if XGO_CORE_NARROW_CPU
    if ((a >> 14) == (a >> 31)) {
        return (a * (c >> 16) + ((a * (c & 0xFFFF) + (1 << 29)) >> 16)) >> 14;
    }
#endif
    return mul_q30(a, c);
}

/* mul_q30 for a factor that may be large: the vertical specific force
 * (1 g is 2^22 in LSB * 256) and what it turns into, up to four products a
 * tick (two at a constant height on a narrow core, xgo_inertial_tick_sc) beyond mul_q30's 32-bit form. On a narrow core, for |a| < 2^23, from c's
 * 8-bit pieces, c = c3 2^24 + c2 2^16 + c1 2^8 + c0 (c3 = c >> 24, |c3| <=
 * 2^6; c2, c1, c0 in 0..255), each product and nested sum within int32
 * (|a ck| <= 255 (2^23 - 1) < 2^31 - 2^23, each carried floor below 2^23):
 *   floor(a c / 2^24) = a c3 + floor((a c2 + floor((a c1 + floor(a c0 / 2^8)) / 2^8)) / 2^8)
 * and floor((a c + 2^29) / 2^30) = floor((floor(a c / 2^24) + 2^5) / 2^6):
 * exact, four MULS instead of a 64-bit product. Out of line (up to four calls);
 * not static, so test_inertial checks it against the 64-bit product. */
int32_t xgo_inertial_mul_q30(int32_t a, xgo_q30_t c)
{
#if XGO_CORE_NARROW_CPU
    if ((a >> 23) == (a >> 31)) {
        int32_t t = (a * (c & 255)) >> 8;
        t = (a * ((c >> 8) & 255) + t) >> 8;
        t = (a * ((c >> 16) & 255) + t) >> 8;
        return (a * (c >> 24) + t + 32) >> 6;
    }
#endif
    return mul_q30(a, c);
}

/* (v k + 2^15) >> 16 for a constant 0 < k < 2^31 and |v| <= 2^20 with
 * |v (k >> 16)| < 2^31 (callers: ACCEL_Q16, GYRO_Q16 with their clamps).
 * Narrow cores: k = kh 2^16 + km 2^8 + kl (km, kl < 2^8), so
 *   floor((v k + 2^15) / 2^16) = v kh + floor((v km + floor((v kl + 2^15) / 2^8)) / 2^8),
 * every product and sum within int32: exact. */
static int32_t scale_q16(int32_t v, int32_t k)
{
#if XGO_CORE_NARROW_CPU
    const int32_t low = (v * (k & 0xFF) + 32768) >> 8;
    return v * (k >> 16) + ((v * ((k >> 8) & 0xFF) + low) >> 8);
#else
    return (int32_t)((xgo_mul_wide(v, k) + 32768) >> 16);
#endif
}
/* 2^20 (D2_LIMIT_Q8) * 417 and 2^18 (the rate clamp) * 2099 < 2^31 */
typedef char xgo_inertial_scale_fits_[(ACCEL_Q16 >> 16) <= 2047 && (GYRO_Q16 >> 16) <= 8191 ? 1 : -1];

/* Inline where registers are plenty (x86-64, a Cortex-M3: two calls a
 * tick less); out of line on a narrow core, where inlining it cost more
 * (a Cortex-M0's eight low registers). */
#if XGO_CORE_NARROW_CPU
static void filter(int32_t state[3], const int32_t input[3], int16_t out[3])
#else
XGO_ALWAYS_INLINE void filter(int32_t state[3], const int32_t input[3], int16_t out[3])
#endif
{
    /* the three axes written out: no loop counter or indexing (six values a tick) */
    state[0] += (input[0] - state[0]) >> XGO_INERTIAL_FILTER_SHIFT;
    out[0] = to_lsb(state[0]);
    state[1] += (input[1] - state[1]) >> XGO_INERTIAL_FILTER_SHIFT;
    out[1] = to_lsb(state[1]);
    state[2] += (input[2] - state[2]) >> XGO_INERTIAL_FILTER_SHIFT;
    out[2] = to_lsb(state[2]);
}

void xgo_inertial_init(xgo_inertial_t *s)
{
    memset(s, 0, sizeof *s);
    s->accel_q8[2] = ONE_G_Q8;
    s->accel[2] = XGO_ACCEL_LSB_PER_G;
    xgo_sincos(xgo_mdeg_to_bam(0), &s->trig_q30[0][0], &s->trig_q30[0][1]);
    xgo_sincos(xgo_mdeg_to_bam(0), &s->trig_q30[1][0], &s->trig_q30[1][1]);
}

/* Inline on a 64-bit host, where a call costs its saved registers and
 * argument moves (xgo_inertial_tick_body: one frame for the whole model,
 * the body's position in registers); out of line on an MCU. */
#if XGO_CORE_DIV64_NATIVE
#define HOST_INLINE XGO_ALWAYS_INLINE
#else
#define HOST_INLINE static
#endif

/* sin and cos of the roll and pitch, shared by the accelerometer and the
 * gyroscope (two sincos instead of four). */
typedef struct attitude_trig_s {
    xgo_q30_t sr, cr, sp, cp;
} attitude_trig_t;

/* Each worked out again only when its angle changed: a body held at a
 * roll or a pitch (standing, walking without a periodic motion on that
 * axis) spares its sincos. */
HOST_INLINE void attitude_trig(xgo_inertial_t *s, const int32_t att_mdeg[3], attitude_trig_t *t)
{
    unsigned axis;
    for (axis = 0; axis < 2; axis++) {
        if (s->trig_mdeg[axis] != att_mdeg[axis]) {
            s->trig_mdeg[axis] = att_mdeg[axis];
            xgo_sincos(xgo_mdeg_to_bam(att_mdeg[axis]), &s->trig_q30[axis][0], &s->trig_q30[axis][1]);
        }
    }
    t->sr = s->trig_q30[0][0];
    t->cr = s->trig_q30[0][1];
    t->sp = s->trig_q30[1][0];
    t->cp = s->trig_q30[1][1];
}

/* Specific force in the body frame, LSB * 256: the world acceleration
 * (a_q8, LSB * 256, world axes) plus 1 g up, turned by R^T. */
HOST_INLINE void specific_force(const int32_t a_q8[3], const xgo_q30_t heading_sc[2],
                                const attitude_trig_t *t, int32_t f[3])
{
    const xgo_q30_t sh = heading_sc[0], ch = heading_sc[1];
    int32_t hx, hy, hz, x1, z1, gx, gz;
    /* Rz(-heading): world -> the body's heading frame */
    hx = mul_q30(a_q8[0], ch) + mul_q30(a_q8[1], sh);
    hy = mul_q30(a_q8[1], ch) - mul_q30(a_q8[0], sh);
    hz = a_q8[2] + ONE_G_Q8;
    /* Ry(-pitch), then Rx(-roll); hz and z1 hold the 1 g. At a constant
     * height (walking, standing) hz is exactly 1 g = 2^22, whose products
     * are shifts: (2^22 c + 2^29) >> 30 = (c + 2^7) >> 8; on a narrow core
     * two calls of four MULS less (elsewhere a product is one instruction). */
    if (XGO_CORE_NARROW_CPU && hz == ONE_G_Q8) {
        gx = (t->sp + 128) >> 8;
        gz = (t->cp + 128) >> 8;
    } else {
        gx = xgo_inertial_mul_q30(hz, t->sp);
        gz = xgo_inertial_mul_q30(hz, t->cp);
    }
    x1 = mul_q30(hx, t->cp) - gx;
    z1 = mul_q30(hx, t->sp) + gz;
    f[0] = x1;
    f[1] = mul_q30(hy, t->cr) + xgo_inertial_mul_q30(z1, t->sr);
    f[2] = xgo_inertial_mul_q30(z1, t->cr) - mul_q30(hy, t->sr);
}

/* Body rates from the Euler rates (mdeg per tick), LSB * 256. */
HOST_INLINE void body_rates(const int32_t d_mdeg[3], const attitude_trig_t *t, int32_t w[3])
{
    const int32_t yaw_cp = mul_q30_rate(d_mdeg[2], t->cp);
    w[0] = d_mdeg[0] - mul_q30_rate(d_mdeg[2], t->sp);
    w[1] = mul_q30_rate(d_mdeg[1], t->cr) + mul_q30_rate(yaw_cp, t->sr);
    w[2] = mul_q30_rate(yaw_cp, t->cr) - mul_q30_rate(d_mdeg[1], t->sr);
}

void xgo_inertial_tick(xgo_inertial_t *s, const int64_t body_q8[3], xgo_bam_t heading,
                       const int32_t att_mdeg[3])
{
    xgo_q30_t sc[2];
    xgo_sincos(heading, &sc[0], &sc[1]);
    xgo_inertial_tick_sc(s, body_q8, sc, att_mdeg);
}

HOST_INLINE void tick_sc(xgo_inertial_t *s, const int64_t body_q8[3], const xgo_q30_t heading_sc[2],
                         const int32_t att_mdeg[3])
{
    int32_t a_q8[3], f[3], d[3], w[3];
    attitude_trig_t trig;
    unsigned i;
    if (s->history == 0) {
        memcpy(s->pos_q8[0], body_q8, sizeof s->pos_q8[0]);
        memcpy(s->att_mdeg, att_mdeg, sizeof s->att_mdeg);
    }
    if (s->history < 2) {
        memcpy(s->pos_q8[1], s->pos_q8[0], sizeof s->pos_q8[1]);
        s->history++;
    }
    /* the history moves on as it is used (no copies after) */
    for (i = 0; i < 3; i++) {
        const int64_t d2 = body_q8[i] - 2 * s->pos_q8[0][i] + s->pos_q8[1][i];
        a_q8[i] = scale_q16(clamp_d2(d2), ACCEL_Q16);
        d[i] = att_mdeg[i] - s->att_mdeg[i];
        if (d[i] < -180000 || d[i] >= 180000) { /* else already an angle: no call */
            d[i] = xgo_wrap_mdeg(d[i]);
        }
        s->pos_q8[1][i] = s->pos_q8[0][i];
        s->pos_q8[0][i] = body_q8[i];
        s->att_mdeg[i] = att_mdeg[i];
    }
    attitude_trig(s, att_mdeg, &trig);
    specific_force(a_q8, heading_sc, &trig, f);
    body_rates(d, &trig, w);
    for (i = 0; i < 3; i++) {
        /* +-2^18 mdeg per tick is far beyond the sensor's range */
        w[i] = scale_q16(clamp32(w[i], 1 << 18), GYRO_Q16);
    }
    filter(s->accel_q8, f, s->accel);
    filter(s->gyro_q8, w, s->gyro);
}

void xgo_inertial_tick_sc(xgo_inertial_t *s, const int64_t body_q8[3], const xgo_q30_t heading_sc[2],
                          const int32_t att_mdeg[3])
{
    tick_sc(s, body_q8, heading_sc, att_mdeg);
}

/* floor((a x - b y + 2^21) / 2^22) for Q30 a, b: one coordinate of a
 * rotated point, * 256 / 2^30 rounded. On a Cortex-M0, for |x|, |y| < 2^19
 * (a body shift: always), from the 10-bit pieces of a and b, a = a2 2^20 +
 * a1 2^10 + a0 (a2 = a >> 20, a1, a0 in 0..1023): with S = a x - b y,
 * floor(S / 2^20) = (a2 x - b2 y) + floor(((a1 x - b1 y) + floor((a0 x -
 * b0 y) / 2^10)) / 2^10), every term within int32, and floor((S + 2^21) /
 * 2^22) = floor((floor(S / 2^20) + 2) / 4): exact, six MULS instead of two
 * wide products. Elsewhere the wide products. */
static int64_t turn_q22(xgo_q30_t a, int32_t x, xgo_q30_t b, int32_t y)
{
#if XGO_CORE_NARROW_CPU
    if ((x >> 19) == (x >> 31) && (y >> 19) == (y >> 31)) {
        int32_t u = (x * (a & 1023) - y * (b & 1023)) >> 10;
        u = (x * ((a >> 10) & 1023) - y * ((b >> 10) & 1023) + u) >> 10;
        return (x * (a >> 20) - y * (b >> 20) + u + 2) >> 2;
    }
#endif
    return (xgo_mul_wide(a, x) - xgo_mul_wide(b, y) + (1 << 21)) >> 22;
}

XGO_ALWAYS_INLINE void body_position(const xgo_odometry_t *o, const xgo_body_pose_t *pose,
                                     int64_t body_q8[3], xgo_q30_t heading_sc[2])
{
    const xgo_q30_t sh = o->yaw_sc[0], ch = o->yaw_sc[1];
    /* (c x - s y) * 256 / 2^30, (s x + c y) * 256 / 2^30 */
    body_q8[0] = o->x_q8 + turn_q22(ch, pose->x_um, sh, pose->y_um);
    body_q8[1] = o->y_q8 + turn_q22(sh, pose->x_um, -ch, pose->y_um);
    body_q8[2] = (int64_t)pose->z_um * 256;
    if (pose->yaw_mdeg == 0) { /* the usual case: the body faces the machine's heading */
        heading_sc[0] = sh;
        heading_sc[1] = ch;
    } else {
        xgo_sincos(o->yaw + xgo_mdeg_to_bam(pose->yaw_mdeg), &heading_sc[0], &heading_sc[1]);
    }
}

void xgo_inertial_body_position(const xgo_odometry_t *o, const xgo_body_pose_t *pose,
                                int64_t body_q8[3], xgo_q30_t heading_sc[2])
{
    body_position(o, pose, body_q8, heading_sc);
}

void xgo_inertial_tick_body(xgo_inertial_t *s, const xgo_odometry_t *o, const xgo_body_pose_t *pose,
                            const int32_t att_mdeg[3])
{
    int64_t body_q8[3];
    xgo_q30_t heading_sc[2];
    body_position(o, pose, body_q8, heading_sc);
    tick_sc(s, body_q8, heading_sc, att_mdeg);
}
#endif /* XGO_WITH_INERTIAL */
