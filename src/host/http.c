/* http.c - request heads in, response heads out (see http.h). */
#include "http.h"

#include <stdio.h>
#include <string.h>

/* RFC 9110 token characters (methods, header names). */
static int xgo_host_http_is_tchar(char c)
{
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (c != '\0' && strchr("!#$%&'*+-.^_`|~", c) != NULL);
}

static int xgo_host_http_lower(int c)
{
    return (c >= 'A' && c <= 'Z') ? c + ('a' - 'A') : c;
}

/* Case-insensitive comparison of text[0..n) with a NUL-terminated word. */
static int xgo_host_http_same(const char *text, size_t n, const char *word)
{
    size_t i;
    if (strlen(word) != n) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (xgo_host_http_lower((unsigned char)text[i]) != xgo_host_http_lower((unsigned char)word[i])) {
            return 0;
        }
    }
    return 1;
}

/* Length of the line at p (up to, not including, "\r\n" or "\n"), and via
 * *next where the following line starts; -1 if no line end before end. A
 * bare CR inside a line is left for the caller to reject. */
static long xgo_host_http_line(const char *p, const char *end, const char **next)
{
    const char *nl = memchr(p, '\n', (size_t)(end - p));
    if (nl == NULL) {
        return -1;
    }
    *next = nl + 1;
    if (nl > p && nl[-1] == '\r') {
        nl--;
    }
    return nl - p;
}

/* "GET /state?x HTTP/1.1": method, target, version, single spaces. */
static int xgo_host_http_request_line(const char *p, size_t n, xgo_host_http_request_t *req,
                                      const char **why)
{
    const char *end = p + n;
    const char *sp1, *sp2, *q;
    size_t mlen;
    for (sp1 = p; sp1 < end && xgo_host_http_is_tchar(*sp1); sp1++) {
    }
    mlen = (size_t)(sp1 - p);
    if (mlen == 0 || mlen > 16 || sp1 == end || *sp1 != ' ') {
        *why = "malformed request line";
        return 400;
    }
    req->method = (mlen == 3 && memcmp(p, "GET", 3) == 0)    ? XGO_HOST_HTTP_GET
                  : (mlen == 4 && memcmp(p, "POST", 4) == 0) ? XGO_HOST_HTTP_POST
                                                             : XGO_HOST_HTTP_OTHER;
    for (sp2 = sp1 + 1; sp2 < end && *sp2 > ' ' && *sp2 < 0x7F; sp2++) {
    }
    if (sp2 == sp1 + 1 || sp2 == end || *sp2 != ' ' || sp1[1] != '/') {
        *why = "malformed request target (want /path)";
        return 400;
    }
    req->path = sp1 + 1;
    q = memchr(req->path, '?', (size_t)(sp2 - req->path));
    req->path_len = (size_t)((q != NULL ? q : sp2) - req->path);
    if (end - (sp2 + 1) != 8 || memcmp(sp2 + 1, "HTTP/", 5) != 0 || sp2[7] != '.' ||
        sp2[6] < '0' || sp2[6] > '9' || sp2[8] < '0' || sp2[8] > '9') {
        *why = "malformed HTTP version";
        return 400;
    }
    if (sp2[6] != '1' || sp2[8] > '1') {
        *why = "only HTTP/1.0 and HTTP/1.1 are served";
        return 505;
    }
    req->minor_version = sp2[8] - '0';
    req->keep_alive = req->minor_version == 1;
    return 200;
}

/* Content-Length: digits only (no sign, no list), within size_t. */
static int xgo_host_http_content_length(const char *v, size_t n, xgo_host_http_request_t *req,
                                        const char **why)
{
    size_t i, value = 0;
    if (req->has_body_length) {
        *why = "Content-Length given twice";
        return 400;
    }
    if (n == 0 || n > 12) {
        *why = n == 0 ? "empty Content-Length" : "body too large";
        return n == 0 ? 400 : 413;
    }
    for (i = 0; i < n; i++) {
        if (v[i] < '0' || v[i] > '9') {
            *why = "Content-Length is not a number";
            return 400;
        }
        value = value * 10u + (size_t)(v[i] - '0');
    }
    req->has_body_length = 1;
    req->body_len = value;
    return 200;
}

