/*
 * reg_units.c - register bytes <-> physical values (see xgo/reg_units.h).
 *
 * Each register is mapped to the codec call the motion core reads it with
 * (motion.c, board.c); encoding searches the byte whose decoding is nearest,
 * so a write means exactly what the board will make of it, whatever the
 * vendor library's own rounding would have sent.
 */
#include "xgo/reg_units.h"

#include "codec.h"
#include "xgo/regs.h"

typedef enum scale_kind_e {
    SCALE_NONE = 0,
    SCALE_IDENTITY,    /* byte = value (battery %) */
    SCALE_SIGNED,      /* xgo_signed_byte_to_value(b, limit): dead band at 0x7F/0x80 */
    SCALE_RANGE,       /* xgo_byte_to_range(range, b) */
    SCALE_PERIOD,      /* 0 off, else xgo_period_byte_to_ms */
    SCALE_MARK_TIME,   /* xgo_mark_time_byte_to_um (0 off) */
    SCALE_SERVO_SPEED, /* xgo_servo_speed_byte_to_mdeg_s */
    SCALE_ATTITUDE     /* inverse of xgo_angle_to_byte */
} scale_kind_t;

typedef struct scale_s {
    scale_kind_t kind;
    xgo_unit_t unit;
    int32_t limit;           /* SCALE_SIGNED */
    const xgo_range_t *range; /* SCALE_RANGE */
} scale_t;

static void set_scale(scale_t *s, scale_kind_t kind, xgo_unit_t unit)
{
    s->kind = kind;
    s->unit = unit;
}

static void set_signed(scale_t *s, xgo_unit_t unit, int32_t limit)
{
    set_scale(s, SCALE_SIGNED, unit);
    s->limit = limit;
}

static void set_range(scale_t *s, xgo_unit_t unit, const xgo_range_t *range)
{
    set_scale(s, SCALE_RANGE, unit);
    s->range = range;
}

/* Feet 0x40..0x4B and servos 0x50..0x5B, as motion.c reads them. */
static int leg_scale(const xgo_profile_t *p, uint8_t addr, scale_t *s)
{
    if (addr >= XGO_REG_LEG1_X && addr <= XGO_REG_LEG4_Z) {
        unsigned axis = (unsigned)(addr - XGO_REG_LEG1_X) % XGO_AXIS_COUNT;
        if (axis == XGO_AXIS_Z) {
            set_range(s, XGO_UNIT_UM, &p->foot_um[XGO_AXIS_Z]);
        } else {
            set_signed(s, XGO_UNIT_UM, p->foot_um[axis].hi);
        }
        return 1;
    }
    if (addr >= XGO_REG_SERVO11 && addr <= XGO_REG_SERVO43) {
        set_range(s, XGO_UNIT_MDEG, &p->joint_mdeg[(addr - XGO_REG_SERVO11) % XGO_JOINT_COUNT]);
        return 1;
    }
    return 0;
}

/* Velocity and body registers 0x30..0x38. */
static int body_scale(const xgo_profile_t *p, uint8_t addr, scale_t *s)
{
    switch (addr) {
    case XGO_REG_VX: set_signed(s, XGO_UNIT_UM_S, XGO_VX_MAX_UM_S); return 1;
    case XGO_REG_VY: set_signed(s, XGO_UNIT_UM_S, XGO_VY_MAX_UM_S); return 1;
    case XGO_REG_VYAW: set_signed(s, XGO_UNIT_MDEG_S, XGO_VYAW_MAX_MDEG_S); return 1;
    case XGO_REG_BODY_X: set_signed(s, XGO_UNIT_UM, p->body_um[XGO_AXIS_X].hi); return 1;
    case XGO_REG_BODY_Y: set_signed(s, XGO_UNIT_UM, p->body_um[XGO_AXIS_Y].hi); return 1;
    case XGO_REG_BODY_Z: set_range(s, XGO_UNIT_UM, &p->body_um[XGO_AXIS_Z]); return 1;
    case XGO_REG_BODY_ROLL: set_signed(s, XGO_UNIT_MDEG, p->body_mdeg[0].hi); return 1;
    case XGO_REG_BODY_PITCH: set_signed(s, XGO_UNIT_MDEG, p->body_mdeg[1].hi); return 1;
    case XGO_REG_BODY_YAW: set_signed(s, XGO_UNIT_MDEG, p->body_mdeg[2].hi); return 1;
    default: return 0;
    }
}

static int other_scale(uint8_t addr, scale_t *s)
{
    switch (addr) {
    case XGO_REG_BATTERY: set_scale(s, SCALE_IDENTITY, XGO_UNIT_PERCENT); return 1;
    case XGO_REG_PERIOD_ROLL:
    case XGO_REG_PERIOD_PITCH:
    case XGO_REG_PERIOD_YAW:
    case XGO_REG_PERIOD_X:
    case XGO_REG_PERIOD_Y:
    case XGO_REG_PERIOD_Z: set_scale(s, SCALE_PERIOD, XGO_UNIT_MS); return 1;
    case XGO_REG_MARK_TIME: set_scale(s, SCALE_MARK_TIME, XGO_UNIT_UM); return 1;
    case XGO_REG_SERVO_SPEED: set_scale(s, SCALE_SERVO_SPEED, XGO_UNIT_MDEG_S); return 1;
    case XGO_REG_IMU_ROLL:
    case XGO_REG_IMU_PITCH:
    case XGO_REG_IMU_YAW: set_scale(s, SCALE_ATTITUDE, XGO_UNIT_MDEG); return 1;
    default: return 0;
    }
}

