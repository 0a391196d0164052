/*
 * test_view_json.c - the view server's JSON writer and reader in process:
 * exact text out (commas, fixed-point rounding, escapes, bounds), and the
 * strict reader's verdict and values on valid and invalid bodies.
 */
#include <string.h>

#include "json_in.h"
#include "json_out.h"
#include "unity.h"

void setUp(void)
{
}

void tearDown(void)
{
}

/* ------------------------------------------------------------- writer */

static char g_buf[512];
static xgo_host_json_t g_w;

static void begin(size_t size)
{
    memset(g_buf, 'X', sizeof g_buf);
    xgo_host_json_init(&g_w, g_buf, size);
}

static void test_writer_places_commas_and_nests(void)
{
    begin(sizeof g_buf);
    xgo_host_json_object_begin(&g_w);
    xgo_host_json_key(&g_w, "a");
    xgo_host_json_int(&g_w, -5);
    xgo_host_json_key(&g_w, "b");
    xgo_host_json_array_begin(&g_w);
    xgo_host_json_uint(&g_w, 1);
    xgo_host_json_array_begin(&g_w);
    xgo_host_json_array_end(&g_w);
    xgo_host_json_object_begin(&g_w);
    xgo_host_json_object_end(&g_w);
    xgo_host_json_bool(&g_w, 1);
    xgo_host_json_bool(&g_w, 0);
    xgo_host_json_null(&g_w);
    xgo_host_json_array_end(&g_w);
    xgo_host_json_key(&g_w, "c");
    xgo_host_json_string(&g_w, "x");
    xgo_host_json_object_end(&g_w);
    TEST_ASSERT_TRUE(xgo_host_json_ok(&g_w));
    TEST_ASSERT_EQUAL_STRING("{\"a\":-5,\"b\":[1,[],{},true,false,null],\"c\":\"x\"}", g_buf);
}

static void test_writer_extreme_integers(void)
{
    begin(sizeof g_buf);
    xgo_host_json_array_begin(&g_w);
    xgo_host_json_int(&g_w, INT64_MIN);
    xgo_host_json_int(&g_w, INT64_MAX);
    xgo_host_json_uint(&g_w, UINT64_MAX);
    xgo_host_json_int(&g_w, 0);
    xgo_host_json_array_end(&g_w);
    TEST_ASSERT_EQUAL_STRING(
        "[-9223372036854775808,9223372036854775807,18446744073709551615,0]", g_buf);
}

/* The fixed-point cases the snapshot uses: mdeg -> 2 decimals, um -> 1. */
static void test_writer_fixed_point_rounds_half_away_from_zero(void)
{
    static const struct {
        int64_t value;
        unsigned scale, decimals;
        const char *text;
    } k_cases[] = {
        {-1234, 3, 2, "-1.23"}, {-1235, 3, 2, "-1.24"}, {1235, 3, 2, "1.24"},
        {1234, 3, 2, "1.23"},   {-4, 3, 2, "0.00"},     {-5, 3, 2, "-0.01"},
        {97650, 3, 1, "97.7"},  {97649, 3, 1, "97.6"},  {0, 3, 1, "0.0"},
        {5, 0, 0, "5"},         {7, 2, 2, "0.07"},      {-120000, 3, 2, "-120.00"},
        {999999, 3, 2, "1000.00"}, {123456789, 9, 9, "0.123456789"},
    };
    size_t i;
    for (i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        begin(sizeof g_buf);
        xgo_host_json_fixed(&g_w, k_cases[i].value, k_cases[i].scale, k_cases[i].decimals);
        TEST_ASSERT_EQUAL_STRING(k_cases[i].text, g_buf);
    }
}

static void test_writer_escapes_strings(void)
{
    static const char k_raw[] = "q\"b\\n\n\x01\x7F\xC3\xA9";
    begin(sizeof g_buf);
    xgo_host_json_string(&g_w, k_raw);
    TEST_ASSERT_EQUAL_STRING("\"q\\\"b\\\\n\\u000A\\u0001\\u007F\\u00C3\\u00A9\"", g_buf);
    begin(sizeof g_buf);
    xgo_host_json_string_n(&g_w, "a\0b", 3);
    TEST_ASSERT_EQUAL_STRING("\"a\\u0000b\"", g_buf);
}

