/*
 * test_firmware_config: the core built with the firmware images' options
 * (XGO_FIRMWARE_OPTIONS, CMakeLists.txt) behaves as xgo/config.h documents
 * for a feature that is compiled out - and still works as a board.
 *
 * Built twice (test/CMakeLists.txt): against the firmware configuration's
 * core, and as test_firmware_config_full against the full core, so every
 * check below also shows what the option changes (#if on the option).
 * Only the public API and Unity: the test helpers link the full core.
 */
#include <string.h>

#include "unity.h"
#include "xgo/board.h"
#include "xgo/emulator.h"
#include "xgo/port.h"

static xgo_board_t board;

void setUp(void)
{
}

void tearDown(void)
{
}

static void init_model(xgo_model_t model)
{
    xgo_board_config_t cfg;
    xgo_board_default_config(&cfg);
    cfg.model = model;
    xgo_board_init(&board, &cfg);
}

static void ticks(unsigned n)
{
    while (n-- > 0) {
        xgo_board_tick(&board);
    }
}

static uint8_t read1(uint8_t addr)
{
    uint8_t v = 0xEE;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, addr, 1, &v));
    return v;
}

static void write1(uint8_t addr, uint8_t value)
{
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_CLI, addr, &value, 1));
}

/* A read request on the wire, checksum computed here: the reply's bytes. */
static size_t wire_read(uint8_t addr, uint8_t n, uint8_t *reply, size_t max)
{
    uint8_t req[9] = {0x55, 0x00, 0x09, 0x02, 0, 0, 0, 0x00, 0xAA};
    unsigned sum = 0x09 + 0x02 + addr + n;
    req[4] = addr;
    req[5] = n;
    req[6] = (uint8_t)~sum;
    xgo_board_receive(&board, req, sizeof req, 0);
    return xgo_board_transmit(&board, reply, max);
}

static void test_models_built_in(void)
{
    TEST_ASSERT_EQUAL_INT(1, xgo_profile_built_in(XGO_PROFILE_MINI));
    TEST_ASSERT_EQUAL_INT(XGO_WITH_LITE, xgo_profile_built_in(XGO_PROFILE_LITE));
    TEST_ASSERT_EQUAL_INT(XGO_WITH_MINI2, xgo_profile_built_in(XGO_PROFILE_MINI2));
    TEST_ASSERT_TRUE(xgo_profile_get(XGO_PROFILE_MINI) == xgo_profile_mini());
    TEST_ASSERT_EQUAL_INT(!XGO_WITH_LITE, xgo_profile_get(XGO_PROFILE_LITE) == xgo_profile_mini());
    TEST_ASSERT_EQUAL_INT(!XGO_WITH_MINI2, xgo_profile_get(XGO_PROFILE_MINI2) == xgo_profile_mini());
}

/* Asked for a Mini2 or a Lite that is not built in, the board is a Mini:
 * version 0x00, firmware "M...". */
static void test_model_not_built_in_is_served_as_mini(void)
{
    uint8_t fw[10];
    init_model(XGO_MODEL_MINI2);
    TEST_ASSERT_EQUAL_HEX8(XGO_WITH_MINI2 ? XGO_VERSION_MINI2 : XGO_VERSION_MINI,
                           read1(XGO_REG_VERSION));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, XGO_REG_FIRMWARE, 10, fw));
    TEST_ASSERT_EQUAL_UINT8(XGO_WITH_MINI2 ? 'W' : 'M', fw[0]);
    init_model(XGO_MODEL_LITE);
    TEST_ASSERT_EQUAL_HEX8(XGO_WITH_LITE ? XGO_VERSION_LITE : XGO_VERSION_MINI,
                           read1(XGO_REG_VERSION));
}

/* Without the Mini2, the arm's registers are what the Mini has there:
 * nothing. A write frame to them is accepted, its bytes ignored and counted;
 * they read 0; the board has no arm. */
