/* seeds.c - the generated seed corpus (see seeds.h). */
#include "seeds.h"

#include <stdio.h>

#include "program.h"
#include "xgo/board.h"

typedef struct seed_s {
    uint8_t *buf;
    size_t len, cap;
} seed_t;

static void put(seed_t *s, uint8_t b)
{
    if (s->len < s->cap) {
        s->buf[s->len++] = b;
    }
}

static void write_n(seed_t *s, uint8_t addr, const uint8_t *data, size_t n)
{
    size_t i;
    put(s, FUZZ_OP_WRITE);
    put(s, addr);
    put(s, (uint8_t)(n - 1u));
    for (i = 0; i < n; i++) {
        put(s, data[i]);
    }
}

static void write1(seed_t *s, uint8_t addr, uint8_t value)
{
    write_n(s, addr, &value, 1);
}

static void read_regs(seed_t *s, uint8_t addr, uint8_t n)
{
    put(s, FUZZ_OP_READ);
    put(s, addr);
    put(s, n);
}

/* About ms of control ticks, then the joints read back. */
static void run_ms(seed_t *s, unsigned ms)
{
    unsigned ticks = ms * XGO_TICK_HZ / 1000u;
    while (ticks > 0) {
        unsigned k = (ticks - 1u) / 8u;
        k = k > 255u ? 255u : k;
        put(s, FUZZ_OP_TICKS);
        put(s, (uint8_t)k);
        ticks -= ticks < FUZZ_TICKS(k) ? ticks : FUZZ_TICKS(k);
    }
    read_regs(s, XGO_REG_SERVO11, 12);
}

static void raw(seed_t *s, const uint8_t *bytes, size_t n)
{
    size_t i;
    put(s, FUZZ_OP_RAW);
    put(s, (uint8_t)(n - 1u));
    for (i = 0; i < n; i++) {
        put(s, bytes[i]);
    }
}

/* ------------------------------------------------------------ recipes */

static void seed_spec(seed_t *s, unsigned arg)
{
    static const uint8_t spec[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA,
                                   0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00, 0xAA};
    (void)arg;
    raw(s, spec, sizeof spec);
    run_ms(s, 500);
}

/* Walking: gait type arg & 3, move mode arg >> 2, turning; then the next
 * gait type while walking. */
static void seed_walk(seed_t *s, unsigned arg)
{
    write1(s, XGO_REG_GAIT_TYPE, (uint8_t)(arg & 3u));
    write1(s, XGO_REG_MOVE_MODE, (uint8_t)(arg >> 2));
    write_n(s, XGO_REG_VX, (const uint8_t *)"\xE0\x60\x98", 3);
    run_ms(s, 1500);
    write1(s, XGO_REG_GAIT_TYPE, (uint8_t)((arg + 1u) & 3u));
    run_ms(s, 1000);
    write_n(s, XGO_REG_VX, (const uint8_t *)"\x20\xA0\x40", 3);
    run_ms(s, 1500);
    write_n(s, XGO_REG_VX, (const uint8_t *)"\x80\x80\x80", 3);
    run_ms(s, 1000);
}

/* Flat out in every direction, turning past +-180 degrees, sudden
 * reversals: what the gait's speed governor is there for. */
static void seed_sprint(seed_t *s, unsigned arg)
{
    static const uint8_t cmd[4][3] = {{0xFF, 0xFF, 0xFF}, {0x00, 0x00, 0x00},
                                      {0xFF, 0x00, 0x00}, {0x00, 0xFF, 0xFF}};
    unsigned i;
    write1(s, XGO_REG_GAIT_TYPE, (uint8_t)arg);
    for (i = 0; i < 4; i++) {
        write_n(s, XGO_REG_VX, cmd[i], 3);
        run_ms(s, i == 0 ? 3000 : 800);
    }
}

static void seed_body(seed_t *s, unsigned arg)
{
    static const uint8_t pose[2][6] = {{0xFF, 0x00, 0x20, 0xFF, 0x00, 0xC0},
                                       {0x00, 0xFF, 0xFF, 0x00, 0xFF, 0x10}};
    static const uint8_t periods[3] = {0x40, 0x80, 0xC0};
    write_n(s, XGO_REG_BODY_X, pose[arg & 1u], 6);
    run_ms(s, 800);
    write_n(s, XGO_REG_PERIOD_ROLL, periods, 3);
    write_n(s, XGO_REG_PERIOD_X, periods, 3);
    write1(s, XGO_REG_MARK_TIME, 0x60);
    run_ms(s, 2500);
    write1(s, XGO_REG_STAND, 1);
    run_ms(s, 800);
}

