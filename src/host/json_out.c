/* json_out.c - bounded JSON writer (see json_out.h). */
#include "json_out.h"

#include <string.h>

void xgo_host_json_init(xgo_host_json_t *w, char *buf, size_t size)
{
    w->buf = buf;
    w->size = size;
    w->len = 0;
    w->overflow = (size == 0);
    w->depth = 0;
    w->has_member = 0;
    w->after_key = 0;
    if (size > 0) {
        buf[0] = '\0';
    }
}

/* Appends n raw bytes, or marks the writer overflowed (nothing partial). */
static void xgo_host_json_raw(xgo_host_json_t *w, const char *s, size_t n)
{
    if (w->overflow) {
        return;
    }
    if (n >= w->size - w->len) {
        w->overflow = 1;
        return;
    }
    memcpy(w->buf + w->len, s, n);
    w->len += n;
    w->buf[w->len] = '\0';
}

static void xgo_host_json_char(xgo_host_json_t *w, char c)
{
    xgo_host_json_raw(w, &c, 1);
}

/* Before any value or key: the comma that separates it from the previous
 * member of the same container. */
static void xgo_host_json_separate(xgo_host_json_t *w)
{
    uint32_t bit = 1u << w->depth;
    if (w->after_key) {
        w->after_key = 0;
        return;
    }
    if (w->has_member & bit) {
        xgo_host_json_char(w, ',');
    }
    w->has_member |= bit;
}

static void xgo_host_json_open(xgo_host_json_t *w, char c)
{
    xgo_host_json_separate(w);
    if (w->depth + 1 >= XGO_HOST_JSON_MAX_DEPTH) {
        w->overflow = 1;
        return;
    }
    xgo_host_json_char(w, c);
    w->depth++;
    w->has_member &= ~(1u << w->depth);
}

static void xgo_host_json_close(xgo_host_json_t *w, char c)
{
    if (w->depth == 0 || w->after_key) {
        w->overflow = 1; /* unbalanced, or a key without its value */
        return;
    }
    xgo_host_json_char(w, c);
    w->depth--;
}

void xgo_host_json_object_begin(xgo_host_json_t *w)
{
    xgo_host_json_open(w, '{');
}

void xgo_host_json_object_end(xgo_host_json_t *w)
{
    xgo_host_json_close(w, '}');
}

void xgo_host_json_array_begin(xgo_host_json_t *w)
{
    xgo_host_json_open(w, '[');
}

void xgo_host_json_array_end(xgo_host_json_t *w)
{
    xgo_host_json_close(w, ']');
}

void xgo_host_json_key(xgo_host_json_t *w, const char *key)
{
    xgo_host_json_string(w, key);
    xgo_host_json_char(w, ':');
    w->after_key = 1;
}

/* Decimal digits of v, most significant first, into the end of tmp. */
static size_t xgo_host_json_digits(uint64_t v, char *tmp, size_t tmp_size)
{
    size_t n = 0;
    do {
        tmp[tmp_size - 1 - n] = (char)('0' + v % 10u);
        v /= 10u;
        n++;
    } while (v != 0 && n < tmp_size);
    return n;
}

static void xgo_host_json_unsigned_text(xgo_host_json_t *w, int negative, uint64_t magnitude)
{
    char tmp[24];
    size_t n = xgo_host_json_digits(magnitude, tmp, sizeof tmp);
    if (negative) {
        xgo_host_json_char(w, '-');
    }
    xgo_host_json_raw(w, tmp + sizeof tmp - n, n);
}

void xgo_host_json_uint(xgo_host_json_t *w, uint64_t v)
{
    xgo_host_json_separate(w);
    xgo_host_json_unsigned_text(w, 0, v);
}

/* |v| without overflow for INT64_MIN. */
static uint64_t xgo_host_json_magnitude(int64_t v)
{
    return v < 0 ? (uint64_t)(-(v + 1)) + 1u : (uint64_t)v;
}

