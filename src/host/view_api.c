/*
 * view_api.c - POST /input and POST /command bodies (see view_api.h).
 * Everything is read and checked before anything is applied: a body with
 * one bad field changes nothing and gets 400 naming that field.
 */
#include "view_api.h"

#include <stdio.h>
#include <string.h>

#include "json_in.h"
#include "xgo/emulator.h"

/* Same bound as --ground-tilt: steeper is no ground a dog stands on. */
#define XGO_HOST_VIEW_MAX_TILT_MDEG 45000
/* The core clamps a shove here (xgo_imu_push); beyond it is refused. */
#define XGO_HOST_VIEW_MAX_PUSH_MDEG 30000

void xgo_host_view_api_error(xgo_host_json_t *reply, const char *why)
{
    xgo_host_json_object_begin(reply);
    xgo_host_json_key(reply, "error");
    xgo_host_json_string(reply, why);
    xgo_host_json_object_end(reply);
}

/* 400 with `why`. */
static int xgo_host_view_api_refuse_why(xgo_host_json_t *reply, const char *why)
{
    xgo_host_view_api_error(reply, why);
    return 400;
}

/* 400 with a message naming one or two things (b unused by fmt: NULL). */
static int xgo_host_view_api_refuse(xgo_host_json_t *reply, const char *fmt, const char *a,
                                    const char *b)
{
    char why[160];
    snprintf(why, sizeof why, fmt, a, b);
    xgo_host_view_api_error(reply, why);
    return 400;
}

/* The body must be one JSON object; *root gets it. 200 or 400. */
static int xgo_host_view_api_object(const char *body, size_t n, xgo_host_json_span_t *root,
                                    xgo_host_json_t *reply)
{
    size_t at;
    const char *why;
    char where[24];
    if (!xgo_host_json_parse(body, n, root, &at, &why)) {
        snprintf(where, sizeof where, "%lu", (unsigned long)at);
        return xgo_host_view_api_refuse(reply, "body is not JSON: %s at byte %s", why, where);
    }
    if (xgo_host_json_type(*root) != XGO_HOST_JSON_OBJECT) {
        return xgo_host_view_api_refuse_why(reply, "body must be a JSON object");
    }
    return 200;
}

/* The member name as text for messages (cut, never unterminated). */
static void xgo_host_view_api_name(xgo_host_json_span_t name, char *out, size_t size)
{
    size_t n = (size_t)(name.end - name.start);
    if (n >= size) {
        n = size - 1;
    }
    memcpy(out, name.start, n);
    out[n] = '\0';
}

/* ------------------------------------------------------------ /input */

typedef struct xgo_host_view_input_s {
    int has_tilt, has_battery, has_push;
    int32_t tilt_mdeg[2];
    int32_t push_mdeg[2];
    uint8_t battery_pct;
} xgo_host_view_input_t;

/* {"roll_deg":R,"pitch_deg":P}, both given, each within +-limit. */
static int xgo_host_view_api_angles(xgo_host_json_span_t v, const char *field, int32_t limit,
                                    int32_t out[2], xgo_host_json_t *reply)
{
    xgo_host_json_cursor_t c;
    xgo_host_json_span_t name, value;
    int seen[2] = {0, 0};
    char text[32];
    if (xgo_host_json_type(v) != XGO_HOST_JSON_OBJECT) {
        return xgo_host_view_api_refuse(reply, "%s must be {\"roll_deg\":R,\"pitch_deg\":P}",
                                        field, NULL);
    }
    xgo_host_json_enter(v, &c);
    while (xgo_host_json_next_member(&c, &name, &value)) {
        int i = xgo_host_json_name_is(name, "roll_deg") ? 0
                : xgo_host_json_name_is(name, "pitch_deg") ? 1
                                                            : -1;
        int64_t mdeg;
        xgo_host_view_api_name(name, text, sizeof text);
        if (i < 0 || seen[i]) {
            return xgo_host_view_api_refuse(reply, i < 0 ? "%s: unknown field '%s'"
                                                         : "%s: field '%s' given twice",
                                            field, text);
        }
        if (!xgo_host_json_scaled(value, 3, -limit, limit, &mdeg)) {
            return xgo_host_view_api_refuse(reply,
                                            limit == XGO_HOST_VIEW_MAX_TILT_MDEG
                                                ? "%s.%s must be a number of degrees within +-45"
                                                : "%s.%s must be a number of degrees within +-30",
                                            field, text);
        }
        seen[i] = 1;
        out[i] = (int32_t)mdeg;
    }
    if (!seen[0] || !seen[1]) {
        return xgo_host_view_api_refuse(reply, "%s needs both roll_deg and pitch_deg", field, NULL);
    }
    return 200;
}