static void test_arm_registers_without_mini2(void)
{
    uint32_t before[XGO_DIAG_COUNT], after[XGO_DIAG_COUNT];
    xgo_board_arm_t arm;
    init_model(XGO_MODEL_MINI2);
    xgo_board_counters(&board, before);
    write1(XGO_REG_ARM_X, 0xC0);
    ticks(50);
    xgo_board_counters(&board, after);
    TEST_ASSERT_EQUAL_UINT32(before[XGO_DIAG_IGNORED_UNMAPPED] + !XGO_WITH_MINI2,
                             after[XGO_DIAG_IGNORED_UNMAPPED]);
    TEST_ASSERT_EQUAL_HEX8(XGO_WITH_MINI2 ? 0xC0 : 0x00, read1(XGO_REG_ARM_X));
    TEST_ASSERT_EQUAL_INT(XGO_WITH_MINI2, xgo_board_arm(&board, &arm));
}

/* Trotting forward for 2 s: the legs walk either way; only with the
 * odometry does the world pose move, only with the inertial model does the
 * accelerometer read anything. */
static void test_walk_without_odometry_and_inertial(void)
{
    int32_t start[XGO_SERVO_COUNT], now[XGO_SERVO_COUNT];
    xgo_world_pose_t world;
    uint8_t block[XGO_IMU_BLOCK_LEN];
    unsigned i, moved = 0, nonzero = 0;
    init_model(XGO_MODEL_MINI);
    xgo_board_joints_mdeg(&board, start);
    write1(XGO_REG_VX, 0xE0);
    ticks(1000);
    xgo_board_joints_mdeg(&board, now);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        moved += now[i] != start[i];
    }
    TEST_ASSERT_TRUE(moved >= 8);
    xgo_board_world_pose(&board, &world);
    if (XGO_WITH_ODOMETRY) {
        TEST_ASSERT_TRUE(world.x_um > 100000); /* 2 s at up to 190 mm/s */
    } else {
        TEST_ASSERT_EQUAL_INT32(0, world.x_um);
        TEST_ASSERT_EQUAL_INT32(0, world.y_um);
        TEST_ASSERT_EQUAL_INT32(0, world.yaw_mdeg);
    }
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                          xgo_board_read(&board, XGO_REG_IMU_BLOCK, XGO_IMU_BLOCK_LEN, block));
    for (i = 0; i < 12; i++) { /* accel x, y, z and gyro x, y, z, int16 LE */
        nonzero += block[i] != 0;
    }
    if (XGO_WITH_INERTIAL) {
        TEST_ASSERT_TRUE(nonzero > 0); /* 1 g on z at least */
    } else {
        TEST_ASSERT_EQUAL_UINT(0, nonzero);
    }
}

/* The spec's read of the twelve servos, byte for byte, with every servo at
 * 0x80 (servo mode): the wire protocol does not depend on the options. */
static void test_spec_read_reply(void)
{
    static const uint8_t expected_head[5] = {0x55, 0x00, 0x14, 0x12, 0x50};
    uint8_t reply[64];
    size_t n, i;
    unsigned sum = 0x14 + 0x12 + 0x50;
    init_model(XGO_MODEL_MINI);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        write1((uint8_t)(XGO_REG_SERVO11 + i), 0x80);
    }
    ticks(1500);
    n = wire_read(XGO_REG_SERVO11, 12, reply, sizeof reply);
    TEST_ASSERT_EQUAL_UINT(20, n);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expected_head, reply, 5);
    for (i = 0; i < 12; i++) {
        TEST_ASSERT_EQUAL_HEX8(0x80, reply[5 + i]);
        sum += reply[5 + i];
    }
    TEST_ASSERT_EQUAL_HEX8((uint8_t)~sum, reply[17]);
    TEST_ASSERT_EQUAL_HEX8(0x00, reply[18]);
    TEST_ASSERT_EQUAL_HEX8(0xAA, reply[19]);
}

