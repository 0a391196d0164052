/* json_in.c - strict JSON checking and reading (see json_in.h). */
#include "json_in.h"

#include <string.h>

/* ------------------------------------------------------------ checking */

typedef struct xgo_host_json_scan_s {
    const char *p;
    const char *end;
    const char *error; /* first failure wins */
    const char *error_p;
} xgo_host_json_scan_t;

static int xgo_host_json_fail(xgo_host_json_scan_t *s, const char *why)
{
    if (s->error == NULL) {
        s->error = why;
        s->error_p = s->p;
    }
    return 0;
}

static void xgo_host_json_ws(xgo_host_json_scan_t *s)
{
    while (s->p < s->end && (*s->p == ' ' || *s->p == '\t' || *s->p == '\n' || *s->p == '\r')) {
        s->p++;
    }
}

static int xgo_host_json_peek(const xgo_host_json_scan_t *s)
{
    return s->p < s->end ? (unsigned char)*s->p : -1;
}

static int xgo_host_json_is_digit(int c)
{
    return c >= '0' && c <= '9';
}

static int xgo_host_json_hex_value(int c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

/* Four hex digits after "\u" (s->p at the first); -1 if malformed. */
static long xgo_host_json_hex4(const char *p, const char *end)
{
    long v = 0;
    int i;
    if (end - p < 4) {
        return -1;
    }
    for (i = 0; i < 4; i++) {
        int h = xgo_host_json_hex_value((unsigned char)p[i]);
        if (h < 0) {
            return -1;
        }
        v = v * 16 + h;
    }
    return v;
}

/* One escape after the backslash (s->p at the letter). Surrogates must
 * come in pairs: a lone half is not a character. */
static int xgo_host_json_escape(xgo_host_json_scan_t *s)
{
    long u;
    int c = xgo_host_json_peek(s);
    if (c != 'u') {
        if (c < 0 || strchr("\"\\/bfnrt", c) == NULL) {
            return xgo_host_json_fail(s, "bad escape in string");
        }
        s->p++;
        return 1;
    }
    u = xgo_host_json_hex4(s->p + 1, s->end);
    if (u < 0 || (u >= 0xDC00 && u <= 0xDFFF)) {
        return xgo_host_json_fail(s, "bad \\u escape in string");
    }
    s->p += 5;
    if (u >= 0xD800 && u <= 0xDBFF) {
        long low = (s->end - s->p >= 6 && s->p[0] == '\\' && s->p[1] == 'u')
                       ? xgo_host_json_hex4(s->p + 2, s->end)
                       : -1;
        if (low < 0xDC00 || low > 0xDFFF) {
            return xgo_host_json_fail(s, "unpaired surrogate in string");
        }
        s->p += 6;
    }
    return 1;
}

/* One UTF-8 sequence starting with a byte >= 0x80 (RFC 3629: no overlong
 * forms, no surrogates, nothing above U+10FFFF). */
static int xgo_host_json_utf8(xgo_host_json_scan_t *s)
{
    const unsigned char *u = (const unsigned char *)s->p;
    size_t left = (size_t)(s->end - s->p);
    unsigned char lo = 0x80, hi = 0xBF;
    size_t more, i;
    if (u[0] >= 0xC2 && u[0] <= 0xDF) {
        more = 1;
    } else if (u[0] >= 0xE0 && u[0] <= 0xEF) {
        more = 2;
        lo = u[0] == 0xE0 ? 0xA0 : 0x80;
        hi = u[0] == 0xED ? 0x9F : 0xBF;
    } else if (u[0] >= 0xF0 && u[0] <= 0xF4) {
        more = 3;
        lo = u[0] == 0xF0 ? 0x90 : 0x80;
        hi = u[0] == 0xF4 ? 0x8F : 0xBF;
    } else {
        return xgo_host_json_fail(s, "invalid UTF-8 in string");
    }
    if (left <= more || u[1] < lo || u[1] > hi) {
        return xgo_host_json_fail(s, "invalid UTF-8 in string");
    }
    for (i = 2; i <= more; i++) {
        if (u[i] < 0x80 || u[i] > 0xBF) {
            return xgo_host_json_fail(s, "invalid UTF-8 in string");
        }
    }
    s->p += more + 1;
    return 1;
}

static int xgo_host_json_check_string(xgo_host_json_scan_t *s)
{
    s->p++; /* the opening quote */
    for (;;) {
        int c = xgo_host_json_peek(s);
        if (c < 0) {
            return xgo_host_json_fail(s, "unterminated string");
        }
        if (c == '"') {
            s->p++;
            return 1;
        }
        if (c < 0x20) {
            return xgo_host_json_fail(s, "control character in string");
        }
        if (c == '\\') {
            s->p++;
            if (!xgo_host_json_escape(s)) {
                return 0;
            }
        } else if (c >= 0x80) {
            if (!xgo_host_json_utf8(s)) {
                return 0;
            }
        } else {
            s->p++;
        }
    }
}

static int xgo_host_json_digits(xgo_host_json_scan_t *s)
{
    if (!xgo_host_json_is_digit(xgo_host_json_peek(s))) {
        return xgo_host_json_fail(s, "digit expected in number");
    }
    while (xgo_host_json_is_digit(xgo_host_json_peek(s))) {
        s->p++;
    }
    return 1;
}

/* -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)? */
static int xgo_host_json_check_number(xgo_host_json_scan_t *s)
{
    if (xgo_host_json_peek(s) == '-') {
        s->p++;
    }
    if (xgo_host_json_peek(s) == '0') {
        s->p++;
        if (xgo_host_json_is_digit(xgo_host_json_peek(s))) {
            return xgo_host_json_fail(s, "leading zero in number");
        }
    } else if (!xgo_host_json_digits(s)) {
        return 0;
    }
    if (xgo_host_json_peek(s) == '.') {
        s->p++;
        if (!xgo_host_json_digits(s)) {
            return 0;
        }
    }
    if (xgo_host_json_peek(s) == 'e' || xgo_host_json_peek(s) == 'E') {
        s->p++;
        if (xgo_host_json_peek(s) == '+' || xgo_host_json_peek(s) == '-') {
            s->p++;
        }
        return xgo_host_json_digits(s);
    }
    return 1;
}

static int xgo_host_json_check_literal(xgo_host_json_scan_t *s, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(s->end - s->p) < n || memcmp(s->p, word, n) != 0) {
        return xgo_host_json_fail(s, "unexpected character");
    }
    s->p += n;
    return 1;
}