static void seed_leg_servo(seed_t *s, unsigned arg)
{
    static const uint8_t feet[12] = {0xFF, 0x00, 0x00, 0x00, 0xFF, 0xFF,
                                     0x40, 0xC0, 0x80, 0xC0, 0x40, 0x20};
    static const uint8_t joints[12] = {0x00, 0xFF, 0x80, 0xFF, 0x00, 0x20,
                                       0xA0, 0x60, 0xFF, 0x10, 0xF0, 0x80};
    if (arg == 0) {
        write_n(s, XGO_REG_LEG1_X, feet, 12);
    } else {
        write1(s, XGO_REG_SERVO_SPEED, (uint8_t)(arg * 60u));
        write_n(s, XGO_REG_SERVO11, joints, 12);
    }
    run_ms(s, 1500);
    write1(s, XGO_REG_VX, 0xC0); /* back to whole-unit mode */
    run_ms(s, 800);
}

static void seed_unload_calibrate(seed_t *s, unsigned arg)
{
    static const uint8_t unload[] = {0x11, 0x22, 0x13, 0x24, 0x21, 0x01, 0x00};
    size_t i;
    (void)arg;
    for (i = 0; i < sizeof unload; i++) {
        write1(s, XGO_REG_UNLOAD, unload[i]);
        run_ms(s, 200);
    }
    write1(s, XGO_REG_CALIBRATION, 1);
    run_ms(s, 300);
    write1(s, XGO_REG_SET_ZERO, 1);
    run_ms(s, 100);
    write1(s, XGO_REG_CALIBRATION, 0);
    run_ms(s, 600);
}

/* A preset action played to its end, another interrupted. */
static void seed_action(seed_t *s, unsigned id)
{
    write1(s, XGO_REG_ACTION, (uint8_t)id);
    run_ms(s, xgo_action_duration_ticks((uint8_t)id) * 1000u / XGO_TICK_HZ + 100u);
    write1(s, XGO_REG_ACTION, (uint8_t)(id == 1u ? 2u : 1u)); /* another, interrupting */
    run_ms(s, 300);
    write1(s, XGO_REG_STAND, 1);
    run_ms(s, 500);
}

static void seed_perform(seed_t *s, unsigned arg)
{
    (void)arg;
    write1(s, XGO_REG_PERFORM, 1);
    run_ms(s, 9000);
    write1(s, XGO_REG_PERFORM, 0);
    run_ms(s, 1000);
}

/* The IMU: self-levelling on a tilted ground, a shove, the heading turn. */
static void seed_imu(seed_t *s, unsigned arg)
{
    (void)arg;
    put(s, FUZZ_OP_TILT);
    put(s, 20); /* 10 degrees */
    put(s, 0xF8);
    write1(s, XGO_REG_IMU_MODE, 1);
    run_ms(s, 1000);
    put(s, FUZZ_OP_PUSH);
    put(s, 0xE0);
    put(s, 30);
    run_ms(s, 1000);
    write1(s, XGO_REG_SET_ORIGIN, 1);
    write_n(s, XGO_REG_TURN_TO, (const uint8_t *)"\x2C\x01", XGO_TURN_TO_LEN); /* 300 */
    run_ms(s, 4000);
    write_n(s, XGO_REG_TURN_TO, (const uint8_t *)"\xD4\xFE", XGO_TURN_TO_LEN);
    run_ms(s, 4000);
    read_regs(s, XGO_REG_IMU_ROLL, 4);
    read_regs(s, XGO_REG_IMU_BLOCK, XGO_IMU_BLOCK_LEN);
    read_regs(s, XGO_REG_IMU_ROLL16, 6);
}

/* Every read view, the writes of other models, names, the battery. */
static void seed_views(seed_t *s, unsigned arg)
{
    static const uint8_t io[4] = {1, 2, 3, 4};
    unsigned a;
    (void)arg;
    for (a = 0; a < 0x100; a += 0x20) {
        read_regs(s, (uint8_t)a, (uint8_t)(a == 0xE0 ? 0x20 : 0x40));
    }
    read_regs(s, XGO_REG_FIRMWARE, XGO_FIRMWARE_LEN);
    read_regs(s, XGO_REG_IMU_PITCH, 4);
    read_regs(s, XGO_REG_IMU_YAW, 4);
    read_regs(s, XGO_REG_DIAG, 60);
    write_n(s, XGO_REG_LED, io, 3);
    write_n(s, XGO_REG_ANALOG_OUT, io, 4);
    write_n(s, 0xC0, io, 2); /* another model's register */
    write_n(s, XGO_REG_BT_NAME, (const uint8_t *)"Rex-01", 6);
    put(s, FUZZ_OP_BATTERY);
    put(s, 7);
    run_ms(s, 500);
    write1(s, XGO_REG_UPGRADE, 1);
}

