/*
 * mcu_selftest.c - the portable core running on a Cortex-M0 (QEMU -M microbit)
 * and, compiled unchanged for the host, the reference it must match.
 *
 *   1. the spec's examples on the wire: with every servo at 0x80 the read
 *      request gets the spec's reply byte for byte; then the write (vx = 0xFF)
 *      and after 1 s of trotting the same read: the reply's framing and its
 *      12 joint bytes;
 *   2. a trot with body pose (as tools/bench_board.c) for 2000 ticks, then the
 *      joints, the IMU bytes, the IMU float32 views, every register and the
 *      diagnostic block read over the wire, plus the internal joint angles;
 *      standing idle; preset action 24 played to its end;
 *   3. a stream of write and read frames fed byte by byte, then in as few
 *      calls as the transmit buffer allows (one with the host's).
 *
 * Lines starting with "RESULT" are the program's results: tools/mcu/run.sh
 * requires them to be identical on the host and on the MCU (the core is
 * integer-only, so they must match bit for bit). "COST" lines are exact
 * instruction counts (measure.h), printed on the MCU only. Exit status 0 when
 * every check passes; a distinct code per failed check otherwise (startup.c
 * has the fault codes). Built with -DMCU_SELFTEST_FAULT it faults at once on
 * purpose (run.sh checks the HardFault exit); built with the core's checks on
 * and -DMCU_SELFTEST_ASSERT it makes a caller's mistake on purpose, which the
 * core's XGO_ASSERT reports through this program's hook (exit 19).
 */
#include <stddef.h>
#include <stdint.h>

#include "actions.h"  /* src/core (private): xgo_action_duration_ticks */
#include "board_io.h" /* test/support: the wire helpers the tests use */
#include "measure.h"
#include "semihost.h"
#include "xgo/board.h"

/* Exit codes */
#define FAIL_SPEC_REPLY 10
#define FAIL_FRAMING 11
#define FAIL_JOINTS_VS_REGS 12
#define FAIL_NOT_TROTTING 13
#define FAIL_STREAM_REPLIES 14
#define FAIL_CALIBRATION 15
#define FAIL_INTERVAL 16
#define FAIL_COUNTERS 17
#define FAIL_ACTION 18
#define FAIL_ASSERT 19        /* a core check failed (xgo_assert_failed) */
#define FAIL_ASSERT_MISSED 20 /* a caller bug went through unnoticed */

#define WARMUP_TICKS 1000u
#define MEASURED_TICKS 1000u
#define STREAM_REPEATS 16u
#define MAX_INTERVAL_INSNS 3500000u /* well inside the 24-bit SysTick range */

static xgo_board_t board; /* 2.6 KB on the M0: in .bss */

/* ---- output without a C library ----------------------------------------- */

typedef struct line_s {
    char s[256];
    size_t n;
} line_t;

static void l_begin(line_t *l, const char *tag)
{
    l->n = 0;
    l->s[0] = '\0';
    while (*tag != '\0' && l->n < sizeof l->s - 2) {
        l->s[l->n++] = *tag++;
    }
    l->s[l->n] = '\0';
}

static void l_char(line_t *l, char c)
{
    if (l->n < sizeof l->s - 2) {
        l->s[l->n++] = c;
        l->s[l->n] = '\0';
    }
}

static void l_str(line_t *l, const char *s)
{
    while (*s != '\0') {
        l_char(l, *s++);
    }
}

static void l_hex(line_t *l, uint32_t v, int digits)
{
    static const char hex[] = "0123456789abcdef";
    int i;
    for (i = digits - 1; i >= 0; i--) {
        l_char(l, hex[(v >> (4 * i)) & 15u]);
    }
}

static void l_bytes(line_t *l, const uint8_t *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        l_char(l, ' ');
        l_hex(l, b[i], 2);
    }
}