static void test_writer_places_prewritten_values(void)
{
    begin(sizeof g_buf);
    xgo_host_json_array_begin(&g_w);
    xgo_host_json_value_text(&g_w, "{\"a\":1}", 7);
    xgo_host_json_value_text(&g_w, "[2]", 3);
    xgo_host_json_array_end(&g_w);
    TEST_ASSERT_TRUE(xgo_host_json_ok(&g_w));
    TEST_ASSERT_EQUAL_STRING("[{\"a\":1},[2]]", g_buf);
}

static void test_writer_hex(void)
{
    static const uint8_t k_bytes[] = {0x55, 0x00, 0xAA, 0x0F};
    begin(sizeof g_buf);
    xgo_host_json_hex(&g_w, k_bytes, sizeof k_bytes);
    TEST_ASSERT_EQUAL_STRING("\"5500AA0F\"", g_buf);
}

/* Out of room: nothing past the end, a NUL inside, and "not ok" for good. */
static void test_writer_never_writes_past_its_buffer(void)
{
    size_t size;
    for (size = 1; size < 22; size++) {
        begin(size);
        xgo_host_json_object_begin(&g_w);
        xgo_host_json_key(&g_w, "name");
        xgo_host_json_string(&g_w, "0123456789");
        xgo_host_json_object_end(&g_w);
        TEST_ASSERT_EQUAL_INT('X', g_buf[size]);
        TEST_ASSERT_TRUE(strlen(g_buf) < size);
        TEST_ASSERT_FALSE(xgo_host_json_ok(&g_w));
    }
    begin(22); /* exactly enough: 21 characters and the NUL */
    xgo_host_json_object_begin(&g_w);
    xgo_host_json_key(&g_w, "name");
    xgo_host_json_string(&g_w, "0123456789");
    xgo_host_json_object_end(&g_w);
    TEST_ASSERT_TRUE(xgo_host_json_ok(&g_w));
    TEST_ASSERT_EQUAL_STRING("{\"name\":\"0123456789\"}", g_buf);
}

static void test_writer_rejects_unbalanced_use(void)
{
    unsigned i;
    begin(sizeof g_buf);
    xgo_host_json_object_begin(&g_w);
    TEST_ASSERT_FALSE(xgo_host_json_ok(&g_w)); /* still open */
    xgo_host_json_key(&g_w, "k");
    xgo_host_json_object_end(&g_w); /* a key without its value */
    TEST_ASSERT_FALSE(xgo_host_json_ok(&g_w));

    begin(sizeof g_buf);
    xgo_host_json_array_end(&g_w); /* nothing open */
    TEST_ASSERT_FALSE(xgo_host_json_ok(&g_w));

    begin(sizeof g_buf);
    for (i = 0; i < XGO_HOST_JSON_MAX_DEPTH; i++) {
        xgo_host_json_array_begin(&g_w);
    }
    TEST_ASSERT_TRUE(g_w.overflow); /* deeper than tracked */
}

/* ------------------------------------------------------------- reader */

static int parses(const char *text)
{
    xgo_host_json_span_t root;
    size_t at;
    const char *why;
    return xgo_host_json_parse(text, strlen(text), &root, &at, &why);
}

static void test_reader_accepts_valid_json(void)
{
    static const char *const k_valid[] = {
        "{}", "[]", " \t\r\n{ } ", "0", "-0", "1.5e+3", "-0.25E-2", "\"\"", "true", "null",
        "{\"a\":[1,{\"b\":\"\\u00e9\\n\\\"\"}],\"c\":false}", "\"\\ud83d\\ude00\"",
        "\"caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80\"", "[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]",
    };
    size_t i;
    for (i = 0; i < sizeof k_valid / sizeof k_valid[0]; i++) {
        TEST_ASSERT_TRUE_MESSAGE(parses(k_valid[i]), k_valid[i]);
    }
}

