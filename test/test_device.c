/*
 * The device layer against a fake port (xgo/port.h), on virtual time: bytes
 * through the ring to replies on the port, the ring's backpressure (RX
 * masked exactly when full, resumed once), replies held while the port is
 * busy and nothing lost, control ticks and their catch-up limit, servo
 * outputs, the non-volatile data restored at init and saved once settled
 * (failures counted and retried), the parser's clock standing still while
 * input waits, a host's hang-up dropping its partial frame once the ring is
 * fed, and when the device may sleep.
 */
#include <string.h>

#include "servos.h" /* XGO_SERVO_LEG_MASK */
#include "unity.h"
#include "xgo/port.h"

/* ---- the fake port ------------------------------------------------------ */

#define OUT_CAP 16384u

struct xgo_port_s {
    uint32_t ms;
    size_t tx_room;           /* what xgo_port_tx_room reports */
    uint8_t out[OUT_CAP];     /* everything written */
    size_t out_len;
    unsigned resumes;
    int nv_valid;             /* xgo_port_nv_load has data */
    xgo_board_nv_t nv;        /* the "flash" */
    int nv_save_ok;
    unsigned nv_save_calls;
    unsigned servo_calls;
    int32_t servo_raw[XGO_SERVO_COUNT];
    uint16_t servo_limp;
};

static struct xgo_port_s port;
static xgo_device_t dev;

uint32_t xgo_port_millis(xgo_port_t *p)
{
    return p->ms;
}

size_t xgo_port_tx_room(xgo_port_t *p)
{
    return p->tx_room;
}

void xgo_port_tx_write(xgo_port_t *p, const uint8_t *bytes, size_t n)
{
    TEST_ASSERT_TRUE_MESSAGE(n <= p->tx_room, "wrote more than the room reported");
    TEST_ASSERT_TRUE(p->out_len + n <= OUT_CAP);
    memcpy(p->out + p->out_len, bytes, n);
    p->out_len += n;
}

void xgo_port_rx_resume(xgo_port_t *p)
{
    p->resumes++;
}

int xgo_port_nv_load(xgo_port_t *p, xgo_board_nv_t *nv)
{
    if (p->nv_valid) {
        *nv = p->nv;
    }
    return p->nv_valid;
}

int xgo_port_nv_save(xgo_port_t *p, const xgo_board_nv_t *nv)
{
    p->nv_save_calls++;
    if (p->nv_save_ok) {
        p->nv = *nv;
        p->nv_valid = 1;
    }
    return p->nv_save_ok;
}

void xgo_port_servo_write(xgo_port_t *p, const int32_t raw_mdeg[XGO_SERVO_COUNT], uint16_t limp)
{
    p->servo_calls++;
    memcpy(p->servo_raw, raw_mdeg, sizeof p->servo_raw);
    p->servo_limp = limp;
}

/* ---- helpers ------------------------------------------------------------ */

static const uint8_t k_spec_read[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
static size_t direct_reply(const uint8_t *req, size_t n, uint8_t *out, size_t cap);

static uint8_t spec_reply[32]; /* a fresh board's answer to k_spec_read */
static size_t spec_reply_len;

void setUp(void)
{
    spec_reply_len = direct_reply(k_spec_read, sizeof k_spec_read, spec_reply, sizeof spec_reply);
    TEST_ASSERT_EQUAL_UINT(20, spec_reply_len);
    memset(&port, 0, sizeof port);
    port.tx_room = 64;
    port.nv_save_ok = 1;
    xgo_device_init(&dev, &port, NULL);
}

void tearDown(void)
{
}

/* What an RX interrupt does: store while the device takes bytes. Returns
 * how many were stored (the rest the UART would hold back). */
static size_t rx(const uint8_t *bytes, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (!xgo_device_rx_put(&dev, bytes[i])) {
            return i + 1;
        }
    }
    return n;
}

static void rx_all(const uint8_t *bytes, size_t n)
{
    TEST_ASSERT_EQUAL_UINT(n, rx(bytes, n));
}

/* A frame through the ring, fed to the board at once. */
static void rx_frame(uint8_t type, uint8_t addr, const uint8_t *data, size_t n)
{
    uint8_t f[XGO_FRAME_MAX_LEN];
    rx_all(f, xgo_frame_encode(type, addr, data, n, f, sizeof f));
    xgo_device_run(&dev);
}

