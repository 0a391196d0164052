/*
 * meaning.h - what a register byte means, as text: physical values in the
 * units people use (cm/s, mm, deg, s; scales from xgo/reg_units.h, the
 * board's own decoding) and the words of coded values (decode.h). Shared by
 * xgo-cli and the Wireshark tables (tools/wireshark), so both say the same.
 */
#ifndef XGO_HOST_MEANING_H
#define XGO_HOST_MEANING_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/profile.h"

/* How a unit (xgo_unit_t) is shown: base units per display unit as a power
 * of ten, the decimals kept, and the display unit's name. */
typedef struct xgo_host_display_s {
    unsigned scale;
    unsigned decimals;
    const char *name;
} xgo_host_display_t;

xgo_host_display_t xgo_host_unit_display(int unit);

/* value / 10^scale with `decimals` digits, half away from zero, no "-0";
 * sign: '+' before positive values. */
void xgo_host_format_fixed(int64_t value, unsigned scale, unsigned decimals, int sign, char *out,
                           size_t out_size);

/* A value in base units (um, mdeg, ms ...) in its display unit: "+25.00 cm/s". */
void xgo_host_format_value(int unit, int32_t value, int sign, char *out, size_t out_size);

/* Byte b of register addr on model p: "+25.00 cm/s", "off", "walk", "lie
 * down"; "" when the raw value says it all, and on the Mini2's arm
 * registers (0x5C read, 0x5D, 0x5E, 0x71..0x77: their scales are the arm
 * model's, not described here). */
void xgo_host_reg_meaning(const xgo_profile_t *p, uint8_t addr, uint8_t b, char *out,
                          size_t out_size);

/* The robot models by name ("mini", "lite", "mini2": the profiles' names),
 * for --profile options and capture notes. XGO_HOST_MODEL_COUNT codes from
 * 0; xgo_host_model_by_name returns a code, or -1 for a name no model has. */
#define XGO_HOST_MODEL_COUNT (XGO_PROFILE_MINI2 + 1u)
int xgo_host_model_by_name(const char *name);

#endif /* XGO_HOST_MEANING_H */