static int xgo_host_view_api_input_member(xgo_host_json_span_t name, xgo_host_json_span_t value,
                                          xgo_host_view_input_t *in, xgo_host_json_t *reply)
{
    char text[32];
    int64_t pct;
    xgo_host_view_api_name(name, text, sizeof text);
    if (xgo_host_json_name_is(name, "ground_tilt") && !in->has_tilt) {
        in->has_tilt = 1;
        return xgo_host_view_api_angles(value, "ground_tilt", XGO_HOST_VIEW_MAX_TILT_MDEG,
                                        in->tilt_mdeg, reply);
    }
    if (xgo_host_json_name_is(name, "push") && !in->has_push) {
        in->has_push = 1;
        return xgo_host_view_api_angles(value, "push", XGO_HOST_VIEW_MAX_PUSH_MDEG, in->push_mdeg,
                                        reply);
    }
    if (xgo_host_json_name_is(name, "battery_pct") && !in->has_battery) {
        in->has_battery = 1;
        if (!xgo_host_json_whole(value, 0, 100, &pct)) {
            return xgo_host_view_api_refuse_why(reply, "battery_pct must be a whole number 0..100");
        }
        in->battery_pct = (uint8_t)pct;
        return 200;
    }
    if (xgo_host_json_name_is(name, "ground_tilt") || xgo_host_json_name_is(name, "push") ||
        xgo_host_json_name_is(name, "battery_pct")) {
        return xgo_host_view_api_refuse(reply, "field '%s' given twice", text, NULL);
    }
    return xgo_host_view_api_refuse(reply, "unknown field '%s' (ground_tilt, battery_pct, push)",
                                    text, NULL);
}

int xgo_host_view_api_input(xgo_board_t *b, const char *body, size_t n, xgo_host_json_t *reply)
{
    xgo_host_view_input_t in;
    xgo_host_json_span_t root, name, value;
    xgo_host_json_cursor_t c;
    int status = xgo_host_view_api_object(body, n, &root, reply);
    memset(&in, 0, sizeof in);
    xgo_host_json_enter(root, &c);
    while (status == 200 && xgo_host_json_next_member(&c, &name, &value)) {
        status = xgo_host_view_api_input_member(name, value, &in, reply);
    }
    if (status != 200) {
        return status;
    }
    if (!in.has_tilt && !in.has_battery && !in.has_push) {
        return xgo_host_view_api_refuse_why(reply, "nothing to apply: give ground_tilt, battery_pct "
                                               "or push");
    }
    if (in.has_tilt) {
        xgo_board_set_ground_tilt(b, in.tilt_mdeg[0], in.tilt_mdeg[1]);
    }
    if (in.has_battery) {
        xgo_board_set_battery(b, in.battery_pct);
    }
    if (in.has_push) {
        xgo_board_push(b, in.push_mdeg[0], in.push_mdeg[1]);
    }
    xgo_host_json_object_begin(reply);
    xgo_host_json_key(reply, "ok");
    xgo_host_json_bool(reply, 1);
    xgo_host_json_object_end(reply);
    return 200;
}

/* ------------------------------------------------------------ /command */

typedef struct xgo_host_view_write_s {
    uint8_t addr;
    uint8_t n;
    uint8_t data[XGO_FRAME_MAX_DATA];
} xgo_host_view_write_t;

/* 48, "0x30" or "vx" (a register name from the core's table). */
static int xgo_host_view_api_addr(xgo_host_json_span_t v, uint8_t *addr)
{
    char text[24];
    int64_t number;
    size_t i;
    if (xgo_host_json_whole(v, 0, 255, &number)) {
        *addr = (uint8_t)number;
        return 1;
    }
    if (!xgo_host_json_ascii(v, text, sizeof text)) {
        return 0;
    }
    if (text[0] == '0' && (text[1] == 'x' || text[1] == 'X') && text[2] != '\0' &&
        strspn(text + 2, "0123456789abcdefABCDEF") == strlen(text + 2) && strlen(text + 2) <= 2) {
        unsigned value = 0;
        sscanf(text + 2, "%x", &value);
        *addr = (uint8_t)value;
        return 1;
    }
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        if (strcmp(d->name, text) == 0) {
            *addr = d->addr;
            return 1;
        }
    }
    return 0;
}

/* "data": [0..255, ...], 1..XGO_FRAME_MAX_DATA bytes. */
static int xgo_host_view_api_data(xgo_host_json_span_t v, xgo_host_view_write_t *w)
{
    xgo_host_json_cursor_t c;
    xgo_host_json_span_t e;
    size_t n = 0;
    if (xgo_host_json_type(v) != XGO_HOST_JSON_ARRAY) {
        return 0;
    }
    xgo_host_json_enter(v, &c);
    while (xgo_host_json_next_element(&c, &e)) {
        int64_t byte;
        if (n == XGO_FRAME_MAX_DATA || !xgo_host_json_whole(e, 0, 255, &byte)) {
            return 0;
        }
        w->data[n++] = (uint8_t)byte;
    }
    w->n = (uint8_t)n;
    return n > 0;
}

