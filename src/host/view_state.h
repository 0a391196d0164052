/*
 * view_state.h - the state object of GET /state and of every GET /events
 * event (docs/view.md lists every field): the board seen through the
 * observer functions of xgo/board.h, plus the frames a client has not been
 * sent yet. One place owns the JSON layout, so /state and /events can never
 * disagree.
 */
#ifndef XGO_HOST_VIEW_STATE_H
#define XGO_HOST_VIEW_STATE_H

#include <stdint.h>

#include "json_out.h"
#include "view_frames.h"
#include "xgo/board.h"

/* Frames sent in one state object at most; earlier ones since the last
 * object are counted in "frames_omitted". */
#define XGO_HOST_VIEW_FRAMES_PER_EVENT 64u

/* Opens the object and writes every member before "frames". model:
 * "mini" or "lite". */
void xgo_host_view_state_open(xgo_host_json_t *w, const xgo_board_t *b, uint64_t seq,
                              int host_connected, const char *model);

/* Name of a value of the mode register ("whole unit", ...). */
const char *xgo_host_view_mode_name(uint8_t mode);

/* "joint_limits_deg": [[lo, hi] x 12] in degrees with `decimals` decimals
 * (/state: 2, like the angles; /meta: 3, the limits' own resolution). */
void xgo_host_view_joint_limits(xgo_host_json_t *w, const xgo_board_t *b, unsigned decimals);

/* Writes "frames" (the events from *cursor on, at most
 * XGO_HOST_VIEW_FRAMES_PER_EVENT, the newest kept), "frames_omitted" and
 * the closing brace, and moves *cursor past the newest event. */
void xgo_host_view_state_close(xgo_host_json_t *w, xgo_host_view_frames_t *f, uint64_t *cursor);

/* Renders the JSON object of up to `budget` events among the newest
 * XGO_HOST_VIEW_FRAMES_PER_EVENT that do not have one yet; returns how many
 * it rendered (0: all there). Lets the server spread that work over turns
 * of the loop; xgo_host_view_state_close renders what is still missing. */
unsigned xgo_host_view_state_render(xgo_host_view_frames_t *f, unsigned budget);

/* Where a new client's cursor starts: the last events already held (up to
 * one object's worth) are new to it, so /state shows recent traffic. */
uint64_t xgo_host_view_state_first_cursor(const xgo_host_view_frames_t *f);

#endif /* XGO_HOST_VIEW_STATE_H */
