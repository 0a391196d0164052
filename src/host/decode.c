/* decode.c - register values in words (see decode.h). Meanings follow the
 * protocol document plus docs/protocol.md errata. */
#include "decode.h"

#include <stdio.h>

#include "xgo/regs.h"

/* Centred registers: 0x00 full reverse .. 0xFF full forward. 0x7F and 0x80
 * both mean zero (the vendor library sends 0x7F for zero). */
static int xgo_host_decode_centred(uint8_t value, char *out, size_t out_size)
{
    int pct;
    if (value == 0x7Fu || value == 0x80u) {
        return snprintf(out, out_size, "0%%");
    }
    pct = value > 0x80u ? ((int)value - 128) * 100 / 127 : ((int)value - 127) * 100 / 127;
    return snprintf(out, out_size, "%+d%%", pct);
}

static int xgo_host_decode_choice(uint8_t value, const char *const *names, size_t count,
                                  char *out, size_t out_size)
{
    if (value < count) {
        return snprintf(out, out_size, "%s", names[value]);
    }
    return snprintf(out, out_size, "invalid");
}

/* The value set and its meaning are the core's (xgo_unload_decode). */
static int xgo_host_decode_unload(uint8_t value, char *out, size_t out_size)
{
    xgo_unload_t u;
    if (!xgo_unload_decode(value, &u)) {
        return snprintf(out, out_size, "invalid");
    }
    if (u.leg == XGO_UNLOAD_ALL_LEGS) {
        return snprintf(out, out_size, u.load ? "all servos loaded" : "unload all servos");
    }
    return snprintf(out, out_size, u.load ? "load leg %d" : "unload leg %d", u.leg + 1);
}

/* Names and the valid ids are the core's (xgo_action_name); 0 stops. */
static int xgo_host_decode_action(uint8_t value, char *out, size_t out_size)
{
    const char *name = xgo_action_name(value);
    if (value == XGO_ACTION_NONE) {
        return snprintf(out, out_size, "default stance");
    }
    if (name != NULL) {
        return snprintf(out, out_size, "%s", name);
    }
    return snprintf(out, out_size, "action %u", (unsigned)value);
}

int xgo_host_decode_value(uint8_t addr, uint8_t value, char *out, size_t out_size)
{
    static const char *const perform[] = {"normal control", "cyclic action"};
    static const char *const calibration[] = {"exit calibration", "enter calibration"};
    static const char *const gaits[] = {"trot", "walk", "high_walk", "slow_trot"};
    static const char *const paces[] = {"normal", "slow", "high"};
    static const char *const imu[] = {"off", "self-stabilizing"};
    static const char *const once[] = {"idle", "do it"};
    /* register 0x00, xgo_mode_t order (the view's /meta uses the same words) */
    static const char *const modes[] = {"whole unit", "leg", "servo", "debug", "action",
                                        "calibration"};
    /* 0x02: XGO_VERSION_* (0x02 is the seed's PRO) */
    static const char *const models[] = {"mini", "lite", "pro", "mini2"};

    out[0] = '\0';
    if ((addr >= XGO_REG_VX && addr <= XGO_REG_BODY_YAW) ||
        (addr >= XGO_REG_LEG1_X && addr <= XGO_REG_LEG4_Z) ||
        (addr >= XGO_REG_SERVO11 && addr <= XGO_REG_SERVO43)) {
        return xgo_host_decode_centred(value, out, out_size) > 0;
    }
    switch (addr) {
    case XGO_REG_MODE:
        return xgo_host_decode_choice(value, modes, 6, out, out_size) > 0;
    case XGO_REG_VERSION:
        return xgo_host_decode_choice(value, models, 4, out, out_size) > 0;
    case XGO_REG_PERFORM:
        return xgo_host_decode_choice(value, perform, 2, out, out_size) > 0;
    case XGO_REG_CALIBRATION:
        return xgo_host_decode_choice(value, calibration, 2, out, out_size) > 0;
    case XGO_REG_GAIT_TYPE:
        return xgo_host_decode_choice(value, gaits, 4, out, out_size) > 0;
    case XGO_REG_UNLOAD:
        return xgo_host_decode_unload(value, out, out_size) > 0;
    case XGO_REG_SET_ZERO:
    case XGO_REG_STAND:
        return xgo_host_decode_choice(value, once, 2, out, out_size) > 0;
    case XGO_REG_PERIOD_ROLL:
    case XGO_REG_PERIOD_PITCH:
    case XGO_REG_PERIOD_YAW:
    case XGO_REG_MARK_TIME:
    case XGO_REG_PERIOD_X:
    case XGO_REG_PERIOD_Y:
    case XGO_REG_PERIOD_Z:
        /* 0 stops; 1..255 scale linearly, and the scale is per model. */
        return value == 0u ? snprintf(out, out_size, "off") > 0 : 0;
    case XGO_REG_MOVE_MODE:
        return xgo_host_decode_choice(value, paces, 3, out, out_size) > 0;
    case XGO_REG_ACTION:
        return xgo_host_decode_action(value, out, out_size) > 0;
    case XGO_REG_IMU_MODE:
        return xgo_host_decode_choice(value, imu, 2, out, out_size) > 0;
    default:
        return 0;
    }
}
