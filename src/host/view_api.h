/*
 * view_api.h - the view's two state-changing requests, as functions of a
 * request body (no sockets, so every bad body has an in-process test):
 *
 *   POST /input    {"ground_tilt":{"roll_deg":R,"pitch_deg":P},
 *                   "battery_pct":N, "push":{"roll_deg":R,"pitch_deg":P}}
 *                  any subset; checked whole before anything is applied.
 *   POST /command  {"writes":[{"addr":48 | "0x30" | "vx", "data":[255]}, ...]}
 *                  each write goes through xgo_board_write(XGO_SOURCE_VIEW):
 *                  the same validation, counters and trace as a write frame
 *                  from the wire.
 *
 * Both return the HTTP status (200, or 400 with {"error":"..."} naming the
 * field) and write the reply object into `reply`. docs/view.md has the
 * details and limits.
 */
#ifndef XGO_HOST_VIEW_API_H
#define XGO_HOST_VIEW_API_H

#include <stddef.h>

#include "json_out.h"
#include "xgo/board.h"

/* Most writes in one /command request. */
#define XGO_HOST_VIEW_MAX_WRITES 32u

int xgo_host_view_api_input(xgo_board_t *b, const char *body, size_t n, xgo_host_json_t *reply);

int xgo_host_view_api_command(xgo_board_t *b, const char *body, size_t n, xgo_host_json_t *reply);

/* {"error":"<why>"} */
void xgo_host_view_api_error(xgo_host_json_t *reply, const char *why);

#endif /* XGO_HOST_VIEW_API_H */
