/*
 * xgo/reg_units.h - what one register byte means in physical units, by the
 * scaling the board itself decodes with (the core's codec: range map, dead
 * band, profile ranges), so host tools (xgo-cli read/write) never re-type a
 * scale:
 *
 *   0x01 battery            %        byte = percent
 *   0x30, 0x31 vx, vy       um/s     signed, +-XGO_VX/VY_MAX_UM_S
 *   0x32 vyaw               mdeg/s   signed, +-XGO_VYAW_MAX_MDEG_S
 *   0x33, 0x34 body x, y    um       signed, +- profile body range
 *   0x35 body z             um       profile body z range
 *   0x36..0x38 body angles  mdeg     signed, +- profile body range
 *   0x39..0x3B, 0x80..0x82  ms       period; byte 0 = off (value 0)
 *   0x3C mark time          um       step height; byte 0 = off (value 0)
 *   0x40.. feet x, y        um       signed, +- profile foot range
 *   feet z                  um       profile foot z range
 *   0x50..0x5B joints       mdeg     profile joint range
 *   0x5C servo speed        mdeg/s
 *   0x62..0x64 attitude     mdeg     the one-byte view, 1 LSB = 180/128 deg
 *
 * Every other register (codes, flags, text, counters) has no unit.
 * Integers only: the caller formats (xgo-cli prints cm/s, mm, deg, s).
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_REG_UNITS_H
#define XGO_REG_UNITS_H

#include <stdint.h>

#include "xgo/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum xgo_unit_e {
    XGO_UNIT_NONE = 0, /* a code, flag or text: no physical meaning */
    XGO_UNIT_PERCENT,
    XGO_UNIT_UM,       /* micrometres */
    XGO_UNIT_UM_S,     /* micrometres per second */
    XGO_UNIT_MDEG,     /* millidegrees */
    XGO_UNIT_MDEG_S,   /* millidegrees per second */
    XGO_UNIT_MS        /* milliseconds */
} xgo_unit_t;

/* The unit of the one-byte register at addr (XGO_UNIT_NONE: none). */
xgo_unit_t xgo_reg_unit(uint8_t addr);

/* The value the board reads byte b of register addr as (profile p, NULL =
 * Mini). Returns 0 (value untouched) for a register without a unit. */
int xgo_reg_byte_to_value(const xgo_profile_t *p, uint8_t addr, uint8_t b, int32_t *value);

/* Results of xgo_reg_value_to_byte. */
#define XGO_REG_VALUE_OK 0
#define XGO_REG_VALUE_NO_UNIT 1      /* the register has no physical unit */
#define XGO_REG_VALUE_OUT_OF_RANGE 2 /* no byte means a value that far out */

/* The byte the board reads as nearest to value (ties: the higher byte, so 0
 * on a signed register gives 0x80, its initial value). Values outside
 * xgo_reg_value_range are out of range; 0 on a period or mark-time register
 * is byte 0, "off". *b is written only with XGO_REG_VALUE_OK. */
int xgo_reg_value_to_byte(const xgo_profile_t *p, uint8_t addr, int32_t value, uint8_t *b);

/* The range a value for addr must lie in (lo <= hi): what bytes 0 and 255
 * mean; for a period or mark-time register, whose byte 0 means "off", the
 * low end is the nominal one (1.5 s, the profile's lowest step height),
 * which byte 1 is nearest to. Returns 0 without a unit. */
int xgo_reg_value_range(const xgo_profile_t *p, uint8_t addr, int32_t *lo, int32_t *hi);

#ifdef __cplusplus
}
#endif

#endif /* XGO_REG_UNITS_H */