static int xgo_host_json_check_value(xgo_host_json_scan_t *s, unsigned depth);

/* An object or array: members/elements separated by commas, no trailing
 * comma. */
static int xgo_host_json_check_container(xgo_host_json_scan_t *s, unsigned depth, char close)
{
    if (depth >= XGO_HOST_JSON_IN_MAX_DEPTH) {
        return xgo_host_json_fail(s, "nested too deeply");
    }
    s->p++;
    xgo_host_json_ws(s);
    if (xgo_host_json_peek(s) == close) {
        s->p++;
        return 1;
    }
    for (;;) {
        if (close == '}') {
            if (xgo_host_json_peek(s) != '"') {
                return xgo_host_json_fail(s, "member name expected");
            }
            if (!xgo_host_json_check_string(s)) {
                return 0;
            }
            xgo_host_json_ws(s);
            if (xgo_host_json_peek(s) != ':') {
                return xgo_host_json_fail(s, "':' expected");
            }
            s->p++;
        }
        if (!xgo_host_json_check_value(s, depth + 1)) {
            return 0;
        }
        xgo_host_json_ws(s);
        if (xgo_host_json_peek(s) == close) {
            s->p++;
            return 1;
        }
        if (xgo_host_json_peek(s) != ',') {
            return xgo_host_json_fail(s, close == '}' ? "',' or '}' expected" : "',' or ']' expected");
        }
        s->p++;
        xgo_host_json_ws(s);
    }
}

static int xgo_host_json_check_value(xgo_host_json_scan_t *s, unsigned depth)
{
    int c;
    xgo_host_json_ws(s);
    c = xgo_host_json_peek(s);
    switch (c) {
    case '{':
        return xgo_host_json_check_container(s, depth, '}');
    case '[':
        return xgo_host_json_check_container(s, depth, ']');
    case '"':
        return xgo_host_json_check_string(s);
    case 't':
        return xgo_host_json_check_literal(s, "true");
    case 'f':
        return xgo_host_json_check_literal(s, "false");
    case 'n':
        return xgo_host_json_check_literal(s, "null");
    case -1:
        return xgo_host_json_fail(s, "value expected");
    default:
        if (c == '-' || xgo_host_json_is_digit(c)) {
            return xgo_host_json_check_number(s);
        }
        return xgo_host_json_fail(s, "unexpected character");
    }
}

int xgo_host_json_parse(const char *text, size_t n, xgo_host_json_span_t *root, size_t *error_at,
                        const char **error)
{
    xgo_host_json_scan_t s;
    const char *start;
    s.p = text;
    s.end = text + n;
    s.error = NULL;
    s.error_p = text;
    xgo_host_json_ws(&s);
    start = s.p;
    if (xgo_host_json_check_value(&s, 0)) {
        root->start = start;
        root->end = s.p;
        xgo_host_json_ws(&s);
        if (s.p == s.end) {
            return 1;
        }
        xgo_host_json_fail(&s, "text after the value");
    }
    *error_at = (size_t)(s.error_p - text);
    *error = s.error;
    return 0;
}