/* Connection: a comma-separated token list; only close/keep-alive matter. */
static void xgo_host_http_connection(const char *v, size_t n, xgo_host_http_request_t *req)
{
    const char *end = v + n;
    while (v < end) {
        const char *comma = memchr(v, ',', (size_t)(end - v));
        const char *tok_end = comma != NULL ? comma : end;
        while (v < tok_end && (*v == ' ' || *v == '\t')) {
            v++;
        }
        while (tok_end > v && (tok_end[-1] == ' ' || tok_end[-1] == '\t')) {
            tok_end--;
        }
        if (xgo_host_http_same(v, (size_t)(tok_end - v), "close")) {
            req->keep_alive = 0;
        } else if (xgo_host_http_same(v, (size_t)(tok_end - v), "keep-alive")) {
            req->keep_alive = 1;
        }
        v = comma != NULL ? comma + 1 : end;
    }
}

/* A header we act on. Returns 200 or the status to answer with. */
static int xgo_host_http_use_header(const char *name, size_t name_len, const char *v, size_t n,
                                    xgo_host_http_request_t *req, const char **why)
{
    if (xgo_host_http_same(name, name_len, "host")) {
        if (req->host != NULL) {
            *why = "Host given twice";
            return 400;
        }
        req->host = v;
        req->host_len = n;
    } else if (xgo_host_http_same(name, name_len, "origin")) {
        req->origin = v;
        req->origin_len = n;
    } else if (xgo_host_http_same(name, name_len, "content-length")) {
        return xgo_host_http_content_length(v, n, req, why);
    } else if (xgo_host_http_same(name, name_len, "transfer-encoding")) {
        *why = "Transfer-Encoding is not supported (send Content-Length)";
        return 501;
    } else if (xgo_host_http_same(name, name_len, "connection")) {
        xgo_host_http_connection(v, n, req);
    }
    return 200;
}

/* "Name: value" with optional whitespace around the value. */
static int xgo_host_http_header(const char *p, size_t n, xgo_host_http_request_t *req,
                                const char **why)
{
    const char *end = p + n;
    const char *colon = p;
    const char *v;
    const char *c;
    while (colon < end && xgo_host_http_is_tchar(*colon)) {
        colon++;
    }
    if (colon == p || colon == end || *colon != ':') {
        *why = (p < end && (*p == ' ' || *p == '\t')) ? "folded header line" : "malformed header";
        return 400;
    }
    for (c = colon + 1; c < end; c++) {
        unsigned char u = (unsigned char)*c;
        if ((u < 0x20 && u != '\t') || u == 0x7F) {
            *why = "control character in a header";
            return 400;
        }
    }
    for (v = colon + 1; v < end && (*v == ' ' || *v == '\t'); v++) {
    }
    while (end > v && (end[-1] == ' ' || end[-1] == '\t')) {
        end--;
    }
    return xgo_host_http_use_header(p, (size_t)(colon - p), v, (size_t)(end - v), req, why);
}

/* Rules that need the whole head. */
static int xgo_host_http_head_rules(xgo_host_http_request_t *req, const char **why)
{
    if (req->minor_version == 1 && req->host == NULL) {
        *why = "HTTP/1.1 request without Host";
        return 400;
    }
    if (req->has_body_length && req->body_len > XGO_HOST_HTTP_BODY_MAX) {
        *why = "body larger than 8 KiB";
        return 413;
    }
    if (req->method == XGO_HOST_HTTP_POST && !req->has_body_length) {
        *why = "POST without Content-Length";
        return 411;
    }
    if (!req->has_body_length) {
        req->body_len = 0;
    }
    return 200;
}

int xgo_host_http_parse(const char *buf, size_t len, xgo_host_http_request_t *req, const char **why)
{
    const char *p = buf;
    const char *end = buf + len;
    const char *next;
    long n;
    int status;

    memset(req, 0, sizeof *req);
    *why = "";
    /* RFC 9112: empty lines before a request line are ignored (some
     * clients send CRLF after a POST body). */
    while ((n = xgo_host_http_line(p, end, &next)) == 0) {
        p = next;
    }
    status = 200;
    if (n >= 0) {
        status = xgo_host_http_request_line(p, (size_t)n, req, why);
        p = next;
    }
    while (n >= 0 && status == 200 && (n = xgo_host_http_line(p, end, &next)) > 0) {
        status = xgo_host_http_header(p, (size_t)n, req, why);
        p = next;
    }
    if (n < 0) {
        /* No blank line yet (the request line and headers so far are
         * fine): wait for more, unless the head is already too long. */
        if (len <= XGO_HOST_HTTP_HEAD_MAX) {
            return XGO_HOST_HTTP_INCOMPLETE;
        }
        *why = "request line and headers larger than 8 KiB";
        return 431;
    }
    if (status != 200) {
        return status;
    }
    if ((size_t)(next - buf) > XGO_HOST_HTTP_HEAD_MAX) {
        *why = "request line and headers larger than 8 KiB";
        return 431;
    }
    req->head_len = (size_t)(next - buf);
    return xgo_host_http_head_rules(req, why);
}

