/*
 * show.c - registers as xgo-cli prints them: address, name, raw bytes and
 * meaning, one line each ("0x30 vx 0xFF +25.00 cm/s"), or one JSON object
 * each. Scales are the core's (xgo/reg_units.h), words the --trace ones.
 */
#include <string.h>

#include "cli.h"
#include "meaning.h"
#include "xgo/board.h"
#include "xgo/reg_units.h"
#include "xgo/regs.h"

void xgo_cli_format_value(int unit, int32_t value, int sign, char *out, size_t out_size)
{
    xgo_host_format_value(unit, value, sign, out, out_size);
}

void xgo_cli_meaning(xgo_cli_t *cli, uint8_t addr, uint8_t b, char *out, size_t out_size)
{
    /* a register with a unit needs the model (asked if unknown); words are
     * the model's where known (the Mini2's rows differ) */
    const xgo_profile_t *p = xgo_reg_unit(addr) != XGO_UNIT_NONE ? xgo_cli_profile(cli) : cli->profile;
    if (xgo_reg_unit(addr) != XGO_UNIT_NONE && p == NULL) {
        out[0] = '\0';
        return;
    }
    xgo_host_reg_meaning(p != NULL ? p : xgo_profile_mini(), addr, b, out, out_size);
}

/* One shown register: what a line and a JSON object are made of. */
typedef struct xgo_cli_line_s {
    uint8_t addr;
    char name[40];
    const uint8_t *bytes;
    size_t n;
    char text[128]; /* meaning, "" when the raw value says it all */
    int has_number; /* JSON "value": number/10^scale in `unit` */
    int64_t number;
    unsigned scale, decimals;
    const char *unit;
} xgo_cli_line_t;

static void xgo_cli_line_init(xgo_cli_line_t *l, const xgo_cli_t *cli, uint8_t addr,
                              const uint8_t *bytes, size_t n)
{
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    memset(l, 0, sizeof *l);
    l->addr = addr;
    l->bytes = bytes;
    l->n = n;
    l->unit = "";
    if (d == NULL) {
        snprintf(l->name, sizeof l->name, "-");
    } else if (d->addr != addr) {
        snprintf(l->name, sizeof l->name, "%s[%u]", d->name, (unsigned)(addr - d->addr));
    } else {
        snprintf(l->name, sizeof l->name, "%s", d->name);
    }
}

static void xgo_cli_line_print(const xgo_cli_line_t *l, xgo_host_json_t *json)
{
    size_t i;
    if (json != NULL) {
        xgo_host_json_object_begin(json);
        xgo_host_json_key(json, "addr");
        xgo_host_json_uint(json, l->addr);
        xgo_host_json_key(json, "name");
        xgo_host_json_string(json, l->name);
        xgo_host_json_key(json, "bytes");
        xgo_host_json_hex(json, l->bytes, l->n);
        if (l->has_number) {
            xgo_host_json_key(json, "value");
            xgo_host_json_fixed(json, l->number, l->scale, l->decimals);
            xgo_host_json_key(json, "unit");
            xgo_host_json_string(json, l->unit);
        }
        xgo_host_json_key(json, "text");
        xgo_host_json_string(json, l->text);
        xgo_host_json_object_end(json);
        return;
    }
    printf("0x%02X %s ", l->addr, l->name);
    if (l->n == 1) {
        printf("0x%02X", l->bytes[0]);
    } else {
        for (i = 0; i < l->n; i++) {
            printf(i ? " %02X" : "%02X", l->bytes[i]);
        }
    }
    printf(l->text[0] != '\0' ? " %s\n" : "\n", l->text);
}

/* Text registers (firmware, bt_name): printable part as a string. */
static void xgo_cli_text(xgo_cli_line_t *l)
{
    size_t i, len = 1;
    l->text[0] = '"';
    for (i = 0; i < l->n && l->bytes[i] != 0 && len + 6 < sizeof l->text; i++) {
        uint8_t c = l->bytes[i];
        len += (size_t)snprintf(l->text + len, sizeof l->text - len,
                                (c >= 0x20u && c < 0x7Fu && c != '"') ? "%c" : "\\x%02X", c);
    }
    snprintf(l->text + len, sizeof l->text - len, "\"");
}

static int16_t xgo_cli_be16(const uint8_t *p)
{
    return (int16_t)(uint16_t)((unsigned)p[0] << 8 | p[1]);
}

