/*
 * json_out.h - writing JSON text into a caller-owned, fixed-size buffer
 * (the view server's /state and /events bodies, POST replies).
 *
 *     xgo_host_json_t w;
 *     xgo_host_json_init(&w, buf, sizeof buf);
 *     xgo_host_json_object_begin(&w);
 *     xgo_host_json_key(&w, "t_ms");      xgo_host_json_uint(&w, 12345);
 *     xgo_host_json_key(&w, "roll_deg");  xgo_host_json_fixed(&w, -1234, 3, 2); // -1.23
 *     xgo_host_json_object_end(&w);
 *     if (!xgo_host_json_ok(&w)) ... too small or unbalanced
 *
 * Commas are placed by the writer. Output is compact (no spaces, no
 * newlines: an SSE `data:` line must not contain one). Numbers are written
 * from integers only - fixed-point values with a chosen number of decimals -
 * so the text is exact and independent of locale. Strings are escaped so the
 * result is always valid JSON, whatever bytes they hold.
 *
 * Bounded: nothing is written past `size`; a writer that ran out of room
 * stays "overflowed" (xgo_host_json_ok() false) and writes nothing more.
 * Pure: no I/O, no allocation.
 */
#ifndef XGO_HOST_JSON_OUT_H
#define XGO_HOST_JSON_OUT_H

#include <stddef.h>
#include <stdint.h>

/* Deepest nesting the writer tracks; deeper begins overflow the writer. */
#define XGO_HOST_JSON_MAX_DEPTH 16u

typedef struct xgo_host_json_s {
    char *buf;
    size_t size;
    size_t len;          /* text so far; buf[len] is always '\0' */
    int overflow;        /* ran out of room or nesting: the text is unusable */
    unsigned depth;      /* open objects/arrays */
    uint32_t has_member; /* bit d: the container at depth d already holds a value */
    int after_key;       /* a key was written; its value comes next */
} xgo_host_json_t;

/* size must be at least 1 (room for the terminating NUL). */
void xgo_host_json_init(xgo_host_json_t *w, char *buf, size_t size);

void xgo_host_json_object_begin(xgo_host_json_t *w);
void xgo_host_json_object_end(xgo_host_json_t *w);
void xgo_host_json_array_begin(xgo_host_json_t *w);
void xgo_host_json_array_end(xgo_host_json_t *w);

/* A member name inside an object; the next call writes its value. */
void xgo_host_json_key(xgo_host_json_t *w, const char *key);

void xgo_host_json_int(xgo_host_json_t *w, int64_t v);
void xgo_host_json_uint(xgo_host_json_t *w, uint64_t v);
void xgo_host_json_bool(xgo_host_json_t *w, int v);
void xgo_host_json_null(xgo_host_json_t *w);

/* value * 10^-scale written with `decimals` digits after the point
 * (decimals <= scale <= 9), rounded half away from zero: (-1234, 3, 2) is
 * -1.23, (97650, 3, 1) is 97.7, (-4, 3, 2) is 0.00 (no "-0"). */
void xgo_host_json_fixed(xgo_host_json_t *w, int64_t value, unsigned scale, unsigned decimals);

/* A NUL-terminated string, escaped: quote, backslash, control characters
 * and bytes >= 0x7F as \uXXXX (text we write is ASCII; anything else comes
 * out as its Latin-1 code point, never as invalid JSON). */
void xgo_host_json_string(xgo_host_json_t *w, const char *s);
/* The same for n bytes that may hold NUL. */
void xgo_host_json_string_n(xgo_host_json_t *w, const char *s, size_t n);

/* n bytes as a string of 2n upper-case hex digits ("55AA00"). */
void xgo_host_json_hex(xgo_host_json_t *w, const uint8_t *bytes, size_t n);

/* n bytes of text that already are one complete JSON value (written by
 * another writer earlier, e.g. a cached object), placed as the next value. */
void xgo_host_json_value_text(xgo_host_json_t *w, const char *text, size_t n);

/* True when the text is complete: every container closed, nothing cut. */
int xgo_host_json_ok(const xgo_host_json_t *w);

#endif /* XGO_HOST_JSON_OUT_H */