static void l_u32(line_t *l, uint32_t v)
{
    char d[10];
    int k = 0;
    do {
        d[k++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v != 0u);
    while (k > 0) {
        l_char(l, d[--k]);
    }
}

static void l_i32(line_t *l, int32_t v)
{
    if (v < 0) {
        l_char(l, '-');
        l_u32(l, 0u - (uint32_t)v);
    } else {
        l_u32(l, (uint32_t)v);
    }
}

/* sum / count with one decimal */
static void l_avg(line_t *l, uint32_t sum, uint32_t count)
{
    uint32_t tenths = (uint32_t)(((uint64_t)sum * 10u + count / 2u) / count);
    l_u32(l, tenths / 10u);
    l_char(l, '.');
    l_u32(l, tenths % 10u);
}

static void l_end(line_t *l)
{
    l_char(l, '\n');
    sh_write0(l->s);
}

static void fail(int code, const char *what)
{
    line_t l;
    l_begin(&l, "FAIL ");
    l_str(&l, what);
    l_end(&l);
    sh_exit(code);
}

/* ---- the core's checks ---------------------------------------------------- */

#if XGO_ASSERT_ENABLED
/* The hook a microcontroller port gives the core's checks (xgo/config.h):
 * say which check failed over the debug channel and stop. A product would
 * log it and reset; it must not return into the core. */
void xgo_assert_failed(const char *file, int line, const char *expr)
{
    line_t l;
    l_begin(&l, "ASSERT ");
    l_str(&l, file);
    l_char(&l, ':');
    l_u32(&l, (uint32_t)line);
    l_str(&l, ": ");
    l_str(&l, expr);
    l_end(&l);
    sh_exit(FAIL_ASSERT);
}
#endif

/* ---- digest: FNV-1a 32 ---------------------------------------------------- */

static uint32_t fnv_bytes(uint32_t h, const uint8_t *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= b[i];
        h *= 16777619u;
    }
    return h;
}

static uint32_t fnv_i32(uint32_t h, int32_t v)
{
    uint8_t b[4];
    uint32_t u = (uint32_t)v;
    b[0] = (uint8_t)u;
    b[1] = (uint8_t)(u >> 8);
    b[2] = (uint8_t)(u >> 16);
    b[3] = (uint8_t)(u >> 24);
    return fnv_bytes(h, b, 4);
}

#define FNV_INIT 2166136261u

/* ---- cost statistics ---------------------------------------------------- */

typedef struct stats_s {
    uint32_t count, sum, min, max;
    uint32_t *samples; /* NULL, or room for every value (percentiles) */
} stats_t;

static void st_init(stats_t *s, uint32_t *samples)
{
    s->count = 0;
    s->sum = 0;
    s->min = 0xFFFFFFFFu;
    s->max = 0;
    s->samples = samples;
}

/* harness overhead in instructions, from calibrate() */
static uint32_t overhead;

static uint32_t insns_of(uint32_t ticks)
{
    uint32_t insns = mcu_ticks_to_insns(ticks);
    if (insns > MAX_INTERVAL_INSNS) {
        fail(FAIL_INTERVAL, "interval too long for the 24-bit SysTick");
    }
    return insns >= overhead ? insns - overhead : 0u;
}

static void st_add(stats_t *s, uint32_t ticks)
{
    uint32_t v = insns_of(ticks);
    if (s->samples != NULL) {
        s->samples[s->count] = v;
    }
    s->count++;
    s->sum += v;
    if (v < s->min) {
        s->min = v;
    }
    if (v > s->max) {
        s->max = v;
    }
}

static int counting; /* 1 on the MCU */

/* Stack depth below the caller (bytes) of the core's entry points, measured
 * with mcu_stack_probe_*; they include the measuring stub's 16 bytes. */
static uint32_t stack_tick, stack_receive, stack_transmit;

static void stack_max(uint32_t *keep, uint32_t depth)
{
    if (depth > *keep) {
        *keep = depth;
    }
}

