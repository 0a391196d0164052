/*
 * The UART line model of xgo-emu --uart-baud (src/host/uart_model.c):
 * hand-worked cases, and random bytes at many speed pairs against a
 * brute-force reference that draws the sent waveform sample by sample on a
 * common time grid and runs a naive receiver over the array.
 */
#include <stdlib.h>
#include <string.h>

#include "board_io.h"
#include "uart_model.h"
#include "unity.h"

void setUp(void)
{
}

void tearDown(void)
{
}

static size_t resample(uint32_t tx, uint32_t rx, const uint8_t *in, size_t n, uint8_t *out,
                       uint8_t *framing, size_t cap)
{
    xgo_host_uart_rx_t r;
    size_t got = 0;
    uint8_t byte;
    int bad;
    xgo_host_uart_rx_begin(&r, tx, rx, in, n);
    while (got < cap && xgo_host_uart_rx_next(&r, &byte, &bad)) {
        out[got] = byte;
        framing[got] = (uint8_t)bad;
        got++;
    }
    return got;
}

/* ------------------------------------------------------------ reference */

#define REF_MAX_SAMPLES 4000000u

static uint32_t gcd(uint32_t a, uint32_t b)
{
    while (b != 0) {
        uint32_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* The line drawn at one sample per 1 / (2 tx' rx') s (tx', rx' the speeds
 * divided by their gcd): a sent bit is 2 rx' samples, a received one 2 tx'.
 * line[0] is the idle line before the first byte; sample t of the burst is
 * line[t + 1]. Then, from the ready time on: find a 1 followed by a 0,
 * sample the start bit half a bit later (still 0, else ready again from
 * there), the data and stop bits a bit apart each. */
static uint8_t ref_line[REF_MAX_SAMPLES];

#define L(t) ref_line[(t) + 1u]

static size_t reference(uint32_t tx, uint32_t rx, const uint8_t *in, size_t n, uint8_t *out,
                        uint8_t *framing)
{
    const uint32_t g = gcd(tx, rx), a = 2u * (rx / g), b = 2u * (tx / g);
    const size_t total = (size_t)n * 10u * a + 20u * b; /* then idle, room to sample */
    size_t i, t = 0, got = 0;
    TEST_ASSERT_TRUE(total + 1u <= REF_MAX_SAMPLES);
    ref_line[0] = 1;
    for (i = 0; i < total; i++) {
        const size_t bit = i / a;
        unsigned level = 1;
        if (bit < n * 10u) {
            const unsigned pos = (unsigned)(bit % 10u);
            level = pos == 0 ? 0u : (pos == 9 ? 1u : (in[bit / 10u] >> (pos - 1u)) & 1u);
        }
        L(i) = (uint8_t)level;
    }
    for (;;) {
        size_t e = t, mid;
        unsigned v = 0, j;
        while (e < n * 10u * a && !(ref_line[e] == 1 && L(e) == 0)) { /* ref_line[e] = L(e - 1) */
            e++;
        }
        if (e >= n * 10u * a) {
            break;
        }
        mid = e + b / 2u;
        if (L(mid) != 0) {
            t = mid; /* a glitch */
            continue;
        }
        for (j = 0; j < 8; j++) {
            v |= (unsigned)L(mid + (j + 1u) * b) << j;
        }
        out[got] = (uint8_t)v;
        framing[got] = L(mid + 9u * b) == 0;
        got++;
        t = mid + 9u * b;
    }
    return got;
}

/* ------------------------------------------------------------ cases */

static void test_equal_speeds_pass_bytes_through(void)
{
    const uint8_t in[] = {0x55, 0x00, 0x09, 0x02, 0x07, 0x0A, 0xE3, 0x00, 0xAA};
    uint8_t out[64], fe[64];
    TEST_ASSERT_EQUAL_UINT(sizeof in, resample(115200, 115200, in, sizeof in, out, fe, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(in, out, sizeof in);
    TEST_ASSERT_EACH_EQUAL_HEX8(0, fe, sizeof in);
}

/* Worked by hand: 0xFF at half the receiver's speed. The start bit spans
 * two received bits, so data bit 0 reads 0: 0xFE, stop bit fine. */
static void test_half_speed_ff_reads_fe(void)
{
    const uint8_t in[] = {0xFF};
    uint8_t out[8], fe[8];
    TEST_ASSERT_EQUAL_UINT(1, resample(57600, 115200, in, 1, out, fe, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0xFE, out[0]);
    TEST_ASSERT_EQUAL_UINT8(0, fe[0]);
}

/* A slow host's 0x00 is nine bits low: twelve of the board's bits each, so
 * the board reads 0x00 with a zero stop bit, then waits for the line to go
 * high - one byte, one framing error. */
static void test_slow_host_gives_zeros_with_framing_errors(void)
{
    const uint8_t in[] = {0x00};
    uint8_t out[8], fe[8];
    uint32_t errors = 0;
    TEST_ASSERT_EQUAL_UINT(1, resample(9600, 115200, in, 1, out, fe, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0x00, out[0]);
    TEST_ASSERT_EQUAL_UINT8(1, fe[0]);
    TEST_ASSERT_EQUAL_UINT(0, xgo_host_uart_to_board(9600, 115200, in, 1, out, sizeof out, &errors));
    TEST_ASSERT_EQUAL_UINT32(1, errors);
    TEST_ASSERT_EQUAL_UINT(1, xgo_host_uart_to_host(9600, 115200, in, 1, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0x00, out[0]); /* the host's tty gives \0 for it */
}

/* The vendor library's firmware read at 2 Mbaud into a 115200 board: the
 * 9 bytes last 45 us, 5.2 of the board's bits - no valid frame can come
 * of it, and there is no answer. */
static void test_fast_host_request_is_garbage(void)
{
    const uint8_t in[] = {0x55, 0x00, 0x09, 0x02, 0x07, 0x0A, 0xE3, 0x00, 0xAA};
    uint8_t out[64], fe[64];
    const size_t got = resample(2000000, 115200, in, sizeof in, out, fe, sizeof out);
    TEST_ASSERT_TRUE(got >= 1 && got <= 2);
    TEST_ASSERT_TRUE(got < sizeof in);
}

static void test_output_never_grows_past_five_per_byte(void)
{
    uint8_t in[64], out[64 * XGO_HOST_UART_GROWTH + 1], fe[sizeof out];
    size_t i;
    for (i = 0; i < sizeof in; i++) {
        in[i] = 0x55; /* 0 1 0 1 ...: five falling edges a frame */
    }
    TEST_ASSERT_TRUE(resample(300, 115200, in, sizeof in, out, fe, sizeof out) <=
                     sizeof in * XGO_HOST_UART_GROWTH);
}

static void test_against_the_reference_at_many_speed_pairs(void)
{
    static const uint32_t speeds[] = {9600, 19200, 38400, 57600, 100000, 115200, 128000,
                                      230400, 460800, 500000, 921600, 1000000, 2000000};
    uint32_t seed = 12345u;
    size_t i, j, pairs = 0, bytes = 0;
    for (i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
        for (j = 0; j < sizeof speeds / sizeof speeds[0]; j++) {
            uint8_t in[12], got[64], want[64], fe_got[64], fe_want[64];
            size_t k, n_got, n_want;
            const uint32_t tx = speeds[i], rx = speeds[j];
            const uint32_t g = gcd(tx, rx);
            if ((size_t)sizeof in * 10u * 2u * (rx / g) + 20u * 2u * (tx / g) + 1u > REF_MAX_SAMPLES) {
                continue; /* too fine a grid for the brute force */
            }
            for (k = 0; k < sizeof in; k++) {
                in[k] = (uint8_t)xgo_test_xorshift32(&seed);
            }
            n_got = resample(tx, rx, in, sizeof in, got, fe_got, sizeof got);
            n_want = tx == rx ? sizeof in : reference(tx, rx, in, sizeof in, want, fe_want);
            if (tx == rx) {
                memcpy(want, in, sizeof in);
                memset(fe_want, 0, sizeof in);
            }
            TEST_ASSERT_EQUAL_UINT_MESSAGE(n_want, n_got, "byte count");
            if (n_want > 0) {
                TEST_ASSERT_EQUAL_HEX8_ARRAY(want, got, n_want);
                TEST_ASSERT_EQUAL_HEX8_ARRAY(fe_want, fe_got, n_want);
            }
            pairs++;
            bytes += n_want;
        }
    }
    TEST_ASSERT_TRUE(pairs >= 120); /* the brute force covered most pairs */
    TEST_ASSERT_TRUE(bytes >= 1000);
}

/* Within a UART's tolerance (2 %) the bytes still come through. */
static void test_small_mismatch_is_tolerated(void)
{
    const uint8_t in[] = {0x55, 0x00, 0x09, 0x02, 0x07, 0x0A, 0xE3, 0x00, 0xAA};
    uint8_t out[64], fe[64];
    TEST_ASSERT_EQUAL_UINT(sizeof in, resample(117500, 115200, in, sizeof in, out, fe, sizeof out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(in, out, sizeof in);
    TEST_ASSERT_EACH_EQUAL_HEX8(0, fe, sizeof in);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_equal_speeds_pass_bytes_through);
    RUN_TEST(test_half_speed_ff_reads_fe);
    RUN_TEST(test_slow_host_gives_zeros_with_framing_errors);
    RUN_TEST(test_fast_host_request_is_garbage);
    RUN_TEST(test_output_never_grows_past_five_per_byte);
    RUN_TEST(test_against_the_reference_at_many_speed_pairs);
    RUN_TEST(test_small_mismatch_is_tolerated);
    return UNITY_END();
}
