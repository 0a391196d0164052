/* json_check.c - strict JSON checking and path lookups for tests (see json_check.h). */
#include "json_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Each step returns where the parsed item ends, or NULL (with c->why and
 * c->at set) where the text stops being JSON. */
typedef struct json_cursor_s {
    const char *start;
    const char *end;
    const char *why;
    const char *at;
} json_cursor_t;

static const char *fail(json_cursor_t *c, const char *p, const char *why)
{
    if (c->why == NULL) {
        c->why = why;
        c->at = p;
    }
    return NULL;
}

static const char *skip_ws(const json_cursor_t *c, const char *p)
{
    while (p < c->end && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) {
        p++;
    }
    return p;
}

static int is_hex(char ch)
{
    return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f') || (ch >= 'A' && ch <= 'F');
}

/* Length of the UTF-8 sequence at p (well-formed per RFC 3629), 0 if bad. */
static size_t utf8_length(const unsigned char *p, size_t left)
{
    size_t len, i;
    unsigned cp;
    if (p[0] < 0x80) {
        return 1;
    }
    len = (p[0] & 0xE0) == 0xC0 ? 2 : (p[0] & 0xF0) == 0xE0 ? 3 : (p[0] & 0xF8) == 0xF0 ? 4 : 0;
    if (len == 0 || left < len) {
        return 0;
    }
    cp = p[0] & (0x7Fu >> len);
    for (i = 1; i < len; i++) {
        if ((p[i] & 0xC0) != 0x80) {
            return 0;
        }
        cp = (cp << 6) | (p[i] & 0x3Fu);
    }
    if ((len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) ||
        cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
        return 0; /* overlong, beyond Unicode, or a surrogate */
    }
    return len;
}

static const char *parse_string(json_cursor_t *c, const char *p)
{
    for (p++; p < c->end; ) {
        unsigned char ch = (unsigned char)*p;
        size_t len;
        if (ch == '"') {
            return p + 1;
        }
        if (ch < 0x20) {
            return fail(c, p, "raw control character in a string");
        }
        if (ch == '\\') {
            if (p + 1 >= c->end) {
                break;
            }
            if (p[1] == 'u') {
                if (c->end - p < 6 || !is_hex(p[2]) || !is_hex(p[3]) || !is_hex(p[4]) ||
                    !is_hex(p[5])) {
                    return fail(c, p, "bad \\u escape");
                }
                p += 6;
                continue;
            }
            if (strchr("\"\\/bfnrt", p[1]) == NULL || p[1] == '\0') {
                return fail(c, p, "bad escape");
            }
            p += 2;
            continue;
        }
        len = utf8_length((const unsigned char *)p, (size_t)(c->end - p));
        if (len == 0) {
            return fail(c, p, "bad UTF-8");
        }
        p += len;
    }
    return fail(c, p, "string not closed");
}

static const char *parse_digits(json_cursor_t *c, const char *p)
{
    if (p >= c->end || *p < '0' || *p > '9') {
        return fail(c, p, "digit expected");
    }
    while (p < c->end && *p >= '0' && *p <= '9') {
        p++;
    }
    return p;
}

static const char *parse_number(json_cursor_t *c, const char *p)
{
    if (*p == '-') {
        p++;
    }
    if (p < c->end && *p == '0') {
        p++;
    } else if ((p = parse_digits(c, p)) == NULL) {
        return NULL;
    }
    if (p < c->end && *p == '.' && (p = parse_digits(c, p + 1)) == NULL) {
        return NULL;
    }
    if (p < c->end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < c->end && (*p == '+' || *p == '-')) {
            p++;
        }
        return parse_digits(c, p);
    }
    return p;
}

static const char *parse_value(json_cursor_t *c, const char *p, int depth);

/* Objects and arrays: `close` is '}' or ']'. */
static const char *parse_container(json_cursor_t *c, const char *p, int depth, char close)
{
    if (depth > 64) {
        return fail(c, p, "nested too deeply");
    }
    p = skip_ws(c, p + 1);
    if (p < c->end && *p == close) {
        return p + 1;
    }
    for (;;) {
        if (close == '}') {
            if (p >= c->end || *p != '"' || (p = parse_string(c, p)) == NULL) {
                return fail(c, p, "member name expected");
            }
            p = skip_ws(c, p);
            if (p >= c->end || *p != ':') {
                return fail(c, p, "':' expected");
            }
            p++;
        }
        if ((p = parse_value(c, p, depth + 1)) == NULL) {
            return NULL;
        }
        p = skip_ws(c, p);
        if (p < c->end && *p == close) {
            return p + 1;
        }
        if (p >= c->end || *p != ',') {
            return fail(c, p, "',' or end of container expected");
        }
        p = skip_ws(c, p + 1);
    }
}

