/*
 * Register file: every documented register's access, initial value and valid
 * set; whole-frame validation; the computed views (firmware window, float32
 * attitude, IMU block, int16 attitude, diagnostic block) and the turn
 * command's two-byte write; unmapped addresses.
 */
#include <math.h>
#include <string.h>

#include "codec.h"
#include "regfile.h"
#include "unity.h"
#include "xgo/regs.h"

static xgo_regs_t regs;

void setUp(void)
{
    xgo_regs_init(&regs, "M-EMU-0.1", 0x00);
}

void tearDown(void)
{
}

/* The spec's MemTable (with the errata applied), written out independently
 * of the descriptor table: address, access, initial value. */
typedef struct {
    uint8_t addr;
    uint8_t access;
    uint8_t initial;
} spec_reg_t;

static const spec_reg_t k_spec[] = {
    {0x00, XGO_ACCESS_R, 0x00},  {0x01, XGO_ACCESS_R, 100},   {0x02, XGO_ACCESS_R, 0x00},
    {0x03, XGO_ACCESS_W, 0x00},  {0x04, XGO_ACCESS_W, 0x00},  {0x09, XGO_ACCESS_RW, 0x00},
    {0x20, XGO_ACCESS_RW, 0x00}, {0x21, XGO_ACCESS_W, 0x00},  {0x30, XGO_ACCESS_RW, 0x80},
    {0x31, XGO_ACCESS_RW, 0x80}, {0x32, XGO_ACCESS_RW, 0x80}, {0x33, XGO_ACCESS_RW, 0x80},
    {0x34, XGO_ACCESS_RW, 0x80}, {0x35, XGO_ACCESS_RW, 0x80}, {0x36, XGO_ACCESS_RW, 0x80},
    {0x37, XGO_ACCESS_RW, 0x80}, {0x38, XGO_ACCESS_RW, 0x80}, {0x39, XGO_ACCESS_RW, 0x00},
    {0x3A, XGO_ACCESS_RW, 0x00}, {0x3B, XGO_ACCESS_RW, 0x00}, {0x3C, XGO_ACCESS_RW, 0x00},
    {0x3D, XGO_ACCESS_RW, 0x00}, {0x3E, XGO_ACCESS_W, 0x00},  {0x40, XGO_ACCESS_RW, 0x80},
    {0x41, XGO_ACCESS_RW, 0x80}, {0x42, XGO_ACCESS_RW, 0x80}, {0x43, XGO_ACCESS_RW, 0x80},
    {0x44, XGO_ACCESS_RW, 0x80}, {0x45, XGO_ACCESS_RW, 0x80}, {0x46, XGO_ACCESS_RW, 0x80},
    {0x47, XGO_ACCESS_RW, 0x80}, {0x48, XGO_ACCESS_RW, 0x80}, {0x49, XGO_ACCESS_RW, 0x80},
    {0x4A, XGO_ACCESS_RW, 0x80}, {0x4B, XGO_ACCESS_RW, 0x80}, {0x50, XGO_ACCESS_RW, 0x80},
    {0x51, XGO_ACCESS_RW, 0x80}, {0x52, XGO_ACCESS_RW, 0x80}, {0x53, XGO_ACCESS_RW, 0x80},
    {0x54, XGO_ACCESS_RW, 0x80}, {0x55, XGO_ACCESS_RW, 0x80}, {0x56, XGO_ACCESS_RW, 0x80},
    {0x57, XGO_ACCESS_RW, 0x80}, {0x58, XGO_ACCESS_RW, 0x80}, {0x59, XGO_ACCESS_RW, 0x80},
    {0x5A, XGO_ACCESS_RW, 0x80}, {0x5B, XGO_ACCESS_RW, 0x80}, {0x5C, XGO_ACCESS_RW, 0x80},
    {0x5D, XGO_ACCESS_W, 0x00},  {0x61, XGO_ACCESS_RW, 0x00}, {0x62, XGO_ACCESS_R, 0x80},
    {0x63, XGO_ACCESS_R, 0x80},  {0x64, XGO_ACCESS_R, 0x80},  {0x80, XGO_ACCESS_RW, 0x00},
    {0x81, XGO_ACCESS_RW, 0x00}, {0x82, XGO_ACCESS_RW, 0x00},
};

/* Valid sets written out independently: returns 1 if v may be written. */
static int spec_valid(uint8_t addr, uint8_t v)
{
    switch (addr) {
    case 0x03: case 0x04: case 0x21: case 0x5D: case 0x61: return v <= 1;
    case 0x09: return v <= 3;
    case 0x3D: return v <= 2;
    case 0x20: return v == 0 || v == 1 || (v >= 0x11 && v <= 0x14) || (v >= 0x21 && v <= 0x24);
    case 0x3E: return v <= 24 || v == 255;
    default: return 1;
    }
}

static uint8_t read1(uint8_t addr)
{
    uint8_t v = 0xEE;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, addr, 1, &v));
    return v;
}

