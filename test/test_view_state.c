/*
 * test_view_state.c - the view's JSON on an in-process board: the state
 * object is strict JSON whose numbers are the board's own observers
 * (rounded as documented), its register dump equals a host's read, the
 * frame log keeps the newest and counts the rest; /meta comes from the
 * core's tables; /input and /command bodies are all-or-nothing and their
 * writes enter the board as XGO_SOURCE_VIEW frames.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "json_check.h"
#include "json_out.h"
#include "unity.h"
#include "view_api.h"
#include "view_frames.h"
#include "view_meta.h"
#include "view_state.h"
#include "actions.h"
#include "xgo/board.h"
#include "xgo/emulator.h"

static xgo_board_t g_board;
static xgo_host_view_frames_t g_frames;
static char g_text[65536];
static xgo_host_json_t g_w;

void setUp(void)
{
    xgo_board_init(&g_board, NULL);
    xgo_host_view_frames_init(&g_frames, &g_board, NULL);
    xgo_board_set_trace(&g_board, xgo_host_view_frames_event, &g_frames);
    xgo_host_json_init(&g_w, g_text, sizeof g_text);
}

void tearDown(void)
{
}

static void ticks(unsigned n)
{
    while (n-- > 0) {
        xgo_board_tick(&g_board);
    }
}

static void write_reg(uint8_t addr, uint8_t value)
{
    uint8_t frame[16];
    size_t n = xgo_frame_encode(XGO_TYPE_WRITE, addr, &value, 1, frame, sizeof frame);
    xgo_board_receive(&g_board, frame, n, 0);
}

/* A whole state object for a client whose cursor is *cursor. */
static const char *state(uint64_t *cursor)
{
    char why[128];
    xgo_host_json_init(&g_w, g_text, sizeof g_text);
    xgo_host_view_state_open(&g_w, &g_board, 7, 1, "mini");
    xgo_host_view_state_close(&g_w, &g_frames, cursor);
    TEST_ASSERT_TRUE(xgo_host_json_ok(&g_w));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_valid(g_text, g_w.len, why, sizeof why), why);
    TEST_ASSERT_NULL(strchr(g_text, '\n')); /* an SSE data line holds it */
    return g_text;
}

static double number(const char *text, const char *path)
{
    double v = NAN;
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_number(text, path, &v), path);
    return v;
}

/* The board's value in thousandths, as the JSON shows it (decimals kept). */
static void assert_value(int32_t thousandths, int decimals, const char *text, const char *path)
{
    double unit = decimals == 2 ? 0.01 : 0.1;
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(unit / 2 + 1e-9, thousandths / 1000.0, number(text, path),
                                      path);
}

static void test_state_numbers_are_the_boards(void)
{
    int32_t joints[XGO_SERVO_COUNT], imu[3], cmd[3], act[3];
    xgo_vec3_t feet[XGO_LEG_COUNT];
    xgo_body_pose_t body;
    xgo_world_pose_t world;
    uint64_t cursor = 0;
    const char *s;
    char path[64];
    unsigned i, k;

    write_reg(XGO_REG_VX, 0xE0); /* walk forward and turn: nothing sits at zero */
    write_reg(XGO_REG_VYAW, 0x40);
    write_reg(XGO_REG_BODY_ROLL, 0xA0);
    ticks(700);
    s = state(&cursor);
    xgo_board_joints_mdeg(&g_board, joints);
    xgo_board_feet_um(&g_board, feet);
    xgo_board_body_pose(&g_board, &body);
    xgo_board_world_pose(&g_board, &world);
    xgo_board_imu_mdeg(&g_board, imu);
    xgo_board_velocity(&g_board, cmd, act);

    TEST_ASSERT_EQUAL_DOUBLE(xgo_board_time_ms(&g_board), number(s, "t_ms"));
    TEST_ASSERT_EQUAL_DOUBLE(7, number(s, "seq"));
    TEST_ASSERT_EQUAL_INT(12, xgo_test_json_count(s, "joints_deg"));
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        int32_t lo, hi;
        snprintf(path, sizeof path, "joints_deg.%u", i);
        assert_value(joints[i], 2, s, path);
        xgo_board_joint_limits_mdeg(&g_board, i, &lo, &hi);
        snprintf(path, sizeof path, "joint_limits_deg.%u.1", i);
        assert_value(hi, 2, s, path);
    }
    for (i = 0; i < XGO_LEG_COUNT; i++) {
        for (k = 0; k < 3; k++) {
            snprintf(path, sizeof path, "feet_mm.%u.%u", i, k);
            assert_value(k == 0 ? feet[i].x : (k == 1 ? feet[i].y : feet[i].z), 1, s, path);
        }
        snprintf(path, sizeof path, "contacts.%u", i);
        TEST_ASSERT_EQUAL_DOUBLE((xgo_board_contacts(&g_board) >> i) & 1u, number(s, path));
    }
    assert_value(body.z_um, 1, s, "body.z_mm");
    assert_value(body.roll_mdeg, 2, s, "body.roll_deg");
    assert_value(world.x_um, 1, s, "world.x_mm");
    assert_value(world.yaw_mdeg, 2, s, "world.yaw_deg");
    assert_value(imu[0], 2, s, "imu.roll_deg");
    assert_value(imu[2], 2, s, "imu.yaw_deg");
    assert_value(cmd[0], 1, s, "speed.cmd.vx_mm_s");
    assert_value(act[2], 2, s, "speed.actual.vyaw_deg_s");
    TEST_ASSERT_TRUE(world.x_um > 100000); /* it walked: the values are not all zero */
    TEST_ASSERT_TRUE(xgo_test_json_is_true(s, "host_connected"));
}