static int16_t xgo_cli_le16(const uint8_t *p)
{
    return (int16_t)(uint16_t)((unsigned)p[1] << 8 | p[0]);
}

static float xgo_cli_le_float(const uint8_t *p)
{
    uint32_t bits = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The 4-byte attitude view at 0x62..0x64: float32 LE degrees. */
static void xgo_cli_attitude(xgo_cli_line_t *l)
{
    float f = xgo_cli_le_float(l->bytes);
    snprintf(l->text, sizeof l->text, "%+.2f deg", (double)f);
    l->has_number = 1;
    l->number = (int64_t)((double)f * 1000.0 + (f < 0 ? -0.5 : 0.5));
    l->scale = 3;
    l->decimals = 3;
    l->unit = "deg";
}

/* 0x66..0x68: int16 big-endian, 0.01 degree. */
static void xgo_cli_attitude16(xgo_cli_line_t *l)
{
    int16_t c = xgo_cli_be16(l->bytes);
    xgo_host_format_fixed(c, 2, 2, 1, l->text, sizeof l->text);
    snprintf(l->text + strlen(l->text), sizeof l->text - strlen(l->text), " deg");
    l->has_number = 1;
    l->number = c;
    l->scale = 2;
    l->decimals = 2;
    l->unit = "deg";
}

/* 0x65: acceleration (16384 = 1 g), angular rate (16.4 = 1 deg/s), angles. */
static void xgo_cli_imu_block(xgo_cli_line_t *l)
{
    const uint8_t *b = l->bytes;
    snprintf(l->text, sizeof l->text,
             "accel %+.3f %+.3f %+.3f g, gyro %+.1f %+.1f %+.1f deg/s, rpy %+.2f %+.2f %+.2f deg",
             xgo_cli_le16(b) / 16384.0, xgo_cli_le16(b + 2) / 16384.0, xgo_cli_le16(b + 4) / 16384.0,
             xgo_cli_le16(b + 6) / 16.4, xgo_cli_le16(b + 8) / 16.4, xgo_cli_le16(b + 10) / 16.4,
             (double)xgo_cli_le_float(b + 12), (double)xgo_cli_le_float(b + 16),
             (double)xgo_cli_le_float(b + 20));
}

/* The diagnostic counters in data (from 0xC4 on), one line each. */
static size_t xgo_cli_show_diag(const uint8_t *data, size_t n, xgo_host_json_t *json)
{
    size_t k;
    for (k = 0; k < XGO_DIAG_COUNT && 4 * k + 4 <= n; k++) {
        xgo_cli_line_t l;
        const uint8_t *p = data + 4 * k;
        uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
        xgo_cli_line_init(&l, NULL, (uint8_t)(XGO_REG_DIAG + 4 * k), p, 4);
        snprintf(l.name, sizeof l.name, "%s", xgo_diag_name((xgo_diag_t)k));
        snprintf(l.text, sizeof l.text, "%lu", (unsigned long)v);
        l.has_number = 1;
        l.number = v;
        xgo_cli_line_print(&l, json);
    }
    return n; /* unused slots are not shown */
}

/* A single byte of a one-byte register (or a byte inside a wider one, or
 * an address the board lacks). */
static void xgo_cli_byte_line(xgo_cli_t *cli, uint8_t addr, const uint8_t *b, xgo_cli_line_t *l)
{
    const xgo_profile_t *p;
    int32_t v;
    xgo_cli_line_init(l, cli, addr, b, 1);
    xgo_cli_meaning(cli, addr, *b, l->text, sizeof l->text);
    if (xgo_reg_unit(addr) != XGO_UNIT_NONE && (p = xgo_cli_profile(cli)) != NULL &&
        xgo_reg_byte_to_value(p, addr, *b, &v)) {
        xgo_host_display_t d = xgo_host_unit_display((int)xgo_reg_unit(addr));
        l->has_number = 1;
        l->number = v;
        l->scale = d.scale;
        l->decimals = d.scale; /* JSON keeps every digit */
        l->unit = d.name;
    }
}

/* The register at data[0] (addr): its line, and how many bytes it took.
 * Views first (the attitude float, the firmware window: only a read that
 * starts there has them), then wider registers, then single bytes. The
 * diagnostic block is left to xgo_cli_show_diag (0 returned). */
static size_t xgo_cli_line_at(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                              int first, xgo_cli_line_t *l)
{
    const xgo_reg_desc_t *d = xgo_cli_reg(cli, addr);
    if (first && addr >= XGO_REG_IMU_ROLL && addr <= XGO_REG_IMU_YAW && n >= 4) {
        xgo_cli_line_init(l, cli, addr, data, 4);
        xgo_cli_attitude(l);
        return 4;
    }
    if (first && addr == XGO_REG_IMU_BLOCK && n >= XGO_IMU_BLOCK_LEN) {
        xgo_cli_line_init(l, cli, addr, data, XGO_IMU_BLOCK_LEN);
        xgo_cli_imu_block(l);
        return XGO_IMU_BLOCK_LEN;
    }
    if (first && addr >= XGO_REG_IMU_ROLL16 && addr <= XGO_REG_IMU_YAW16 && n >= 2) {
        xgo_cli_line_init(l, cli, addr, data, 2);
        xgo_cli_attitude16(l);
        return 2;
    }
    if (first && addr == XGO_REG_FIRMWARE) {
        /* any length read from 0x07 is the string */
        xgo_cli_line_init(l, cli, addr, data, n < XGO_FIRMWARE_LEN ? n : XGO_FIRMWARE_LEN);
        xgo_cli_text(l);
        return l->n;
    }
    if (addr == XGO_REG_DIAG && n >= 4) {
        return 0;
    }
    if (d != NULL && d->addr == addr && d->valid == XGO_VALID_ASCII) {
        /* text: as much of it as the read (or write) covers */
        xgo_cli_line_init(l, cli, addr, data, n < d->width ? n : d->width);
        xgo_cli_text(l);
        return l->n;
    }
    if (d != NULL && d->addr == addr && d->width > 1 && n >= d->width) {
        xgo_cli_line_init(l, cli, addr, data, d->width);
        return d->width;
    }
    xgo_cli_byte_line(cli, addr, data, l);
    return 1;
}

void xgo_cli_show_regs(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                       xgo_host_json_t *json)
{
    size_t i = 0;
    while (i < n) {
        xgo_cli_line_t l;
        size_t took = xgo_cli_line_at(cli, (uint8_t)(addr + i), data + i, n - i, i == 0, &l);
        if (took == 0) {
            i += xgo_cli_show_diag(data + i, n - i, json);
            continue;
        }
        xgo_cli_line_print(&l, json);
        i += took;
    }
}

void xgo_cli_show_write(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n,
                        xgo_host_json_t *json)
{
    if (addr == XGO_REG_TURN_TO && n == 2) {
        /* the write view: one int16 big-endian heading, not two registers */
        xgo_cli_line_t l;
        int16_t deg = xgo_cli_be16(data);
        xgo_cli_line_init(&l, cli, addr, data, 2);
        snprintf(l.text, sizeof l.text, "%+d deg", deg);
        l.has_number = 1;
        l.number = deg;
        l.unit = "deg";
        xgo_cli_line_print(&l, json);
        return;
    }
    xgo_cli_show_regs(cli, addr, data, n, json);
}

void xgo_cli_reg_text(xgo_cli_t *cli, uint8_t addr, const uint8_t *data, size_t n, char *out,
                      size_t out_size)
{
    xgo_cli_line_t l;
    size_t i;
    if (xgo_cli_line_at(cli, addr, data, n, 1, &l) == 0) {
        snprintf(out, out_size, "0x%02X", data[0]);
        return;
    }
    if (l.text[0] != '\0') {
        snprintf(out, out_size, "%s", l.text);
        return;
    }
    out[0] = '\0';
    for (i = 0; i < l.n && 3 * i + 5 < out_size; i++) {
        snprintf(out + strlen(out), out_size - strlen(out), i ? " %02X" : "0x%02X", l.bytes[i]);
    }
}

xgo_host_json_t *xgo_cli_json_begin(xgo_cli_t *cli)
{
    static char buf[1u << 17];
    static xgo_host_json_t w;
    xgo_host_json_init(&w, buf, sizeof buf);
    xgo_host_json_object_begin(&w);
    xgo_host_json_key(&w, "ok");
    xgo_host_json_bool(&w, 1);
    if (cli->port != NULL) {
        xgo_host_json_key(&w, "port");
        xgo_host_json_string(&w, cli->port);
    }
    return &w;
}

void xgo_cli_json_end(xgo_host_json_t *w)
{
    xgo_host_json_object_end(w);
    printf("%s\n", xgo_host_json_ok(w) ? w->buf : "{\"ok\":false,\"error\":\"output too large\"}");
}