void xgo_host_json_int(xgo_host_json_t *w, int64_t v)
{
    xgo_host_json_separate(w);
    xgo_host_json_unsigned_text(w, v < 0, xgo_host_json_magnitude(v));
}

void xgo_host_json_bool(xgo_host_json_t *w, int v)
{
    xgo_host_json_separate(w);
    if (v) {
        xgo_host_json_raw(w, "true", 4);
    } else {
        xgo_host_json_raw(w, "false", 5);
    }
}

void xgo_host_json_null(xgo_host_json_t *w)
{
    xgo_host_json_separate(w);
    xgo_host_json_raw(w, "null", 4);
}

static uint64_t xgo_host_json_pow10(unsigned e)
{
    uint64_t p = 1;
    while (e-- > 0) {
        p *= 10u;
    }
    return p;
}

void xgo_host_json_fixed(xgo_host_json_t *w, int64_t value, unsigned scale, unsigned decimals)
{
    uint64_t mag;
    uint64_t drop;
    uint64_t unit;
    uint64_t whole;
    uint64_t frac;
    char tmp[24];
    size_t n;

    if (scale > 9u || decimals > scale) {
        w->overflow = 1; /* a caller bug: make it visible, not silently wrong */
        return;
    }
    xgo_host_json_separate(w);
    drop = xgo_host_json_pow10(scale - decimals);
    unit = xgo_host_json_pow10(decimals);
    mag = xgo_host_json_magnitude(value);
    mag = mag / drop + (drop > 1u && mag % drop >= drop / 2u ? 1u : 0u);
    whole = mag / unit;
    frac = mag % unit;
    xgo_host_json_unsigned_text(w, value < 0 && mag != 0, whole);
    if (decimals == 0) {
        return;
    }
    xgo_host_json_char(w, '.');
    n = xgo_host_json_digits(frac, tmp, sizeof tmp);
    while (n < decimals) {
        tmp[sizeof tmp - 1 - n] = '0';
        n++;
    }
    xgo_host_json_raw(w, tmp + sizeof tmp - n, n);
}

void xgo_host_json_string_n(xgo_host_json_t *w, const char *s, size_t n)
{
    static const char k_hex[] = "0123456789ABCDEF";
    size_t i;
    xgo_host_json_separate(w);
    xgo_host_json_char(w, '"');
    for (i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\') {
            char esc[2];
            esc[0] = '\\';
            esc[1] = (char)c;
            xgo_host_json_raw(w, esc, 2);
        } else if (c < 0x20u || c >= 0x7Fu) {
            char esc[6] = {'\\', 'u', '0', '0', 0, 0};
            esc[4] = k_hex[c >> 4];
            esc[5] = k_hex[c & 0x0Fu];
            xgo_host_json_raw(w, esc, sizeof esc);
        } else {
            xgo_host_json_char(w, (char)c);
        }
    }
    xgo_host_json_char(w, '"');
}

void xgo_host_json_string(xgo_host_json_t *w, const char *s)
{
    xgo_host_json_string_n(w, s, strlen(s));
}

void xgo_host_json_hex(xgo_host_json_t *w, const uint8_t *bytes, size_t n)
{
    static const char k_hex[] = "0123456789ABCDEF";
    size_t i;
    xgo_host_json_separate(w);
    xgo_host_json_char(w, '"');
    for (i = 0; i < n; i++) {
        char pair[2];
        pair[0] = k_hex[bytes[i] >> 4];
        pair[1] = k_hex[bytes[i] & 0x0Fu];
        xgo_host_json_raw(w, pair, 2);
    }
    xgo_host_json_char(w, '"');
}

void xgo_host_json_value_text(xgo_host_json_t *w, const char *text, size_t n)
{
    xgo_host_json_separate(w);
    xgo_host_json_raw(w, text, n);
}

int xgo_host_json_ok(const xgo_host_json_t *w)
{
    return !w->overflow && w->depth == 0 && !w->after_key && w->len > 0;
}
