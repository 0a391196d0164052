/*
 * regarg.c - the words of xgo-cli's commands: registers by name or address,
 * values raw, physical (with a unit) or as the words the register's values
 * have. Names, access, valid sets and scales all come from the core's
 * tables (xgo/regs.h, xgo/reg_units.h) and the --trace words (decode.h).
 */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "decode.h"
#include "xgo/reg_units.h"
#include "xgo/regs.h"

const xgo_reg_desc_t *xgo_cli_reg(const xgo_cli_t *cli, uint8_t addr)
{
    return xgo_reg_find_model(addr, cli != NULL && cli->profile != NULL && cli->profile->arm != NULL);
}

const char *xgo_cli_reg_name(const xgo_cli_t *cli, uint8_t addr)
{
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    return d != NULL ? d->name : "-";
}

int xgo_cli_parse_number(const char *word, long lo, long hi, long *out)
{
    char *end = NULL;
    long v;
    const char *p = word;
    int base = 10;
    if (*p == '-' && lo < 0) {
        p++;
    }
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        base = 16;
        p += 2;
    }
    if (!isxdigit((unsigned char)*p) || (base == 10 && !isdigit((unsigned char)*p))) {
        return 0;
    }
    errno = 0;
    v = strtol(p, &end, base);
    if (errno != 0 || *end != '\0') {
        return 0;
    }
    if (word[0] == '-') {
        v = -v;
    }
    if (v < lo || v > hi) {
        return 0;
    }
    *out = v;
    return 1;
}

/* Does name end with "_" + word? */
static int xgo_cli_suffix_match(const char *name, const char *word)
{
    size_t n = strlen(name), w = strlen(word);
    return n > w + 1 && name[n - w - 1] == '_' && strcmp(name + n - w, word) == 0;
}

/* Same kind of value: what a unit suffix can be written to. */
static int xgo_cli_reg_fits(const xgo_reg_desc_t *d, int want_write, int unit)
{
    if (want_write && (d->access & XGO_ACCESS_W) == 0) {
        return 0;
    }
    return unit == XGO_UNIT_NONE || (int)xgo_reg_unit(d->addr) == unit;
}

int xgo_cli_parse_reg(const char *word, int want_write, int unit, uint8_t *addr, char *err,
                      size_t err_size)
{
    long v;
    size_t i, count = 0, len = 0;
    const xgo_reg_desc_t *found = NULL;
    char names[256];
    if (xgo_cli_parse_number(word, 0, 255, &v)) {
        *addr = (uint8_t)v;
        return 1;
    }
    for (i = 0; i < xgo_reg_table_size(); i++) {
        if (strcmp(xgo_reg_table_entry(i)->name, word) == 0) {
            *addr = xgo_reg_table_entry(i)->addr;
            return 1;
        }
    }
    names[0] = '\0';
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        if (xgo_cli_suffix_match(d->name, word) && xgo_cli_reg_fits(d, want_write, unit)) {
            found = d;
            count++;
            if (len + strlen(d->name) + 3 < sizeof names) {
                len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", count > 1 ? ", " : "",
                                        d->name);
            }
        }
    }
    if (count == 1) {
        *addr = found->addr;
        return 1;
    }
    if (count == 0) {
        snprintf(err, err_size, "unknown register '%s' (a name as `xgo-cli dump` lists, or an address)",
                 word);
    } else {
        snprintf(err, err_size, "ambiguous register '%s': %s", word, names);
    }
    return 0;
}

static int xgo_cli_hexval(int c)
{
    return isdigit(c) ? c - '0' : tolower(c) - 'a' + 10;
}

/* "55", "5500", "0x55": pairs of hex digits into out. */
static int xgo_cli_hex_word(const char *w, uint8_t *out, size_t cap, size_t *n)
{
    size_t i, len;
    if (w[0] == '0' && (w[1] == 'x' || w[1] == 'X')) {
        w += 2;
    }
    len = strlen(w);
    if (len == 0 || len % 2 != 0) {
        return 0;
    }
    for (i = 0; i < len; i += 2) {
        if (!isxdigit((unsigned char)w[i]) || !isxdigit((unsigned char)w[i + 1]) || *n >= cap) {
            return 0;
        }
        out[(*n)++] = (uint8_t)(xgo_cli_hexval((unsigned char)w[i]) * 16 +
                                xgo_cli_hexval((unsigned char)w[i + 1]));
    }
    return 1;
}