/* Refused writes: read-only registers, values outside the valid sets,
 * from the wire and from the view, bad ranges, non-volatile data. */
static void seed_refused(seed_t *s, unsigned arg)
{
    static const uint8_t nv[22] = {'N', 'e', 'w', 0, 0, 0, 0, 0, 0, 0, 10, 246, 3, 0, 0, 0,
                                   0, 0, 0, 0, 0, 120};
    size_t i;
    (void)arg;
    write1(s, XGO_REG_MODE, 3);
    write1(s, XGO_REG_BATTERY, 5);
    write1(s, XGO_REG_GAIT_TYPE, 9);
    write1(s, XGO_REG_ACTION, 30);
    write1(s, XGO_REG_UNLOAD, 0x33);
    write_n(s, XGO_REG_BT_NAME, (const uint8_t *)"\x01\x02", 2);
    put(s, FUZZ_OP_VIEW_WRITE);
    put(s, XGO_REG_VX);
    put(s, 2);
    put(s, 0xFF);
    put(s, 0x00);
    put(s, FUZZ_OP_VIEW_WRITE);
    put(s, 0xF0);
    put(s, 0x20); /* past 0xFF */
    for (i = 0; i < 0x20; i++) {
        put(s, (uint8_t)i);
    }
    put(s, FUZZ_OP_NV);
    for (i = 0; i < sizeof nv; i++) {
        put(s, nv[i]);
    }
    run_ms(s, 300);
}

/* Bad bytes: noise, broken frames, silence, a hang-up, replies that do not
 * fit the transmit buffer. */
static void seed_bad_wire(seed_t *s, unsigned arg)
{
    static const uint8_t junk[] = {'h', 'i', 0x55, 0x13, 0x55, 0x00, 0x03, 0x55, 0x00, 0x09,
                                   0x07, 0x30, 0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x99, 0x00,
                                   0xAA, 0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x01, 0xAA,
                                   0x55, 0x00, 0x0A, 0x02, 0x30, 0x01, 0x00, 0x00, 0x00, 0xAA};
    uint8_t reads[7 * XGO_READ_REQUEST_LEN];
    unsigned i;
    (void)arg;
    raw(s, junk, sizeof junk);
    raw(s, (const uint8_t *)"\x55\x00\xFF\x00\x30", 5); /* a long write, begun */
    put(s, FUZZ_OP_SILENCE);
    put(s, 250);
    raw(s, (const uint8_t *)"\x55\x00\x40\x00", 4);
    put(s, FUZZ_OP_HANGUP);
    for (i = 0; i < 7; i++) { /* 7 x 255 reply bytes in one go */
        const uint8_t count = XGO_FRAME_MAX_DATA;
        xgo_frame_encode(XGO_TYPE_READ, 0x00, &count, 1, reads + i * XGO_READ_REQUEST_LEN,
                         XGO_READ_REQUEST_LEN);
    }
    raw(s, reads, sizeof reads);
    read_regs(s, 0x00, 0); /* count 0 */
    read_regs(s, 0xF0, 0x20);
}

/* The Mini2's arm: a point (x, z), a polar point, the claw, the two arm
 * servos by angle, the arm's mode while walking; everything read back. */
static void seed_arm(seed_t *s, unsigned arg)
{
    static const uint8_t points[3][2] = {{0xC0, 0x80}, {0x00, 0xFF}, {0xFF, 0x00}};
    static const uint8_t servos[2] = {0x20, 0xE0};
    write1(s, XGO_REG_ARM_SPEED, (uint8_t)(0x40u + 0x40u * arg));
    write_n(s, XGO_REG_ARM_X, points[arg % 3u], 2);
    run_ms(s, 1200);
    write_n(s, XGO_REG_ARM_THETA, points[(arg + 1u) % 3u], 2);
    write1(s, XGO_REG_CLAW, (uint8_t)(arg ? 0xFF : 0x00));
    run_ms(s, 1200);
    write_n(s, XGO_REG_ARM_ELBOW, servos, 2);
    run_ms(s, 800);
    write1(s, XGO_REG_ARM_MODE, 1);
    write_n(s, XGO_REG_VX, (const uint8_t *)"\xE0\x80\xA0", 3);
    run_ms(s, 1500);
    write1(s, XGO_REG_ARM_MODE, 0);
    write_n(s, XGO_REG_VX, (const uint8_t *)"\x80\x80\x80", 3);
    run_ms(s, 500);
    read_regs(s, XGO_REG_ARM_ELBOW, 2);
    read_regs(s, XGO_REG_CLAW, 7);
}

