/*
 * fuzz_board.c - libFuzzer target for the whole core: an input is a program
 * (program.h) that drives one board - wire bytes, well-formed requests,
 * control ticks in every mode and action, silence, hang-ups, the emulator's
 * inputs, writes from the view, non-volatile data - while promises.c checks
 * what the board promises after every step (replies, read-only registers,
 * joint steps and limits, counters, units). A broken promise aborts.
 *
 * The board runs on its own (xgo/board.h) or, when the program's first byte
 * says so, inside the device layer through a port (xgo/port.h,
 * device_port.c): the same promises hold either way.
 *
 * Built with libFuzzer when the compiler is clang (fuzz_board); replay.c
 * runs saved inputs and the seed corpus without it (fuzz_board_replay).
 */
#include <stdint.h>
#include <string.h>

#include "device_port.h"
#include "program.h"
#include "promises.h"
#include "xgo/emulator.h"
#include "xgo/profile.h"

typedef struct fuzz_run_s {
    const uint8_t *in;
    size_t size, at;
    xgo_board_t *board;
    xgo_device_t *device; /* NULL: the board on its own */
    fuzz_promises_t promises;
    uint32_t now_ms;   /* the parser's clock */
    unsigned ticks;    /* run so far */
} fuzz_run_t;

/* The next input byte; 0 once the input is used up. */
static uint8_t next(fuzz_run_t *r)
{
    return r->at < r->size ? r->in[r->at++] : 0u;
}

static void feed(fuzz_run_t *r, const uint8_t *bytes, size_t n)
{
    fuzz_promises_before_write(&r->promises);
    if (r->device != NULL) {
        xgo_device_stats_t before, after;
        xgo_device_stats(r->device, &before);
        fuzz_device_receive(r->device, bytes, n);
        xgo_device_stats(r->device, &after);
        fuzz_promises_fed(&r->promises, after.rx_bytes - before.rx_bytes);
    } else {
        fuzz_promises_fed(&r->promises, n);
        xgo_board_receive(r->board, bytes, n, r->now_ms);
    }
    fuzz_promises_after_write(&r->promises);
}

/* The parser's clock moves on: silence on the line (or time between ticks). */
static void quiet(fuzz_run_t *r, uint32_t ms)
{
    r->now_ms += ms;
    if (r->device != NULL) {
        r->device->port->now_ms += ms;
        xgo_device_run(r->device);
    } else {
        xgo_board_poll(r->board, r->now_ms);
    }
}

static void op_raw(fuzz_run_t *r)
{
    uint8_t bytes[64];
    size_t n = 1u + next(r) % sizeof bytes, i;
    for (i = 0; i < n; i++) {
        bytes[i] = next(r);
    }
    feed(r, bytes, n);
}

static void op_write(fuzz_run_t *r)
{
    uint8_t data[16], frame[16 + XGO_FRAME_OVERHEAD];
    const uint8_t addr = next(r), shape = next(r);
    size_t n = 1u + (shape & 15u), i;
    for (i = 0; i < n; i++) {
        data[i] = next(r);
    }
    n = xgo_frame_encode((shape & 0x80u) ? XGO_TYPE_WRITE_LEGACY : XGO_TYPE_WRITE, addr, data, n,
                         frame, sizeof frame);
    feed(r, frame, n);
    fuzz_promises_units(&r->promises, addr, data, n - XGO_FRAME_OVERHEAD);
}

static void op_read(fuzz_run_t *r)
{
    uint8_t frame[XGO_READ_REQUEST_LEN];
    const uint8_t addr = next(r), count = next(r);
    feed(r, frame, xgo_frame_encode(XGO_TYPE_READ, addr, &count, 1, frame, sizeof frame));
}

static void op_ticks(fuzz_run_t *r)
{
    unsigned k = FUZZ_TICKS(next(r));
    while (k-- > 0 && r->ticks < FUZZ_MAX_TICKS) {
        r->ticks++;
        if (r->device != NULL) {
            r->now_ms += 1000u / XGO_TICK_HZ;
            fuzz_device_tick(r->device);
        } else {
            xgo_board_tick(r->board);
            quiet(r, 1000u / XGO_TICK_HZ);
        }
        fuzz_promises_after_tick(&r->promises);
    }
}

static void op_view_write(fuzz_run_t *r)
{
    uint8_t data[255];
    const uint8_t addr = next(r);
    size_t n = next(r), i;
    for (i = 0; i < n; i++) {
        data[i] = next(r);
    }
    fuzz_promises_before_write(&r->promises);
    (void)xgo_board_write(r->board, XGO_SOURCE_VIEW, addr, data, n);
    fuzz_promises_after_write(&r->promises);
}