static int xgo_host_view_api_write(xgo_host_json_span_t v, size_t index, xgo_host_view_write_t *w,
                                   xgo_host_json_t *reply)
{
    xgo_host_json_cursor_t c;
    xgo_host_json_span_t name, value;
    int has_addr = 0, has_data = 0;
    char at[24];
    snprintf(at, sizeof at, "writes[%lu]", (unsigned long)index);
    if (xgo_host_json_type(v) != XGO_HOST_JSON_OBJECT) {
        return xgo_host_view_api_refuse(reply, "%s must be {\"addr\":A,\"data\":[...]}", at, NULL);
    }
    xgo_host_json_enter(v, &c);
    while (xgo_host_json_next_member(&c, &name, &value)) {
        if (xgo_host_json_name_is(name, "addr") && !has_addr) {
            has_addr = 1;
            if (!xgo_host_view_api_addr(value, &w->addr)) {
                return xgo_host_view_api_refuse(
                    reply, "%s.addr must be 0..255, \"0xHH\" or a register name", at, NULL);
            }
        } else if (xgo_host_json_name_is(name, "data") && !has_data) {
            has_data = 1;
            if (!xgo_host_view_api_data(value, w)) {
                return xgo_host_view_api_refuse(reply, "%s.data must be 1..247 numbers 0..255",
                                                at, NULL);
            }
        } else {
            return xgo_host_view_api_refuse(reply, "%s: unexpected or repeated field", at, NULL);
        }
    }
    if (!has_addr || !has_data) {
        return xgo_host_view_api_refuse(reply, "%s needs addr and data", at, NULL);
    }
    return 200;
}

/* The "writes" array of the body into writes[]; 200 or 400. */
static int xgo_host_view_api_writes(xgo_host_json_span_t root, xgo_host_view_write_t *writes,
                                    size_t *count, xgo_host_json_t *reply)
{
    xgo_host_json_cursor_t c, a;
    xgo_host_json_span_t name, value, e;
    int status = 200;
    *count = 0;
    xgo_host_json_enter(root, &c);
    if (!xgo_host_json_next_member(&c, &name, &value) || !xgo_host_json_name_is(name, "writes") ||
        xgo_host_json_next_member(&c, &name, &value) ||
        xgo_host_json_type(value) != XGO_HOST_JSON_ARRAY) {
        return xgo_host_view_api_refuse_why(reply, "body must be {\"writes\":[...]}");
    }
    xgo_host_json_enter(value, &a);
    while (status == 200 && xgo_host_json_next_element(&a, &e)) {
        if (*count == XGO_HOST_VIEW_MAX_WRITES) {
            return xgo_host_view_api_refuse_why(reply, "at most 32 writes per request");
        }
        status = xgo_host_view_api_write(e, *count, &writes[*count], reply);
        (*count)++;
    }
    if (status == 200 && *count == 0) {
        return xgo_host_view_api_refuse_why(reply, "writes is empty");
    }
    return status;
}

int xgo_host_view_api_command(xgo_board_t *b, const char *body, size_t n, xgo_host_json_t *reply)
{
    static xgo_host_view_write_t writes[XGO_HOST_VIEW_MAX_WRITES]; /* 8 KB: not on the stack */
    xgo_host_json_span_t root;
    size_t count, i;
    int status = xgo_host_view_api_object(body, n, &root, reply);
    if (status == 200) {
        status = xgo_host_view_api_writes(root, writes, &count, reply);
    }
    if (status != 200) {
        return status;
    }
    xgo_host_json_object_begin(reply);
    xgo_host_json_key(reply, "results");
    xgo_host_json_array_begin(reply);
    for (i = 0; i < count; i++) {
        xgo_drop_reason_t why =
            xgo_board_write(b, XGO_SOURCE_VIEW, writes[i].addr, writes[i].data, writes[i].n);
        xgo_host_json_object_begin(reply);
        xgo_host_json_key(reply, "addr");
        xgo_host_json_uint(reply, writes[i].addr);
        xgo_host_json_key(reply, "n");
        xgo_host_json_uint(reply, writes[i].n);
        xgo_host_json_key(reply, "result");
        xgo_host_json_string(reply, why == XGO_DROP_NONE ? "ok" : xgo_drop_reason_name(why));
        xgo_host_json_object_end(reply);
    }
    xgo_host_json_array_end(reply);
    xgo_host_json_object_end(reply);
    return 200;
}