static const char *parse_value(json_cursor_t *c, const char *p, int depth)
{
    static const char *const k_words[] = {"true", "false", "null"};
    size_t i;
    p = skip_ws(c, p);
    if (p >= c->end) {
        return fail(c, p, "value expected");
    }
    if (*p == '{' || *p == '[') {
        return parse_container(c, p, depth, *p == '{' ? '}' : ']');
    }
    if (*p == '"') {
        return parse_string(c, p);
    }
    if (*p == '-' || (*p >= '0' && *p <= '9')) {
        return parse_number(c, p);
    }
    for (i = 0; i < 3; i++) {
        size_t n = strlen(k_words[i]);
        if ((size_t)(c->end - p) >= n && memcmp(p, k_words[i], n) == 0) {
            return p + n;
        }
    }
    return fail(c, p, "not a JSON value");
}

int xgo_test_json_valid(const char *text, size_t n, char *why, size_t why_size)
{
    json_cursor_t c;
    const char *p;
    c.start = text;
    c.end = text + n;
    c.why = NULL;
    c.at = text;
    p = parse_value(&c, text, 0);
    if (p != NULL && skip_ws(&c, p) != c.end) {
        fail(&c, skip_ws(&c, p), "text after the value");
        p = NULL;
    }
    if (p == NULL) {
        snprintf(why, why_size, "%s at offset %ld", c.why, (long)(c.at - text));
        return 0;
    }
    return 1;
}

/* ------------------------------------------------------------ lookups */

/* The value at path in checked, NUL-terminated text; NULL if absent. */
static const char *find(const char *text, const char *path)
{
    json_cursor_t c;
    const char *p;
    c.start = text;
    c.end = text + strlen(text);
    c.why = NULL;
    p = skip_ws(&c, text);
    while (*path != '\0') {
        const char *dot = strchr(path, '.');
        size_t seg = dot != NULL ? (size_t)(dot - path) : strlen(path);
        long index = *p == '[' ? strtol(path, NULL, 10) : -1;
        if (*p != '{' && *p != '[') {
            return NULL;
        }
        p = skip_ws(&c, p + 1);
        for (;;) {
            int match;
            if (*p == '}' || *p == ']') {
                return NULL;
            }
            if (index < 0) {
                const char *name = p + 1;
                p = parse_string(&c, p);
                match = (size_t)(p - 1 - name) == seg && memcmp(name, path, seg) == 0;
                p = skip_ws(&c, skip_ws(&c, p) + 1); /* past ':' */
            } else {
                match = index-- == 0;
            }
            if (match) {
                break;
            }
            p = skip_ws(&c, parse_value(&c, p, 0));
            p = skip_ws(&c, p + 1); /* past ',' */
        }
        path += seg + (dot != NULL);
    }
    return p;
}

int xgo_test_json_number(const char *text, const char *path, double *out)
{
    const char *p = find(text, path);
    char *end;
    if (p == NULL || (*p != '-' && (*p < '0' || *p > '9'))) {
        return 0;
    }
    *out = strtod(p, &end);
    return end != p;
}

int xgo_test_json_string(const char *text, const char *path, char *out, size_t out_size)
{
    const char *p = find(text, path);
    size_t n = 0;
    if (p == NULL || *p != '"') {
        return 0;
    }
    for (p++; *p != '"'; p++) {
        if (*p == '\\' && (p[1] == '"' || p[1] == '\\' || p[1] == '/')) {
            p++;
        }
        if (n + 1 >= out_size) {
            return 0;
        }
        out[n++] = *p;
    }
    out[n] = '\0';
    return 1;
}

long xgo_test_json_count(const char *text, const char *path)
{
    json_cursor_t c;
    const char *p = find(text, path);
    long n = 0;
    int object;
    if (p == NULL || (*p != '[' && *p != '{')) {
        return -1;
    }
    c.start = text;
    c.end = text + strlen(text);
    c.why = NULL;
    object = *p == '{';
    p = skip_ws(&c, p + 1);
    while (*p != ']' && *p != '}') {
        if (object) {
            p = skip_ws(&c, parse_string(&c, p)) + 1; /* the name and its ':' */
        }
        p = skip_ws(&c, parse_value(&c, p, 0));
        n++;
        if (*p == ',') {
            p = skip_ws(&c, p + 1);
        }
    }
    return n;
}

int xgo_test_json_is_true(const char *text, const char *path)
{
    const char *p = find(text, path);
    return p != NULL && strncmp(p, "true", 4) == 0;
}