static void test_every_spec_register_has_its_access_and_initial_value(void)
{
    size_t i;
    for (i = 0; i < sizeof k_spec / sizeof k_spec[0]; i++) {
        const xgo_reg_desc_t *d = xgo_reg_find(k_spec[i].addr);
        TEST_ASSERT_NOT_NULL_MESSAGE(d, "register missing from the table");
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(k_spec[i].access, d->access, d->name);
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(k_spec[i].initial, read1(k_spec[i].addr), d->name);
    }
}

static void test_every_value_of_every_register_is_accepted_or_rejected_whole(void)
{
    size_t i;
    unsigned v;
    for (i = 0; i < sizeof k_spec / sizeof k_spec[0]; i++) {
        const uint8_t addr = k_spec[i].addr;
        for (v = 0; v < 256; v++) {
            xgo_regs_t before;
            const uint8_t value = (uint8_t)v;
            xgo_drop_reason_t why;
            setUp();
            before = regs;
            why = xgo_regs_write(&regs, addr, &value, 1);
            if (k_spec[i].access == XGO_ACCESS_R) {
                TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, why);
            } else if (!spec_valid(addr, value)) {
                TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, why);
            } else {
                TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, why);
                if (addr >= XGO_REG_SERVO11 && addr <= XGO_REG_SERVO43) {
                    /* a servo command: kept apart, the read still gives the joint */
                    TEST_ASSERT_EQUAL_HEX8(value, xgo_regs_servo_command(&regs, addr - XGO_REG_SERVO11));
                    TEST_ASSERT_EQUAL_HEX8(before.mem[addr], read1(addr));
                } else {
                    TEST_ASSERT_EQUAL_HEX8(value, read1(addr));
                }
                TEST_ASSERT_TRUE(xgo_regs_take_written(&regs, addr));
                TEST_ASSERT_FALSE(xgo_regs_take_written(&regs, addr));
                continue;
            }
            /* Rejected: not a single byte changed. */
            TEST_ASSERT_EQUAL_MEMORY(before.mem, regs.mem, sizeof regs.mem);
            TEST_ASSERT_EQUAL_MEMORY(before.written, regs.written, sizeof regs.written);
        }
    }
}

static void test_frame_with_one_bad_byte_changes_nothing(void)
{
    /* vx, vy, vyaw ok ... but 0x3D (pace) = 7 is invalid. */
    const uint8_t data[14] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 7};
    xgo_regs_t before = regs;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x30, data, sizeof data));
    TEST_ASSERT_EQUAL_MEMORY(before.mem, regs.mem, sizeof regs.mem);
    TEST_ASSERT_EQUAL_UINT32(1, regs.stats.rejected_value);
    TEST_ASSERT_EQUAL_UINT32(0, regs.stats.writes_ok);
}

static void test_frame_touching_read_only_changes_nothing(void)
{
    /* 0x5D..0x64 spans writable registers and the read-only IMU. */
    const uint8_t data[8] = {0, 0, 0, 0, 1, 0, 0, 0};
    xgo_regs_t before = regs;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0x5D, data, sizeof data));
    TEST_ASSERT_EQUAL_MEMORY(before.mem, regs.mem, sizeof regs.mem);
    TEST_ASSERT_EQUAL_UINT32(1, regs.stats.rejected_read_only);
}

static void test_multi_byte_write_applies_all(void)
{
    const uint8_t feet[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    uint8_t back[12];
    unsigned i;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x40, feet, sizeof feet));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x40, sizeof back, back));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(feet, back, sizeof feet);
    TEST_ASSERT_EQUAL_UINT32(1, regs.stats.writes_ok);
    /* twelve servo commands: each taken, none read back (the joints are read) */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x50, feet, sizeof feet));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x50, sizeof back, back));
    for (i = 0; i < 12; i++) {
        TEST_ASSERT_EQUAL_HEX8(feet[i], xgo_regs_servo_command(&regs, i));
        TEST_ASSERT_TRUE(xgo_regs_take_written(&regs, (uint8_t)(0x50 + i)));
        TEST_ASSERT_EQUAL_HEX8(0x80, back[i]);
    }
}

/* The summary flag the motion core skips its per-tick look with: set by
 * every accepted write (whatever the register), taken once; a rejected
 * frame sets nothing. */
static void test_any_written_is_set_by_every_write_and_taken_once(void)
{
    const uint8_t vx = 0x01, bad = 0x07;
    TEST_ASSERT_FALSE(xgo_regs_take_any_written(&regs));
    TEST_ASSERT_NOT_EQUAL(XGO_DROP_NONE, xgo_regs_write(&regs, 0x09, &bad, 1));
    TEST_ASSERT_FALSE(xgo_regs_take_any_written(&regs));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, XGO_REG_VX, &vx, 1));
    TEST_ASSERT_TRUE(xgo_regs_take_any_written(&regs));
    TEST_ASSERT_FALSE(xgo_regs_take_any_written(&regs));
    TEST_ASSERT_TRUE(xgo_regs_take_written(&regs, XGO_REG_VX)); /* the register's own flag stays */
}

