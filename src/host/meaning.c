/* meaning.c - register bytes as text (see meaning.h). */
#include "meaning.h"

#include <stdio.h>
#include <string.h>

#include "decode.h"
#include "xgo/reg_units.h"
#include "xgo/regs.h"

xgo_host_display_t xgo_host_unit_display(int unit)
{
    xgo_host_display_t d = {0, 0, ""};
    switch (unit) {
    case XGO_UNIT_UM_S: d.scale = 4; d.decimals = 2; d.name = "cm/s"; break; /* the vendor's unit */
    case XGO_UNIT_MDEG_S: d.scale = 3; d.decimals = 2; d.name = "deg/s"; break;
    case XGO_UNIT_MDEG: d.scale = 3; d.decimals = 2; d.name = "deg"; break;
    case XGO_UNIT_UM: d.scale = 3; d.decimals = 2; d.name = "mm"; break;
    case XGO_UNIT_MS: d.scale = 3; d.decimals = 3; d.name = "s"; break;
    case XGO_UNIT_PERCENT: d.name = "%"; break;
    default: break;
    }
    return d;
}

void xgo_host_format_fixed(int64_t value, unsigned scale, unsigned decimals, int sign, char *out,
                           size_t out_size)
{
    int64_t div = 1, keep = 1, mag = value < 0 ? -value : value;
    unsigned i;
    for (i = 0; i < scale; i++) {
        div *= 10;
    }
    for (i = 0; i < decimals; i++) {
        keep *= 10;
    }
    mag = (mag * keep * 2 + div) / (2 * div); /* in units of 10^-decimals */
    snprintf(out, out_size, "%s%lld", mag == 0 ? "" : (value < 0 ? "-" : (sign ? "+" : "")),
             (long long)(mag / keep));
    if (decimals > 0) {
        size_t len = strlen(out);
        snprintf(out + len, out_size - len, ".%0*lld", (int)decimals, (long long)(mag % keep));
    }
}

void xgo_host_format_value(int unit, int32_t value, int sign, char *out, size_t out_size)
{
    xgo_host_display_t d = xgo_host_unit_display(unit);
    size_t len;
    xgo_host_format_fixed(value, d.scale, d.decimals, sign, out, out_size);
    len = strlen(out);
    snprintf(out + len, out_size - len, unit == XGO_UNIT_PERCENT ? "%s" : " %s", d.name);
}

/* On a model with the arm (the Mini2) some addresses are other registers
 * (0x5D, 0x5E, 0x71..0x77: the arm's) and 0x5C reads the claw: the Mini's
 * words and scales do not apply there. */
static int xgo_host_other_model_row(const xgo_profile_t *p, uint8_t addr)
{
    size_t i;
    if (p->arm == NULL) {
        return 0;
    }
    if (addr == XGO_REG_SERVO_SPEED) {
        return 1;
    }
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        if ((d->flags & XGO_REGF_ARM) != 0 && addr >= d->addr && addr < d->addr + d->width) {
            return 1;
        }
    }
    return 0;
}

void xgo_host_reg_meaning(const xgo_profile_t *p, uint8_t addr, uint8_t b, char *out,
                          size_t out_size)
{
    int32_t v, lo, hi;
    out[0] = '\0';
    if (xgo_host_other_model_row(p, addr)) {
        return;
    }
    if (xgo_reg_byte_to_value(p, addr, b, &v)) {
        int unit = (int)xgo_reg_unit(addr);
        if (b == 0 && (unit == XGO_UNIT_MS || addr == XGO_REG_MARK_TIME)) {
            snprintf(out, out_size, "off"); /* byte 0 of a period or mark time */
            return;
        }
        /* registers that mean negative values too show a '+' */
        (void)xgo_reg_value_range(p, addr, &lo, &hi);
        xgo_host_format_value(unit, v, lo < 0, out, out_size);
        return;
    }
    if (!xgo_host_decode_value(addr, b, out, out_size)) {
        out[0] = '\0';
    }
}

int xgo_host_model_by_name(const char *name)
{
    unsigned m;
    for (m = 0; m < XGO_HOST_MODEL_COUNT; m++) {
        if (strcmp(xgo_profile_get(m)->name, name) == 0) {
            return (int)m;
        }
    }
    return -1;
}