/* A preset action still runs and ends (the keyframe tables are in). */
static void test_action_runs(void)
{
    unsigned t;
    init_model(XGO_MODEL_MINI);
    write1(XGO_REG_ACTION, XGO_ACTION_SIT);
    ticks(10);
    TEST_ASSERT_EQUAL_UINT8(XGO_ACTION_SIT, xgo_board_action(&board));
    for (t = 0; t < 20 * XGO_TICK_HZ && xgo_board_action(&board) != 0; t++) {
        xgo_board_tick(&board);
    }
    TEST_ASSERT_EQUAL_UINT8(0, xgo_board_action(&board));
}

/* A frame longer than XGO_PARSER_FRAME_MAX (firmware: 24) is dropped as a
 * bad length, and the read request right behind it is still answered: its
 * bytes are rescanned. 24 bytes (16 data: 0x31..0x40, the whole-unit
 * registers with the two-byte heading, valid values) still pass and are
 * applied. The vendor library's longest write is 12 bytes (the joints),
 * test_fw_serial's 12. */
static void test_frame_length_limit(void)
{
    static uint8_t bytes[2 * 40 + 9];
    uint32_t before[XGO_DIAG_COUNT], after[XGO_DIAG_COUNT];
    uint8_t reply[64], data[17];
    size_t n = 0;
    memset(data, 0x80, sizeof data);
    data[0] = 0x90; /* vy, to see that the 16-byte write is applied */
    data[XGO_REG_MOVE_MODE - 0x31] = 0; /* a valid pace */
    data[XGO_REG_ACTION - 0x31] = 0;    /* no action */
    data[XGO_REG_TURN_TO - 0x31] = 0;   /* a heading (two bytes with 0x40) */
    init_model(XGO_MODEL_MINI);
    xgo_board_counters(&board, before);
    n += xgo_frame_encode(XGO_TYPE_WRITE, 0x31, data, 16, &bytes[n], sizeof bytes - n);
    n += xgo_frame_encode(XGO_TYPE_WRITE, 0x31, data, 17, &bytes[n], sizeof bytes - n);
    TEST_ASSERT_EQUAL_UINT(24 + 25, n);
    xgo_board_receive(&board, bytes, n, 0);
    TEST_ASSERT_EQUAL_UINT(20, wire_read(XGO_REG_SERVO11, 12, reply, sizeof reply));
    xgo_board_counters(&board, after);
    TEST_ASSERT_EQUAL_UINT32(XGO_PARSER_FRAME_MAX < 25u ? 1u : 0u,
                             after[XGO_DIAG_BAD_LENGTH] - before[XGO_DIAG_BAD_LENGTH]);
    TEST_ASSERT_EQUAL_UINT32(XGO_PARSER_FRAME_MAX < 25u ? 2u : 3u,
                             after[XGO_DIAG_FRAMES_OK] - before[XGO_DIAG_FRAMES_OK]);
    TEST_ASSERT_EQUAL_HEX8(0x90, read1(XGO_REG_VY));
}

/* Without the Mini2 the register image stores nothing at 0x22..0x2F,
 * 0x6C..0x7F and 0x83..0x8F (xgo/board_state.h): a Mini has no register
 * there either way. A write across a gap lands on both sides of it (its gap
 * bytes ignored and counted), a read across it gives 0 in the gap and the
 * registers after it as written - on the wire as through xgo_board_read.
 * The full core keeps the image flat and answers the same. */