static void test_unmapped_addresses_read_zero_and_ignore_writes(void)
{
    /* What the vendor library writes on other models (move to mid, teach,
     * arm, claw, wheels, extra servos). */
    static const uint8_t others[] = {0x22, 0x23, 0x24, 0x5F, 0x70, 0x71, 0x72, 0x73, 0x74,
                                     0x75, 0x76, 0x77, 0xA1, 0xB0, 0xB1, 0xC0};
    size_t i;
    for (i = 0; i < sizeof others; i++) {
        const uint8_t v = 0x5A;
        TEST_ASSERT_NULL(xgo_reg_find(others[i]));
        TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, others[i], &v, 1));
        TEST_ASSERT_EQUAL_HEX8(0x00, read1(others[i]));
    }
    TEST_ASSERT_EQUAL_UINT32(sizeof others, regs.stats.ignored_unmapped);
    TEST_ASSERT_EQUAL_STRING("-", xgo_reg_name(0xC0));
}

static void test_write_across_a_gap_applies_the_mapped_part(void)
{
    /* 0x4B (leg4_z), 0x4C..0x4F (none), 0x50 (servo11) */
    const uint8_t data[6] = {0x11, 0x22, 0x33, 0x44, 0x55, 0x66};
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x4B, data, sizeof data));
    TEST_ASSERT_EQUAL_HEX8(0x11, read1(0x4B));
    TEST_ASSERT_EQUAL_HEX8(0x00, read1(0x4D));
    TEST_ASSERT_EQUAL_HEX8(0x66, xgo_regs_servo_command(&regs, 0));
    TEST_ASSERT_EQUAL_UINT32(1, regs.stats.ignored_unmapped);
}

static void test_firmware_window_and_gait_type_share_0x09(void)
{
    const uint8_t trot_walk = 1;
    uint8_t fw[10];
    static const uint8_t expected[10] = {'M', '-', 'E', 'M', 'U', '-', '0', '.', '1', 0};
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x09, &trot_walk, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x07, 10, fw));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expected, fw, 10);
    TEST_ASSERT_EQUAL_HEX8(1, read1(0x09));
    TEST_ASSERT_EQUAL_HEX8('M', read1(0x07));
    TEST_ASSERT_EQUAL_STRING("gait_type", xgo_reg_name(0x09));
    TEST_ASSERT_EQUAL_STRING("firmware", xgo_reg_name(0x0A));
}

/* The string is kept in the image's window but for its byte at 0x09 (kept
 * apart): short, full-length, longer and missing strings read back NUL
 * padded and cut at 10, whatever the gait type holds. */
static void test_firmware_strings_of_any_length(void)
{
    static const struct {
        const char *in;
        char out[10];
    } k_cases[] = {
        {"AB", {'A', 'B'}},
        {"ABC", {'A', 'B', 'C'}},
        {"0123456789", {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9'}},
        {"0123456789XYZ", {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9'}},
        {NULL, {0}},
    };
    const uint8_t slow_trot = 3;
    uint8_t fw[10];
    size_t i;
    for (i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        xgo_regs_init(&regs, k_cases[i].in, 0x00);
        TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x09, &slow_trot, 1));
        TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x07, 10, fw));
        TEST_ASSERT_EQUAL_HEX8_ARRAY(k_cases[i].out, fw, 10);
        TEST_ASSERT_EQUAL_HEX8(3, read1(0x09));
    }
}

static void test_firmware_is_read_only(void)
{
    const uint8_t x = 'X';
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0x07, &x, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0x10, &x, 1));
}

static void test_lite_identity(void)
{
    uint8_t fw[10];
    xgo_regs_init(&regs, "L-EMU-0.1", 0x01);
    TEST_ASSERT_EQUAL_HEX8(0x01, read1(0x02));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x07, 10, fw));
    TEST_ASSERT_EQUAL_HEX8('L', fw[0]);
}

/* The board's per-address lookup (a start table in flash, searched back
 * from the address) gives, for every address of every model, the row that
 * comes first in table order (xgo_reg_find_model, a plain scan); and the
 * overlaps the table has land where docs/registers.md puts them. */
static void test_every_address_finds_the_first_row_of_its_model(void)
{
    static const uint8_t versions[] = {0x00, XGO_VERSION_LITE, XGO_VERSION_MINI2};
    size_t v;
    unsigned a;
    for (v = 0; v < sizeof versions; v++) {
        const int arm = versions[v] == XGO_VERSION_MINI2;
        xgo_regs_init(&regs, "M-EMU-0.1", versions[v]);
        for (a = 0; a < XGO_REG_COUNT; a++) {
            TEST_ASSERT_TRUE_MESSAGE(xgo_regs_find(&regs, (uint8_t)a) == xgo_reg_find_model((uint8_t)a, arm),
                                     "row of an address");
        }
        TEST_ASSERT_EQUAL_HEX8(XGO_REG_GAIT_TYPE, xgo_regs_find(&regs, 0x09)->addr);
        TEST_ASSERT_EQUAL_HEX8(XGO_REG_FIRMWARE, xgo_regs_find(&regs, 0x0A)->addr);
        TEST_ASSERT_EQUAL_HEX8(XGO_REG_FIRMWARE, xgo_regs_find(&regs, 0x10)->addr);
        TEST_ASSERT_NULL(xgo_regs_find(&regs, 0x11));
        TEST_ASSERT_EQUAL_HEX8(XGO_REG_DIAG, xgo_regs_find(&regs, 0xFF)->addr);
        TEST_ASSERT_NULL(xgo_regs_find(&regs, 0xC3));
        TEST_ASSERT_EQUAL_UINT8(arm ? XGO_REGF_ARM : XGO_REGF_AUTO_CLEAR_NO_ARM,
                                xgo_regs_find(&regs, 0x5D)->flags);
        TEST_ASSERT_TRUE(arm ? xgo_regs_find(&regs, 0x77) != NULL : xgo_regs_find(&regs, 0x77) == NULL);
    }
}