static void op_nv(fuzz_run_t *r)
{
    xgo_board_nv_t nv;
    unsigned i;
    for (i = 0; i < XGO_BT_NAME_LEN; i++) {
        nv.bt_name[i] = (char)next(r);
    }
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        nv.zero_offset_mdeg[i] = (int8_t)next(r) * 3000;
    }
    (void)xgo_board_set_nv(r->board, &nv);
    fuzz_promises_rebase_joints(&r->promises);
}

/* roll, pitch: two int8 x 500 mdeg (up to +-64 degrees). */
static void next_angles(fuzz_run_t *r, int32_t *roll, int32_t *pitch)
{
    *roll = (int8_t)next(r) * 500;
    *pitch = (int8_t)next(r) * 500;
}

static void step(fuzz_run_t *r, fuzz_op_t op)
{
    int32_t roll, pitch;
    switch (op) {
    case FUZZ_OP_RAW: op_raw(r); break;
    case FUZZ_OP_WRITE: op_write(r); break;
    case FUZZ_OP_READ: op_read(r); break;
    case FUZZ_OP_TICKS: op_ticks(r); break;
    case FUZZ_OP_SILENCE: quiet(r, next(r)); break;
    case FUZZ_OP_HANGUP: xgo_board_hangup(r->board); break;
    case FUZZ_OP_TILT:
        next_angles(r, &roll, &pitch);
        xgo_board_set_ground_tilt(r->board, roll, pitch);
        break;
    case FUZZ_OP_BATTERY: xgo_board_set_battery(r->board, next(r)); break;
    case FUZZ_OP_PUSH:
        next_angles(r, &roll, &pitch);
        xgo_board_push(r->board, roll, pitch);
        break;
    case FUZZ_OP_VIEW_WRITE: op_view_write(r); break;
    case FUZZ_OP_NV: op_nv(r); break;
    case FUZZ_OP_COUNT: break;
    }
}

/* Everything the board sent since the last drain, checked. The device's
 * main loop runs first: a hang-up or a view write may have queued replies
 * on the board since it last ran. */
static void drain(fuzz_run_t *r)
{
    static uint8_t out[FUZZ_PORT_OUT_CAP];
    size_t n;
    if (r->device != NULL) {
        xgo_device_run(r->device);
        n = fuzz_device_output(r->device, out, sizeof out);
    } else {
        n = xgo_board_transmit(r->board, out, sizeof out);
    }
    fuzz_promises_drain(&r->promises, out, n, r->now_ms);
}

/* Byte 0 (program.h): bit 0 Lite, bits 1-2 the silence timeout, bit 3
 * through the device layer, bits 4-6 the battery (0..7 -> 0..100 %: the
 * API takes at most 100, more is a caller bug that XGO_ASSERT stops), bit 7
 * the Mini2 (its arm is fuzzed only on that model). */
static void start(fuzz_run_t *r, uint8_t config)
{
    static const uint32_t k_timeouts[4] = {0, 5, XGO_PARSER_DEFAULT_TIMEOUT_MS, 200};
    static xgo_board_t board; /* static: large, keeps the fuzzer's stack small */
    static xgo_device_t device;
    static xgo_port_t port;
    xgo_board_config_t cfg;
    xgo_board_default_config(&cfg);
    cfg.model = (config & FUZZ_CONFIG_MINI2) ? XGO_MODEL_MINI2 : (config & 1u) ? XGO_MODEL_LITE : XGO_MODEL_MINI;
    cfg.parser_timeout_ms = k_timeouts[(config >> 1) & 3u];
    cfg.battery_pct = (uint8_t)(((config >> 4) & 7u) * 100u / 7u);
    if (config & FUZZ_CONFIG_DEVICE) {
        fuzz_device_init(&device, &port, &cfg);
        r->device = &device;
        r->board = xgo_device_board(&device);
    } else {
        xgo_board_init(&board, &cfg);
        r->board = &board;
    }
    fuzz_promises_init(&r->promises, r->board, xgo_profile_get((unsigned)cfg.model));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fuzz_run_t run;
    if (size < 1) {
        return 0;
    }
    memset(&run, 0, sizeof run);
    run.in = data;
    run.size = size;
    run.at = 1;
    start(&run, data[0]);
    while (run.at < run.size) {
        step(&run, (fuzz_op_t)(next(&run) % FUZZ_OP_COUNT));
        drain(&run);
    }
    xgo_board_hangup(run.board);
    drain(&run);
    fuzz_promises_finish(&run.promises);
    return 0;
}