/* ------------------------------------------------------------- trust */

/* Splits "host[:port]" / "[v6]:port"; returns 0 if malformed. */
static int xgo_host_http_split_host(const char *v, size_t n, size_t *name_len, long *port)
{
    const char *colon = NULL;
    size_t i;
    *port = -1;
    if (n > 0 && v[0] == '[') {
        const char *close = memchr(v, ']', n);
        if (close == NULL) {
            return 0;
        }
        colon = (close + 1 < v + n) ? close + 1 : NULL;
        if (colon != NULL && *colon != ':') {
            return 0;
        }
    } else {
        for (i = n; i > 0 && colon == NULL; i--) {
            colon = v[i - 1] == ':' ? v + i - 1 : NULL;
        }
    }
    *name_len = colon != NULL ? (size_t)(colon - v) : n;
    if (colon != NULL) {
        const char *d = colon + 1;
        long value = 0;
        if (d == v + n || v + n - d > 5) {
            return 0;
        }
        for (; d < v + n; d++) {
            if (*d < '0' || *d > '9') {
                return 0;
            }
            value = value * 10 + (*d - '0');
        }
        *port = value;
    }
    return *name_len > 0;
}

int xgo_host_http_trusted(const xgo_host_http_request_t *req, const char *bound_host,
                          unsigned port, const char **why)
{
    size_t name_len;
    long host_port;
    if (req->host == NULL ||
        !xgo_host_http_split_host(req->host, req->host_len, &name_len, &host_port)) {
        *why = "missing or malformed Host header";
        return 0;
    }
    if (!xgo_host_http_same(req->host, name_len, "localhost") &&
        !xgo_host_http_same(req->host, name_len, "127.0.0.1") &&
        !xgo_host_http_same(req->host, name_len, "[::1]") &&
        !xgo_host_http_same(req->host, name_len, bound_host)) {
        *why = "Host header does not name this server (DNS rebinding?)";
        return 0;
    }
    /* No port in Host means port 80. */
    if (host_port < 0 ? port != 80u : (unsigned long)host_port != port) {
        *why = "Host header names another port";
        return 0;
    }
    if (req->origin != NULL) {
        size_t i;
        int same = req->origin_len == req->host_len + 7 && xgo_host_http_same(req->origin, 7, "http://");
        for (i = 0; same && i < req->host_len; i++) {
            same = xgo_host_http_lower((unsigned char)req->origin[7 + i]) ==
                   xgo_host_http_lower((unsigned char)req->host[i]);
        }
        if (!same) {
            *why = "Origin is another site";
            return 0;
        }
    }
    return 1;
}

/* ------------------------------------------------------------ responses */

const char *xgo_host_http_reason(int status)
{
    switch (status) {
    case 200:
        return "OK";
    case 400:
        return "Bad Request";
    case 403:
        return "Forbidden";
    case 404:
        return "Not Found";
    case 405:
        return "Method Not Allowed";
    case 408:
        return "Request Timeout";
    case 411:
        return "Length Required";
    case 413:
        return "Content Too Large";
    case 431:
        return "Request Header Fields Too Large";
    case 501:
        return "Not Implemented";
    case 503:
        return "Service Unavailable";
    case 505:
        return "HTTP Version Not Supported";
    default:
        return "Error";
    }
}

size_t xgo_host_http_head(char *out, size_t out_size, int status, const char *content_type,
                          size_t body_len, int keep_alive, const char *extra)
{
    char length[40] = "";
    int n;
    if (body_len != XGO_HOST_HTTP_STREAM) {
        snprintf(length, sizeof length, "Content-Length: %lu\r\n", (unsigned long)body_len);
    }
    n = snprintf(out, out_size,
                 "HTTP/1.1 %d %s\r\n"
                 "Content-Type: %s\r\n"
                 "%s"
                 "Cache-Control: no-store\r\n"
                 "X-Content-Type-Options: nosniff\r\n"
                 "Connection: %s\r\n"
                 "%s"
                 "\r\n",
                 status, xgo_host_http_reason(status), content_type, length,
                 keep_alive ? "keep-alive" : "close", extra);
    return (n > 0 && (size_t)n < out_size) ? (size_t)n : 0;
}
