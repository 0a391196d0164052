/*
 * test_view_http.c - the view server's HTTP request parsing, trust check
 * and response heads, in process: every malformed head gets its status,
 * partial heads wait, the 8 KiB caps hold at their exact edges.
 */
#include <string.h>

#include "http.h"
#include "unity.h"

void setUp(void)
{
}

void tearDown(void)
{
}

static xgo_host_http_request_t g_req;
static const char *g_why;

static int parse(const char *text)
{
    return xgo_host_http_parse(text, strlen(text), &g_req, &g_why);
}

static void assert_text(const char *expected, const char *p, size_t n)
{
    TEST_ASSERT_EQUAL_UINT(strlen(expected), n);
    TEST_ASSERT_EQUAL_MEMORY(expected, p, n);
}

static void test_parses_a_browser_get(void)
{
    static const char k_head[] = "GET /state?t=1 HTTP/1.1\r\n"
                                 "Host: 127.0.0.1:8080\r\n"
                                 "User-Agent: x\r\n"
                                 "Accept: */*\r\n"
                                 "\r\n"
                                 "GET / HTTP/1.1\r\n"; /* a pipelined next request */
    TEST_ASSERT_EQUAL_INT(200, parse(k_head));
    TEST_ASSERT_EQUAL_INT(XGO_HOST_HTTP_GET, g_req.method);
    assert_text("/state", g_req.path, g_req.path_len);
    assert_text("127.0.0.1:8080", g_req.host, g_req.host_len);
    TEST_ASSERT_EQUAL_INT(1, g_req.minor_version);
    TEST_ASSERT_TRUE(g_req.keep_alive);
    TEST_ASSERT_FALSE(g_req.has_body_length);
    TEST_ASSERT_EQUAL_UINT(0, g_req.body_len);
    TEST_ASSERT_EQUAL_UINT(strlen(k_head) - strlen("GET / HTTP/1.1\r\n"), g_req.head_len);
}

static void test_parses_a_post_with_body_length_and_origin(void)
{
    TEST_ASSERT_EQUAL_INT(200, parse("\r\nPOST /input HTTP/1.1\r\nhOsT:   localhost:9 \t\r\n"
                                     "Content-Length: 12\r\nOrigin: http://localhost:9\r\n"
                                     "Connection: foo, Close\r\n\r\n{\"battery"));
    TEST_ASSERT_EQUAL_INT(XGO_HOST_HTTP_POST, g_req.method);
    assert_text("/input", g_req.path, g_req.path_len);
    assert_text("localhost:9", g_req.host, g_req.host_len);
    assert_text("http://localhost:9", g_req.origin, g_req.origin_len);
    TEST_ASSERT_TRUE(g_req.has_body_length);
    TEST_ASSERT_EQUAL_UINT(12, g_req.body_len);
    TEST_ASSERT_FALSE(g_req.keep_alive);
}

static void test_http10_and_bare_newlines(void)
{
    TEST_ASSERT_EQUAL_INT(200, parse("GET / HTTP/1.0\n\n"));
    TEST_ASSERT_EQUAL_INT(0, g_req.minor_version);
    TEST_ASSERT_FALSE(g_req.keep_alive);
    TEST_ASSERT_NULL(g_req.host); /* 1.0 needs no Host */
    TEST_ASSERT_EQUAL_UINT(16, g_req.head_len);
    TEST_ASSERT_EQUAL_INT(200, parse("GET / HTTP/1.0\r\nConnection: keep-alive\r\n\r\n"));
    TEST_ASSERT_TRUE(g_req.keep_alive);
}

static void test_other_methods_are_recognised_not_served(void)
{
    TEST_ASSERT_EQUAL_INT(200, parse("DELETE /state HTTP/1.1\r\nHost: x\r\n\r\n"));
    TEST_ASSERT_EQUAL_INT(XGO_HOST_HTTP_OTHER, g_req.method);
    TEST_ASSERT_EQUAL_INT(200, parse("get / HTTP/1.1\r\nHost: x\r\n\r\n")); /* case matters */
    TEST_ASSERT_EQUAL_INT(XGO_HOST_HTTP_OTHER, g_req.method);
}

/* Every prefix of a good head waits for more. */
static void test_partial_heads_wait(void)
{
    static const char k_head[] = "POST /command HTTP/1.1\r\nHost: localhost:1\r\n"
                                 "Content-Length: 2\r\n\r\n";
    size_t n;
    for (n = 0; n < sizeof k_head - 1; n++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(XGO_HOST_HTTP_INCOMPLETE,
                                      xgo_host_http_parse(k_head, n, &g_req, &g_why), k_head + n);
    }
    TEST_ASSERT_EQUAL_INT(200, xgo_host_http_parse(k_head, n, &g_req, &g_why));
}