/* ------------------------------------------------------ walking checked text */

xgo_host_json_type_t xgo_host_json_type(xgo_host_json_span_t v)
{
    if (v.start >= v.end) {
        return XGO_HOST_JSON_INVALID;
    }
    switch (*v.start) {
    case '{':
        return XGO_HOST_JSON_OBJECT;
    case '[':
        return XGO_HOST_JSON_ARRAY;
    case '"':
        return XGO_HOST_JSON_STRING;
    case 't':
        return XGO_HOST_JSON_TRUE;
    case 'f':
        return XGO_HOST_JSON_FALSE;
    case 'n':
        return XGO_HOST_JSON_NULL;
    default:
        return XGO_HOST_JSON_NUMBER;
    }
}

/* End of the checked string starting at p (its opening quote). */
static const char *xgo_host_json_skip_string(const char *p, const char *end)
{
    for (p++; p < end && *p != '"'; p++) {
        if (*p == '\\') {
            p++; /* the escaped character; \u's hex digits hold no quote */
        }
    }
    return p < end ? p + 1 : end;
}

/* End of the checked value starting at p. */
static const char *xgo_host_json_skip_value(const char *p, const char *end)
{
    unsigned depth = 0;
    if (*p == '"') {
        return xgo_host_json_skip_string(p, end);
    }
    if (*p != '{' && *p != '[') {
        while (p < end && strchr(",]} \t\r\n", *p) == NULL) {
            p++;
        }
        return p;
    }
    while (p < end) {
        if (*p == '"') {
            p = xgo_host_json_skip_string(p, end);
            continue;
        }
        if (*p == '{' || *p == '[') {
            depth++;
        } else if (*p == '}' || *p == ']') {
            if (--depth == 0) {
                return p + 1;
            }
        }
        p++;
    }
    return end;
}

/* Skips whitespace and one separating comma. */
static void xgo_host_json_cursor_skip(xgo_host_json_cursor_t *c)
{
    while (c->p < c->end && strchr(" \t\r\n,", *c->p) != NULL) {
        c->p++;
    }
}

void xgo_host_json_enter(xgo_host_json_span_t container, xgo_host_json_cursor_t *c)
{
    c->p = container.start + 1;
    c->end = container.end - 1; /* the closing bracket */
}

int xgo_host_json_next_element(xgo_host_json_cursor_t *c, xgo_host_json_span_t *value)
{
    xgo_host_json_cursor_skip(c);
    if (c->p >= c->end) {
        return 0;
    }
    value->start = c->p;
    value->end = xgo_host_json_skip_value(c->p, c->end);
    c->p = value->end;
    return 1;
}

int xgo_host_json_next_member(xgo_host_json_cursor_t *c, xgo_host_json_span_t *name,
                              xgo_host_json_span_t *value)
{
    xgo_host_json_cursor_skip(c);
    if (c->p >= c->end) {
        return 0;
    }
    name->start = c->p + 1;
    c->p = xgo_host_json_skip_string(c->p, c->end);
    name->end = c->p - 1;
    while (c->p < c->end && *c->p != ':') {
        c->p++;
    }
    c->p++;
    while (c->p < c->end && strchr(" \t\r\n", *c->p) != NULL) {
        c->p++;
    }
    return xgo_host_json_next_element(c, value);
}

int xgo_host_json_name_is(xgo_host_json_span_t name, const char *literal)
{
    size_t n = strlen(literal);
    return (size_t)(name.end - name.start) == n && memcmp(name.start, literal, n) == 0;
}

/* ------------------------------------------------------------- numbers */

/* Decimal digits kept from a mantissa; later ones only refine rounding
 * beyond anything our ranges can see. */
#define XGO_HOST_JSON_MAX_DIGITS 18

/* Magnitude bound for scaled results: far beyond every range we check,
 * far below overflow. */
#define XGO_HOST_JSON_MAX_MAGNITUDE 1000000000000000LL

typedef struct xgo_host_json_decimal_s {
    int negative;
    uint64_t mantissa; /* significant digits kept */
    long exp10;        /* value = mantissa * 10^exp10 */
} xgo_host_json_decimal_t;

