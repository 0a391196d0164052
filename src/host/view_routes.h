/*
 * view_routes.h - what each view request is answered with (view_routes.c),
 * and the queueing primitive both halves of the server share. Internal to
 * the view server: view_server.c owns the connections, this file the
 * answers.
 */
#ifndef XGO_HOST_VIEW_ROUTES_H
#define XGO_HOST_VIEW_ROUTES_H

#include <stddef.h>
#include <stdint.h>

#include "http.h"
#include "json_out.h"
#include "view_server.h"

/* Answers the complete request at the start of c->in (head parsed into
 * req, body right after it): queues the answer on c, and turns c into an
 * event stream for GET /events. */
void xgo_host_view_route(xgo_host_view_t *v, xgo_host_view_client_t *c,
                         const xgo_host_http_request_t *req, uint64_t now_us);

/* Queues `status` with {"error":why}; closes after it unless keep_alive. */
void xgo_host_view_answer_error(xgo_host_view_t *v, xgo_host_view_client_t *c, int status,
                                const char *why, int keep_alive);

/* Writes the members every client's copy of a state object shares into buf
 * (a new object: v->seq grows). The writer is then handed to
 * xgo_host_view_send_event once per client. */
void xgo_host_view_begin_object(xgo_host_view_t *v, xgo_host_json_t *prefix, char *buf,
                                size_t size);

/* Queues one SSE event for c: the shared members plus c's frames. -1 if
 * its output buffer cannot take it (the client has fallen behind). */
int xgo_host_view_send_event(xgo_host_view_t *v, xgo_host_view_client_t *c,
                             const xgo_host_json_t *prefix);

/* Appends n bytes to c's output; -1 (nothing appended) if they do not fit.
 * (view_server.c) */
int xgo_host_view_queue(xgo_host_view_client_t *c, const void *bytes, size_t n);

/* Bytes c's output can still take. (view_server.c) */
size_t xgo_host_view_room(const xgo_host_view_client_t *c);

#endif /* XGO_HOST_VIEW_ROUTES_H */