static void test_register_image_gap(void)
{
    uint8_t data[0x84 - 0x69], got[sizeof data], reply[80];
    uint32_t before[XGO_DIAG_COUNT], after[XGO_DIAG_COUNT];
    unsigned i;
    init_model(XGO_MODEL_MINI);
    memset(data, 0x5A, sizeof data);
    xgo_board_counters(&board, before);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                          xgo_board_write(&board, XGO_SOURCE_CLI, 0x69, data, sizeof data));
    xgo_board_counters(&board, after);
    TEST_ASSERT_EQUAL_UINT32(1, after[XGO_DIAG_IGNORED_UNMAPPED] - before[XGO_DIAG_IGNORED_UNMAPPED]);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x69, sizeof got, got));
    for (i = 0; i < sizeof got; i++) {
        const unsigned addr = 0x69u + i;
        const int stored = addr <= 0x6Bu || (addr >= XGO_REG_PERIOD_X && addr <= XGO_REG_PERIOD_Z);
        TEST_ASSERT_EQUAL_HEX8(stored ? 0x5A : 0x00, got[i]);
    }
    TEST_ASSERT_EQUAL_UINT(8 + sizeof got, wire_read(0x69, (uint8_t)sizeof got, reply, sizeof reply));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(got, &reply[5], sizeof got);
    write1(XGO_REG_DIGITAL_IN, 0xA5); /* the image's last byte */
    TEST_ASSERT_EQUAL_HEX8(0xA5, read1(XGO_REG_DIGITAL_IN));
    TEST_ASSERT_EQUAL_HEX8(0x00, read1(0x7F));

    /* The other two gaps: 0x82 | 0x83..0x8F | 0x90, and 0x21 | 0x22..0x2F | 0x30. */
    memset(data, 0x3C, sizeof data);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_write(&board, XGO_SOURCE_CLI, 0x82, data, 15));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x80, 20, got));
    for (i = 0; i < 20; i++) {
        const unsigned addr = 0x80u + i;
        const uint8_t want = addr < 0x82u ? 0x5A : addr == 0x82u || addr == 0x90u ? 0x3C
                             : addr == XGO_REG_DIGITAL_IN                      ? 0xA5
                                                                               : 0x00;
        TEST_ASSERT_EQUAL_HEX8(want, got[i]);
    }
    TEST_ASSERT_EQUAL_UINT(8 + 22, wire_read(0x1C, 22, reply, sizeof reply));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x1C, 22, got));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(got, &reply[5], 22);
    for (i = 0x22u - 0x1Cu; i < 0x30u - 0x1Cu; i++) {
        TEST_ASSERT_EQUAL_HEX8(0x00, got[i]);
    }
    TEST_ASSERT_EQUAL_HEX8(0x80, got[XGO_REG_VX - 0x1Cu]); /* initial */
    TEST_ASSERT_EQUAL_HEX8(0x80, got[XGO_REG_VY - 0x1Cu]);
}

/* The traced replies and dropped replies (their data copied at the event). */
static struct {
    unsigned tx, overflows;
    uint8_t addr, len;
    uint8_t data[247];
} traced;

static void trace_replies(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    if (ev->kind == XGO_TRACE_RX || ev->frame == NULL) {
        return;
    }
    if (ev->kind == XGO_TRACE_TX) {
        traced.tx++;
    } else if (ev->reason == XGO_DROP_TX_OVERFLOW) {
        traced.overflows++;
    } else {
        return;
    }
    traced.addr = ev->frame->addr;
    traced.len = ev->frame->len;
    memcpy(traced.data, ev->frame->data, ev->frame->len);
}

/* The longest read the firmware's transmit buffer answers (113 bytes: reads
 * of up to 105), or 120 with the host's buffer (the test's own bound). */
#define LONGEST_READ (XGO_TX_BUFFER_SIZE - 8u < 120u ? XGO_TX_BUFFER_SIZE - 8u : 120u)

/* A read whose reply does not fit the transmit buffer even when it is empty
 * (firmware: 113 bytes, so reads of up to 105) is dropped whole and counted
 * in tx_overflow: not a byte of it is queued, and the trace still shows the
 * data it would have carried. The next read is answered, byte for byte what
 * the registers hold (the reply is built in place in the transmit buffer).
 * The full core answers both. The vendor library's longest read is 24
 * bytes, test_fw_serial's 48, the diagnostic block (xgo-cli diag) 60. */
