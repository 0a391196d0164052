/*
 * view_meta.h - GET /meta: the constant facts the view page labels and
 * scales with (register table, action names, modes, gaits, paces, joint
 * limits, leg geometry, register ranges), from the core's own tables.
 */
#ifndef XGO_HOST_VIEW_META_H
#define XGO_HOST_VIEW_META_H

#include "json_out.h"
#include "xgo/board.h"

/* Writes the /meta object for board b, initialised for model (xgo_model_t). */
void xgo_host_view_meta(xgo_host_json_t *w, const xgo_board_t *b, unsigned model);

#endif /* XGO_HOST_VIEW_META_H */