static void test_malformed_heads_get_their_status(void)
{
    static const struct {
        const char *head;
        int status;
        const char *why;
    } k_cases[] = {
        {"GET  / HTTP/1.1\r\nHost: x\r\n\r\n", 400, "malformed request target (want /path)"},
        {"GET / HTTP/1.1 \r\nHost: x\r\n\r\n", 400, "malformed HTTP version"},
        {"GET http://x/ HTTP/1.1\r\nHost: x\r\n\r\n", 400, "malformed request target (want /path)"},
        {"G(T / HTTP/1.1\r\nHost: x\r\n\r\n", 400, "malformed request line"},
        {"/ HTTP/1.1\r\n\r\n", 400, "malformed request line"},
        {"GET / HTTP/1.1\rX\r\nHost: x\r\n\r\n", 400, "malformed HTTP version"},
        {"GET / FTP/1.1\r\n\r\n", 400, "malformed HTTP version"},
        {"GET / HTTP/2.0\r\n\r\n", 505, "only HTTP/1.0 and HTTP/1.1 are served"},
        {"GET / HTTP/1.2\r\n\r\n", 505, "only HTTP/1.0 and HTTP/1.1 are served"},
        {"GET / HTTP/1.1\r\n\r\n", 400, "HTTP/1.1 request without Host"},
        {"GET / HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n", 400, "Host given twice"},
        {"GET / HTTP/1.1\r\nHost : a\r\n\r\n", 400, "malformed header"},
        {"GET / HTTP/1.1\r\nHost: a\r\n folded\r\n\r\n", 400, "folded header line"},
        {"GET / HTTP/1.1\r\nHost: a\r\nX: a\rb\r\n\r\n", 400, "control character in a header"},
        {"GET / HTTP/1.1\r\nNoColon\r\n\r\n", 400, "malformed header"},
        {"POST /input HTTP/1.1\r\nHost: a\r\n\r\n", 411, "POST without Content-Length"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: -1\r\n\r\n", 400,
         "Content-Length is not a number"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: 1, 1\r\n\r\n", 400,
         "Content-Length is not a number"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: 1\r\nContent-Length: 1\r\n\r\n", 400,
         "Content-Length given twice"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: 8193\r\n\r\n", 413,
         "body larger than 8 KiB"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: 99999999999999999999\r\n\r\n", 413,
         "body too large"},
        {"POST /input HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked\r\n\r\n", 501,
         "Transfer-Encoding is not supported (send Content-Length)"},
    };
    size_t i;
    for (i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(k_cases[i].status, parse(k_cases[i].head), k_cases[i].head);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(k_cases[i].why, g_why, k_cases[i].head);
    }
}

/* A malformed first line is refused before the rest of the head arrives. */
static void test_bad_request_line_is_refused_early(void)
{
    TEST_ASSERT_EQUAL_INT(400, parse("GET  /\r\n"));
    TEST_ASSERT_EQUAL_INT(400, parse("GET / HTTP/1.1\r\nbad header\r\nHost: x"));
}

/* Request line + headers: 8192 bytes are served, 8193 are not. */
static void test_head_cap_is_exactly_8_KiB(void)
{
    static char head[XGO_HOST_HTTP_HEAD_MAX + 64];
    static const char k_start[] = "GET / HTTP/1.1\r\nHost: x\r\nX-Pad: ";
    size_t pad = XGO_HOST_HTTP_HEAD_MAX - (sizeof k_start - 1) - 4;
    memcpy(head, k_start, sizeof k_start - 1);
    memset(head + sizeof k_start - 1, 'a', pad);
    memcpy(head + sizeof k_start - 1 + pad, "\r\n\r\n", 4);
    TEST_ASSERT_EQUAL_INT(200, xgo_host_http_parse(head, XGO_HOST_HTTP_HEAD_MAX, &g_req, &g_why));
    TEST_ASSERT_EQUAL_UINT(XGO_HOST_HTTP_HEAD_MAX, g_req.head_len);

    memset(head + sizeof k_start - 1, 'a', pad + 1);
    memcpy(head + sizeof k_start - 1 + pad + 1, "\r\n\r\n", 4);
    TEST_ASSERT_EQUAL_INT(431,
                          xgo_host_http_parse(head, XGO_HOST_HTTP_HEAD_MAX + 1, &g_req, &g_why));
    /* Not yet complete but already too long: no need to wait for the end. */
    memset(head, 'a', sizeof head);
    memcpy(head, "GET /", 5);
    TEST_ASSERT_EQUAL_INT(XGO_HOST_HTTP_INCOMPLETE,
                          xgo_host_http_parse(head, XGO_HOST_HTTP_HEAD_MAX, &g_req, &g_why));
    TEST_ASSERT_EQUAL_INT(431,
                          xgo_host_http_parse(head, XGO_HOST_HTTP_HEAD_MAX + 1, &g_req, &g_why));
}