int xgo_cli_parse_hex(int argc, char **argv, uint8_t *out, size_t cap, char *err, size_t err_size)
{
    size_t n = 0;
    int i;
    for (i = 0; i < argc; i++) {
        /* a word may hold several, quoted as one: "55 00 09,02" */
        char word[1024];
        char *tok, *save = NULL;
        snprintf(word, sizeof word, "%s", argv[i]);
        for (tok = strtok_r(word, " \t\n,:", &save); tok != NULL; tok = strtok_r(NULL, " \t\n,:", &save)) {
            if (!xgo_cli_hex_word(tok, out, cap, &n)) {
                snprintf(err, err_size, "'%s' is not hex bytes (pairs of hex digits, e.g. 55 00 09)",
                         tok);
                return -1;
            }
        }
    }
    return (int)n;
}

/* ---- physical values */

typedef struct xgo_cli_unit_s {
    const char *suffix;
    int unit;         /* xgo_unit_t */
    int32_t per_unit; /* base units (um, mdeg, ms ...) per suffix unit */
} xgo_cli_unit_t;

/* Longest suffixes first: "mm/s" before "m/s" before "s". */
static const xgo_cli_unit_t xgo_cli_units[] = {
    {"mdeg/s", XGO_UNIT_MDEG_S, 1},   {"deg/s", XGO_UNIT_MDEG_S, 1000},
    {"\xC2\xB0/s", XGO_UNIT_MDEG_S, 1000},
    {"um/s", XGO_UNIT_UM_S, 1},       {"mm/s", XGO_UNIT_UM_S, 1000},
    {"cm/s", XGO_UNIT_UM_S, 10000},   {"m/s", XGO_UNIT_UM_S, 1000000},
    {"mdeg", XGO_UNIT_MDEG, 1},       {"deg", XGO_UNIT_MDEG, 1000},
    {"\xC2\xB0", XGO_UNIT_MDEG, 1000},
    {"um", XGO_UNIT_UM, 1},           {"mm", XGO_UNIT_UM, 1000},
    {"cm", XGO_UNIT_UM, 10000},       {"ms", XGO_UNIT_MS, 1},
    {"m", XGO_UNIT_UM, 1000000},      {"s", XGO_UNIT_MS, 1000},
    {"%", XGO_UNIT_PERCENT, 1},
};

/* The number part "[+-]D[.D]" of value: its length, 0 if none. */
static size_t xgo_cli_number_len(const char *v)
{
    size_t i = 0;
    if (v[i] == '+' || v[i] == '-') {
        i++;
    }
    if (!isdigit((unsigned char)v[i])) {
        return 0;
    }
    while (isdigit((unsigned char)v[i])) {
        i++;
    }
    if (v[i] == '.' && isdigit((unsigned char)v[i + 1])) {
        i++;
        while (isdigit((unsigned char)v[i])) {
            i++;
        }
    }
    return i;
}

static const xgo_cli_unit_t *xgo_cli_find_unit(const char *value)
{
    size_t num = xgo_cli_number_len(value);
    size_t i;
    const char *suffix = value + num;
    if (num == 0) {
        return NULL;
    }
    while (*suffix == ' ') {
        suffix++;
    }
    for (i = 0; i < sizeof xgo_cli_units / sizeof xgo_cli_units[0]; i++) {
        if (strcmp(suffix, xgo_cli_units[i].suffix) == 0) {
            return &xgo_cli_units[i];
        }
    }
    return NULL;
}

int xgo_cli_value_unit(const char *value)
{
    const xgo_cli_unit_t *u = xgo_cli_find_unit(value);
    return u != NULL ? u->unit : XGO_UNIT_NONE;
}

/* "12.5" x per_unit -> base units, exact decimal arithmetic, rounded half
 * away from zero. 0 when it does not fit an int32. */
static int xgo_cli_scale(const char *v, int32_t per_unit, int32_t *out)
{
    int64_t whole = 0, frac = 0, scale = 1, r;
    int neg = v[0] == '-';
    if (*v == '+' || *v == '-') {
        v++;
    }
    for (; isdigit((unsigned char)*v); v++) {
        whole = whole * 10 + (*v - '0');
        if (whole > 2147483647LL) {
            return 0;
        }
    }
    if (*v == '.') {
        for (v++; isdigit((unsigned char)*v) && scale < 1000000000LL; v++) {
            frac = frac * 10 + (*v - '0');
            scale *= 10;
        }
    }
    r = whole * per_unit + (frac * per_unit * 2 + scale) / (2 * scale);
    if (r > 2147483647LL) {
        return 0;
    }
    *out = (int32_t)(neg ? -r : r);
    return 1;
}