/* The Mini2's arm: its servos and points as the board reports them; the
 * Mini has none ("arm": null). */
static void test_state_shows_the_arm(void)
{
    xgo_board_config_t cfg;
    xgo_board_arm_t arm;
    uint64_t cursor = 0;
    const char *s = state(&cursor);
    double v;
    TEST_ASSERT_NOT_NULL(strstr(s, "\"arm\":null"));
    xgo_board_default_config(&cfg);
    cfg.model = XGO_MODEL_MINI2;
    xgo_board_init(&g_board, &cfg);
    write_reg(0x73, 0xA0); /* arm(x, z) */
    write_reg(0x74, 0x60);
    ticks(300);
    s = state(&cursor);
    TEST_ASSERT_EQUAL_INT(1, xgo_board_arm(&g_board, &arm));
    TEST_ASSERT_EQUAL_INT(3, xgo_test_json_count(s, "arm.joints_deg"));
    assert_value(arm.joints_mdeg[XGO_ARM_SHOULDER], 2, s, "arm.joints_deg.2");
    assert_value(arm.joints_mdeg[XGO_ARM_ELBOW], 2, s, "arm.joints_deg.1");
    assert_value(arm.shoulder_um.x, 1, s, "arm.shoulder_mm.0");
    assert_value(arm.elbow_um.z, 1, s, "arm.elbow_mm.2");
    assert_value(arm.claw_um.x, 1, s, "arm.claw_mm.0");
    assert_value(arm.claw_um.z, 1, s, "arm.claw_mm.2");
    TEST_ASSERT_FALSE(xgo_test_json_number(s, "arm.out_of_reach", &v)); /* a bool */
    TEST_ASSERT_TRUE(arm.claw_um.x != arm.shoulder_um.x); /* it moved off the shoulder */
}

static void test_state_regs_are_a_host_read(void)
{
    uint8_t expected[XGO_REG_COUNT];
    char hex[2 * XGO_REG_COUNT + 1];
    uint64_t cursor = 0;
    unsigned i;
    const uint8_t bad[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x99, 0x00, 0xAA};
    xgo_board_receive(&g_board, bad, sizeof bad, 0); /* bad_checksum = 1 in the diag block */
    write_reg(XGO_REG_BODY_Z, 0x20);
    ticks(50);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&g_board, 0, 247, expected));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&g_board, 247, 9, expected + 247));
    TEST_ASSERT_TRUE(xgo_test_json_string(state(&cursor), "regs", hex, sizeof hex));
    TEST_ASSERT_EQUAL_UINT(2 * XGO_REG_COUNT, strlen(hex));
    for (i = 0; i < XGO_REG_COUNT; i++) {
        unsigned byte = 0;
        sscanf(hex + 2 * i, "%2X", &byte);
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(expected[i], byte, "register byte");
    }
    TEST_ASSERT_EQUAL_HEX8(0x20, expected[XGO_REG_BODY_Z]);
    TEST_ASSERT_EQUAL_HEX8(1, expected[XGO_REG_DIAG + 4 * XGO_DIAG_BAD_CHECKSUM]);
    TEST_ASSERT_EQUAL_DOUBLE(1, number(g_text, "counters.bad_checksum"));
    TEST_ASSERT_EQUAL_INT(XGO_DIAG_COUNT, xgo_test_json_count(g_text, "counters"));
}