/* What a board driven directly answers to the same bytes (a fresh one: the
 * device's board must behave exactly like it). */
static size_t direct_reply(const uint8_t *req, size_t n, uint8_t *out, size_t cap)
{
    static xgo_board_t ref;
    xgo_board_init(&ref, NULL);
    xgo_board_receive(&ref, req, n, 0);
    return xgo_board_transmit(&ref, out, cap);
}

static void ticks(unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        port.ms += 1000u / XGO_TICK_HZ;
        xgo_device_tick_due(&dev);
        xgo_device_run(&dev);
    }
}

static uint32_t counter(xgo_diag_t which)
{
    uint32_t all[XGO_DIAG_COUNT];
    xgo_board_counters(xgo_device_board(&dev), all);
    return all[which];
}

static xgo_device_stats_t stats(void)
{
    xgo_device_stats_t s;
    xgo_device_stats(&dev, &s);
    return s;
}

/* ---- tests -------------------------------------------------------------- */

static void test_spec_read_through_the_ring_gets_the_spec_reply(void)
{
    rx_all(k_spec_read, sizeof k_spec_read);
    TEST_ASSERT_EQUAL_UINT(0, port.out_len); /* nothing happens in the interrupt */
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT(spec_reply_len, port.out_len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(spec_reply, port.out, spec_reply_len);
    TEST_ASSERT_EQUAL_UINT32(sizeof k_spec_read, stats().rx_bytes);
    TEST_ASSERT_EQUAL_UINT32(spec_reply_len, stats().tx_bytes);
    TEST_ASSERT_TRUE(xgo_device_idle(&dev));
}

static void test_ring_asks_for_a_pause_exactly_when_full_and_resumes_once(void)
{
    uint8_t noise[XGO_PORT_RX_RING_SIZE];
    memset(noise, 0x11, sizeof noise);
    TEST_ASSERT_EQUAL_UINT(XGO_PORT_RX_RING_SIZE, rx(noise, sizeof noise)); /* 0 at the last */
    TEST_ASSERT_EQUAL_UINT32(1, stats().rx_pauses);
    TEST_ASSERT_FALSE(xgo_device_idle(&dev));
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT(1, port.resumes);
    TEST_ASSERT_EQUAL_UINT32(XGO_PORT_RX_RING_SIZE, stats().rx_bytes);
    /* The ring wrapped: a request across its end is still one frame. */
    rx_all(k_spec_read, sizeof k_spec_read);
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(spec_reply, port.out, spec_reply_len);
    TEST_ASSERT_EQUAL_UINT(1, port.resumes); /* no pause, no resume */
}

/* 40 requests for 247 bytes each (a 255-byte reply each, 10 KB in all)
 * while the port takes nothing: the board's buffer fills, input waits in the
 * ring, RX pauses; then the port drains and every reply arrives, in order. */
static void test_busy_port_holds_replies_and_loses_nothing(void)
{
    static const uint8_t count = XGO_FRAME_MAX_DATA;
    uint8_t reqs[40 * XGO_READ_REQUEST_LEN];
    size_t i, stored = 0, got = 0;
    uint8_t reply_len = 0;
    for (i = 0; i < 40; i++) {
        xgo_frame_encode(XGO_TYPE_READ, 0x00, &count, 1, reqs + i * 9u, 9u);
    }
    port.tx_room = 0;
    while (stored < sizeof reqs) {
        stored += rx(reqs + stored, sizeof reqs - stored);
        xgo_device_run(&dev);
        if (stored < sizeof reqs && dev.rx_paused) {
            break; /* the UART holds the rest */
        }
    }
    TEST_ASSERT_EQUAL_UINT(0, port.out_len);
    TEST_ASSERT_TRUE_MESSAGE(xgo_device_idle(&dev), "a blocked port must let the device sleep");
    port.tx_room = 17; /* odd, so replies straddle writes */
    while (got < 40) {
        if (dev.rx_paused == 0 && stored < sizeof reqs) {
            stored += rx(reqs + stored, sizeof reqs - stored);
        }
        xgo_device_run(&dev);
        got = port.out_len / (count + 8u);
        TEST_ASSERT_TRUE(port.out_len <= 40u * (count + 8u));
        if (stored == sizeof reqs && dev.rx_head == dev.rx_tail &&
            xgo_board_tx_pending(xgo_device_board(&dev)) == 0) {
            break;
        }
    }
    TEST_ASSERT_EQUAL_UINT(40u * (count + 8u), port.out_len);
    reply_len = port.out[2];
    TEST_ASSERT_EQUAL_UINT8(count + 8u, reply_len);
    for (i = 0; i < 40; i++) {
        TEST_ASSERT_EQUAL_HEX8(0x55, port.out[i * reply_len]);
        TEST_ASSERT_EQUAL_HEX8(0xAA, port.out[i * reply_len + reply_len - 1u]);
    }
    TEST_ASSERT_EQUAL_UINT32(0, counter(XGO_DIAG_TX_OVERFLOW));
    TEST_ASSERT_EQUAL_UINT32(40, counter(XGO_DIAG_FRAMES_OK));
}

static void test_ticks_run_when_due_and_drive_the_servo_outputs(void)
{
    const xgo_board_t *b = xgo_device_board(&dev);
    int32_t joints[XGO_SERVO_COUNT];
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(0, xgo_board_time_ms(b)); /* no period elapsed yet */
    TEST_ASSERT_EQUAL_UINT(0, port.servo_calls);
    xgo_device_tick_due(&dev);
    xgo_device_tick_due(&dev);
    xgo_device_tick_due(&dev);
    TEST_ASSERT_FALSE(xgo_device_idle(&dev));
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(3u * 1000u / XGO_TICK_HZ, xgo_board_time_ms(b));
    TEST_ASSERT_EQUAL_UINT(3, port.servo_calls);
    TEST_ASSERT_EQUAL_UINT32(3, stats().ticks);
    xgo_board_joints_mdeg(b, joints);
    TEST_ASSERT_EQUAL_INT32_ARRAY(joints, port.servo_raw, XGO_SERVO_COUNT); /* no offsets */
    TEST_ASSERT_EQUAL_HEX16(0, port.servo_limp);
    TEST_ASSERT_TRUE(xgo_device_idle(&dev));
}

static void test_unloaded_joints_are_reported_limp(void)
{
    static const uint8_t unload_leg1 = 0x11; /* 0x20: unload leg 1 */
    rx_frame(XGO_TYPE_WRITE, 0x20, &unload_leg1, 1);
    ticks(2);
    TEST_ASSERT_EQUAL_HEX16(XGO_SERVO_LEG_MASK(0), port.servo_limp);
}

static void test_a_long_stall_skips_the_ticks_beyond_the_catchup_limit(void)
{
    unsigned i;
    for (i = 0; i < XGO_PORT_MAX_CATCHUP_TICKS + 10u; i++) {
        xgo_device_tick_due(&dev);
    }
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(XGO_PORT_MAX_CATCHUP_TICKS, stats().ticks);
    TEST_ASSERT_EQUAL_UINT32(10, stats().ticks_skipped);
    TEST_ASSERT_EQUAL_UINT(XGO_PORT_MAX_CATCHUP_TICKS, port.servo_calls);
    TEST_ASSERT_TRUE(xgo_device_idle(&dev));
}

static void test_saved_nv_is_restored_at_init(void)
{
    static const char name[] = "Rex";
    uint8_t read_count = XGO_BT_NAME_LEN;
    xgo_board_nv_t nv;
    memset(&nv, 0, sizeof nv);
    memcpy(nv.bt_name, name, sizeof name - 1u);
    nv.zero_offset_mdeg[4] = -2500;
    port.nv = nv;
    port.nv_valid = 1;
    xgo_device_init(&dev, &port, NULL);
    rx_frame(XGO_TYPE_READ, 0x13, &read_count, 1);
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT(XGO_BT_NAME_LEN + 8u, port.out_len);
    TEST_ASSERT_EQUAL_HEX8(0x13, port.out[4]);
    TEST_ASSERT_EQUAL_MEMORY(name, &port.out[5], 3);
    TEST_ASSERT_EQUAL_HEX8(0, port.out[8]);
    ticks(1);
    TEST_ASSERT_EQUAL_INT32(dev.board.motion.servos.angle_mdeg[4] - 2500, port.servo_raw[4]);
    ticks(2u * XGO_PORT_NV_SETTLE_TICKS);
    TEST_ASSERT_EQUAL_UINT(0, port.nv_save_calls); /* restoring is no change */
}

static void test_invalid_saved_nv_keeps_the_defaults(void)
{
    xgo_board_nv_t before, nv;
    xgo_board_get_nv(xgo_device_board(&dev), &before);
    memset(&nv, 0, sizeof nv);
    nv.bt_name[0] = 0x07; /* not printable */
    nv.zero_offset_mdeg[0] = 1000;
    port.nv = nv;
    port.nv_valid = 1;
    xgo_device_init(&dev, &port, NULL);
    xgo_board_get_nv(xgo_device_board(&dev), &nv);
    TEST_ASSERT_EQUAL_MEMORY(before.bt_name, nv.bt_name, sizeof nv.bt_name);
    TEST_ASSERT_EQUAL_INT32_ARRAY(before.zero_offset_mdeg, nv.zero_offset_mdeg, XGO_SERVO_COUNT);
}

static void test_renaming_is_saved_once_after_it_settles(void)
{
    static const char name[] = "Rex";
    rx_frame(XGO_TYPE_WRITE, 0x13, (const uint8_t *)name, 3);
    ticks(1);
    TEST_ASSERT_EQUAL_UINT(0, port.nv_save_calls);
    ticks(XGO_PORT_NV_SETTLE_TICKS - 1u);
    TEST_ASSERT_EQUAL_UINT(0, port.nv_save_calls);
    ticks(1);
    TEST_ASSERT_EQUAL_UINT(1, port.nv_save_calls);
    TEST_ASSERT_EQUAL_STRING("Rex", port.nv.bt_name);
    ticks(3u * XGO_PORT_NV_SETTLE_TICKS);
    TEST_ASSERT_EQUAL_UINT(1, port.nv_save_calls);
    TEST_ASSERT_EQUAL_UINT32(1, stats().nv_saves);
}

static void test_a_failed_save_is_counted_and_retried(void)
{
    static const char name[] = "Max";
    port.nv_save_ok = 0;
    rx_frame(XGO_TYPE_WRITE, 0x13, (const uint8_t *)name, 3);
    ticks(1u + XGO_PORT_NV_SETTLE_TICKS);
    TEST_ASSERT_EQUAL_UINT(1, port.nv_save_calls);
    TEST_ASSERT_EQUAL_UINT32(1, stats().nv_save_failures);
    port.nv_save_ok = 1;
    ticks(XGO_PORT_NV_SETTLE_TICKS);
    TEST_ASSERT_EQUAL_UINT(2, port.nv_save_calls);
    TEST_ASSERT_EQUAL_STRING("Max", port.nv.bt_name);
    TEST_ASSERT_EQUAL_UINT32(1, stats().nv_saves);
}

/* Silence on the line drops a partial frame after the parser's timeout. */
static void test_silence_drops_a_partial_frame(void)
{
    rx_all(k_spec_read, 5);
    ticks(XGO_PARSER_DEFAULT_TIMEOUT_MS / 2u + 1u);
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_TIMEOUTS));
}