static void print_stats(const char *what, const stats_t *s)
{
    line_t l;
    if (!counting || s->count == 0) {
        return;
    }
    l_begin(&l, "COST ");
    l_str(&l, what);
    l_str(&l, ": min ");
    l_u32(&l, s->min);
    l_str(&l, " avg ");
    l_avg(&l, s->sum, s->count);
    l_str(&l, " max ");
    l_u32(&l, s->max);
    l_str(&l, " instructions (n=");
    l_u32(&l, s->count);
    l_str(&l, ")");
    l_end(&l);
    if (s->samples != NULL) {
        uint32_t i, j, over = 0;
        for (i = 1; i < s->count; i++) { /* insertion sort */
            uint32_t v = s->samples[i];
            for (j = i; j > 0 && s->samples[j - 1] > v; j--) {
                s->samples[j] = s->samples[j - 1];
            }
            s->samples[j] = v;
        }
        for (i = 0; i < s->count; i++) {
            if (2u * s->samples[i] > 3u * s->samples[s->count / 2u]) {
                over++;
            }
        }
        l_begin(&l, "COST ");
        l_str(&l, what);
        l_str(&l, ": p50 ");
        l_u32(&l, s->samples[s->count / 2u]);
        l_str(&l, " p90 ");
        l_u32(&l, s->samples[s->count * 9u / 10u]);
        l_str(&l, " p99 ");
        l_u32(&l, s->samples[s->count * 99u / 100u]);
        l_str(&l, "; ");
        l_u32(&l, over);
        l_str(&l, " of ");
        l_u32(&l, s->count);
        l_str(&l, " over 1.5 x p50");
        l_end(&l);
    }
}

/* The harness costs a fixed number of instructions (BL, one LDR); an empty
 * function and a loop of exactly 4n+1 instructions pin it down and prove the
 * counts exact. */
static void calibrate(void)
{
    static const uint32_t ns[4] = {1u, 10u, 100u, 1000u};
    uint32_t empty, i;
    line_t l;

    if (!counting) {
        return;
    }
    empty = mcu_ticks_to_insns(mcu_ticks_empty());
    if (empty < 1u) {
        fail(FAIL_CALIBRATION, "empty function measured as 0 instructions");
    }
    overhead = empty - 1u;
    l_begin(&l, "COST calibration: harness overhead ");
    l_u32(&l, overhead);
    l_str(&l, " instructions; 4n+1 loop:");
    for (i = 0; i < 4u; i++) {
        uint32_t got = insns_of(mcu_ticks_loop(ns[i]));
        l_str(&l, " n=");
        l_u32(&l, ns[i]);
        l_str(&l, "->");
        l_u32(&l, got);
        if (got != 4u * ns[i] + 1u) {
            l_end(&l);
            fail(FAIL_CALIBRATION, "loop of 4n+1 instructions not counted exactly");
        }
    }
    l_str(&l, " (exact)");
    l_end(&l);
}

/* ---- the wire ------------------------------------------------------------ */

static void send(const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    (void)mcu_ticks_receive(&board, bytes, n, now_ms);
}

static void write_reg(uint8_t addr, uint8_t v, uint32_t now_ms)
{
    xgo_test_write1(&board, addr, v, now_ms);
}

/* The longest read whose reply fits the transmit buffer (xgo/config.h; the
 * firmware configuration's 113 bytes answer reads of up to 105). */
#define READ_MAX                                                                   \
    (XGO_TX_BUFFER_SIZE - XGO_FRAME_OVERHEAD < XGO_FRAME_MAX_DATA                  \
         ? XGO_TX_BUFFER_SIZE - XGO_FRAME_OVERHEAD                                 \
         : XGO_FRAME_MAX_DATA)

/* Read count registers at addr over the wire, in requests of at most
 * READ_MAX bytes (one with the host's buffer); checks each reply's framing
 * independently of the core's encoder and returns the data in data. */