static const char *xgo_cli_unit_words(int unit)
{
    switch (unit) {
    case XGO_UNIT_UM_S: return "cm/s, mm/s, m/s";
    case XGO_UNIT_MDEG_S: return "deg/s";
    case XGO_UNIT_MDEG: return "deg";
    case XGO_UNIT_UM: return "mm, cm, um";
    case XGO_UNIT_MS: return "s, ms";
    case XGO_UNIT_PERCENT: return "%";
    default: return "none";
    }
}

/* A physical value for a one-byte register with a unit. */
static int xgo_cli_physical(xgo_cli_t *cli, uint8_t addr, const char *value, uint8_t *out,
                            char *err, size_t err_size)
{
    const xgo_cli_unit_t *u = xgo_cli_find_unit(value);
    const xgo_profile_t *p;
    int32_t v, lo, hi;
    char a[48], b[48];
    int reg_unit = (int)xgo_reg_unit(addr);
    if (reg_unit == XGO_UNIT_NONE || u->unit != reg_unit) {
        snprintf(err, err_size, "%s takes %s, not '%s'", xgo_cli_reg_name(cli, addr),
                 reg_unit == XGO_UNIT_NONE ? "no unit" : xgo_cli_unit_words(reg_unit), value);
        return -1;
    }
    if (!xgo_cli_scale(value, u->per_unit, &v)) {
        snprintf(err, err_size, "'%s' is too large", value);
        return -1;
    }
    p = xgo_cli_profile(cli);
    if (p == NULL) {
        snprintf(err, err_size, "%s (needed to know the model for '%s'; or give --profile)", cli->err,
                 value);
        return -1;
    }
    if (xgo_reg_value_to_byte(p, addr, v, out) != XGO_REG_VALUE_OK) {
        (void)xgo_reg_value_range(p, addr, &lo, &hi);
        xgo_cli_format_value(reg_unit, lo, lo < 0, a, sizeof a);
        xgo_cli_format_value(reg_unit, hi, lo < 0, b, sizeof b);
        snprintf(err, err_size, "%s=%s is out of range: %s .. %s on the %s", xgo_cli_reg_name(cli, addr), value,
                 a, b, p->name);
        return -1;
    }
    return 1;
}

/* "lie down", "lie_down", "Lie-Down" are the same word. */
static int xgo_cli_same_word(const char *a, const char *b)
{
    for (; *a != '\0' && *b != '\0'; a++, b++) {
        char x = (*a == '_' || *a == '-') ? ' ' : (char)tolower((unsigned char)*a);
        char y = (*b == '_' || *b == '-') ? ' ' : (char)tolower((unsigned char)*b);
        if (x != y) {
            return 0;
        }
    }
    return *a == *b;
}

/* A word the register's values have (the --trace words): its byte. */
static int xgo_cli_word_value(uint8_t addr, const char *value, uint8_t *out)
{
    unsigned v;
    if (xgo_reg_unit(addr) != XGO_UNIT_NONE) {
        return 0; /* "+100%" words of centred registers: use a unit instead */
    }
    for (v = 0; v < 256; v++) {
        char word[64];
        if (xgo_host_decode_value(addr, (uint8_t)v, word, sizeof word) &&
            xgo_cli_same_word(word, value) && strcmp(word, "invalid") != 0) {
            *out = (uint8_t)v;
            return 1;
        }
    }
    return 0;
}

/* Raw: "0xff", "255", "0x8080" (two bytes), or a quoted/plain text for a
 * text register. Returns the count or -1. */