static void test_body_cap_is_exactly_8_KiB(void)
{
    TEST_ASSERT_EQUAL_INT(200, parse("POST /input HTTP/1.1\r\nHost: a\r\nContent-Length: 8192\r\n\r\n"));
    TEST_ASSERT_EQUAL_UINT(XGO_HOST_HTTP_BODY_MAX, g_req.body_len);
    TEST_ASSERT_EQUAL_INT(413, parse("GET / HTTP/1.1\r\nHost: a\r\nContent-Length: 8193\r\n\r\n"));
}

static int trusted(const char *head, const char *bound, unsigned port)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(200, parse(head), head);
    return xgo_host_http_trusted(&g_req, bound, port, &g_why);
}

static void test_trust_needs_our_host_and_port(void)
{
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: 127.0.0.1:8080\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: LocalHost:8080\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: [::1]:8080\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: 10.0.0.7:81\r\n\r\n", "10.0.0.7", 81));
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: localhost\r\n\r\n", "127.0.0.1", 80));

    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: evil.example:8080\r\n\r\n", "127.0.0.1",
                              8080));
    TEST_ASSERT_EQUAL_STRING("Host header does not name this server (DNS rebinding?)", g_why);
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost.evil:8080\r\n\r\n", "127.0.0.1",
                              8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: 10.0.0.7:81\r\n\r\n", "127.0.0.1", 81));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8081\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_EQUAL_STRING("Host header names another port", g_why);
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080x\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: [::1\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: :8080\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.0\r\n\r\n", "127.0.0.1", 8080));
    TEST_ASSERT_EQUAL_STRING("missing or malformed Host header", g_why);
}

static void test_trust_needs_our_origin_if_any(void)
{
    TEST_ASSERT_TRUE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080\r\n"
                             "Origin: http://LOCALHOST:8080\r\n\r\n",
                             "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080\r\n"
                              "Origin: http://evil.example\r\n\r\n",
                              "127.0.0.1", 8080));
    TEST_ASSERT_EQUAL_STRING("Origin is another site", g_why);
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080\r\nOrigin: null\r\n\r\n",
                              "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080\r\n"
                              "Origin: https://localhost:8080\r\n\r\n",
                              "127.0.0.1", 8080));
    TEST_ASSERT_FALSE(trusted("GET / HTTP/1.1\r\nHost: localhost:8080\r\n"
                              "Origin: http://127.0.0.1:8080\r\n\r\n",
                              "127.0.0.1", 8080));
}

static void test_response_head(void)
{
    char out[512];
    size_t n = xgo_host_http_head(out, sizeof out, 404, "application/json", 17, 1, "");
    TEST_ASSERT_EQUAL_STRING("HTTP/1.1 404 Not Found\r\n"
                             "Content-Type: application/json\r\n"
                             "Content-Length: 17\r\n"
                             "Cache-Control: no-store\r\n"
                             "X-Content-Type-Options: nosniff\r\n"
                             "Connection: keep-alive\r\n"
                             "\r\n",
                             out);
    TEST_ASSERT_EQUAL_UINT(strlen(out), n);
    n = xgo_host_http_head(out, sizeof out, 200, "text/event-stream", XGO_HOST_HTTP_STREAM, 0,
                           "Allow: GET\r\n");
    TEST_ASSERT_EQUAL_STRING("HTTP/1.1 200 OK\r\n"
                             "Content-Type: text/event-stream\r\n"
                             "Cache-Control: no-store\r\n"
                             "X-Content-Type-Options: nosniff\r\n"
                             "Connection: close\r\n"
                             "Allow: GET\r\n"
                             "\r\n",
                             out);
    TEST_ASSERT_EQUAL_UINT(0, xgo_host_http_head(out, 20, 200, "text/plain", 0, 1, ""));
    TEST_ASSERT_EQUAL_STRING("Request Header Fields Too Large", xgo_host_http_reason(431));
    TEST_ASSERT_EQUAL_STRING("Error", xgo_host_http_reason(299));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_parses_a_browser_get);
    RUN_TEST(test_parses_a_post_with_body_length_and_origin);
    RUN_TEST(test_http10_and_bare_newlines);
    RUN_TEST(test_other_methods_are_recognised_not_served);
    RUN_TEST(test_partial_heads_wait);
    RUN_TEST(test_malformed_heads_get_their_status);
    RUN_TEST(test_bad_request_line_is_refused_early);
    RUN_TEST(test_head_cap_is_exactly_8_KiB);
    RUN_TEST(test_body_cap_is_exactly_8_KiB);
    RUN_TEST(test_trust_needs_our_host_and_port);
    RUN_TEST(test_trust_needs_our_origin_if_any);
    RUN_TEST(test_response_head);
    return UNITY_END();
}