static void test_reader_refuses_invalid_json_with_a_reason(void)
{
    static const struct {
        const char *text;
        size_t at;
        const char *why;
    } k_invalid[] = {
        {"", 0, "value expected"},
        {"{", 1, "member name expected"},
        {"{\"a\":1,}", 7, "member name expected"},
        {"[1,]", 3, "unexpected character"},
        {"[1 2]", 3, "',' or ']' expected"},
        {"{\"a\" 1}", 5, "':' expected"},
        {"{'a':1}", 1, "member name expected"},
        {"01", 1, "leading zero in number"},
        {"1.", 2, "digit expected in number"},
        {".5", 0, "unexpected character"},
        {"1e", 2, "digit expected in number"},
        {"+1", 0, "unexpected character"},
        {"NaN", 0, "unexpected character"},
        {"tru", 0, "unexpected character"},
        {"\"a\x01\"", 2, "control character in string"},
        {"\"\\x\"", 2, "bad escape in string"},
        {"\"\\u12G4\"", 2, "bad \\u escape in string"},
        {"\"\\udc00\"", 2, "bad \\u escape in string"},
        {"\"\\ud800x\"", 7, "unpaired surrogate in string"},
        {"\"\xC0\x80\"", 1, "invalid UTF-8 in string"},
        {"\"\xED\xA0\x80\"", 1, "invalid UTF-8 in string"},
        {"\"\xE2\x82\"", 1, "invalid UTF-8 in string"},
        {"\"abc", 4, "unterminated string"},
        {"{} {}", 3, "text after the value"},
        {"[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]", 16, "nested too deeply"},
    };
    size_t i;
    for (i = 0; i < sizeof k_invalid / sizeof k_invalid[0]; i++) {
        xgo_host_json_span_t root;
        size_t at = 999;
        const char *why = NULL;
        const char *text = k_invalid[i].text;
        TEST_ASSERT_FALSE_MESSAGE(xgo_host_json_parse(text, strlen(text), &root, &at, &why), text);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(k_invalid[i].why, why, text);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(k_invalid[i].at, at, text);
    }
}

/* A NUL inside the given length is not the end of the text. */
static void test_reader_sees_embedded_nul(void)
{
    xgo_host_json_span_t root;
    size_t at;
    const char *why;
    TEST_ASSERT_FALSE(xgo_host_json_parse("{}\0{}", 5, &root, &at, &why));
    TEST_ASSERT_FALSE(xgo_host_json_parse("\"a\0b\"", 5, &root, &at, &why));
}

static xgo_host_json_span_t root_of(const char *text)
{
    xgo_host_json_span_t root;
    size_t at;
    const char *why;
    TEST_ASSERT_TRUE_MESSAGE(xgo_host_json_parse(text, strlen(text), &root, &at, &why), text);
    return root;
}