static void test_reply_longer_than_transmit_buffer(void)
{
    static uint8_t reply[256];
    uint8_t regs[LONGEST_READ + 1u];
    uint32_t before[XGO_DIAG_COUNT], after[XGO_DIAG_COUNT];
    const int fits = XGO_TX_BUFFER_SIZE >= LONGEST_READ + 1u + 8u;
    unsigned sum = (LONGEST_READ + 8u) + 0x12u + 0x30u, i;
    init_model(XGO_MODEL_MINI);
    memset(&traced, 0, sizeof traced);
    xgo_board_set_trace(&board, trace_replies, NULL);
    xgo_board_counters(&board, before);
    TEST_ASSERT_EQUAL_UINT(fits ? LONGEST_READ + 9u : 0u,
                           wire_read(0x00, LONGEST_READ + 1u, reply, sizeof reply));
    TEST_ASSERT_EQUAL_UINT(0, xgo_board_tx_pending(&board)); /* nothing half-queued */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x00, LONGEST_READ + 1u, regs));
    if (XGO_WITH_TRACE) { /* a build without the hook has nothing to show */
        TEST_ASSERT_EQUAL_UINT(fits ? 0u : 1u, traced.overflows);
        TEST_ASSERT_EQUAL_UINT(LONGEST_READ + 1u, traced.len);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(regs, traced.data, LONGEST_READ + 1u);
    }

    /* The longest answered read: from 0x30 on, the whole-unit registers,
     * the joints, the IMU bytes and what follows. */
    TEST_ASSERT_EQUAL_UINT(LONGEST_READ + 8u, wire_read(0x30, LONGEST_READ, reply, sizeof reply));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, 0x30, LONGEST_READ, regs));
    TEST_ASSERT_EQUAL_HEX8(0x55, reply[0]);
    TEST_ASSERT_EQUAL_HEX8(0x00, reply[1]);
    TEST_ASSERT_EQUAL_HEX8(LONGEST_READ + 8u, reply[2]);
    TEST_ASSERT_EQUAL_HEX8(0x12, reply[3]);
    TEST_ASSERT_EQUAL_HEX8(0x30, reply[4]);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(regs, &reply[5], LONGEST_READ);
    for (i = 0; i < LONGEST_READ; i++) {
        sum += regs[i];
    }
    TEST_ASSERT_EQUAL_HEX8((uint8_t)~sum, reply[LONGEST_READ + 5u]);
    TEST_ASSERT_EQUAL_HEX8(0x00, reply[LONGEST_READ + 6u]);
    TEST_ASSERT_EQUAL_HEX8(0xAA, reply[LONGEST_READ + 7u]);
    if (XGO_WITH_TRACE) {
        TEST_ASSERT_EQUAL_UINT(fits ? 2u : 1u, traced.tx);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(regs, traced.data, LONGEST_READ);
    }
    xgo_board_counters(&board, after);
    TEST_ASSERT_EQUAL_UINT32(fits ? 0u : 1u,
                             after[XGO_DIAG_TX_OVERFLOW] - before[XGO_DIAG_TX_OVERFLOW]);
    xgo_board_set_trace(&board, NULL, NULL);
}

/* The diagnostic block (60 bytes) in one read, as xgo-cli diag asks for it:
 * the firmware's transmit buffer answers it. */
static void test_diag_block_in_one_read(void)
{
    static uint8_t reply[256];
    uint8_t block[60];
    init_model(XGO_MODEL_MINI);
    TEST_ASSERT_EQUAL_UINT(68, wire_read(XGO_REG_DIAG, 60, reply, sizeof reply));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_board_read(&board, XGO_REG_DIAG, 60, block));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(block, &reply[5], 60);
}

/* The trace hook only where it is built in: without it a hook that is set
 * is never called, and the drops are counted all the same. */
static unsigned trace_events, trace_drops;
static void count_trace(void *ctx, const xgo_trace_event_t *ev)
{
    (void)ctx;
    ++trace_events;
    trace_drops += ev->kind == XGO_TRACE_DROP;
}