static const char *xgo_host_json_mantissa(const char *p, const char *end, xgo_host_json_decimal_t *d)
{
    int digits = 0;
    int fraction = 0;
    for (; p < end && (xgo_host_json_is_digit(*p) || *p == '.'); p++) {
        if (*p == '.') {
            fraction = 1;
            continue;
        }
        if (d->mantissa == 0 && *p == '0') {
            d->exp10 -= fraction; /* leading zeros: no digit kept */
            continue;
        }
        if (digits < XGO_HOST_JSON_MAX_DIGITS) {
            d->mantissa = d->mantissa * 10u + (uint64_t)(*p - '0');
            digits++;
            d->exp10 -= fraction;
        } else if (!fraction) {
            d->exp10++; /* an integer digit dropped: one more power of ten */
        }
    }
    return p;
}

/* Splits a checked number into sign, kept digits and exponent. */
static void xgo_host_json_decimal(xgo_host_json_span_t v, xgo_host_json_decimal_t *d)
{
    const char *p = v.start;
    long e = 0;
    int e_negative = 0;
    d->negative = (*p == '-');
    d->mantissa = 0;
    d->exp10 = 0;
    p = xgo_host_json_mantissa(p + d->negative, v.end, d);
    if (p < v.end && (*p == 'e' || *p == 'E')) {
        p++;
        e_negative = (*p == '-');
        if (*p == '-' || *p == '+') {
            p++;
        }
        for (; p < v.end && xgo_host_json_is_digit(*p); p++) {
            if (e < 100000) {
                e = e * 10 + (*p - '0'); /* huge exponents saturate */
            }
        }
    }
    d->exp10 += e_negative ? -e : e;
}

/* mantissa * 10^(exp10 + scale), rounded; 0 when beyond the bound. */
static int xgo_host_json_decimal_scale(const xgo_host_json_decimal_t *d, unsigned scale,
                                       int64_t *out, int *exact)
{
    long e = d->exp10 + (long)scale;
    uint64_t m = d->mantissa;
    *exact = 1;
    for (; e > 0 && m != 0; e--) {
        if (m > (uint64_t)XGO_HOST_JSON_MAX_MAGNITUDE) {
            return 0;
        }
        m *= 10u;
    }
    for (; e < 0 && m != 0; e++) {
        uint64_t digit = m % 10u;
        m /= 10u;
        if (digit != 0) {
            *exact = 0;
        }
        if (e == -1 && digit >= 5u) {
            m++; /* half away from zero, on the last division */
        }
    }
    if (m > (uint64_t)XGO_HOST_JSON_MAX_MAGNITUDE) {
        return 0;
    }
    *out = d->negative ? -(int64_t)m : (int64_t)m;
    return 1;
}

int xgo_host_json_scaled(xgo_host_json_span_t v, unsigned scale, int64_t lo, int64_t hi,
                         int64_t *out)
{
    xgo_host_json_decimal_t d;
    int64_t value;
    int exact;
    if (xgo_host_json_type(v) != XGO_HOST_JSON_NUMBER || scale > 6u) {
        return 0;
    }
    xgo_host_json_decimal(v, &d);
    if (!xgo_host_json_decimal_scale(&d, scale, &value, &exact) || value < lo || value > hi) {
        return 0;
    }
    *out = value;
    return 1;
}

int xgo_host_json_whole(xgo_host_json_span_t v, int64_t lo, int64_t hi, int64_t *out)
{
    xgo_host_json_decimal_t d;
    int64_t value;
    int exact;
    if (xgo_host_json_type(v) != XGO_HOST_JSON_NUMBER) {
        return 0;
    }
    xgo_host_json_decimal(v, &d);
    if (!xgo_host_json_decimal_scale(&d, 0, &value, &exact) || !exact || value < lo ||
        value > hi) {
        return 0;
    }
    *out = value;
    return 1;
}

/* ------------------------------------------------------------- strings */

int xgo_host_json_ascii(xgo_host_json_span_t v, char *out, size_t out_size)
{
    const char *p = v.start + 1;
    const char *end = v.end - 1; /* the closing quote */
    size_t n = 0;
    if (xgo_host_json_type(v) != XGO_HOST_JSON_STRING || out_size == 0) {
        return 0;
    }
    while (p < end) {
        long c = (unsigned char)*p++;
        if (c == '\\') {
            static const char k_from[] = "\"\\/bfnrt";
            static const char k_to[] = "\"\\/\b\f\n\r\t";
            const char *hit = strchr(k_from, *p);
            if (*p == 'u') {
                c = xgo_host_json_hex4(p + 1, end);
                p += 5;
            } else {
                c = k_to[hit - k_from];
                p++;
            }
        }
        if (c <= 0 || c >= 0x80 || n + 1 >= out_size) {
            return 0;
        }
        out[n++] = (char)c;
    }
    out[n] = '\0';
    return 1;
}