static void read_name(char out[11])
{
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x13, 10, (uint8_t *)out));
    out[10] = '\0';
}

static void test_bluetooth_name(void)
{
    char name[11];
    read_name(name);
    TEST_ASSERT_EQUAL_STRING("XGOMINI", name);

    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x13, (const uint8_t *)"Rex", 3));
    read_name(name);
    TEST_ASSERT_EQUAL_STRING("Rex", name); /* shorter write sets the whole name */
    TEST_ASSERT_EQUAL_MEMORY("Rex\0\0\0\0\0\0\0", name, 10);

    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                          xgo_regs_write(&regs, 0x13, (const uint8_t *)"0123456789", 10));
    read_name(name);
    TEST_ASSERT_EQUAL_STRING("0123456789", name);
}

static void test_bluetooth_name_rejects_bad_input(void)
{
    const uint8_t chinese[3] = {0xE7, 0x8B, 0x97};
    const uint8_t with_nul[3] = {'a', 0x00, 'b'};
    char name[11];
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x13, chinese, 3));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x13, with_nul, 3));
    /* starting in the middle of the name */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x15, (const uint8_t *)"ab", 2));
    read_name(name);
    TEST_ASSERT_EQUAL_STRING("XGOMINI", name);
}

static void test_restore_initial_keeps_nonvolatile_and_identity(void)
{
    const uint8_t fast = 0xFF;
    char name[11];
    xgo_regs_write(&regs, 0x13, (const uint8_t *)"Rex", 3);
    xgo_regs_write(&regs, 0x30, &fast, 1);
    xgo_regs_set(&regs, XGO_REG_BATTERY, 42);
    xgo_regs_restore_initial(&regs);
    TEST_ASSERT_EQUAL_HEX8(0x80, read1(0x30));
    TEST_ASSERT_EQUAL_UINT8(42, read1(0x01));
    read_name(name);
    TEST_ASSERT_EQUAL_STRING("Rex", name);
    TEST_ASSERT_FALSE(xgo_regs_take_written(&regs, 0x30));
}

static void test_read_ranges(void)
{
    uint8_t out[XGO_FRAME_MAX_DATA];
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_regs_read(&regs, 0x00, 0, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_regs_read(&regs, 0x00, 248, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_regs_read(&regs, 0xFF, 2, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0xFF, 1, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x09, 247, out));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_RANGE, xgo_regs_write(&regs, 0xFF, out, 2));
}

/* --- computed views ---------------------------------------------------- */

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static void test_float32_bits_match_the_compiler_for_every_millidegree(void)
{
    int32_t m;
    for (m = -400000; m <= 400000; m++) {
        /* Double rounding (exact -> double -> float) cannot differ from
         * direct rounding here: m/1000 is never within 2^-53 (relative) of a
         * float midpoint unless equal to it (the gap is >= 1/(1000*2^24)). */
        const uint32_t want = float_bits((float)((double)m / 1000.0));
        if (want != xgo_mdeg_to_float32_bits(m)) {
            TEST_ASSERT_EQUAL_HEX32_MESSAGE(want, xgo_mdeg_to_float32_bits(m), "mdeg mismatch");
        }
    }
    TEST_ASSERT_EQUAL_HEX32(float_bits((float)(2147483647.0 / 1000.0)),
                            xgo_mdeg_to_float32_bits(INT32_MAX));
    TEST_ASSERT_EQUAL_HEX32(float_bits((float)(-2147483648.0 / 1000.0)),
                            xgo_mdeg_to_float32_bits(INT32_MIN));
    TEST_ASSERT_EQUAL_HEX32(0, xgo_mdeg_to_float32_bits(0));
    /* Exact ties between two floats (only reachable near 2^31): ties-to-even. */
    TEST_ASSERT_EQUAL_HEX32(float_bits((float)(2097152125.0 / 1000.0)),
                            xgo_mdeg_to_float32_bits(2097152125));
    TEST_ASSERT_EQUAL_HEX32(float_bits((float)(2097152375.0 / 1000.0)),
                            xgo_mdeg_to_float32_bits(2097152375));
    TEST_ASSERT_EQUAL_HEX32(float_bits((float)(-2097152375.0 / 1000.0)),
                            xgo_mdeg_to_float32_bits(-2097152375));
}

static void test_four_byte_attitude_reads_are_float32_le(void)
{
    uint8_t out[4];
    float f;
    xgo_regs_set_attitude(&regs, 12340, -5500, 179999);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x62, 4, out));
    memcpy(&f, out, 4); /* host is little-endian (x86-64 / ARM) */
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 12.34, f);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x63, 4, out));
    memcpy(&f, out, 4);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, -5.5, f);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x64, 4, out));
    memcpy(&f, out, 4);
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 179.999, f);
}