static void read_regs(uint8_t addr, uint8_t count, uint32_t now_ms, uint8_t *data)
{
    while (count > 0) {
        const uint8_t n = (uint8_t)(count < READ_MAX ? count : READ_MAX);
        const xgo_test_reply_t problem = xgo_test_read(&board, addr, n, now_ms, data);
        if (problem != XGO_TEST_REPLY_OK) {
            fail(FAIL_FRAMING, xgo_test_reply_name(problem));
        }
        addr = (uint8_t)(addr + n);
        data += n;
        count = (uint8_t)(count - n);
    }
}

/* One register as the board holds it (no frame). */
static uint8_t reg(uint8_t addr)
{
    uint8_t v = 0;
    (void)xgo_board_read(&board, addr, 1, &v);
    return v;
}

static void result_bytes(const char *what, const uint8_t *b, size_t n)
{
    line_t l;
    l_begin(&l, "RESULT ");
    l_str(&l, what);
    l_char(&l, ':');
    l_bytes(&l, b, n);
    l_end(&l);
}

static void result_hex32(const char *what, uint32_t v)
{
    line_t l;
    l_begin(&l, "RESULT ");
    l_str(&l, what);
    l_str(&l, ": ");
    l_hex(&l, v, 8);
    l_end(&l);
}

/* ---- 1. the spec's examples ----------------------------------------------- */

static void spec_examples(void)
{
    static const uint8_t write_vx[] = {0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
    static const uint8_t read_servos[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
    static const uint8_t expected[] = {0x55, 0x00, 0x14, 0x12, 0x50, 0x80, 0x80, 0x80, 0x80, 0x80,
                                       0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x89, 0x00, 0xAA};
    uint8_t reply[64];
    uint8_t joints[12];
    size_t n, i;
    uint32_t t;

    uint8_t mid[12];

    /* The spec's reply has every joint at 0x80: servo mode, all at 0x80. */
    xgo_board_init(&board, NULL);
    for (i = 0; i < sizeof mid; i++) {
        mid[i] = 0x80;
    }
    n = xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_SERVO11, mid, sizeof mid, reply, sizeof reply);
    send(reply, n, 0);
    for (t = 0; t < 2u * XGO_TICK_HZ; t++) {
        (void)mcu_ticks_tick(&board);
    }
    send(read_servos, sizeof read_servos, 2000);
    n = xgo_board_transmit(&board, reply, sizeof reply);
    if (n != sizeof expected) {
        fail(FAIL_SPEC_REPLY, "spec read example: reply length");
    }
    for (i = 0; i < n; i++) {
        if (reply[i] != expected[i]) {
            fail(FAIL_SPEC_REPLY, "spec read example: reply bytes");
        }
    }
    result_bytes("servos at 0x80 2 s, spec read reply", reply, n);

    /* The spec's write: vx = 0xFF, no answer; the robot trots. */
    send(write_vx, sizeof write_vx, 2001);
    if (xgo_board_tx_pending(&board) != 0) {
        fail(FAIL_SPEC_REPLY, "a write was answered");
    }
    if (reg(XGO_REG_VX) != 0xFF) {
        fail(FAIL_SPEC_REPLY, "spec write example: vx not 0xFF");
    }

    /* 1 s of trotting at vx = 0xFF, then the same request again. */
    for (t = 0; t < XGO_TICK_HZ; t++) {
        (void)mcu_ticks_tick(&board);
    }
    send(read_servos, sizeof read_servos, 3002);
    n = xgo_board_transmit(&board, reply, sizeof reply);
    if (n != 20 || reply[0] != 0x55 || reply[1] != 0x00 || reply[2] != 0x14 ||
        reply[3] != 0x12 || reply[4] != 0x50 || reply[18] != 0x00 || reply[19] != 0xAA) {
        fail(FAIL_FRAMING, "read after 1 s: framing");
    }
    if (reply[17] != xgo_frame_checksum(0x14, 0x12, 0x50, &reply[5], 12)) {
        fail(FAIL_FRAMING, "read after 1 s: checksum");
    }
    for (i = 0; i < 12; i++) {
        joints[i] = reply[5 + i];
        if (joints[i] != reg((uint8_t)(XGO_REG_SERVO11 + i))) {
            fail(FAIL_JOINTS_VS_REGS, "reply joints differ from registers 0x50..0x5B");
        }
    }
    result_bytes("then vx=0xFF 500 ticks, spec read reply", reply, n);
}

/* ---- 2. trot with body pose; action 24 ------------------------------------ */

/* Internal state the observers do not show (servo targets, the IMU's yaw
 * integral, the battery charge): a white-box digest, on purpose. */
static uint32_t state_digest(uint32_t h)
{
    size_t i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        h = fnv_i32(h, board.motion.servos.angle_mdeg[i]);
        h = fnv_i32(h, board.motion.servos.target_mdeg[i]);
    }
    h = fnv_i32(h, board.motion.imu.roll_mdeg);
    h = fnv_i32(h, board.motion.imu.pitch_mdeg);
    h = fnv_i32(h, board.motion.imu.yaw_mdeg);
    h = fnv_i32(h, board.motion.imu.yaw_acc);
    h = fnv_i32(h, (int32_t)board.motion.battery.charge_upct);
    return h;
}