/* Input that waited in the ring is not silence: the rest of a frame came
 * in while the main loop was stalled far longer than the timeout (a burst
 * of catch-up ticks); the frame survives and is answered. */
static void test_input_waiting_in_the_ring_is_not_silence(void)
{
    unsigned i;
    rx_all(k_spec_read, 4);
    xgo_device_run(&dev); /* a frame in progress */
    port.ms += 5;
    rx_all(k_spec_read + 4, sizeof k_spec_read - 4u);
    port.ms += 5u * XGO_PARSER_DEFAULT_TIMEOUT_MS;
    for (i = 0; i < 5u * XGO_PARSER_DEFAULT_TIMEOUT_MS * XGO_TICK_HZ / 1000u; i++) {
        xgo_device_tick_due(&dev);
    }
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(0, counter(XGO_DIAG_TIMEOUTS));
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_FRAMES_OK));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(spec_reply, port.out, spec_reply_len);
}

/* A hang-up with the ring empty drops the partial frame at once; with
 * --timeout-ms 0 (no silence timeout) nothing else would. */
static void test_a_hangup_drops_the_partial_frame_at_once(void)
{
    xgo_board_config_t cfg;
    xgo_board_default_config(&cfg);
    cfg.parser_timeout_ms = 0;
    xgo_device_init(&dev, &port, &cfg);
    rx_all(k_spec_read, 5);
    xgo_device_run(&dev);
    ticks(100);
    TEST_ASSERT_EQUAL_UINT32(0, counter(XGO_DIAG_HANGUP_DISCARDS));
    xgo_device_hangup(&dev);
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_HANGUP_DISCARDS));
    /* The next host's request is answered, not swallowed. */
    rx_all(k_spec_read, sizeof k_spec_read);
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT(spec_reply_len, port.out_len);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(spec_reply, port.out, spec_reply_len);
}

