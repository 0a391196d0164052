/*
 * test_host_uart.c - xgo-emu --uart-baud end to end: a host whose port is
 * set to the board's speed is answered; at any other speed its request
 * reaches the board garbled, is not answered, and the framing errors it
 * caused are counted in the diagnostic block - exactly as many as the line
 * model (src/host/uart_model.c, tested on its own in test_uart_model)
 * predicts for that request.
 *
 * Real processes, a real pty and real time; every wait is bounded.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "uart_model.h"
#include "unity.h"
#include "xgo/board.h"
#include "xgo/protocol.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define EMU_START_TIMEOUT_MS 5000
#define EMU_EXIT_TIMEOUT_MS 5000
#define REPLY_TIMEOUT_MS 1000
#define SILENCE_MS 200

static xgo_test_emu_t g_emu;
static int g_port = -1;
static char g_dir[64];
static char g_link[128];

static void emu_start(const char *baud)
{
    const char *args[] = {"--link", g_link, "--uart-baud", baud, NULL};
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT_MESSAGE(XGO_TEST_EMU_PTY_OK,
                                  xgo_test_emu_read_pty(&g_emu, EMU_START_TIMEOUT_MS),
                                  "no pty path on xgo-emu's stdout");
}

static void port_at(speed_t speed)
{
    if (g_port >= 0) {
        close(g_port);
    }
    g_port = xgo_test_port_open_like_pyserial(g_link, speed);
    TEST_ASSERT_TRUE_MESSAGE(g_port >= 0, "cannot open the emulator's port");
}

/* The firmware read; returns the reply bytes received (18: answered). */
static size_t read_firmware(uint8_t reply[XGO_FRAME_MAX_LEN], long timeout_ms)
{
    return xgo_test_read_reply(g_port, XGO_REG_FIRMWARE, XGO_FIRMWARE_LEN, reply, timeout_ms);
}

static uint32_t framing_errors(void)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    const uint8_t at = (uint8_t)(XGO_REG_DIAG + 4u * XGO_DIAG_FRAMING_ERRORS);
    TEST_ASSERT_EQUAL_INT(4 + XGO_FRAME_OVERHEAD,
                          (int)xgo_test_read_reply(g_port, at, 4, reply, REPLY_TIMEOUT_MS));
    return (uint32_t)reply[5] | (uint32_t)reply[6] << 8 | (uint32_t)reply[7] << 16 |
           (uint32_t)reply[8] << 24;
}

/* What the model says the board makes of the firmware read at host_baud. */
static uint32_t predicted_framing_errors(uint32_t host_baud, uint32_t board_baud)
{
    uint8_t req[XGO_READ_REQUEST_LEN], out[XGO_READ_REQUEST_LEN * XGO_HOST_UART_GROWTH];
    uint32_t errors = 0;
    const size_t n = xgo_test_read_request(XGO_REG_FIRMWARE, XGO_FIRMWARE_LEN, req);
    (void)xgo_host_uart_to_board(host_baud, board_baud, req, n, out, sizeof out, &errors);
    return errors;
}

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    g_port = -1;
}

void tearDown(void)
{
    if (g_port >= 0) {
        close(g_port);
        g_port = -1;
    }
    xgo_test_emu_kill(&g_emu);
    unlink(g_link);
}

static void test_the_boards_speed_is_answered(void)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    emu_start("115200");
    port_at(B115200);
    TEST_ASSERT_EQUAL_INT(XGO_FIRMWARE_LEN + XGO_FRAME_OVERHEAD,
                          (int)read_firmware(reply, REPLY_TIMEOUT_MS));
    TEST_ASSERT_EQUAL_HEX8('M', reply[5]);
    TEST_ASSERT_EQUAL_UINT32(0, framing_errors());
}

/* The speeds the vendor library's auto-baud scan tries, and a slow one. */
static void test_other_speeds_get_no_answer_and_count_framing_errors(void)
{
    static const struct {
        speed_t code;
        uint32_t baud;
    } speeds[] = {{B2000000, 2000000}, {B500000, 500000}, {B921600, 921600},
                  {B1000000, 1000000}, {B9600, 9600},     {B57600, 57600}};
    uint8_t reply[XGO_FRAME_MAX_LEN];
    uint32_t want = 0;
    size_t i;
    emu_start("115200");
    for (i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
        port_at(speeds[i].code);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, (int)read_firmware(reply, SILENCE_MS),
                                      "a reply at the wrong speed");
        want += predicted_framing_errors(speeds[i].baud, 115200);
    }
    port_at(B115200);
    TEST_ASSERT_TRUE(want > 0);
    TEST_ASSERT_EQUAL_UINT32(want, framing_errors());
}

/* A board switched to 2 Mbaud (as after the vendor's RL programs): the
 * library's first probe at 115200 fails, its second finds it. */
static void test_a_fast_board_answers_only_at_its_speed(void)
{
    uint8_t reply[XGO_FRAME_MAX_LEN];
    emu_start("2000000");
    port_at(B115200);
    TEST_ASSERT_EQUAL_INT(0, (int)read_firmware(reply, SILENCE_MS));
    port_at(B2000000);
    TEST_ASSERT_EQUAL_INT(XGO_FIRMWARE_LEN + XGO_FRAME_OVERHEAD,
                          (int)read_firmware(reply, REPLY_TIMEOUT_MS));
    TEST_ASSERT_EQUAL_UINT32(predicted_framing_errors(115200, 2000000), framing_errors());
}

int main(void)
{
    int failures;
    strcpy(g_dir, "/tmp/xgo-uart-test-XXXXXX");
    if (mkdtemp(g_dir) == NULL) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(g_link, sizeof g_link, "%s/ttyXGO", g_dir);
    UNITY_BEGIN();
    RUN_TEST(test_the_boards_speed_is_answered);
    RUN_TEST(test_other_speeds_get_no_answer_and_count_framing_errors);
    RUN_TEST(test_a_fast_board_answers_only_at_its_speed);
    failures = UNITY_END();
    rmdir(g_dir);
    return failures;
}