/* Everything a host can read, over the wire; digest of it all. */
static uint32_t wire_digest(const char *tag, uint32_t now_ms)
{
    uint8_t buf[XGO_FRAME_MAX_DATA];
    uint32_t h = FNV_INIT;
    line_t l;
    int k;

    read_regs(XGO_REG_SERVO11, 12, now_ms, buf);
    h = fnv_bytes(h, buf, 12);
    l_begin(&l, "RESULT ");
    l_str(&l, tag);
    l_str(&l, " joints 0x50..0x5B:");
    l_bytes(&l, buf, 12);
    l_end(&l);

    read_regs(XGO_REG_IMU_ROLL, 3, now_ms, buf);
    h = fnv_bytes(h, buf, 3);
    l_begin(&l, "RESULT ");
    l_str(&l, tag);
    l_str(&l, " imu bytes 0x62..0x64:");
    l_bytes(&l, buf, 3);
    l_str(&l, "; float32 roll pitch yaw:");
    for (k = 0; k < 3; k++) {
        uint32_t bits;
        read_regs((uint8_t)(XGO_REG_IMU_ROLL + k), 4, now_ms, buf);
        h = fnv_bytes(h, buf, 4);
        bits = (uint32_t)buf[0] | (uint32_t)buf[1] << 8 | (uint32_t)buf[2] << 16 |
               (uint32_t)buf[3] << 24;
        l_char(&l, ' ');
        l_hex(&l, bits, 8);
    }
    l_end(&l);

    read_regs(0x00, XGO_REG_DIAG, now_ms, buf); /* every register below the diagnostic block */
    h = fnv_bytes(h, buf, XGO_REG_DIAG);
    read_regs(XGO_REG_DIAG, 4 * XGO_DIAG_SLOTS, now_ms, buf);
    h = fnv_bytes(h, buf, 4 * XGO_DIAG_SLOTS);
    return h;
}

static uint32_t trot_samples[MEASURED_TICKS];