/* A read of the diagnostic block by frame and by xgo_board_read agree. */
static void test_board_read_equals_a_read_frame(void)
{
    uint8_t request[16], reply[XGO_FRAME_MAX_LEN], direct[48];
    size_t n = xgo_frame_encode(XGO_TYPE_READ, XGO_REG_DIAG, (const uint8_t[]){48}, 1, request,
                                sizeof request);
    write_reg(0x01, 5); /* read-only: rejected_read_only = 1 */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&g_board, XGO_REG_DIAG, 48, direct));
    xgo_board_receive(&g_board, request, n, 0);
    TEST_ASSERT_EQUAL_UINT(48 + XGO_FRAME_OVERHEAD, xgo_board_transmit(&g_board, reply, sizeof reply));
    /* The frame itself counts as frames_ok before the reply is built. */
    direct[4 * XGO_DIAG_FRAMES_OK] += 1;
    TEST_ASSERT_EQUAL_HEX8_ARRAY(direct, reply + 5, 48);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_board_read(&g_board, 250, 7, direct));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_board_read(&g_board, 0, 0, direct));
}

static void test_frames_keep_the_newest_and_count_the_rest(void)
{
    uint64_t cursor = xgo_host_view_state_first_cursor(&g_frames);
    char text[128];
    unsigned i;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_json_count(state(&cursor), "frames"));
    for (i = 0; i < 100; i++) {
        write_reg(XGO_REG_VX, (uint8_t)i);
    }
    state(&cursor);
    TEST_ASSERT_EQUAL_INT(XGO_HOST_VIEW_FRAMES_PER_EVENT, xgo_test_json_count(g_text, "frames"));
    TEST_ASSERT_EQUAL_DOUBLE(100 - XGO_HOST_VIEW_FRAMES_PER_EVENT, number(g_text, "frames_omitted"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.63.text", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("write 0x30 vx n=1 [63] vx=63(-22%)", text);
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.63.kind", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("rx", text);
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.63.source", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("wire", text);
    TEST_ASSERT_EQUAL_DOUBLE(0x30, number(g_text, "frames.63.addr"));
    TEST_ASSERT_EQUAL_DOUBLE(1, number(g_text, "frames.63.n"));
    /* Nothing new: an empty list, nothing omitted. */
    state(&cursor);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_json_count(g_text, "frames"));
    TEST_ASSERT_EQUAL_DOUBLE(0, number(g_text, "frames_omitted"));
    /* More than the ring holds since this client's last object. */
    for (i = 0; i < XGO_HOST_VIEW_FRAME_RING + 10; i++) {
        write_reg(XGO_REG_VY, 0x80);
    }
    state(&cursor);
    TEST_ASSERT_EQUAL_DOUBLE(XGO_HOST_VIEW_FRAME_RING + 10 - XGO_HOST_VIEW_FRAMES_PER_EVENT,
                             number(g_text, "frames_omitted"));
}

static void test_parser_drop_has_no_address(void)
{
    static const uint8_t bad[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x99, 0x00, 0xAA};
    uint64_t cursor = xgo_host_view_state_first_cursor(&g_frames);
    char text[128];
    xgo_board_receive(&g_board, bad, sizeof bad, 0);
    state(&cursor);
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.0.kind", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("drop", text);
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.0.text", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("bad checksum [55 00 09 02 50 0C 99 00 AA] checksum 99, expected 98", text);
    TEST_ASSERT_NOT_NULL(strstr(g_text, "\"addr\":null,\"n\":9,"));
}

/* A flood of garbage is folded into a few noise entries, as --trace folds
 * it into lines: the frame after it is still in the list. */