static void test_reader_walks_objects_and_arrays(void)
{
    xgo_host_json_span_t root = root_of(" { \"ab\" : [ 1 , \"x,]}\" , {\"k\":[]} ] , \"c\":-2 } ");
    xgo_host_json_cursor_t c, a;
    xgo_host_json_span_t name, value, e;
    TEST_ASSERT_EQUAL_INT(XGO_HOST_JSON_OBJECT, xgo_host_json_type(root));
    xgo_host_json_enter(root, &c);
    TEST_ASSERT_TRUE(xgo_host_json_next_member(&c, &name, &value));
    TEST_ASSERT_TRUE(xgo_host_json_name_is(name, "ab"));
    TEST_ASSERT_FALSE(xgo_host_json_name_is(name, "a"));
    TEST_ASSERT_EQUAL_INT(XGO_HOST_JSON_ARRAY, xgo_host_json_type(value));
    xgo_host_json_enter(value, &a);
    TEST_ASSERT_TRUE(xgo_host_json_next_element(&a, &e));
    TEST_ASSERT_EQUAL_STRING_LEN("1", e.start, (size_t)(e.end - e.start));
    TEST_ASSERT_TRUE(xgo_host_json_next_element(&a, &e));
    TEST_ASSERT_EQUAL_STRING_LEN("\"x,]}\"", e.start, (size_t)(e.end - e.start));
    TEST_ASSERT_TRUE(xgo_host_json_next_element(&a, &e));
    TEST_ASSERT_EQUAL_STRING_LEN("{\"k\":[]}", e.start, (size_t)(e.end - e.start));
    TEST_ASSERT_FALSE(xgo_host_json_next_element(&a, &e));
    TEST_ASSERT_TRUE(xgo_host_json_next_member(&c, &name, &value));
    TEST_ASSERT_TRUE(xgo_host_json_name_is(name, "c"));
    TEST_ASSERT_EQUAL_STRING_LEN("-2", value.start, (size_t)(value.end - value.start));
    TEST_ASSERT_FALSE(xgo_host_json_next_member(&c, &name, &value));

    root = root_of("[]");
    xgo_host_json_enter(root, &a);
    TEST_ASSERT_FALSE(xgo_host_json_next_element(&a, &e));
}

/* Fixed-point conversion, exact where a double would not be. */
static void test_reader_numbers_to_fixed_point(void)
{
    static const struct {
        const char *text;
        unsigned scale;
        int64_t value;
    } k_cases[] = {
        {"2.5", 3, 2500},          {"-2.5", 3, -2500},    {"45", 3, 45000},
        {"0.0005", 3, 1},          {"-0.0005", 3, -1},    {"0.00049", 3, 0},
        {"1e-4", 3, 0},            {"1.5e2", 0, 150},     {"25E-1", 0, 3},
        {"0.1", 3, 100},           {"45.0004", 3, 45000}, {"-0", 3, 0},
        {"0.000000000000000000000000001e27", 0, 1},
        {"45.000000000000000000000000000001", 3, 45000},
    };
    size_t i;
    for (i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        int64_t v = 77;
        int ok = xgo_host_json_scaled(root_of(k_cases[i].text), k_cases[i].scale, INT64_MIN + 1,
                                      INT64_MAX, &v);
        TEST_ASSERT_TRUE_MESSAGE(ok, k_cases[i].text);
        TEST_ASSERT_EQUAL_INT64_MESSAGE(k_cases[i].value, v, k_cases[i].text);
    }
}

static void test_reader_ranges_and_whole_numbers(void)
{
    int64_t v = 0;
    TEST_ASSERT_TRUE(xgo_host_json_scaled(root_of("45"), 3, -45000, 45000, &v));
    TEST_ASSERT_FALSE(xgo_host_json_scaled(root_of("45.001"), 3, -45000, 45000, &v));
    TEST_ASSERT_FALSE(xgo_host_json_scaled(root_of("-45.001"), 3, -45000, 45000, &v));
    TEST_ASSERT_FALSE(xgo_host_json_scaled(root_of("\"5\""), 3, -45000, 45000, &v));
    TEST_ASSERT_FALSE(xgo_host_json_scaled(root_of("1e999999999"), 3, -45000, 45000, &v));
    /* Beyond the converter's bound (1e15 in the scaled unit): refused, not wrapped. */
    TEST_ASSERT_FALSE(
        xgo_host_json_scaled(root_of("123456789012345678901234"), 0, INT64_MIN + 1, INT64_MAX, &v));
    TEST_ASSERT_TRUE(xgo_host_json_scaled(root_of("1e-999999999"), 3, -45000, 45000, &v));
    TEST_ASSERT_EQUAL_INT64(0, v);

    TEST_ASSERT_TRUE(xgo_host_json_whole(root_of("100"), 0, 100, &v));
    TEST_ASSERT_EQUAL_INT64(100, v);
    TEST_ASSERT_TRUE(xgo_host_json_whole(root_of("5.0"), 0, 100, &v));
    TEST_ASSERT_EQUAL_INT64(5, v);
    TEST_ASSERT_TRUE(xgo_host_json_whole(root_of("2e1"), 0, 100, &v));
    TEST_ASSERT_EQUAL_INT64(20, v);
    TEST_ASSERT_FALSE(xgo_host_json_whole(root_of("5.5"), 0, 100, &v));
    TEST_ASSERT_FALSE(xgo_host_json_whole(root_of("101"), 0, 100, &v));
    TEST_ASSERT_FALSE(xgo_host_json_whole(root_of("-1"), 0, 100, &v));
    TEST_ASSERT_FALSE(xgo_host_json_whole(root_of("true"), 0, 100, &v));
}