static void trot(void)
{
    stats_t warm, steady;
    uint32_t t, h;
    uintptr_t mark;
    line_t l;
    xgo_gait_status_t gait;
    int32_t q[XGO_SERVO_COUNT];

    xgo_board_init(&board, NULL);
    write_reg(XGO_REG_VX, 0xE0, 0);        /* forward ~19 cm/s */
    write_reg(XGO_REG_VYAW, 0xA0, 0);      /* turning ~25 deg/s */
    write_reg(XGO_REG_BODY_ROLL, 0xA0, 0); /* body pose on top */
    write_reg(XGO_REG_BODY_Z, 0x60, 0);
    write_reg(XGO_REG_PERIOD_PITCH, 0x40, 0);
    st_init(&warm, NULL);
    st_init(&steady, trot_samples);
    mark = mcu_stack_probe_begin();
    for (t = 0; t < WARMUP_TICKS; t++) {
        st_add(&warm, mcu_ticks_tick(&board));
    }
    for (t = 0; t < MEASURED_TICKS; t++) {
        st_add(&steady, mcu_ticks_tick(&board));
    }
    stack_max(&stack_tick, mcu_stack_probe_end(mark));
    xgo_board_gait(&board, &gait);
    if (!gait.walking) {
        fail(FAIL_NOT_TROTTING, "the robot is not trotting after 2000 ticks");
    }
    h = wire_digest("trot 2000 ticks", 4000);
    result_hex32("trot 2000 ticks wire digest", h);
    result_hex32("trot 2000 ticks state digest (angles, targets, imu, battery)",
                 state_digest(FNV_INIT));
    l_begin(&l, "RESULT trot 2000 ticks joint angles mdeg:");
    xgo_board_joints_mdeg(&board, q);
    for (t = 0; t < XGO_SERVO_COUNT; t++) {
        l_char(&l, ' ');
        l_i32(&l, q[t]);
    }
    l_end(&l);
    print_stats("xgo_board_tick, trot + body pose, ticks 1..1000 (start, ramp)", &warm);
    print_stats("xgo_board_tick, trot + body pose, ticks 1001..2000 (steady)", &steady);

    /* Standing idle. */
    xgo_board_init(&board, NULL);
    st_init(&steady, NULL);
    for (t = 0; t < 200u; t++) {
        st_add(&steady, mcu_ticks_tick(&board));
    }
    print_stats("xgo_board_tick, standing idle", &steady);
    result_hex32("idle 200 ticks state digest", state_digest(FNV_INIT));

    /* Preset action 24 (naughty, 7 s) to its end. */
    write_reg(XGO_REG_ACTION, 24, 400);
    st_init(&steady, NULL);
    mark = mcu_stack_probe_begin();
    for (t = 0; t < xgo_action_duration_ticks(24); t++) {
        st_add(&steady, mcu_ticks_tick(&board));
    }
    stack_max(&stack_tick, mcu_stack_probe_end(mark));
    if (xgo_board_action(&board) != 0) {
        fail(FAIL_ACTION, "action 24 still running after its duration");
    }
    print_stats("xgo_board_tick, preset action 24 (naughty, 7 s)", &steady);
    h = wire_digest("action 24", 4000);
    result_hex32("action 24 wire digest", h);
    result_hex32("action 24 state digest", state_digest(FNV_INIT));
}

/* ---- 3. a stream of frames ------------------------------------------------ */

static uint8_t stream[1600];

/* Writes and reads as a host sends them, values varying per repeat. */
static size_t build_stream(uint32_t *reads, uint32_t *reply_bytes)
{
    size_t n = 0;
    uint32_t r;
    *reads = 0;
    *reply_bytes = 0;
    for (r = 0; r < STREAM_REPEATS; r++) {
        uint8_t v = (uint8_t)(0x60 + 8u * r);
        uint8_t body[6];
        uint8_t cnt;
        size_t k;
        for (k = 0; k < sizeof body; k++) {
            body[k] = (uint8_t)(v + 3u * k);
        }
        n += xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_VX, &v, 1, &stream[n], sizeof stream - n);
        n += xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_VYAW, &v, 1, &stream[n], sizeof stream - n);
        n += xgo_frame_encode(XGO_TYPE_WRITE, XGO_REG_BODY_X, body, sizeof body, &stream[n],
                              sizeof stream - n);
        cnt = 12;
        n += xgo_frame_encode(XGO_TYPE_READ, XGO_REG_SERVO11, &cnt, 1, &stream[n],
                              sizeof stream - n);
        cnt = 1;
        n += xgo_frame_encode(XGO_TYPE_READ, XGO_REG_BATTERY, &cnt, 1, &stream[n],
                              sizeof stream - n);
        cnt = 4;
        n += xgo_frame_encode(XGO_TYPE_READ, XGO_REG_IMU_YAW, &cnt, 1, &stream[n],
                              sizeof stream - n);
        *reads += 3;
        *reply_bytes += (12 + 8) + (1 + 8) + (4 + 8);
    }
    return n;
}