static void test_noise_flood_is_folded_and_the_frame_after_it_kept(void)
{
    static uint8_t noise[20000];
    uint64_t cursor = xgo_host_view_state_first_cursor(&g_frames);
    char text[256];
    unsigned i;
    for (i = 0; i < sizeof noise; i++) {
        noise[i] = (uint8_t)(i % 2 ? 'h' : 'e'); /* never 0x55: no header */
    }
    for (i = 0; i < sizeof noise; i += 1000) { /* as reads from the pty arrive */
        xgo_board_receive(&g_board, noise + i, 1000, 0);
    }
    write_reg(XGO_REG_VX, 0xFF);
    state(&cursor);
    TEST_ASSERT_EQUAL_INT(2, xgo_test_json_count(g_text, "frames"));
    TEST_ASSERT_EQUAL_DOUBLE(0, number(g_text, "frames_omitted"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.0.text", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("noise n=20000 [65 68 65 68 65 68 65 68 65 68 65 68 65 68 65 68 ...]",
                             text);
    TEST_ASSERT_EQUAL_DOUBLE(20000, number(g_text, "frames.0.n"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "frames.1.text", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("write 0x30 vx n=1 [FF] vx=FF(+100%)", text);
    /* once sent, an entry is not changed: new noise starts a new one */
    xgo_board_receive(&g_board, noise, 5, 0);
    state(&cursor);
    TEST_ASSERT_EQUAL_INT(1, xgo_test_json_count(g_text, "frames"));
    TEST_ASSERT_EQUAL_DOUBLE(5, number(g_text, "frames.0.n"));
}

/* ------------------------------------------------------------ /input */

static int post_input(const char *body)
{
    xgo_host_json_init(&g_w, g_text, sizeof g_text);
    return xgo_host_view_api_input(&g_board, body, strlen(body), &g_w);
}

static void test_input_applies_every_field(void)
{
    int32_t roll, pitch, imu[3];
    TEST_ASSERT_EQUAL_INT(200, post_input("{\"ground_tilt\":{\"roll_deg\":10,\"pitch_deg\":-4.5},"
                                          "\"battery_pct\":42}"));
    TEST_ASSERT_EQUAL_STRING("{\"ok\":true}", g_text);
    xgo_board_ground_tilt(&g_board, &roll, &pitch);
    TEST_ASSERT_EQUAL_INT32(10000, roll);
    TEST_ASSERT_EQUAL_INT32(-4500, pitch);
    TEST_ASSERT_EQUAL_UINT8(42, xgo_board_battery_pct(&g_board));
    ticks(5);
    xgo_board_imu_mdeg(&g_board, imu);
    TEST_ASSERT_INT32_WITHIN(100, 10000, imu[0]); /* the IMU reads the slope */

    TEST_ASSERT_EQUAL_INT(200, post_input("{\"push\":{\"pitch_deg\":20,\"roll_deg\":0}}"));
    ticks(5);
    xgo_board_imu_mdeg(&g_board, imu);
    TEST_ASSERT_TRUE(imu[1] < -4500 + -2000 || imu[1] > -4500 + 2000); /* the shove shows */
}

static void test_bad_input_changes_nothing(void)
{
    static const struct {
        const char *body;
        const char *error;
    } k_cases[] = {
        {"", "{\"error\":\"body is not JSON: value expected at byte 0\"}"},
        {"{\"battery_pct\":50,}", "{\"error\":\"body is not JSON: member name expected at byte 18\"}"},
        {"[1]", "{\"error\":\"body must be a JSON object\"}"},
        {"{}", "{\"error\":\"nothing to apply: give ground_tilt, battery_pct or push\"}"},
        {"{\"battery_pct\":50,\"battery\":1}",
         "{\"error\":\"unknown field 'battery' (ground_tilt, battery_pct, push)\"}"},
        {"{\"battery_pct\":50,\"battery_pct\":51}", "{\"error\":\"field 'battery_pct' given twice\"}"},
        {"{\"battery_pct\":101}", "{\"error\":\"battery_pct must be a whole number 0..100\"}"},
        {"{\"battery_pct\":50.5}", "{\"error\":\"battery_pct must be a whole number 0..100\"}"},
        {"{\"battery_pct\":\"50\"}", "{\"error\":\"battery_pct must be a whole number 0..100\"}"},
        {"{\"battery_pct\":50,\"push\":{\"roll_deg\":31,\"pitch_deg\":0}}",
         "{\"error\":\"push.roll_deg must be a number of degrees within +-30\"}"},
        {"{\"battery_pct\":50,\"ground_tilt\":{\"roll_deg\":1}}",
         "{\"error\":\"ground_tilt needs both roll_deg and pitch_deg\"}"},
        {"{\"ground_tilt\":{\"roll_deg\":1,\"pitch_deg\":45.001}}",
         "{\"error\":\"ground_tilt.pitch_deg must be a number of degrees within +-45\"}"},
        {"{\"ground_tilt\":{\"roll_deg\":1,\"pitch_deg\":2,\"yaw_deg\":0}}",
         "{\"error\":\"ground_tilt: unknown field 'yaw_deg'\"}"},
        {"{\"ground_tilt\":[1,2]}",
         "{\"error\":\"ground_tilt must be {\\\"roll_deg\\\":R,\\\"pitch_deg\\\":P}\"}"},
    };
    size_t i;
    for (i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        int32_t roll, pitch;
        TEST_ASSERT_EQUAL_INT_MESSAGE(400, post_input(k_cases[i].body), k_cases[i].body);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(k_cases[i].error, g_text, k_cases[i].body);
        xgo_board_ground_tilt(&g_board, &roll, &pitch);
        TEST_ASSERT_EQUAL_INT32(0, roll);
        TEST_ASSERT_EQUAL_INT32(0, pitch);
        TEST_ASSERT_EQUAL_UINT8(100, xgo_board_battery_pct(&g_board));
    }
}

/* ------------------------------------------------------------ /command */

static uint8_t g_sources[8];
static xgo_trace_kind_t g_kinds[8];
static size_t g_events;

static void record_event(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    if (g_events < 8) {
        g_sources[g_events] = ev->source;
        g_kinds[g_events] = ev->kind;
    }
    g_events++;
}

static int post_command(const char *body)
{
    xgo_host_json_init(&g_w, g_text, sizeof g_text);
    return xgo_host_view_api_command(&g_board, body, strlen(body), &g_w);
}

static uint8_t reg(uint8_t addr)
{
    uint8_t v = 0;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&g_board, addr, 1, &v));
    return v;
}

static void test_command_writes_through_the_board_as_view(void)
{
    g_events = 0;
    xgo_board_set_trace(&g_board, record_event, NULL);
    TEST_ASSERT_EQUAL_INT(200, post_command("{\"writes\":[{\"addr\":48,\"data\":[200]},"
                                            "{\"addr\":\"0x31\",\"data\":[100]},"
                                            "{\"data\":[10,20],\"addr\":\"body_x\"},"
                                            "{\"addr\":\"battery\",\"data\":[5]}]}"));
    TEST_ASSERT_EQUAL_STRING("{\"results\":[{\"addr\":48,\"n\":1,\"result\":\"ok\"},"
                             "{\"addr\":49,\"n\":1,\"result\":\"ok\"},"
                             "{\"addr\":51,\"n\":2,\"result\":\"ok\"},"
                             "{\"addr\":1,\"n\":1,\"result\":\"read-only register\"}]}",
                             g_text);
    TEST_ASSERT_EQUAL_HEX8(200, reg(0x30));
    TEST_ASSERT_EQUAL_HEX8(100, reg(0x31));
    TEST_ASSERT_EQUAL_HEX8(10, reg(0x33));
    TEST_ASSERT_EQUAL_HEX8(20, reg(0x34));
    TEST_ASSERT_EQUAL_HEX8(100, reg(0x01)); /* refused by the board, as from the wire */
    TEST_ASSERT_EQUAL_UINT(4, g_events);
    TEST_ASSERT_EQUAL_UINT8(XGO_SOURCE_VIEW, g_sources[0]);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_RX, g_kinds[0]);
    TEST_ASSERT_EQUAL_UINT8(XGO_SOURCE_VIEW, g_sources[3]);
    TEST_ASSERT_EQUAL_INT(XGO_TRACE_DROP, g_kinds[3]);
    {
        uint32_t counters[XGO_DIAG_COUNT];
        xgo_board_counters(&g_board, counters);
        TEST_ASSERT_EQUAL_UINT32(1, counters[XGO_DIAG_REJECTED_READ_ONLY]);
    }
}

