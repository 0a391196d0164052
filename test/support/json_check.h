/*
 * json_check.h - a small strict JSON checker for the tests of the view
 * server, written apart from the server's own reader (src/host/json_in.c)
 * so the two cannot share a mistake.
 *
 * xgo_test_json_valid() accepts exactly RFC 8259 JSON text (one value,
 * whitespace around it). The lookups take a checked text and a path of
 * member names and array indexes separated by dots ("world.x_mm",
 * "joints_deg.3", "frames.0.source"; "" is the whole text).
 */
#ifndef XGO_TEST_JSON_CHECK_H
#define XGO_TEST_JSON_CHECK_H

#include <stddef.h>

/* 1 if text[0..n) is valid JSON; else 0 with a reason and offset in why. */
int xgo_test_json_valid(const char *text, size_t n, char *why, size_t why_size);

/* The value at path as a double (a number), 1 when found. */
int xgo_test_json_number(const char *text, const char *path, double *out);

/* The string at path copied into out (escapes other than \" \\ \/ kept as
 * written), 1 when found and it fits. */
int xgo_test_json_string(const char *text, const char *path, char *out, size_t out_size);

/* Elements of the array (or members of the object) at path, -1 if none. */
long xgo_test_json_count(const char *text, const char *path);

/* 1 if the value at path is the literal true. */
int xgo_test_json_is_true(const char *text, const char *path);

#endif /* XGO_TEST_JSON_CHECK_H */