/* Bytes the departed host sent before hanging up are still in the ring: a
 * whole request among them is answered, and only then is the partial frame
 * after it dropped. */
static void test_a_hangup_waits_for_the_ring_to_be_fed(void)
{
    rx_all(k_spec_read, sizeof k_spec_read);
    rx_all(k_spec_read, 4);
    xgo_device_hangup(&dev);
    TEST_ASSERT_EQUAL_UINT32(0, counter(XGO_DIAG_HANGUP_DISCARDS)); /* not fed yet */
    TEST_ASSERT_FALSE(xgo_device_idle(&dev));
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_FRAMES_OK));
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_HANGUP_DISCARDS));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(spec_reply, port.out, spec_reply_len);
    TEST_ASSERT_EQUAL_UINT(spec_reply_len, port.out_len);
    /* Once done, it is done: a later partial frame is not dropped by it. */
    rx_all(k_spec_read, 4);
    xgo_device_run(&dev);
    TEST_ASSERT_EQUAL_UINT32(1, counter(XGO_DIAG_HANGUP_DISCARDS));
}

static void test_idle_only_when_nothing_can_be_done(void)
{
    TEST_ASSERT_TRUE(xgo_device_idle(&dev));
    rx_all(k_spec_read, 1);
    TEST_ASSERT_FALSE(xgo_device_idle(&dev)); /* a byte to feed */
    xgo_device_run(&dev);
    TEST_ASSERT_TRUE(xgo_device_idle(&dev)); /* a partial frame: the next tick polls */
    port.tx_room = 0;
    rx_all(k_spec_read + 1, sizeof k_spec_read - 1u);
    xgo_device_run(&dev);
    TEST_ASSERT_TRUE(xgo_board_tx_pending(xgo_device_board(&dev)) > 0);
    TEST_ASSERT_TRUE(xgo_device_idle(&dev)); /* reply waits for the port's wake-up */
    port.tx_room = 1;
    TEST_ASSERT_FALSE(xgo_device_idle(&dev));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_spec_read_through_the_ring_gets_the_spec_reply);
    RUN_TEST(test_ring_asks_for_a_pause_exactly_when_full_and_resumes_once);
    RUN_TEST(test_busy_port_holds_replies_and_loses_nothing);
    RUN_TEST(test_ticks_run_when_due_and_drive_the_servo_outputs);
    RUN_TEST(test_unloaded_joints_are_reported_limp);
    RUN_TEST(test_a_long_stall_skips_the_ticks_beyond_the_catchup_limit);
    RUN_TEST(test_saved_nv_is_restored_at_init);
    RUN_TEST(test_invalid_saved_nv_keeps_the_defaults);
    RUN_TEST(test_renaming_is_saved_once_after_it_settles);
    RUN_TEST(test_a_failed_save_is_counted_and_retried);
    RUN_TEST(test_silence_drops_a_partial_frame);
    RUN_TEST(test_input_waiting_in_the_ring_is_not_silence);
    RUN_TEST(test_a_hangup_drops_the_partial_frame_at_once);
    RUN_TEST(test_a_hangup_waits_for_the_ring_to_be_fed);
    RUN_TEST(test_idle_only_when_nothing_can_be_done);
    return UNITY_END();
}
