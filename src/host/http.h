/*
 * http.h - the HTTP/1.1 pieces of the view server that need no socket:
 * parsing a request head, deciding whether a POST may be trusted, and
 * writing a response head. Pure functions on caller-owned buffers, so every
 * malformed request has an in-process unit test (test/test_view_http.c).
 *
 * Only what a browser and curl send is accepted: origin-form targets,
 * HTTP/1.0 or 1.1, a body only with Content-Length (no chunked uploads).
 * Anything else gets a status and a one-line reason.
 */
#ifndef XGO_HOST_HTTP_H
#define XGO_HOST_HTTP_H

#include <stddef.h>

/* Request line + headers, including the blank line: beyond this, 431. */
#define XGO_HOST_HTTP_HEAD_MAX 8192u
/* Request body (Content-Length): beyond this, 413. */
#define XGO_HOST_HTTP_BODY_MAX 8192u

typedef enum xgo_host_http_method_e {
    XGO_HOST_HTTP_GET = 0,
    XGO_HOST_HTTP_POST,
    XGO_HOST_HTTP_OTHER /* a well-formed method we do not serve (405 or 404) */
} xgo_host_http_method_t;

/* A parsed head. Text fields point into the caller's buffer (not
 * NUL-terminated: use the lengths). */
typedef struct xgo_host_http_request_s {
    xgo_host_http_method_t method;
    const char *path;     /* "/state" (the query string, if any, is cut off) */
    size_t path_len;
    int minor_version;    /* 0 or 1 */
    const char *host;     /* Host header value, NULL if absent */
    size_t host_len;
    const char *origin;   /* Origin header value, NULL if absent */
    size_t origin_len;
    int has_body_length;  /* Content-Length given */
    size_t body_len;      /* its value */
    int keep_alive;       /* the connection may carry another request */
    size_t head_len;      /* bytes of the head, blank line included */
} xgo_host_http_request_t;

/* Result of xgo_host_http_parse: 0 (more bytes needed), 200 (a complete,
 * acceptable head in *req), or the status to answer with. */
#define XGO_HOST_HTTP_INCOMPLETE 0

/* Parses the head at the start of buf[0..len). Returns
 *   XGO_HOST_HTTP_INCOMPLETE - no blank line yet and len within
 *                              XGO_HOST_HTTP_HEAD_MAX: read more;
 *   200 - *req filled (the body, if any, follows at req->head_len);
 *   400 malformed, 411 POST without Content-Length, 413 body too large,
 *   431 head too large, 501 Transfer-Encoding, 505 not HTTP/1.x;
 *   *why then says what was wrong, in a few words. */
int xgo_host_http_parse(const char *buf, size_t len, xgo_host_http_request_t *req, const char **why);

/* May a state-changing request be trusted? Its Host header must name
 * "localhost", "127.0.0.1", "[::1]" or `bound_host` (the address the
 * connection reached, e.g. "192.168.1.5"), with no port or `port`; a
 * DNS-rebinding page sends its own name instead. If an Origin header is
 * present it must be "http://" + that same host (a page of another site
 * posting here). Returns 1 when trusted, else 0 and *why. */
int xgo_host_http_trusted(const xgo_host_http_request_t *req, const char *bound_host,
                          unsigned port, const char **why);

/* Reason phrase for a status code ("Not Found"); "Error" if unknown. */
const char *xgo_host_http_reason(int status);

/* Writes a response head into out: status line, Content-Type, then
 * Content-Length (omitted when body_len is XGO_HOST_HTTP_STREAM), the fixed
 * safety headers, Connection, `extra` (CRLF-terminated lines or ""), blank
 * line. Returns its length, or 0 if out is too small. */
#define XGO_HOST_HTTP_STREAM ((size_t)-1)
size_t xgo_host_http_head(char *out, size_t out_size, int status, const char *content_type,
                          size_t body_len, int keep_alive, const char *extra);

#endif /* XGO_HOST_HTTP_H */