typedef struct recipe_s {
    const char *name;
    void (*build)(seed_t *s, unsigned arg);
    unsigned first, last; /* arg runs first..last: one seed each */
    uint8_t config;       /* byte 0 */
} recipe_t;

/* Byte 0 (program.h): the battery's nearest of 0..7 sevenths << 4 |
 * timeout << 1 | lite; DEVICE and MINI2 or-ed in. */
#define CFG(lite, timeout, battery) (uint8_t)((((battery) * 7u + 50u) / 100u) << 4 | (timeout) << 1 | (lite))
#define DEVICE FUZZ_CONFIG_DEVICE
#define MINI2 FUZZ_CONFIG_MINI2

static const recipe_t k_recipes[] = {
    {"spec", seed_spec, 0, 0, CFG(0, 2, 100)},
    {"walk", seed_walk, 0, 11, CFG(0, 2, 100)},
    {"walk-lite", seed_walk, 0, 3, CFG(1, 2, 60)},
    {"sprint", seed_sprint, 0, 3, CFG(0, 2, 100)},
    {"sprint-lite", seed_sprint, 0, 3, CFG(1, 2, 100)},
    {"body", seed_body, 0, 1, CFG(0, 2, 100)},
    {"body-lite", seed_body, 0, 0, CFG(1, 1, 100)},
    {"leg-servo", seed_leg_servo, 0, 3, CFG(0, 2, 100)},
    {"unload-calibrate", seed_unload_calibrate, 0, 0, CFG(0, 2, 100)},
    {"action", seed_action, 1, XGO_ACTION_LAST, CFG(0, 2, 100)},
    {"action-lite", seed_action, 1, XGO_ACTION_LAST, CFG(1, 2, 100)},
    {"reset", seed_action, XGO_ACTION_RESET, XGO_ACTION_RESET, CFG(0, 2, 100)},
    {"perform", seed_perform, 0, 0, CFG(0, 2, 12)},
    {"imu", seed_imu, 0, 0, CFG(0, 2, 100)},
    {"views", seed_views, 0, 0, CFG(0, 3, 40)},
    {"refused", seed_refused, 0, 0, CFG(0, 0, 100)},
    {"bad-wire", seed_bad_wire, 0, 0, CFG(0, 1, 100)},
    {"bad-wire-no-timeout", seed_bad_wire, 0, 0, CFG(1, 0, 100)},
    {"arm-mini2", seed_arm, 0, 2, CFG(0, 2, 100) | MINI2},
    {"walk-mini2", seed_walk, 0, 3, CFG(0, 2, 100) | MINI2},
    {"action-mini2", seed_action, 1, XGO_ACTION_LAST, CFG(0, 2, 100) | MINI2},
    {"views-mini2", seed_views, 0, 0, CFG(0, 3, 60) | MINI2},
    /* the same through the device layer (xgo/port.h) */
    {"device-spec", seed_spec, 0, 0, CFG(0, 2, 100) | DEVICE},
    {"device-walk", seed_walk, 0, 3, CFG(0, 2, 100) | DEVICE},
    {"device-action", seed_action, 3, 3, CFG(0, 2, 100) | DEVICE},
    {"device-calibrate", seed_unload_calibrate, 0, 0, CFG(0, 2, 100) | DEVICE},
    {"device-views", seed_views, 0, 0, CFG(0, 3, 100) | DEVICE},
    {"device-bad-wire", seed_bad_wire, 0, 0, CFG(1, 1, 100) | DEVICE},
    {"device-arm-mini2", seed_arm, 1, 1, CFG(0, 2, 100) | DEVICE | MINI2},
};

/* The recipe and argument of seed i, or NULL. */
static const recipe_t *find(unsigned i, unsigned *arg)
{
    size_t r;
    for (r = 0; r < sizeof k_recipes / sizeof k_recipes[0]; r++) {
        unsigned n = k_recipes[r].last - k_recipes[r].first + 1u;
        if (i < n) {
            *arg = k_recipes[r].first + i;
            return &k_recipes[r];
        }
        i -= n;
    }
    return NULL;
}

size_t fuzz_seed(unsigned i, uint8_t *buf, size_t cap)
{
    unsigned arg;
    const recipe_t *r = find(i, &arg);
    seed_t s;
    if (r == NULL || cap == 0) {
        return 0;
    }
    s.buf = buf;
    s.len = 0;
    s.cap = cap;
    put(&s, r->config);
    r->build(&s, arg);
    return s.len;
}

const char *fuzz_seed_name(unsigned i, char *buf, size_t cap)
{
    unsigned arg = 0;
    const recipe_t *r = find(i, &arg);
    snprintf(buf, cap, "%s-%03u", r != NULL ? r->name : "none", arg);
    return buf;
}
