/* http_client.c - HTTP over loopback for tests and benches (see http_client.h). */
#include "http_client.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>
#include <unistd.h>

#include "test_clock.h"

int xgo_test_http_connect(unsigned port)
{
    return xgo_test_http_connect_rcvbuf(port, 0);
}

int xgo_test_http_connect_rcvbuf(unsigned port, int rcvbuf)
{
    struct sockaddr_in sa;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        return -1;
    }
    if (rcvbuf > 0) {
        (void)setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    }
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_port = htons((unsigned short)port);
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, (struct sockaddr *)&sa, sizeof sa) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

/* Waits until fd is ready for `events` or the deadline passes. */
static int wait_fd(int fd, short events, long long deadline_ms)
{
    struct pollfd pfd;
    long long left = deadline_ms - xgo_test_now_ms();
    pfd.fd = fd;
    pfd.events = events;
    pfd.revents = 0;
    return left > 0 && poll(&pfd, 1, (int)left) > 0;
}

int xgo_test_http_send(int fd, const void *bytes, size_t n, long timeout_ms)
{
    long long deadline = xgo_test_now_ms() + timeout_ms;
    const char *p = bytes;
    while (n > 0) {
        ssize_t w;
        if (!wait_fd(fd, POLLOUT, deadline)) {
            return -1;
        }
        w = send(fd, p, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w < 0 && (errno == EAGAIN || errno == EINTR)) {
            continue;
        }
        if (w <= 0) {
            return -1;
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

/* Has r->text a whole answer? Sets status, body, body_len when it has. */
static int complete(xgo_test_http_response_t *r, int eof)
{
    const char *end = strstr(r->text, "\r\n\r\n");
    char length[32];
    size_t head_len, want;
    if (end == NULL) {
        return 0;
    }
    head_len = (size_t)(end - r->text) + 4;
    if (xgo_test_http_header(r, "Content-Length", length, sizeof length)) {
        want = (size_t)strtoul(length, NULL, 10);
        if (r->len < head_len + want) {
            return 0;
        }
    } else if (!eof) {
        return 0; /* no length: the body ends at EOF */
    } else {
        want = r->len - head_len;
    }
    r->status = atoi(r->text + 9);
    r->body = r->text + head_len;
    r->body_len = want;
    return 1;
}

int xgo_test_http_read(int fd, xgo_test_http_response_t *r, long timeout_ms)
{
    long long deadline = xgo_test_now_ms() + timeout_ms;
    r->status = 0;
    r->len = 0;
    r->text[0] = '\0';
    r->body = r->text;
    r->body_len = 0;
    for (;;) {
        ssize_t n;
        if (!wait_fd(fd, POLLIN, deadline)) {
            return 0;
        }
        n = recv(fd, r->text + r->len, XGO_TEST_HTTP_MAX - r->len, MSG_DONTWAIT);
        if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
            continue;
        }
        if (n > 0) {
            r->len += (size_t)n;
            r->text[r->len] = '\0';
        }
        if (complete(r, n <= 0)) {
            return r->status;
        }
        if (n <= 0 || r->len == XGO_TEST_HTTP_MAX) {
            return 0;
        }
    }
}

int xgo_test_http_exchange(unsigned port, const char *request, size_t n,
                           xgo_test_http_response_t *r, long timeout_ms)
{
    int fd = xgo_test_http_connect(port);
    int status = 0;
    r->status = 0;
    if (fd < 0) {
        return 0;
    }
    if (xgo_test_http_send(fd, request, n, timeout_ms) == 0) {
        status = xgo_test_http_read(fd, r, timeout_ms);
    }
    close(fd);
    return status;
}

int xgo_test_http_get(unsigned port, const char *path, xgo_test_http_response_t *r)
{
    char request[512];
    int n = snprintf(request, sizeof request,
                     "GET %s HTTP/1.1\r\nHost: 127.0.0.1:%u\r\nConnection: close\r\n\r\n", path,
                     port);
    return xgo_test_http_exchange(port, request, (size_t)n, r, 2000);
}

int xgo_test_http_post(unsigned port, const char *path, const char *json,
                       xgo_test_http_response_t *r)
{
    static char request[16384];
    int n = snprintf(request, sizeof request,
                     "POST %s HTTP/1.1\r\nHost: 127.0.0.1:%u\r\nContent-Type: application/json\r\n"
                     "Content-Length: %lu\r\nConnection: close\r\n\r\n%s",
                     path, port, (unsigned long)strlen(json), json);
    return xgo_test_http_exchange(port, request, (size_t)n, r, 2000);
}

int xgo_test_http_header(const xgo_test_http_response_t *r, const char *name, char *out,
                         size_t out_size)
{
    const char *line = strstr(r->text, "\r\n");
    const char *head_end = strstr(r->text, "\r\n\r\n");
    size_t name_len = strlen(name);
    while (line != NULL && head_end != NULL && line < head_end) {
        line += 2;
        if (strncasecmp(line, name, name_len) == 0 && line[name_len] == ':') {
            const char *v = line + name_len + 1;
            size_t n;
            while (*v == ' ') {
                v++;
            }
            n = strcspn(v, "\r");
            if (n >= out_size) {
                return 0;
            }
            memcpy(out, v, n);
            out[n] = '\0';
            return 1;
        }
        line = strstr(line, "\r\n");
    }
    return 0;
}

int xgo_test_sse_open(xgo_test_sse_t *s, unsigned port, long timeout_ms)
{
    char request[256];
    int n = snprintf(request, sizeof request,
                     "GET /events HTTP/1.1\r\nHost: 127.0.0.1:%u\r\nAccept: text/event-stream\r\n\r\n",
                     port);
    s->len = 0;
    s->fd = xgo_test_http_connect(port);
    if (s->fd < 0) {
        return -1;
    }
    if (xgo_test_http_send(s->fd, request, (size_t)n, timeout_ms) != 0) {
        close(s->fd);
        s->fd = -1;
        return -1;
    }
    return 0;
}

int xgo_test_sse_next(xgo_test_sse_t *s, char *out, size_t out_size, long timeout_ms)
{
    long long deadline = xgo_test_now_ms() + timeout_ms;
    for (;;) {
        char *data = NULL;
        char *end = NULL;
        ssize_t n;
        s->pending[s->len] = '\0';
        data = strstr(s->pending, "\ndata: ");
        end = data != NULL ? strstr(data, "\n\n") : NULL;
        if (end != NULL) {
            size_t len = (size_t)(end - (data + 7));
            size_t used = (size_t)(end + 2 - s->pending);
            if (len >= out_size) {
                return 0;
            }
            memcpy(out, data + 7, len);
            out[len] = '\0';
            /* keep the "\n" before the next event's "data: " */
            memmove(s->pending, s->pending + used - 1, s->len - used + 1);
            s->len -= used - 1;
            return 1;
        }
        if (!wait_fd(s->fd, POLLIN, deadline)) {
            return 0;
        }
        n = recv(s->fd, s->pending + s->len, sizeof s->pending - 1 - s->len, MSG_DONTWAIT);
        if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
            return 0;
        }
        if (n > 0) {
            s->len += (size_t)n;
        }
    }
}

unsigned xgo_test_http_view_port(const char *stdout_text)
{
    const char *line = strstr(stdout_text, "view: http://");
    const char *colon;
    if (line == NULL) {
        return 0;
    }
    colon = strchr(line + 13, ':');
    return colon != NULL ? (unsigned)strtoul(colon + 1, NULL, 10) : 0;
}
