/*
 * view_routes.c - the answer to each view request (see view_routes.h):
 * which path and method get what, the page's compiled-in files, state
 * objects and events, and the checks before a POST may change anything.
 */
#include "view_routes.h"

#include <string.h>

#include "view_api.h"
#include "view_assets.h"
#include "view_meta.h"

/* The page may load only what we serve (no third-party script can run in
 * it, and it works offline); no other site may frame it. */
#define XGO_HOST_VIEW_PAGE_HEADERS                                                              \
    "Content-Security-Policy: default-src 'self'; script-src 'self' 'unsafe-inline'; "         \
    "style-src 'self' 'unsafe-inline'; img-src 'self' data:; frame-ancestors 'none'\r\n"

static int xgo_host_view_path_is(const xgo_host_http_request_t *req, const char *path)
{
    size_t n = strlen(path);
    return req->path_len == n && memcmp(req->path, path, n) == 0;
}

/* Queues head and body; after a closing answer the connection is shut. */
static void xgo_host_view_respond(xgo_host_view_t *v, xgo_host_view_client_t *c, int status,
                                  const char *type, const char *body, size_t n, int keep_alive,
                                  const char *extra)
{
    char head[512];
    size_t head_len = xgo_host_http_head(head, sizeof head, status, type, n, keep_alive, extra);
    if (head_len == 0 || head_len + n > xgo_host_view_room(c)) {
        c->close_when_sent = 1; /* cannot happen with our sizes; never half an answer */
        return;
    }
    (void)xgo_host_view_queue(c, head, head_len);
    (void)xgo_host_view_queue(c, body, n);
    if (status < 400) {
        v->counters.requests++;
    } else {
        v->counters.bad_requests++;
    }
    if (!keep_alive) {
        c->close_when_sent = 1;
    }
}

static void xgo_host_view_answer_json(xgo_host_view_t *v, xgo_host_view_client_t *c, int status,
                                      const xgo_host_json_t *w, int keep_alive, const char *extra)
{
    if (!xgo_host_json_ok(w)) {
        static const char k_body[] = "{\"error\":\"answer too large\"}";
        xgo_host_view_respond(v, c, 500, "application/json", k_body, sizeof k_body - 1, 0, "");
        return;
    }
    xgo_host_view_respond(v, c, status, "application/json", w->buf, w->len, keep_alive, extra);
}

static void xgo_host_view_answer_error_extra(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                             int status, const char *why, int keep_alive,
                                             const char *extra)
{
    xgo_host_json_t w;
    xgo_host_json_init(&w, v->object, sizeof v->object);
    xgo_host_view_api_error(&w, why);
    xgo_host_view_answer_json(v, c, status, &w, keep_alive, extra);
}

void xgo_host_view_answer_error(xgo_host_view_t *v, xgo_host_view_client_t *c, int status,
                                const char *why, int keep_alive)
{
    xgo_host_view_answer_error_extra(v, c, status, why, keep_alive, "");
}

/* ------------------------------------------------------------ state */

void xgo_host_view_begin_object(xgo_host_view_t *v, xgo_host_json_t *prefix, char *buf,
                                size_t size)
{
    v->seq++;
    xgo_host_json_init(prefix, buf, size);
    xgo_host_view_state_open(prefix, v->board, v->seq, xgo_host_loop_host_attached(v->loop),
                             v->profile->name);
}

int xgo_host_view_send_event(xgo_host_view_t *v, xgo_host_view_client_t *c,
                             const xgo_host_json_t *prefix)
{
    xgo_host_json_t w = *prefix; /* the shared members, then this client's frames */
    xgo_host_view_state_close(&w, &v->frames, &c->frame_cursor);
    if (!xgo_host_json_ok(&w) || 8u + w.len > xgo_host_view_room(c)) {
        return -1;
    }
    (void)xgo_host_view_queue(c, "data: ", 6);
    (void)xgo_host_view_queue(c, w.buf, w.len);
    (void)xgo_host_view_queue(c, "\n\n", 2);
    v->counters.events++;
    return 0;
}

static void xgo_host_view_get_state(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                    const xgo_host_http_request_t *req, uint64_t now_us)
{
    xgo_host_json_t w;
    uint64_t cursor = xgo_host_view_state_first_cursor(&v->frames);
    (void)now_us;
    xgo_host_view_begin_object(v, &w, v->object, sizeof v->object);
    xgo_host_view_state_close(&w, &v->frames, &cursor);
    xgo_host_view_answer_json(v, c, 200, &w, req->keep_alive, "");
}

static void xgo_host_view_get_meta(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                   const xgo_host_http_request_t *req, uint64_t now_us)
{
    xgo_host_json_t w;
    (void)now_us;
    xgo_host_json_init(&w, v->object, sizeof v->object);
    xgo_host_view_meta(&w, v->board, v->model);
    xgo_host_view_answer_json(v, c, 200, &w, req->keep_alive, "");
}

/* The answer's head, then one event at once (the page draws without
 * waiting a period), then one per period from xgo_host_view_emit. */