static void test_one_byte_attitude_reads_are_the_byte_encoding(void)
{
    uint8_t out[3];
    xgo_regs_set_attitude(&regs, 90000, -45000, -180000);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x62, 3, out));
    TEST_ASSERT_EQUAL_HEX8(0x80 + 64, out[0]);
    TEST_ASSERT_EQUAL_HEX8(0x80 - 32, out[1]);
    TEST_ASSERT_EQUAL_HEX8(0x00, out[2]);
}

static void test_angle_byte_encoding_against_reference(void)
{
    int32_t m;
    for (m = -200000; m <= 200000; m += 7) {
        double ref = 128.0 + (double)m / 1000.0 * 128.0 / 180.0;
        long want = (long)floor(ref + 0.5);
        if (m < 0 && fabs(ref - floor(ref) - 0.5) < 1e-12) {
            want = (long)floor(ref); /* half away from zero for negatives */
        }
        if (want < 0) want = 0;
        if (want > 255) want = 255;
        TEST_ASSERT_EQUAL_UINT8((uint8_t)want, xgo_angle_to_byte(m));
    }
    TEST_ASSERT_EQUAL_UINT8(0x80, xgo_angle_to_byte(0));
    TEST_ASSERT_EQUAL_UINT8(0, xgo_angle_to_byte(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT8(255, xgo_angle_to_byte(INT32_MAX));
}

/* The vendor's range map of a joint, in double: 0 at or below lo, 255 at or
 * above hi, floor(255 (v - lo) / (hi - lo)) between. */
static uint8_t joint_byte_reference(const xgo_range_t *r, int32_t v)
{
    if (v <= r->lo) return 0;
    if (v >= r->hi) return 255;
    return (uint8_t)floor(255.0 * ((double)v - r->lo) / ((double)r->hi - r->lo));
}

/* 0x50..0x5B read the joints through xgo_range_to_byte (the board forms
 * them on read: test_board checks the reads): the vendor's map of every
 * profile's ranges, at the bounds, beyond them (any int32) and between. */
static void test_joint_bytes_are_the_range_map(void)
{
    static const int32_t extremes[] = {INT32_MIN, INT32_MIN + 1, -(1 << 30) - 1, -(1 << 30), 0,
                                       (1 << 30) - 1, 1 << 30, INT32_MAX - 1, INT32_MAX};
    const xgo_profile_t *profiles[3];
    uint32_t seed = 7u;
    unsigned k, n, leg, j;
    int32_t step;
    profiles[0] = xgo_profile_mini();
    profiles[1] = xgo_profile_lite();
    profiles[2] = xgo_profile_mini2();
    for (k = 0; k < 3; k++) {
        const xgo_profile_t *p = profiles[k];
        for (j = 0; j < XGO_JOINT_COUNT; j++) { /* a sweep past both ends */
            const xgo_range_t *r = &p->joint_mdeg[j];
            for (step = -300; step <= 25800; step += 37) {
                const int32_t v = r->lo + (int32_t)(((int64_t)(r->hi - r->lo) * step) / 25500);
                TEST_ASSERT_EQUAL_UINT8(joint_byte_reference(r, v), xgo_joint_to_byte(p, (xgo_joint_t)j, v));
            }
        }
        for (n = 0; n < 4000; n++) {
            int32_t q[XGO_LEG_COUNT][XGO_JOINT_COUNT];
            uint8_t got[XGO_SERVO_COUNT];
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                for (j = 0; j < XGO_JOINT_COUNT; j++) {
                    const xgo_range_t *r = &p->joint_mdeg[j];
                    seed = seed * 1103515245u + 12345u;
                    switch ((seed >> 16) % 6u) {
                    case 0:
                        q[leg][j] = r->lo + (int32_t)((seed >> 8) % 5u) - 2;
                        break;
                    case 1:
                        q[leg][j] = r->hi + (int32_t)((seed >> 8) % 5u) - 2;
                        break;
                    case 2:
                        q[leg][j] = extremes[(seed >> 8) % (sizeof extremes / sizeof extremes[0])];
                        break;
                    default:
                        q[leg][j] = r->lo + (int32_t)((seed >> 4) % 400001u) - 100000;
                        break;
                    }
                }
            }
            xgo_joints_to_bytes(p, (const int32_t(*)[XGO_JOINT_COUNT])q, got);
            for (leg = 0; leg < XGO_LEG_COUNT; leg++) {
                for (j = 0; j < XGO_JOINT_COUNT; j++) {
                    TEST_ASSERT_EQUAL_UINT8(joint_byte_reference(&p->joint_mdeg[j], q[leg][j]),
                                            got[leg * XGO_JOINT_COUNT + j]);
                }
            }
        }
    }
}

/* The register file keeps no counters: the board forms the block on read
 * (test_board: test_diag_block_is_formed_on_read). Here it reads 0 and
 * refuses writes. */
/* The image stores 0x00..0x93 (XGO_REGS_STORED): a read across its end
 * gives the stored bytes, then 0 for the unmapped addresses after them. */
static void test_read_across_the_stored_image(void)
{
    const uint8_t io[4] = {1, 2, 3, 4};
    uint8_t out[0x20];
    size_t i;
    TEST_ASSERT_EQUAL_UINT(0x94, XGO_REGS_STORED);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x90, io, sizeof io));
    memset(out, 0xEE, sizeof out);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x90, sizeof out, out));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(io, out, sizeof io);
    for (i = sizeof io; i < sizeof out; i++) {
        TEST_ASSERT_EQUAL_HEX8(0, out[i]);
    }
    memset(out, 0xEE, sizeof out);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0xA0, sizeof out, out));
    for (i = 0; i < sizeof out; i++) {
        TEST_ASSERT_EQUAL_HEX8(0, out[i]);
    }
    for (i = XGO_REGS_STORED; i < XGO_REG_DIAG; i++) {
        TEST_ASSERT_NULL(xgo_reg_find((uint8_t)i)); /* nothing unstored but the block is mapped */
    }
}

