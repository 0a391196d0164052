/*
 * http_client.h - the client side of xgo-emu --view for the tests and the
 * bench: raw HTTP/1.1 over loopback TCP, every wait bounded by a timeout.
 * Requests are sent as given (so tests can send malformed ones); answers
 * are read whole (Content-Length) and split into status, head and body.
 */
#ifndef XGO_TEST_HTTP_CLIENT_H
#define XGO_TEST_HTTP_CLIENT_H

#include <stddef.h>

#define XGO_TEST_HTTP_MAX 262144u /* largest answer kept */

typedef struct xgo_test_http_response_s {
    int status;           /* 0: no (complete) answer */
    char text[XGO_TEST_HTTP_MAX + 1]; /* the whole answer, NUL-terminated */
    size_t len;
    const char *body;     /* inside text, NUL-terminated */
    size_t body_len;
} xgo_test_http_response_t;

/* A blocking TCP connection to 127.0.0.1:port, or -1. */
int xgo_test_http_connect(unsigned port);
/* The same with the receive buffer set to rcvbuf bytes before connecting
 * (a client that reads slowly, or never, fills it sooner). */
int xgo_test_http_connect_rcvbuf(unsigned port, int rcvbuf);

/* Sends all n bytes (waiting at most timeout_ms); 0 or -1. */
int xgo_test_http_send(int fd, const void *bytes, size_t n, long timeout_ms);

/* Reads one answer (head, then Content-Length bytes of body, or up to EOF
 * if it has none) within timeout_ms. Returns its status, 0 if incomplete. */
int xgo_test_http_read(int fd, xgo_test_http_response_t *r, long timeout_ms);

/* Connects, sends `request` as is, reads the answer, closes. */
int xgo_test_http_exchange(unsigned port, const char *request, size_t n,
                           xgo_test_http_response_t *r, long timeout_ms);

/* GET path / POST path with a JSON body, well-formed, Host 127.0.0.1:port. */
int xgo_test_http_get(unsigned port, const char *path, xgo_test_http_response_t *r);
int xgo_test_http_post(unsigned port, const char *path, const char *json,
                       xgo_test_http_response_t *r);

/* Value of header `name` in the answer's head (case-insensitive) into
 * out; 1 if present. */
int xgo_test_http_header(const xgo_test_http_response_t *r, const char *name, char *out,
                         size_t out_size);

/* Reads from an event stream until one whole "data: ...\n\n" event is in;
 * copies its data (without "data: ") into out. Bytes after it stay in
 * `pending` for the next call. Returns 1, or 0 at timeout or EOF. */
typedef struct xgo_test_sse_s {
    int fd;
    char pending[XGO_TEST_HTTP_MAX];
    size_t len;
} xgo_test_sse_t;
int xgo_test_sse_open(xgo_test_sse_t *s, unsigned port, long timeout_ms);
int xgo_test_sse_next(xgo_test_sse_t *s, char *out, size_t out_size, long timeout_ms);

/* The port xgo-emu printed as "view: http://HOST:PORT/" in `stdout_text`,
 * 0 if there is no such line. */
unsigned xgo_test_http_view_port(const char *stdout_text);

#endif /* XGO_TEST_HTTP_CLIENT_H */