/* Reply bytes a frame of the stream asks for (no write here is answered). */
static size_t reply_size(const uint8_t *frame)
{
    return frame[3] == XGO_TYPE_READ ? (size_t)frame[5] + XGO_FRAME_OVERHEAD : 0u;
}

/* Feeds stream[0..n) in as few calls as the transmit buffer allows - each
 * call the frames whose replies fit its room, as a port's device layer does
 * (xgo/port.h) - and drains the replies into out after each call. With the
 * host's 1,024-byte buffer that is the whole stream in one call; a firmware
 * configuration's 256 bytes take several. Returns the receive calls'
 * instructions (sum); *got: reply bytes, *calls: receive calls. */
static uint32_t feed_in_chunks(size_t n, uint8_t *out, uint32_t *got, uint32_t *calls)
{
    uint32_t insns = 0;
    size_t i = 0;
    *got = 0;
    *calls = 0;
    while (i < n) {
        size_t end = i, replies = 0;
        uintptr_t mark;
        while (end < n && replies + reply_size(&stream[end]) <= XGO_TX_BUFFER_SIZE) {
            replies += reply_size(&stream[end]);
            end += stream[end + 2]; /* LEN = whole frame */
        }
        mark = mcu_stack_probe_begin();
        insns += insns_of(mcu_ticks_receive(&board, &stream[i], end - i, 1000));
        stack_max(&stack_receive, mcu_stack_probe_end(mark));
        if (xgo_board_tx_pending(&board) != replies) {
            fail(FAIL_STREAM_REPLIES, "stream in chunks: a chunk's reply bytes");
        }
        mark = mcu_stack_probe_begin();
        (void)mcu_ticks_transmit(&board, &out[*got], replies);
        stack_max(&stack_transmit, mcu_stack_probe_end(mark));
        *got += (uint32_t)replies;
        (*calls)++;
        i = end;
    }
    return insns;
}