static void test_diag_block_is_read_only(void)
{
    uint8_t out[4];
    uint8_t slots[4 * XGO_DIAG_SLOTS];
    size_t i;
    TEST_ASSERT_EQUAL_UINT(0xC4, XGO_REG_DIAG);
    TEST_ASSERT_EQUAL_UINT(0x100, 0xC4 + 4 * XGO_DIAG_SLOTS);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0xC4, 4 * XGO_DIAG_SLOTS, slots));
    for (i = 0; i < 4 * XGO_DIAG_SLOTS; i++) {
        TEST_ASSERT_EQUAL_HEX8(0, slots[i]);
    }
    memset(out, 1, sizeof out);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0xC4, out, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0xE0, out, 1));
    /* 0xC0..0xC3 (written by the vendor library on other models) stay outside */
    TEST_ASSERT_NULL(xgo_reg_find(0xC3));
}

static void test_table_is_consistent(void)
{
    size_t i;
    TEST_ASSERT_GREATER_OR_EQUAL_UINT(sizeof k_spec / sizeof k_spec[0], xgo_reg_table_size());
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        TEST_ASSERT_NOT_NULL(d->name);
        TEST_ASSERT_TRUE(d->width >= 1 && (unsigned)d->addr + d->width <= 256u);
        if (d->flags & XGO_REGF_AUTO_CLEAR) {
            TEST_ASSERT_EQUAL_UINT8(0, d->initial);
        }
    }
    TEST_ASSERT_NULL(xgo_reg_table_entry(xgo_reg_table_size()));
}

/* The current vendor library's registers the Mini and Lite answer (issue 11):
 * upgrade, set origin, turn to heading, the IMU views, LED, I/O. */
static const spec_reg_t k_vendor[] = {
    {0x05, XGO_ACCESS_W, 0x00},  {0x06, XGO_ACCESS_W, 0x00},  {0x3F, XGO_ACCESS_RW, 0x01},
    {0x65, XGO_ACCESS_R, 0x00},  {0x66, XGO_ACCESS_R, 0x00},  {0x67, XGO_ACCESS_R, 0x00},
    {0x68, XGO_ACCESS_R, 0x00},  {0x69, XGO_ACCESS_RW, 0x00}, {0x6A, XGO_ACCESS_RW, 0x00},
    {0x6B, XGO_ACCESS_RW, 0x00}, {0x90, XGO_ACCESS_RW, 0x00}, {0x91, XGO_ACCESS_RW, 0x00},
    {0x92, XGO_ACCESS_RW, 0x00}, {0x93, XGO_ACCESS_RW, 0x00},
};

static void test_vendor_registers_have_their_access_and_initial_value(void)
{
    size_t i;
    for (i = 0; i < sizeof k_vendor / sizeof k_vendor[0]; i++) {
        const xgo_reg_desc_t *d = xgo_reg_find(k_vendor[i].addr);
        TEST_ASSERT_NOT_NULL_MESSAGE(d, "register missing from the table");
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(k_vendor[i].access, d->access, d->name);
        TEST_ASSERT_EQUAL_HEX8_MESSAGE(k_vendor[i].initial, regs.mem[k_vendor[i].addr], d->name);
    }
}

static void test_upgrade_and_origin_take_0_or_1(void)
{
    const uint8_t two = 2, one = 1;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x05, &two, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x06, &two, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x05, &one, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x06, &one, 1));
    TEST_ASSERT_EQUAL_HEX8(1, read1(0x05));
    TEST_ASSERT_TRUE(xgo_regs_take_written(&regs, 0x06));
}

static void test_led_and_io_keep_what_was_written(void)
{
    const uint8_t rgb[3] = {0x12, 0x34, 0x56}, io[4] = {200, 1, 77, 0};
    uint8_t back[4];
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x69, rgb, sizeof rgb));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x69, 3, back));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(rgb, back, 3);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x90, io, sizeof io));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x90, 4, back));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(io, back, 4);
    TEST_ASSERT_EQUAL_UINT32(0, regs.stats.ignored_unmapped);
    /* a colour is written from its first byte */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x6A, rgb, 1));
}