static void xgo_host_view_get_events(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                     const xgo_host_http_request_t *req, uint64_t now_us)
{
    static const char k_retry[] = "retry: 1000\n\n"; /* reconnect after 1 s */
    char head[512];
    xgo_host_json_t prefix;
    size_t n = xgo_host_http_head(head, sizeof head, 200, "text/event-stream",
                                  XGO_HOST_HTTP_STREAM, 1, "");
    (void)req;
    (void)now_us;
    (void)xgo_host_view_queue(c, head, n);
    (void)xgo_host_view_queue(c, k_retry, sizeof k_retry - 1);
    v->counters.requests++;
    c->state = XGO_HOST_VIEW_STREAMING;
    c->frame_cursor = xgo_host_view_state_first_cursor(&v->frames);
    xgo_host_view_begin_object(v, &prefix, v->object, sizeof v->object);
    (void)xgo_host_view_send_event(v, c, &prefix); /* an empty buffer takes one */
}

/* ------------------------------------------------------------ POST */

static void xgo_host_view_post(xgo_host_view_t *v, xgo_host_view_client_t *c,
                               const xgo_host_http_request_t *req, uint64_t now_us)
{
    const char *body = c->in + req->head_len;
    const char *why;
    xgo_host_json_t w;
    int status;
    if (!xgo_host_http_trusted(req, c->local_host, v->port, &why)) {
        xgo_host_view_answer_error(v, c, 403, why, req->keep_alive);
        return;
    }
    xgo_host_json_init(&w, v->object, sizeof v->object);
    if (v->frames.trace_out != NULL) {
        v->frames.trace_out->now_us = now_us; /* --trace's time column */
    }
    if (xgo_host_view_path_is(req, "/input")) {
        status = xgo_host_view_api_input(v->board, body, req->body_len, &w);
    } else {
        status = xgo_host_view_api_command(v->board, body, req->body_len, &w);
    }
    xgo_host_view_answer_json(v, c, status, &w, req->keep_alive, "");
}

/* ------------------------------------------------------------ routing */

static const xgo_host_view_asset_t *xgo_host_view_find_asset(const xgo_host_http_request_t *req)
{
    size_t i;
    for (i = 0; i < xgo_host_view_asset_count; i++) {
        if (xgo_host_view_path_is(req, xgo_host_view_assets[i].path)) {
            return &xgo_host_view_assets[i];
        }
    }
    return NULL;
}

static void xgo_host_view_get_asset(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                    const xgo_host_http_request_t *req,
                                    const xgo_host_view_asset_t *a)
{
    char head[512];
    size_t n = xgo_host_http_head(head, sizeof head, 200, a->content_type, a->len,
                                  req->keep_alive, XGO_HOST_VIEW_PAGE_HEADERS);
    (void)xgo_host_view_queue(c, head, n);
    c->body = a->data; /* sent from the binary's own bytes, not copied */
    c->body_len = a->len;
    c->body_sent = 0;
    v->counters.requests++;
    if (!req->keep_alive) {
        c->close_when_sent = 1;
    }
}

typedef void (*xgo_host_view_handler_fn)(xgo_host_view_t *v, xgo_host_view_client_t *c,
                                         const xgo_host_http_request_t *req, uint64_t now_us);

typedef struct xgo_host_view_route_s {
    const char *path;
    xgo_host_http_method_t method;
    xgo_host_view_handler_fn handler;
} xgo_host_view_route_t;

static const xgo_host_view_route_t xgo_host_view_routes[] = {
    {"/state", XGO_HOST_HTTP_GET, xgo_host_view_get_state},
    {"/events", XGO_HOST_HTTP_GET, xgo_host_view_get_events},
    {"/meta", XGO_HOST_HTTP_GET, xgo_host_view_get_meta},
    {"/input", XGO_HOST_HTTP_POST, xgo_host_view_post},
    {"/command", XGO_HOST_HTTP_POST, xgo_host_view_post},
};

void xgo_host_view_route(xgo_host_view_t *v, xgo_host_view_client_t *c,
                         const xgo_host_http_request_t *req, uint64_t now_us)
{
    const xgo_host_view_asset_t *asset = xgo_host_view_find_asset(req);
    size_t i;
    for (i = 0; i < sizeof xgo_host_view_routes / sizeof xgo_host_view_routes[0]; i++) {
        const xgo_host_view_route_t *r = &xgo_host_view_routes[i];
        if (!xgo_host_view_path_is(req, r->path)) {
            continue;
        }
        if (req->method == r->method) {
            r->handler(v, c, req, now_us);
        } else if (r->method == XGO_HOST_HTTP_GET) {
            xgo_host_view_answer_error_extra(v, c, 405, "use GET", req->keep_alive,
                                             "Allow: GET\r\n");
        } else {
            xgo_host_view_answer_error_extra(v, c, 405, "use POST", req->keep_alive,
                                             "Allow: POST\r\n");
        }
        return;
    }
    if (asset == NULL) {
        xgo_host_view_answer_error(v, c, 404, "no such path", req->keep_alive);
    } else if (req->method == XGO_HOST_HTTP_GET) {
        xgo_host_view_get_asset(v, c, req, asset);
    } else {
        xgo_host_view_answer_error_extra(v, c, 405, "use GET", req->keep_alive, "Allow: GET\r\n");
    }
}