static int scale_of(const xgo_profile_t *p, uint8_t addr, scale_t *s)
{
    s->kind = SCALE_NONE;
    s->unit = XGO_UNIT_NONE;
    s->limit = 0;
    s->range = NULL;
    return leg_scale(p, addr, s) || body_scale(p, addr, s) || other_scale(addr, s);
}

/* The one-byte attitude view: xgo_angle_to_byte's inverse, 1 LSB = 180/128
 * deg = 5625/4 mdeg exactly, rounded half away from zero. */
static int32_t attitude_byte_to_mdeg(uint8_t b)
{
    int32_t q = ((int32_t)b - 128) * 5625;
    return (q >= 0 ? q + 2 : q - 2) / 4;
}

static int32_t decode(const xgo_profile_t *p, const scale_t *s, uint8_t b)
{
    switch (s->kind) {
    case SCALE_IDENTITY: return b;
    case SCALE_SIGNED: return xgo_signed_byte_to_value(b, s->limit);
    case SCALE_RANGE: return xgo_byte_to_range(s->range, b);
    case SCALE_PERIOD: return b == 0 ? 0 : xgo_period_byte_to_ms(b);
    case SCALE_MARK_TIME: return xgo_mark_time_byte_to_um(p, b);
    case SCALE_SERVO_SPEED: return xgo_servo_speed_byte_to_mdeg_s(b);
    case SCALE_ATTITUDE: return attitude_byte_to_mdeg(b);
    default: return 0;
    }
}

/* Byte 0 of a period or mark-time register means "off", not a step. */
static int has_off_byte(const scale_t *s)
{
    return s->kind == SCALE_PERIOD || s->kind == SCALE_MARK_TIME;
}

xgo_unit_t xgo_reg_unit(uint8_t addr)
{
    scale_t s;
    return scale_of(xgo_profile_mini(), addr, &s) ? s.unit : XGO_UNIT_NONE;
}

int xgo_reg_byte_to_value(const xgo_profile_t *p, uint8_t addr, uint8_t b, int32_t *value)
{
    scale_t s;
    if (p == NULL) {
        p = xgo_profile_mini();
    }
    if (!scale_of(p, addr, &s)) {
        return 0;
    }
    *value = decode(p, &s, b);
    return 1;
}

int xgo_reg_value_range(const xgo_profile_t *p, uint8_t addr, int32_t *lo, int32_t *hi)
{
    scale_t s;
    int32_t a, z;
    if (p == NULL) {
        p = xgo_profile_mini();
    }
    if (!scale_of(p, addr, &s)) {
        return 0;
    }
    /* Every decoding is monotonic in the byte: the ends are the extremes.
     * Where byte 0 means "off", the range still starts where the linear map
     * would put byte 0 (1.5 s, the profile's lowest step): byte 1 is the
     * nearest step to such a value. */
    if (s.kind == SCALE_PERIOD) {
        a = xgo_period_byte_to_ms(0);
    } else if (s.kind == SCALE_MARK_TIME) {
        a = p->mark_time_um.lo;
    } else {
        a = decode(p, &s, 0u);
    }
    z = decode(p, &s, 255u);
    *lo = a < z ? a : z;
    *hi = a < z ? z : a;
    return 1;
}

int xgo_reg_value_to_byte(const xgo_profile_t *p, uint8_t addr, int32_t value, uint8_t *b)
{
    scale_t s;
    int32_t lo, hi;
    unsigned i, best = 0;
    uint32_t best_err = 0xFFFFFFFFu;
    if (p == NULL) {
        p = xgo_profile_mini();
    }
    if (!scale_of(p, addr, &s)) {
        return XGO_REG_VALUE_NO_UNIT;
    }
    if (has_off_byte(&s) && value == 0) {
        *b = 0;
        return XGO_REG_VALUE_OK;
    }
    if (!xgo_reg_value_range(p, addr, &lo, &hi) || value < lo || value > hi) {
        return XGO_REG_VALUE_OUT_OF_RANGE;
    }
    for (i = has_off_byte(&s) ? 1u : 0u; i < 256u; i++) {
        int64_t d = (int64_t)decode(p, &s, (uint8_t)i) - value;
        uint32_t err = (uint32_t)(d < 0 ? -d : d);
        if (err <= best_err) { /* "<=": ties go to the higher byte */
            best_err = err;
            best = i;
        }
    }
    *b = (uint8_t)best;
    return XGO_REG_VALUE_OK;
}