static void test_turn_to_write_is_one_command(void)
{
    const uint8_t left90[2] = {0x00, 0x5A}, right90[2] = {0xFF, 0xA6};
    const uint8_t action_and_turn[3] = {0, 0x01, 0x0E}; /* 0x3E, then 270 degrees */
    const uint8_t turn_and_leg1_y[3] = {0x00, 0x2D, 0x99};
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x3F, left90, 2));
    TEST_ASSERT_EQUAL_INT(90, xgo_regs_turn_to_deg(&regs));
    TEST_ASSERT_EQUAL_HEX8(0, read1(0x3F));        /* turning until the board says done */
    TEST_ASSERT_EQUAL_HEX8(0x80, read1(0x40));     /* leg 1 x untouched ... */
    TEST_ASSERT_FALSE(xgo_regs_was_written(&regs, 0x40)); /* ... and not flagged */
    TEST_ASSERT_TRUE(xgo_regs_take_written(&regs, 0x3F));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x3F, right90, 2));
    TEST_ASSERT_EQUAL_INT(-90, xgo_regs_turn_to_deg(&regs));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x3E, action_and_turn, 3));
    TEST_ASSERT_EQUAL_INT(270, xgo_regs_turn_to_deg(&regs));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_write(&regs, 0x3F, turn_and_leg1_y, 3));
    TEST_ASSERT_EQUAL_INT(45, xgo_regs_turn_to_deg(&regs));
    TEST_ASSERT_EQUAL_HEX8(0x99, read1(0x41));     /* the third byte goes on to 0x41 */
    TEST_ASSERT_EQUAL_HEX8(0x80, read1(0x40));
}

static void test_half_a_heading_is_rejected(void)
{
    const uint8_t one = 0x00, action_then_half_heading[2] = {0x00, 0x00};
    xgo_regs_t before = regs;
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE, xgo_regs_write(&regs, 0x3F, &one, 1));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_BAD_VALUE,
                          xgo_regs_write(&regs, 0x3E, action_then_half_heading, 2));
    TEST_ASSERT_EQUAL_MEMORY(before.mem, regs.mem, sizeof regs.mem);
    TEST_ASSERT_EQUAL_MEMORY(before.written, regs.written, sizeof regs.written);
    TEST_ASSERT_EQUAL_UINT32(2, regs.stats.rejected_value);
}

static int16_t le16(const uint8_t *p)
{
    return (int16_t)(uint16_t)(p[0] | (unsigned)p[1] << 8);
}

static float le_float(const uint8_t *p)
{
    float f;
    memcpy(&f, p, 4); /* host is little-endian (x86-64 / ARM) */
    return f;
}

static void test_imu_block_is_accel_gyro_int16_then_float_angles(void)
{
    const int16_t accel[3] = {-1234, 567, 16384}, gyro[3] = {-32768, 1, 32767};
    uint8_t out[XGO_IMU_BLOCK_LEN + 2], shorter[6];
    size_t i;
    xgo_regs_set_attitude(&regs, 12340, -5500, 179999);
    xgo_regs_set_inertial(&regs, accel, gyro);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x65, sizeof out, out));
    for (i = 0; i < 3; i++) {
        TEST_ASSERT_EQUAL_INT16(accel[i], le16(&out[2 * i]));
        TEST_ASSERT_EQUAL_INT16(gyro[i], le16(&out[6 + 2 * i]));
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 12.34, le_float(&out[12]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, -5.5, le_float(&out[16]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 179.999, le_float(&out[20]));
    TEST_ASSERT_EQUAL_HEX8(regs.mem[0x65 + 24], out[24]); /* past the block: flat */
    TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, 0x65, sizeof shorter, shorter));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(out, shorter, sizeof shorter);
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0x65, out, 1));
}

static void test_int16_attitude_views_are_big_endian_centidegrees(void)
{
    int32_t m;
    uint8_t out[2];
    for (m = -200003; m <= 200003; m += 7) {
        const double c = (double)m / 10.0;
        const long want = (long)(c >= 0 ? floor(c + 0.5) : -floor(-c + 0.5));
        unsigned axis;
        xgo_regs_set_attitude(&regs, m, -m, m / 2);
        for (axis = 0; axis < 3; axis++) {
            const int32_t v = axis == 0 ? m : (axis == 1 ? -m : m / 2);
            const double cv = (double)v / 10.0;
            const long w = (long)(cv >= 0 ? floor(cv + 0.5) : -floor(-cv + 0.5));
            TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE,
                                  xgo_regs_read(&regs, (uint8_t)(0x66 + axis), 2, out));
            TEST_ASSERT_EQUAL_INT(w, (int16_t)(uint16_t)(out[0] << 8 | out[1]));
        }
        TEST_ASSERT_EQUAL_INT(want, xgo_mdeg_to_centideg(m));
    }
    TEST_ASSERT_EQUAL_INT(32767, xgo_mdeg_to_centideg(INT32_MAX));
    TEST_ASSERT_EQUAL_INT(-32767, xgo_mdeg_to_centideg(INT32_MIN));
    TEST_ASSERT_EQUAL_INT(XGO_DROP_READ_ONLY, xgo_regs_write(&regs, 0x66, out, 2));
}