static void test_bad_command_writes_nothing(void)
{
    static const char *const k_bodies[] = {
        "{}",
        "{\"writes\":[]}",
        "{\"writes\":{}}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]}],\"x\":1}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":256,\"data\":[1]}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":\"nope\",\"data\":[1]}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":\"0x130\",\"data\":[1]}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":49,\"data\":[256]}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":49,\"data\":[]}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":49}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":49,\"data\":[1],\"n\":1}]}",
        "{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":49,\"data\":[1.5]}]}",
    };
    size_t i;
    for (i = 0; i < sizeof k_bodies / sizeof k_bodies[0]; i++) {
        char error[160];
        TEST_ASSERT_EQUAL_INT_MESSAGE(400, post_command(k_bodies[i]), k_bodies[i]);
        TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "error", error, sizeof error));
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(0x80, reg(0x30), k_bodies[i]);
    }
    post_command("{\"writes\":[{\"addr\":48,\"data\":[1]},{\"addr\":\"nope\",\"data\":[1]}]}");
    TEST_ASSERT_EQUAL_STRING(
        "{\"error\":\"writes[1].addr must be 0..255, \\\"0xHH\\\" or a register name\"}", g_text);
}

/* ------------------------------------------------------------ /meta */

static long named_actions(void)
{
    long n = 0;
    unsigned id;
    for (id = 1; id < 256; id++) {
        n += xgo_action_name((uint8_t)id) != NULL;
    }
    return n;
}