static int xgo_cli_raw_value(const xgo_cli_t *cli, uint8_t addr, const char *value, uint8_t *out,
                             size_t cap, char *err, size_t err_size)
{
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    size_t n = 0;
    long v;
    if (d != NULL && d->valid == XGO_VALID_ASCII) {
        size_t len = strlen(value);
        if (len >= 2 && value[0] == '"' && value[len - 1] == '"') {
            value++;
            len -= 2;
        }
        if (len == 0 || len > cap || len > d->width) {
            snprintf(err, err_size, "%s takes 1..%u characters", d->name, (unsigned)d->width);
            return -1;
        }
        memcpy(out, value, len);
        return (int)len;
    }
    if (value[0] == '0' && (value[1] == 'x' || value[1] == 'X') && strlen(value) > 4 &&
        xgo_cli_hex_word(value, out, cap, &n)) {
        return (int)n;
    }
    if (xgo_cli_parse_number(value, 0, 255, &v)) {
        out[0] = (uint8_t)v;
        return 1;
    }
    if (xgo_cli_word_value(addr, value, out)) {
        return 1;
    }
    if (xgo_reg_unit(addr) != XGO_UNIT_NONE) {
        snprintf(err, err_size, "'%s' is no byte 0..255 and has no unit (%s takes %s)", value,
                 xgo_cli_reg_name(cli, addr), xgo_cli_unit_words((int)xgo_reg_unit(addr)));
    } else {
        snprintf(err, err_size, "'%s' is no byte 0..255 (0x00..0xFF) nor a value %s has", value,
                 xgo_cli_reg_name(cli, addr));
    }
    return -1;
}

/* turn_to (0x3F) takes a heading as two bytes, int16 big-endian degrees
 * (its write view, docs/registers.md). */
static int xgo_cli_heading(const char *value, uint8_t *out, char *err, size_t err_size)
{
    const xgo_cli_unit_t *u = xgo_cli_find_unit(value);
    int32_t mdeg;
    long deg;
    if (u->unit != XGO_UNIT_MDEG || !xgo_cli_scale(value, u->per_unit, &mdeg)) {
        snprintf(err, err_size, "turn_to takes a heading in deg, not '%s'", value);
        return -1;
    }
    deg = (long)((mdeg >= 0 ? mdeg + 500 : mdeg - 500) / 1000);
    if (deg < -32768 || deg > 32767) {
        snprintf(err, err_size, "turn_to=%s is out of range: -32768 .. 32767 deg", value);
        return -1;
    }
    out[0] = (uint8_t)(((unsigned long)deg >> 8) & 0xFFu);
    out[1] = (uint8_t)((unsigned long)deg & 0xFFu);
    return 2;
}

/* Refuses what the board would refuse: read-only bytes, values outside a
 * register's valid set, a write past 0xFF. */
static int xgo_cli_check_write(const xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                               char *err, size_t err_size)
{
    size_t i;
    if ((size_t)addr + n > XGO_REG_COUNT) {
        snprintf(err, err_size, "%lu bytes at 0x%02X run past 0xFF", (unsigned long)n, addr);
        return -1;
    }
    for (i = 0; i < n; i++) {
        const xgo_reg_desc_t *d = xgo_cli_reg(cli, (uint8_t)(addr + i));
        if (d == NULL) {
            continue; /* the board ignores bytes for addresses it lacks (counted) */
        }
        if ((d->access & XGO_ACCESS_W) == 0) {
            snprintf(err, err_size, "%s (0x%02X) is read-only", d->name, d->addr);
            return -1;
        }
        if (!xgo_reg_value_valid(d, data[i])) {
            snprintf(err, err_size, "0x%02X is not a value %s takes", data[i], d->name);
            return -1;
        }
    }
    return 0;
}

int xgo_cli_parse_value(xgo_cli_t *cli, uint8_t addr, const char *value, uint8_t *out,
                        size_t cap, char *err, size_t err_size)
{
    int n;
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    if (value[0] == '\0') {
        snprintf(err, err_size, "%s= needs a value", xgo_cli_reg_name(cli, addr));
        return -1;
    }
    if (addr == XGO_REG_TURN_TO && xgo_cli_find_unit(value) != NULL) {
        n = xgo_cli_heading(value, out, err, err_size);
    } else if (xgo_cli_find_unit(value) != NULL && (d == NULL || d->valid != XGO_VALID_ASCII)) {
        n = xgo_cli_physical(cli, addr, value, out, err, err_size);
    } else {
        n = xgo_cli_raw_value(cli, addr, value, out, cap, err, err_size);
    }
    if (n < 0 || xgo_cli_check_write(cli, addr, out, (size_t)n, err, err_size) != 0) {
        return -1;
    }
    return n;
}