static void test_reader_ascii_strings(void)
{
    char out[8];
    TEST_ASSERT_TRUE(xgo_host_json_ascii(root_of("\"0x30\""), out, sizeof out));
    TEST_ASSERT_EQUAL_STRING("0x30", out);
    TEST_ASSERT_TRUE(xgo_host_json_ascii(root_of("\"v\\u0078\\n\""), out, sizeof out));
    TEST_ASSERT_EQUAL_STRING("vx\n", out);
    TEST_ASSERT_TRUE(xgo_host_json_ascii(root_of("\"1234567\""), out, sizeof out));
    TEST_ASSERT_FALSE(xgo_host_json_ascii(root_of("\"12345678\""), out, sizeof out));
    TEST_ASSERT_FALSE(xgo_host_json_ascii(root_of("\"\\u0000\""), out, sizeof out));
    TEST_ASSERT_FALSE(xgo_host_json_ascii(root_of("\"\\u00e9\""), out, sizeof out));
    TEST_ASSERT_FALSE(xgo_host_json_ascii(root_of("\"\xC3\xA9\""), out, sizeof out));
    TEST_ASSERT_FALSE(xgo_host_json_ascii(root_of("48"), out, sizeof out));
}

/* What the writer writes, the reader accepts (and reads back). */
static void test_writer_output_reads_back(void)
{
    xgo_host_json_span_t root, name, value;
    xgo_host_json_cursor_t c;
    int64_t v;
    begin(sizeof g_buf);
    xgo_host_json_object_begin(&g_w);
    xgo_host_json_key(&g_w, "roll_deg");
    xgo_host_json_fixed(&g_w, -12345, 3, 2);
    xgo_host_json_key(&g_w, "s");
    xgo_host_json_string(&g_w, "\x01\"\\\xFF");
    xgo_host_json_object_end(&g_w);
    root = root_of(g_buf);
    xgo_host_json_enter(root, &c);
    TEST_ASSERT_TRUE(xgo_host_json_next_member(&c, &name, &value));
    TEST_ASSERT_TRUE(xgo_host_json_scaled(value, 3, -100000, 100000, &v));
    TEST_ASSERT_EQUAL_INT64(-12350, v);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_writer_places_commas_and_nests);
    RUN_TEST(test_writer_extreme_integers);
    RUN_TEST(test_writer_fixed_point_rounds_half_away_from_zero);
    RUN_TEST(test_writer_escapes_strings);
    RUN_TEST(test_writer_places_prewritten_values);
    RUN_TEST(test_writer_hex);
    RUN_TEST(test_writer_never_writes_past_its_buffer);
    RUN_TEST(test_writer_rejects_unbalanced_use);
    RUN_TEST(test_reader_accepts_valid_json);
    RUN_TEST(test_reader_refuses_invalid_json_with_a_reason);
    RUN_TEST(test_reader_sees_embedded_nul);
    RUN_TEST(test_reader_walks_objects_and_arrays);
    RUN_TEST(test_reader_numbers_to_fixed_point);
    RUN_TEST(test_reader_ranges_and_whole_numbers);
    RUN_TEST(test_reader_ascii_strings);
    RUN_TEST(test_writer_output_reads_back);
    return UNITY_END();
}