static void test_trace_hook(void)
{
    static const uint8_t garbage[] = {0x55, 0x00, 0x09, 0x02, 0x30, 0x01, 0x00, 0x00, 0xAA}; /* bad checksum */
    uint32_t before[XGO_DIAG_COUNT], after[XGO_DIAG_COUNT];
    uint8_t reply[16];
    init_model(XGO_MODEL_MINI);
    trace_events = trace_drops = 0;
    xgo_board_set_trace(&board, count_trace, NULL);
    xgo_board_counters(&board, before);
    xgo_board_receive(&board, garbage, sizeof garbage, 0);
    TEST_ASSERT_EQUAL_UINT(9, wire_read(XGO_REG_BATTERY, 1, reply, sizeof reply)); /* answered */
    xgo_board_counters(&board, after);
    TEST_ASSERT_EQUAL_UINT32(1, after[XGO_DIAG_BAD_CHECKSUM] - before[XGO_DIAG_BAD_CHECKSUM]);
    if (XGO_WITH_TRACE) { /* the drops (the frame, its bytes rescanned), the request, its reply */
        TEST_ASSERT_GREATER_OR_EQUAL_UINT(1, trace_drops);
        TEST_ASSERT_EQUAL_UINT(trace_drops + 2u, trace_events);
    } else {
        TEST_ASSERT_EQUAL_UINT(0, trace_events);
    }
    xgo_board_set_trace(&board, NULL, NULL);
}

/* Emulator inputs (ground tilt, a shove) only where they are built in:
 * without them the calls do nothing, the ground reads level and the IMU
 * gives the same attitude as on a board nobody tilted or pushed. */
static void test_emulator_inputs(void)
{
    static xgo_board_t plain;
    int32_t roll, pitch, imu[3], imu_plain[3];
    init_model(XGO_MODEL_MINI);
    xgo_board_init(&plain, NULL);
    xgo_board_set_ground_tilt(&board, 10000, -5000);
    xgo_board_push(&board, 8000, 0);
    xgo_board_ground_tilt(&board, &roll, &pitch);
    TEST_ASSERT_EQUAL_INT32(XGO_WITH_EMULATOR_INPUTS ? 10000 : 0, roll);
    TEST_ASSERT_EQUAL_INT32(XGO_WITH_EMULATOR_INPUTS ? -5000 : 0, pitch);
    ticks(5);
    while (xgo_board_time_ms(&plain) < xgo_board_time_ms(&board)) {
        xgo_board_tick(&plain);
    }
    xgo_board_imu_mdeg(&board, imu);
    xgo_board_imu_mdeg(&plain, imu_plain);
    TEST_ASSERT_EQUAL_INT(XGO_WITH_EMULATOR_INPUTS ? 0 : 1, imu[0] == imu_plain[0]);
    TEST_ASSERT_EQUAL_INT(XGO_WITH_EMULATOR_INPUTS ? 0 : 1, imu[1] == imu_plain[1]);
    TEST_ASSERT_EQUAL_INT32(imu_plain[2], imu[2]);
}

/* Names only where they are built in; the lookups answer either way. */
static void test_names(void)
{
    if (XGO_WITH_NAMES) {
        TEST_ASSERT_EQUAL_STRING("vx", xgo_reg_name(XGO_REG_VX));
        TEST_ASSERT_EQUAL_STRING("sit", xgo_action_name(XGO_ACTION_SIT));
        TEST_ASSERT_EQUAL_STRING("frames_ok", xgo_diag_name(XGO_DIAG_FRAMES_OK));
    } else {
        TEST_ASSERT_EQUAL_STRING("", xgo_reg_name(XGO_REG_VX));
        TEST_ASSERT_EQUAL_STRING("", xgo_action_name(XGO_ACTION_SIT));
        TEST_ASSERT_EQUAL_STRING("", xgo_diag_name(XGO_DIAG_FRAMES_OK));
    }
    TEST_ASSERT_EQUAL_STRING("-", xgo_reg_name(0x11)); /* no register there */
    TEST_ASSERT_NULL(xgo_action_name(0));
    TEST_ASSERT_EQUAL_STRING("unknown", xgo_diag_name(XGO_DIAG_COUNT));
    TEST_ASSERT_EQUAL_UINT8(XGO_REG_VX, xgo_reg_find(XGO_REG_VX)->addr);
}

/* ---- the device layer (xgo/port.h) with the configuration's buffers ---- */