/* The board's reads form the IMU's registers from the motion core's outputs
 * (xgo_regs_read_imu) into a file that never stored them: any window over
 * them must give what a file that stored them (xgo_regs_set_attitude and
 * _inertial, the board's old store every tick) gives, its bytes at 0x62..
 * 0x64 those xgo_regs_get returns where no view covers them. */
static uint32_t imu_rand(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void test_imu_registers_formed_from_outputs_equal_the_stored(void)
{
    xgo_regs_t fresh;
    uint32_t seed = 0x1234567u;
    unsigned k;
    xgo_regs_init(&fresh, "T", 0);
    for (k = 0; k < 20000; k++) {
        xgo_regs_imu_t imu;
        uint8_t want[XGO_FRAME_MAX_DATA], got[XGO_FRAME_MAX_DATA + 1];
        const unsigned addr = 0x40u + imu_rand(&seed) % 0x40u;
        const unsigned n = 1u + imu_rand(&seed) % (k % 4u == 0 ? 40u : 8u);
        unsigned i;
        for (i = 0; i < 3; i++) {
            const uint32_t v = imu_rand(&seed);
            imu.attitude_mdeg[i] = k % 8u == 0 ? (int32_t)v : (int32_t)(v % 400001u) - 200000;
#if XGO_WITH_INERTIAL
            imu.accel[i] = (int16_t)(uint16_t)imu_rand(&seed);
            imu.gyro[i] = (int16_t)(uint16_t)imu_rand(&seed);
#endif
        }
        xgo_regs_set_attitude(&regs, imu.attitude_mdeg[0], imu.attitude_mdeg[1], imu.attitude_mdeg[2]);
#if XGO_WITH_INERTIAL
        xgo_regs_set_inertial(&regs, imu.accel, imu.gyro);
#endif
        TEST_ASSERT_EQUAL_INT(XGO_DROP_NONE, xgo_regs_read(&regs, (uint8_t)addr, n, want));
        got[n] = 0xA5;
        xgo_regs_read_imu(&fresh, &imu, (uint8_t)addr, n, got);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(want, got, n);
        TEST_ASSERT_EQUAL_HEX8(0xA5, got[n]);
        if (!(addr >= XGO_REG_IMU_ROLL && addr <= XGO_REG_IMU_YAW16)) {
            for (i = 0; i < 3; i++) {
                const unsigned at = XGO_REG_IMU_ROLL + i;
                if (at >= addr && at < addr + n) {
                    TEST_ASSERT_EQUAL_HEX8(xgo_regs_get(&regs, (uint8_t)at), got[at - addr]);
                }
            }
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_spec_register_has_its_access_and_initial_value);
    RUN_TEST(test_every_value_of_every_register_is_accepted_or_rejected_whole);
    RUN_TEST(test_frame_with_one_bad_byte_changes_nothing);
    RUN_TEST(test_frame_touching_read_only_changes_nothing);
    RUN_TEST(test_multi_byte_write_applies_all);
    RUN_TEST(test_any_written_is_set_by_every_write_and_taken_once);
    RUN_TEST(test_unmapped_addresses_read_zero_and_ignore_writes);
    RUN_TEST(test_write_across_a_gap_applies_the_mapped_part);
    RUN_TEST(test_firmware_window_and_gait_type_share_0x09);
    RUN_TEST(test_firmware_strings_of_any_length);
    RUN_TEST(test_firmware_is_read_only);
    RUN_TEST(test_lite_identity);
    RUN_TEST(test_every_address_finds_the_first_row_of_its_model);
    RUN_TEST(test_bluetooth_name);
    RUN_TEST(test_bluetooth_name_rejects_bad_input);
    RUN_TEST(test_restore_initial_keeps_nonvolatile_and_identity);
    RUN_TEST(test_read_ranges);
    RUN_TEST(test_float32_bits_match_the_compiler_for_every_millidegree);
    RUN_TEST(test_four_byte_attitude_reads_are_float32_le);
    RUN_TEST(test_one_byte_attitude_reads_are_the_byte_encoding);
    RUN_TEST(test_angle_byte_encoding_against_reference);
    RUN_TEST(test_joint_bytes_are_the_range_map);
    RUN_TEST(test_read_across_the_stored_image);
    RUN_TEST(test_diag_block_is_read_only);
    RUN_TEST(test_table_is_consistent);
    RUN_TEST(test_vendor_registers_have_their_access_and_initial_value);
    RUN_TEST(test_upgrade_and_origin_take_0_or_1);
    RUN_TEST(test_led_and_io_keep_what_was_written);
    RUN_TEST(test_turn_to_write_is_one_command);
    RUN_TEST(test_half_a_heading_is_rejected);
    RUN_TEST(test_imu_block_is_accel_gyro_int16_then_float_angles);
    RUN_TEST(test_int16_attitude_views_are_big_endian_centidegrees);
    RUN_TEST(test_imu_registers_formed_from_outputs_equal_the_stored);
    return UNITY_END();
}