static void parse_stream(void)
{
    static uint8_t out[1200];
    stats_t per_byte, last_byte, other_byte, tx;
    uint32_t reads, reply_bytes, got, h, frames_before, whole, calls;
    uint32_t counters[XGO_DIAG_COUNT];
    size_t n, i, pos, frame_end;
    line_t l;

    n = build_stream(&reads, &reply_bytes);
    xgo_board_init(&board, NULL);
    st_init(&per_byte, NULL);
    st_init(&last_byte, NULL);
    st_init(&other_byte, NULL);
    st_init(&tx, NULL);

    /* Byte by byte, as a UART RX interrupt would; 1 ms per frame. */
    h = FNV_INIT;
    got = 0;
    pos = 0;
    for (i = 0, frame_end = 0; i < n; i++) {
        uint32_t c;
        if (i == frame_end) {
            frame_end = i + stream[i + 2]; /* LEN = whole frame */
        }
        c = mcu_ticks_receive(&board, &stream[i], 1, (uint32_t)(10 + pos));
        st_add(&per_byte, c);
        if (i + 1 == frame_end) {
            size_t pending = xgo_board_tx_pending(&board);
            st_add(&last_byte, c);
            pos++;
            if (pending > 0) {
                st_add(&tx, mcu_ticks_transmit(&board, out, sizeof out));
                h = fnv_bytes(h, out, pending);
                got += (uint32_t)pending;
            }
        } else {
            st_add(&other_byte, c);
        }
    }
    if (got != reply_bytes) {
        fail(FAIL_STREAM_REPLIES, "byte-by-byte stream: reply bytes");
    }
    xgo_board_counters(&board, counters);
    frames_before = counters[XGO_DIAG_FRAMES_OK];
    if (frames_before != 6u * STREAM_REPEATS || counters[XGO_DIAG_BYTES_DISCARDED] != 0) {
        fail(FAIL_COUNTERS, "byte-by-byte stream: frames_ok / bytes_discarded");
    }
    result_hex32("stream byte by byte, replies digest", h);

    /* The whole stream in as few calls as the transmit buffer allows. */
    whole = feed_in_chunks(n, out, &got, &calls);
    if (got != reply_bytes) {
        fail(FAIL_STREAM_REPLIES, "stream in chunks: reply bytes");
    }
    if (fnv_bytes(FNV_INIT, out, reply_bytes) != h) {
        fail(FAIL_STREAM_REPLIES, "stream in chunks: replies differ from byte by byte");
    }
    xgo_board_counters(&board, counters);
    if (counters[XGO_DIAG_FRAMES_OK] != 2u * frames_before) {
        fail(FAIL_COUNTERS, "stream in chunks: frames_ok");
    }

    if (counting) {
        l_begin(&l, "COST stream: ");
        l_u32(&l, (uint32_t)n);
        l_str(&l, " bytes, ");
        l_u32(&l, 6u * STREAM_REPEATS);
        l_str(&l, " frames (per repeat: write vx, write vyaw, write 6 body bytes, read 12 "
                  "joints, read battery, read yaw float)");
        l_end(&l);
        print_stats("xgo_board_receive, 1 byte per call, every byte", &per_byte);
        print_stats("xgo_board_receive, 1 byte per call, a frame's last byte (apply/answer)",
                    &last_byte);
        print_stats("xgo_board_receive, 1 byte per call, other bytes", &other_byte);
        print_stats("xgo_board_transmit, one reply (9..20 bytes) per call", &tx);
        l_begin(&l, "COST xgo_board_receive, whole stream in ");
        l_u32(&l, calls);
        l_str(&l, calls == 1 ? " call: " : " calls (the frames whose replies fit the transmit "
                                         "buffer, drained between calls): ");
        l_u32(&l, whole);
        l_str(&l, " instructions = ");
        l_avg(&l, whole, (uint32_t)n);
        l_str(&l, " per byte");
        l_end(&l);
    }
}

int main(void)
{
    line_t l;

#ifdef MCU_SELFTEST_FAULT
    /* run.sh checks the fault path: an undefined instruction is a HardFault
     * (on a Cortex-M3 an escalated UsageFault); startup.c reports it and
     * exits with 91. */
    __asm__ volatile("udf #0");
#endif
#ifdef MCU_SELFTEST_ASSERT
    {   /* joint 12 does not exist: a caller's bug, not bad input */
        int32_t lo, hi;
        xgo_board_init(&board, NULL);
        xgo_board_joint_limits_mdeg(&board, XGO_SERVO_COUNT, &lo, &hi);
        fail(FAIL_ASSERT_MISSED, "joint 12 went unnoticed");
    }
#endif
    counting = mcu_count_start();
    calibrate();
    spec_examples();
    trot();
    parse_stream();

    l_begin(&l, "INFO sizeof(xgo_board_t) = ");
    l_u32(&l, (uint32_t)sizeof(xgo_board_t));
    l_str(&l, " bytes");
    l_end(&l);
    if (counting) {
        l_begin(&l, "COST stack: deepest use ");
        l_u32(&l, mcu_stack_used());
        l_str(&l, " bytes (this program); RAM never touched ");
        l_u32(&l, mcu_stack_free_min());
        l_str(&l, " bytes");
        l_end(&l);
        l_begin(&l, "COST stack below the caller (incl. 16 bytes of the measuring stub): "
                    "xgo_board_tick ");
        l_u32(&l, stack_tick);
        l_str(&l, ", xgo_board_receive ");
        l_u32(&l, stack_receive);
        l_str(&l, ", xgo_board_transmit ");
        l_u32(&l, stack_transmit);
        l_str(&l, " bytes");
        l_end(&l);
    }
    sh_write0("PASS\n");
    return 0;
}