/* A port whose UART takes a few bytes at a time, so replies pile up in the
 * board's transmit buffer while requests keep arriving. */
struct xgo_port_s {
    uint8_t out[1024];
    size_t n;
};

static xgo_port_t port;
static xgo_device_t device;

uint32_t xgo_port_millis(xgo_port_t *p)
{
    (void)p;
    return 0;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    return sizeof p->out - p->n < 5u ? sizeof p->out - p->n : 5u;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    memcpy(&p->out[p->n], bytes, n);
    p->n += n;
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    (void)p;
}

int xgo_port_nv_load(xgo_port_t *p, xgo_board_nv_t *nv)
{
    (void)p, (void)nv;
    return 0;
}

int xgo_port_nv_save(xgo_port_t *p, const xgo_board_nv_t *nv)
{
    (void)p, (void)nv;
    return 1;
}

void xgo_port_servo_write(xgo_port_t *p, const int32_t raw_mdeg[XGO_SERVO_COUNT], uint16_t limp)
{
    (void)p, (void)raw_mdeg, (void)limp;
}

/* Twelve back-to-back reads of the twelve joints (240 reply bytes, more than
 * the firmware's 113-byte transmit buffer holds) through the device: every
 * reply arrives whole and in order, none is dropped. The device feeds input
 * only while the longest reply the board can queue still fits. */
static void test_device_back_to_back_reads(void)
{
    static const uint8_t req[9] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
    uint32_t counters[XGO_DIAG_COUNT];
    xgo_device_stats_t stats;
    unsigned i, rounds;
    memset(&port, 0, sizeof port);
    xgo_device_init(&device, &port, NULL);
    for (i = 0; i < 12u * sizeof req; i++) {
        /* A full ring (the firmware's holds 64 bytes: less than the 108
         * sent) masks RX until the device has fed it on: as a port does. */
        for (rounds = 0; rounds < 1000 && !xgo_device_rx_accepting(&device); rounds++) {
            xgo_device_run(&device);
        }
        TEST_ASSERT_TRUE(xgo_device_rx_accepting(&device));
        (void)xgo_device_rx_put(&device, req[i % sizeof req]);
    }
    for (rounds = 0; rounds < 1000 && port.n < 12u * 20u; rounds++) {
        xgo_device_run(&device);
    }
    TEST_ASSERT_EQUAL_UINT(12u * 20u, port.n);
    for (i = 0; i < 12; i++) {
        TEST_ASSERT_EQUAL_HEX8(0x55, port.out[20 * i]);
        TEST_ASSERT_EQUAL_HEX8(0x14, port.out[20 * i + 2]);
        TEST_ASSERT_EQUAL_HEX8(0xAA, port.out[20 * i + 19]);
    }
    xgo_board_counters(xgo_device_board(&device), counters);
    TEST_ASSERT_EQUAL_UINT32(12, counters[XGO_DIAG_FRAMES_OK]);
    TEST_ASSERT_EQUAL_UINT32(0, counters[XGO_DIAG_TX_OVERFLOW]);
    xgo_device_stats(&device, &stats);
    TEST_ASSERT_EQUAL_UINT32(XGO_PORT_RX_RING_SIZE < 108u ? 1u : 0u, stats.rx_pauses > 0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_models_built_in);
    RUN_TEST(test_model_not_built_in_is_served_as_mini);
    RUN_TEST(test_arm_registers_without_mini2);
    RUN_TEST(test_walk_without_odometry_and_inertial);
    RUN_TEST(test_spec_read_reply);
    RUN_TEST(test_action_runs);
    RUN_TEST(test_frame_length_limit);
    RUN_TEST(test_register_image_gap);
    RUN_TEST(test_reply_longer_than_transmit_buffer);
    RUN_TEST(test_diag_block_in_one_read);
    RUN_TEST(test_trace_hook);
    RUN_TEST(test_emulator_inputs);
    RUN_TEST(test_names);
    RUN_TEST(test_device_back_to_back_reads);
    return UNITY_END();
}
