/*
 * test_view_record.c - xgo-emu --record FILE.csv: the header line names the
 * columns in the documented order, every row has one value per column, rows
 * come every tick (or every 1/N s of board time with --record-hz N), and the
 * numbers follow the board (a walk shows in world_x_mm). Misuse and an
 * uncreatable file are refused.
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
#include "test_clock.h"
#include "unity.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

/* The header as docs/view.md and /work's contract list it, spelled out here
 * (not generated) so a change in the program shows as a failure. */
static const char k_header[] =
    "t_ms,mode,action,"
    "j11_deg,j12_deg,j13_deg,j21_deg,j22_deg,j23_deg,j31_deg,j32_deg,j33_deg,j41_deg,j42_deg,"
    "j43_deg,"
    "foot1_x_mm,foot1_y_mm,foot1_z_mm,foot2_x_mm,foot2_y_mm,foot2_z_mm,"
    "foot3_x_mm,foot3_y_mm,foot3_z_mm,foot4_x_mm,foot4_y_mm,foot4_z_mm,"
    "contact1,contact2,contact3,contact4,"
    "body_x_mm,body_y_mm,body_z_mm,body_roll_deg,body_pitch_deg,body_yaw_deg,"
    "world_x_mm,world_y_mm,world_yaw_deg,imu_roll_deg,imu_pitch_deg,imu_yaw_deg,battery_pct,"
    "cmd_vx_mm_s,cmd_vy_mm_s,cmd_vyaw_deg_s,act_vx_mm_s,act_vy_mm_s,act_vyaw_deg_s\n";

#define COLUMNS 50
#define WORLD_X_COLUMN 37

static xgo_test_emu_t g_emu;
static char g_path[64];
static char g_csv[4 << 20];

void setUp(void)
{
    xgo_test_emu_init(&g_emu);
    snprintf(g_path, sizeof g_path, "/tmp/xgo-record-%d.csv", (int)getpid());
}

void tearDown(void)
{
    if (g_emu.pid > 0) {
        xgo_test_emu_kill(&g_emu);
    }
    unlink(g_path);
}

/* Runs xgo-emu --record g_path [extra...] for about ms, walking forward
 * from the start, then reads the whole file into g_csv. */
static size_t record(const char *hz, long ms)
{
    const char *args[5] = {"--record", g_path, hz != NULL ? "--record-hz" : NULL, hz, NULL};
    const uint8_t full = 0xFF;
    FILE *f;
    size_t n;
    int tty;
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, args, NULL));
    TEST_ASSERT_EQUAL_INT(XGO_TEST_EMU_PTY_OK, xgo_test_emu_read_pty(&g_emu, 5000));
    tty = xgo_test_port_open_like_pyserial(g_emu.pty, B115200);
    TEST_ASSERT_TRUE(tty >= 0);
    TEST_ASSERT_EQUAL_INT(0, xgo_test_write_regs(tty, 0x30, &full, 1, 1000));
    xgo_test_sleep_ms(ms);
    close(tty);
    TEST_ASSERT_TRUE(xgo_test_emu_stop(&g_emu, SIGTERM, 5000));
    TEST_ASSERT_EQUAL_INT(0, WEXITSTATUS(g_emu.status));
    f = fopen(g_path, "r");
    TEST_ASSERT_NOT_NULL(f);
    n = fread(g_csv, 1, sizeof g_csv - 1, f);
    fclose(f);
    g_csv[n] = '\0';
    return n;
}

/* Splits the rows after the header: checks the column count of each and
 * returns the count of rows; t[] gets t_ms, x[] world_x_mm (first max). */
static size_t rows(double *t, double *x, size_t max)
{
    char *line = g_csv + strlen(k_header);
    size_t count = 0;
    while (*line != '\0') {
        char *end = strchr(line, '\n');
        char *field = line;
        int col;
        TEST_ASSERT_NOT_NULL_MESSAGE(end, "last row without a newline");
        *end = '\0';
        for (col = 0; col < COLUMNS; col++) {
            char *next;
            double v = strtod(field, &next);
            TEST_ASSERT_TRUE_MESSAGE(next != field, "empty or non-numeric field");
            TEST_ASSERT_TRUE_MESSAGE(col == COLUMNS - 1 ? *next == '\0' : *next == ',', line);
            if (count < max && col == 0) {
                t[count] = v;
            }
            if (count < max && col == WORLD_X_COLUMN) {
                x[count] = v;
            }
            field = next + 1;
        }
        count++;
        line = end + 1;
    }
    return count;
}

static void test_a_row_every_tick(void)
{
    static double t[4096], x[4096];
    size_t n, i;
    record(NULL, 700);
    TEST_ASSERT_EQUAL_STRING_LEN(k_header, g_csv, strlen(k_header));
    n = rows(t, x, 4096);
    TEST_ASSERT_TRUE(n > 100 && n < 4096);
    for (i = 1; i < n; i++) {
        TEST_ASSERT_EQUAL_DOUBLE(t[i - 1] + 2.0, t[i]); /* 500 Hz of board time */
    }
    TEST_ASSERT_TRUE(x[n - 1] > x[0] + 20.0); /* it walked forward */
}

static void test_record_hz_thins_the_rows(void)
{
    static double t[4096], x[4096];
    size_t n, i;
    record("50", 700);
    TEST_ASSERT_EQUAL_STRING_LEN(k_header, g_csv, strlen(k_header));
    n = rows(t, x, 4096);
    TEST_ASSERT_TRUE(n > 5);
    for (i = 1; i < n; i++) {
        TEST_ASSERT_EQUAL_DOUBLE(t[i - 1] + 20.0, t[i]);
    }
}

static void test_misuse_and_bad_paths_are_refused(void)
{
    const char *bad_hz[] = {"--record", g_path, "--record-hz", "0", NULL};
    const char *no_record[] = {"--record-hz", "10", NULL};
    const char *bad_dir[] = {"--record", "/nonexistent-dir/x.csv", NULL};
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, bad_hz, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_emu, 5000));
    TEST_ASSERT_EQUAL_INT(2, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "xgo-emu: --record-hz must be a whole number 1..500, not '0'\n"));
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, no_record, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_emu, 5000));
    TEST_ASSERT_EQUAL_INT(2, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "xgo-emu: --record-hz needs --record\n"));
    TEST_ASSERT_EQUAL_INT(0, xgo_test_emu_spawn(&g_emu, XGO_EMU_PATH, bad_dir, NULL));
    TEST_ASSERT_TRUE(xgo_test_emu_wait(&g_emu, 5000));
    TEST_ASSERT_EQUAL_INT(1, WEXITSTATUS(g_emu.status));
    TEST_ASSERT_EQUAL_STRING("", g_emu.out); /* stopped before the pty line */
    TEST_ASSERT_NOT_NULL(strstr(g_emu.err, "xgo-emu: --record /nonexistent-dir/x.csv: No such file or directory\n"));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_row_every_tick);
    RUN_TEST(test_record_hz_thins_the_rows);
    RUN_TEST(test_misuse_and_bad_paths_are_refused);
    return UNITY_END();
}
