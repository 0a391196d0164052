/*
 * json_in.h - reading the small JSON bodies of the view server's POST
 * requests (/input, /command), strictly and without allocation.
 *
 * Two steps, so a request is either understood whole or refused whole:
 *   1. xgo_host_json_parse() checks that the text is exactly one JSON value
 *      (RFC 8259: number grammar, string escapes, UTF-8, nesting at most
 *      XGO_HOST_JSON_IN_MAX_DEPTH) and says where and why it is not;
 *   2. on checked text, cursors walk objects and arrays, and the getters turn
 *      values into integers or fixed-point numbers (no floating point, so
 *      "2.5" degrees is exactly 2500 mdeg) with range checks.
 * Values are spans into the caller's text; nothing is copied until asked.
 * Pure: no I/O, no allocation, no globals.
 */
#ifndef XGO_HOST_JSON_IN_H
#define XGO_HOST_JSON_IN_H

#include <stddef.h>
#include <stdint.h>

#define XGO_HOST_JSON_IN_MAX_DEPTH 16u

typedef enum xgo_host_json_type_e {
    XGO_HOST_JSON_INVALID = 0,
    XGO_HOST_JSON_OBJECT,
    XGO_HOST_JSON_ARRAY,
    XGO_HOST_JSON_STRING,
    XGO_HOST_JSON_NUMBER,
    XGO_HOST_JSON_TRUE,
    XGO_HOST_JSON_FALSE,
    XGO_HOST_JSON_NULL
} xgo_host_json_type_t;

/* One value's text, [start, end). For a member name: the characters
 * between the quotes, undecoded. */
typedef struct xgo_host_json_span_s {
    const char *start;
    const char *end;
} xgo_host_json_span_t;

/* Checks text[0..n). Returns 1 and sets *root (whitespace around it
 * excluded), or 0 and sets *error_at (offset of the offending byte) and
 * *error (a short static message such as "bad escape in string"). */
int xgo_host_json_parse(const char *text, size_t n, xgo_host_json_span_t *root, size_t *error_at,
                        const char **error);

/* Type of a checked value (from its first character). */
xgo_host_json_type_t xgo_host_json_type(xgo_host_json_span_t v);

/* Walking a checked object or array. */
typedef struct xgo_host_json_cursor_s {
    const char *p;
    const char *end;
} xgo_host_json_cursor_t;

/* Start at the first member/element of a checked object/array. */
void xgo_host_json_enter(xgo_host_json_span_t container, xgo_host_json_cursor_t *c);
/* Next member: 1 with its name and value, 0 at the end. */
int xgo_host_json_next_member(xgo_host_json_cursor_t *c, xgo_host_json_span_t *name,
                              xgo_host_json_span_t *value);
/* Next element: 1 with its value, 0 at the end. */
int xgo_host_json_next_element(xgo_host_json_cursor_t *c, xgo_host_json_span_t *value);

/* A member name (span from next_member) equals `literal` exactly. Names
 * written with escapes never match (none of ours needs one). */
int xgo_host_json_name_is(xgo_host_json_span_t name, const char *literal);

/* A number as value * 10^scale (scale 0..6), rounded half away from zero;
 * 1 and *out when it is a number within lo..hi (in the scaled unit), else 0.
 * ("2.5", 3) -> 2500; ("-1e-4", 3) -> 0; ("45.0004", 3) -> 45000. */
int xgo_host_json_scaled(xgo_host_json_span_t v, unsigned scale, int64_t lo, int64_t hi,
                         int64_t *out);

/* A number that is a whole value (5, 5.0, 5e0) within lo..hi. */
int xgo_host_json_whole(xgo_host_json_span_t v, int64_t lo, int64_t hi, int64_t *out);

/* A string's content into out (NUL-terminated) when it is a string whose
 * decoded text is ASCII without NUL and fits; escapes are decoded. 1 or 0. */
int xgo_host_json_ascii(xgo_host_json_span_t v, char *out, size_t out_size);

#endif /* XGO_HOST_JSON_IN_H */