static void test_meta_comes_from_the_core(void)
{
    char why[128], text[64];
    int32_t lo, hi;
    xgo_host_json_init(&g_w, g_text, sizeof g_text);
    xgo_host_view_meta(&g_w, &g_board, XGO_MODEL_MINI);
    TEST_ASSERT_TRUE(xgo_host_json_ok(&g_w));
    TEST_ASSERT_TRUE_MESSAGE(xgo_test_json_valid(g_text, g_w.len, why, sizeof why), why);
    TEST_ASSERT_EQUAL_INT((long)xgo_reg_table_size(), xgo_test_json_count(g_text, "registers"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "registers.10.name", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING(xgo_reg_table_entry(10)->name, text);
    TEST_ASSERT_EQUAL_INT(named_actions(), xgo_test_json_count(g_text, "actions"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "actions.0.name", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING(xgo_action_name(1), text);
    TEST_ASSERT_EQUAL_INT(6, xgo_test_json_count(g_text, "modes"));
    TEST_ASSERT_EQUAL_INT(4, xgo_test_json_count(g_text, "gaits"));
    TEST_ASSERT_EQUAL_INT(3, xgo_test_json_count(g_text, "paces"));
    TEST_ASSERT_TRUE(xgo_test_json_string(g_text, "gaits.0", text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("trot", text);
    xgo_board_joint_limits_mdeg(&g_board, 4, &lo, &hi);
    TEST_ASSERT_DOUBLE_WITHIN(0.0005, lo / 1000.0, number(g_text, "joint_limits_deg.4.0"));
    TEST_ASSERT_DOUBLE_WITHIN(0.0005, xgo_profile_mini()->thigh_um / 1000.0,
                              number(g_text, "geometry.thigh_mm"));
    TEST_ASSERT_DOUBLE_WITHIN(0.0005, xgo_profile_mini()->body_mdeg[1].hi / 1000.0,
                              number(g_text, "ranges.body_deg.1.1"));
    TEST_ASSERT_TRUE(number(g_text, "ranges.vx_mm_s") > 100);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_state_numbers_are_the_boards);
    RUN_TEST(test_state_shows_the_arm);
    RUN_TEST(test_state_regs_are_a_host_read);
    RUN_TEST(test_board_read_equals_a_read_frame);
    RUN_TEST(test_frames_keep_the_newest_and_count_the_rest);
    RUN_TEST(test_parser_drop_has_no_address);
    RUN_TEST(test_noise_flood_is_folded_and_the_frame_after_it_kept);
    RUN_TEST(test_input_applies_every_field);
    RUN_TEST(test_bad_input_changes_nothing);
    RUN_TEST(test_command_writes_through_the_board_as_view);
    RUN_TEST(test_bad_command_writes_nothing);
    RUN_TEST(test_meta_comes_from_the_core);
    return UNITY_END();
}
