/*
 * test_wireshark.c - the dissector (tools/wireshark/xgo.lua with its
 * generated tables) in tshark, on the capture test_capture made with
 * xgo-emu: every frame's direction, type, address, register name, data and
 * checksum status as tshark prints them must be exactly the frames the test
 * sent and received (its own list, XGO_FIXTURE_DIR/capture_fixture.expect);
 * stray bytes, a decoded value and the settings note show up too.
 * Skipped (77) when tshark is not installed (.ci/run installs it).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "emu_process.h"
#include "unity.h"

#if !defined(XGO_TSHARK) || !defined(XGO_DISSECTOR) || !defined(XGO_FIXTURE_DIR)
#error "XGO_TSHARK, XGO_DISSECTOR and XGO_FIXTURE_DIR must be defined"
#endif

static xgo_test_emu_t g_tshark;
static char g_capture[300];

void setUp(void)
{
    xgo_test_emu_init(&g_tshark);
}

void tearDown(void)
{
    xgo_test_emu_kill(&g_tshark);
}

/* tshark -T fields with the given -e fields, one line per packet. */
static void tshark_fields(const char *const *fields)
{
    const char *args[40];
    size_t n = 0;
    args[n++] = "-X";
    args[n++] = "lua_script:" XGO_DISSECTOR;
    args[n++] = "-r";
    args[n++] = g_capture;
    args[n++] = "-T";
    args[n++] = "fields";
    args[n++] = "-E";
    args[n++] = "separator=|";
    args[n++] = "-E";
    args[n++] = "occurrence=a";
    args[n++] = "-E";
    args[n++] = "aggregator=,";
    for (; *fields != NULL && n < 38; fields++) {
        args[n++] = "-e";
        args[n++] = *fields;
    }
    args[n] = NULL;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_tshark, XGO_TSHARK, args, NULL));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_emu_wait(&g_tshark, 60000), "tshark did not finish");
    TEST_ASSERT_TRUE(WIFEXITED(g_tshark.status));
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, WEXITSTATUS(g_tshark.status), g_tshark.err);
    TEST_ASSERT_NULL_MESSAGE(strstr(g_tshark.err, "Lua: Error"), g_tshark.err);
}

/* Splits s at sep into at most max parts (in place). */
static size_t split(char *s, char sep, char **parts, size_t max)
{
    size_t n = 0;
    parts[n++] = s;
    for (; *s != '\0' && n < max; s++) {
        if (*s == sep) {
            *s = '\0';
            parts[n++] = s + 1;
        }
    }
    return n;
}

/* One packet's line -> its frames, "dir|type|addr|reg|data|status" each,
 * appended to out. */
static void frames_of_line(char *line, char *out, size_t out_size)
{
    char *col[6], *lists[5][64];
    size_t count[5], i, k;
    TEST_ASSERT_EQUAL_UINT(6, split(line, '|', col, 6));
    if (col[1][0] == '\0') {
        return; /* a note, a hang-up, or only part of a frame */
    }
    for (k = 0; k < 5; k++) {
        count[k] = split(col[k + 1], ',', lists[k], 64);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(count[0], count[k], "a frame without all of its fields");
    }
    for (i = 0; i < count[0]; i++) {
        size_t len = strlen(out);
        snprintf(out + len, out_size - len, "%s|%s|%s|%s|%s|%s\n", col[0], lists[0][i], lists[1][i],
                 lists[2][i], lists[3][i], lists[4][i]);
    }
}

static void read_file(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "r");
    size_t n;
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
}

static void test_frames_match_what_was_sent_and_received(void)
{
    static const char *const fields[] = {"xgo.direction", "xgo.type", "xgo.addr", "xgo.reg",
                                         "xgo.data", "xgo.checksum.status", NULL};
    static char expect[65536], got[65536];
    char path[320];
    char *line, *save = NULL;
    snprintf(path, sizeof path, "%s/capture_fixture.expect", XGO_FIXTURE_DIR);
    read_file(path, expect, sizeof expect);
    TEST_ASSERT_TRUE(strlen(expect) > 200);
    tshark_fields(fields);
    got[0] = '\0';
    for (line = strtok_r(g_tshark.out, "\n", &save); line != NULL; line = strtok_r(NULL, "\n", &save)) {
        frames_of_line(line, got, sizeof got);
    }
    TEST_ASSERT_EQUAL_STRING(expect, got);
}

static void test_values_strays_and_note(void)
{
    static const char *const fields[] = {"xgo.value", "xgo.garbage", "xgo.note", NULL};
    tshark_fields(fields);
    /* the walk command decoded with the core's scale (vyaw: -100 + 160 * 200 / 255
     * = 25.49 deg/s); "hello" outside any frame */
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(g_tshark.out, "vx = 0xFF (+25.00 cm/s)"), g_tshark.out);
    TEST_ASSERT_NOT_NULL(strstr(g_tshark.out, "vyaw = 0xA0 (+25.49 deg/s)"));
    TEST_ASSERT_NOT_NULL(strstr(g_tshark.out, "|68 65 6c 6c 6f|"));
    TEST_ASSERT_NOT_NULL(strstr(g_tshark.out, "version = 0x00 (mini)"));
    TEST_ASSERT_NOT_NULL(strstr(g_tshark.out, "frames_ok = "));
    TEST_ASSERT_NOT_NULL(strstr(g_tshark.out, "xgo-emu 0.1.0 profile=mini "));
}

int main(void)
{
    if (XGO_TSHARK[0] == '\0' || access(XGO_TSHARK, X_OK) != 0) {
        printf("tshark not found: skipped (apt-get install tshark)\n");
        return 77;
    }
    snprintf(g_capture, sizeof g_capture, "%s/capture_fixture.pcap", XGO_FIXTURE_DIR);
    UNITY_BEGIN();
    RUN_TEST(test_frames_match_what_was_sent_and_received);
    RUN_TEST(test_values_strays_and_note);
    return UNITY_END();
}
