/*
 * The register map (xgo/regs.h: descriptor table, lookups, value sets) and
 * the register file built from it (regfile.h: whole-frame validation,
 * computed views).
 */
#include "xgo/regs.h"

#include <string.h>

#include "check.h"
#include "codec.h"
#include "compiler.h"
#include "regfile.h"
#include "xgo/profile.h"

/* Flags column: 0 or a XGO_REGF_ suffix. */
#define XGO_REGF_0 0u

#if XGO_WITH_NAMES
#define REG_NAME_(nm) , nm
#else
#define REG_NAME_(nm)
#endif

static const xgo_reg_desc_t k_regs[] = {
#define XGO_REG_DESC_(id, a, w, acc, fl, init, v, l, h, nm)                                  \
    {(uint8_t)(a), (uint8_t)(w), XGO_ACCESS_##acc, (uint8_t)(XGO_REGF_##fl + 0), (uint8_t)(init), \
     (uint8_t)XGO_VALID_##v, (uint8_t)(l), (uint8_t)(h) REG_NAME_(nm)},
    XGO_REG_LIST(XGO_REG_DESC_)
#undef XGO_REG_DESC_
};

#define REG_TABLE_SIZE (sizeof k_regs / sizeof k_regs[0])

size_t xgo_reg_table_size(void)
{
    return REG_TABLE_SIZE;
}

const xgo_reg_desc_t *xgo_reg_table_entry(size_t i)
{
    return i < REG_TABLE_SIZE ? &k_regs[i] : NULL;
}

unsigned xgo_version_profile(uint8_t version)
{
    return version == XGO_VERSION_LITE ? XGO_PROFILE_LITE
           : version == XGO_VERSION_MINI2 ? XGO_PROFILE_MINI2
                                          : XGO_PROFILE_MINI;
}

int xgo_reg_for_model(const xgo_reg_desc_t *d, int arm)
{
    return (d->flags & (arm ? XGO_REGF_NO_ARM : XGO_REGF_ARM)) == 0;
}

static int for_model(const xgo_reg_desc_t *d, int arm)
{
    return xgo_reg_for_model(d, arm);
}

/* Row numbers of k_regs, for the start table below. */
enum reg_row_e {
#define REG_ROW_(id, a, w, acc, fl, init, v, l, h, nm) REG_ROW_##id,
    XGO_REG_LIST(REG_ROW_)
#undef REG_ROW_
    REG_ROWS_
};
typedef char xgo_reg_rows_fit_byte_[REG_ROWS_ < 0xFF ? 1 : -1];

/* No row is wider than the OR of all the widths. */
enum {
#define REG_WIDTH_OR_(id, a, w, acc, fl, init, v, l, h, nm) | (w)
    REG_WIDTH_BOUND = 0 XGO_REG_LIST(REG_WIDTH_OR_)
#undef REG_WIDTH_OR_
};

/* Every row but the diagnostic block lies in the stored image
 * (XGO_REGS_STORED, xgo/board_state.h). */
#define REG_STORED_(id, a, w, acc, fl, init, v, l, h, nm)                                      \
    typedef char xgo_reg_stored_##id##_[(XGO_REG_##id == XGO_REG_DIAG ||                       \
                                         (unsigned)(a) + (unsigned)(w) <= XGO_REGS_STORED)      \
                                            ? 1                                                 \
                                            : -1];
XGO_REG_LIST(REG_STORED_)
#undef REG_STORED_
typedef char xgo_regs_diag_above_stored_[XGO_REG_DIAG >= XGO_REGS_STORED ? 1 : -1];

/* Only the arm's rows lie in the image's gaps (XGO_REGS_GAPn_START..END,
 * xgo/board_state.h: there are some only without the Mini2, whose rows are
 * then never this model's). */
#define REG_CLEAR_OF_(a, w, n)                                                                 \
    ((unsigned)(a) + (unsigned)(w) <= XGO_REGS_GAP##n##_START || (unsigned)(a) >= XGO_REGS_GAP##n##_END)
#define REG_OUT_OF_GAPS_(id, a, w, acc, fl, init, v, l, h, nm)                                 \
    typedef char xgo_reg_out_of_gaps_##id##_[(((XGO_REGF_##fl + 0u) & XGO_REGF_ARM) != 0u ||   \
                                              (REG_CLEAR_OF_(a, w, 1) && REG_CLEAR_OF_(a, w, 2) && \
                                               REG_CLEAR_OF_(a, w, 3)))                        \
                                                 ? 1                                           \
                                                 : -1];
XGO_REG_LIST(REG_OUT_OF_GAPS_)
#undef REG_OUT_OF_GAPS_
#undef REG_CLEAR_OF_
typedef char xgo_regs_gaps_in_order_[XGO_REGS_GAP1_END <= XGO_REGS_GAP2_START &&
                                             XGO_REGS_GAP2_END <= XGO_REGS_GAP3_START &&
                                             XGO_REGS_GAP3_END <= XGO_REGS_STORED
                                         ? 1
                                         : -1];

/* The image is reached at these fixed addresses directly: all below the
 * first gap, where the slot is the address. */
typedef char xgo_regs_direct_below_gaps_[XGO_REG_BT_NAME + XGO_BT_NAME_LEN <= XGO_REGS_GAP1_START &&
                                                 XGO_REG_FIRMWARE + XGO_FIRMWARE_LEN <=
                                                     XGO_REGS_GAP1_START &&
                                                 XGO_REG_VERSION < XGO_REGS_GAP1_START
                                             ? 1
                                             : -1];

/* The stored runs of addresses, between the gaps (reads copy them). */
static const uint8_t k_stored[4][2] = {
    {0x00u, XGO_REGS_GAP1_START},
    {XGO_REGS_GAP1_END, XGO_REGS_GAP2_START},
    {XGO_REGS_GAP2_END, XGO_REGS_GAP3_START},
    {XGO_REGS_GAP3_END, XGO_REGS_STORED},
};

#if !XGO_WITH_MINI2
/* How much lower than its address a stored address sits, by its block of
 * 16 addresses: every gap ends on a block boundary, so all stored addresses
 * of a block have the same gaps below them. A table lookup, not three
 * compares: the tick reaches the image through this about a dozen times. */
typedef char xgo_regs_gaps_end_on_blocks_[XGO_REGS_GAP1_END % 16u == 0u &&
                                                  XGO_REGS_GAP2_END % 16u == 0u &&
                                                  XGO_REGS_GAP3_END % 16u == 0u
                                              ? 1
                                              : -1];
/* From regfile.h's constant form (one formula for both): at a block's first
 * address the gaps below are those that end at or before it, and no gap
 * ends inside a block (above), so they are the whole block's. */
#define GAPS_BELOW_(block) (16u * (block) - XGO_REGS_SLOT(16u * (block)))
static const uint8_t k_gaps_below[(XGO_REGS_STORED + 15u) / 16u] = {
    GAPS_BELOW_(0u), GAPS_BELOW_(1u), GAPS_BELOW_(2u), GAPS_BELOW_(3u), GAPS_BELOW_(4u),
    GAPS_BELOW_(5u), GAPS_BELOW_(6u), GAPS_BELOW_(7u), GAPS_BELOW_(8u), GAPS_BELOW_(9u),
};
#undef GAPS_BELOW_
#endif

/* Where a stored address (below XGO_REGS_STORED, in no gap) sits in mem
 * and in written: lower by the length of the gaps below it (with the Mini2
 * there are none: the address itself). No check of its own: it runs about
 * a dozen times a tick. */
XGO_ALWAYS_INLINE unsigned slot(unsigned addr)
{
#if XGO_WITH_MINI2
    return addr;
#else
    return addr - k_gaps_below[addr >> 4]; /* callers: row addresses (none in a gap, above) */
#endif
}

/* Where each row starts, a constant in flash rather than a per-address map
 * in every board's RAM: k_start[addr] = row + 1 for rows on every model or
 * on the models without the arm, k_start[XGO_REG_COUNT + addr] for the
 * arm's rows (they take addresses the Mini uses otherwise); 0: no row
 * starts there. Two rows of one half starting at one address would be a
 * repeated initializer (-Woverride-init, an error with -Werror). */
#define REG_START_SLOT_(fl, a) \
    ((((XGO_REGF_##fl + 0u) & XGO_REGF_ARM) != 0u ? XGO_REG_COUNT : 0u) + (unsigned)(a))
static const uint8_t k_start[] = {
#define REG_START_(id, a, w, acc, fl, init, v, l, h, nm) [REG_START_SLOT_(fl, a)] = REG_ROW_##id + 1,
    XGO_REG_LIST(REG_START_)
#undef REG_START_
};

/* The row that starts at `start` in one half of k_start and covers addr on
 * this model, or NULL. */
static const xgo_reg_desc_t *row_at(const xgo_regs_t *r, unsigned slot, unsigned addr)
{
    const xgo_reg_desc_t *d;
    if (slot >= sizeof k_start || k_start[slot] == 0u) {
        return NULL;
    }
    d = &k_regs[k_start[slot] - 1u];
    return for_model(d, r->arm) && addr < (unsigned)d->addr + d->width ? d : NULL;
}

/* The row that holds addr on this model: the nearest one starting at or
 * below it that covers it (the arm's first). Rows overlap only where a
 * one-byte row sits inside a wider one (0x09 in the firmware window), so
 * this is the first row in table order (xgo_reg_find_model): test_regs
 * checks every address of every model. */
static const xgo_reg_desc_t *desc_at(const xgo_regs_t *r, unsigned addr)
{
    unsigned back;
    for (back = 0; back < (unsigned)REG_WIDTH_BOUND && back <= addr; back++) {
        const xgo_reg_desc_t *d = r->arm ? row_at(r, XGO_REG_COUNT + addr - back, addr) : NULL;
        if (d == NULL) {
            d = row_at(r, addr - back, addr);
        }
        if (d != NULL) {
            return d;
        }
    }
    return NULL;
}

const xgo_reg_desc_t *xgo_reg_find_model(uint8_t addr, int arm)
{
    size_t i;
    for (i = 0; i < REG_TABLE_SIZE; i++) {
        const xgo_reg_desc_t *d = &k_regs[i];
        if (for_model(d, arm) && addr >= d->addr && (unsigned)addr < (unsigned)d->addr + d->width) {
            return d;
        }
    }
    return NULL;
}

const xgo_reg_desc_t *xgo_reg_find(uint8_t addr)
{
    return xgo_reg_find_model(addr, 0);
}

const char *xgo_reg_name(uint8_t addr)
{
    const xgo_reg_desc_t *d = xgo_reg_find(addr);
#if XGO_WITH_NAMES
    return d != NULL ? d->name : "-";
#else
    return d != NULL ? "" : "-";
#endif
}

int xgo_reg_value_valid(const xgo_reg_desc_t *d, uint8_t v)
{
    switch ((xgo_valid_t)d->valid) {
    case XGO_VALID_ANY: return 1;
    case XGO_VALID_RANGE: return v >= d->lo && v <= d->hi;
    case XGO_VALID_UNLOAD: {
        xgo_unload_t u;
        return xgo_unload_decode(v, &u);
    }
    case XGO_VALID_ACTION: return v <= XGO_ACTION_LAST || v == XGO_ACTION_RESET;
    case XGO_VALID_ASCII: return v >= 0x20 && v <= 0x7E;
    }
    XGO_ASSERT(!"a valid set of the table"); /* the table uses only the sets above */
    return 0;
}

static void mark_written(xgo_regs_t *r, uint8_t addr)
{
    const unsigned s = slot(addr);
    r->written[s >> 3] = (uint8_t)(r->written[s >> 3] | (1u << (s & 7u)));
    r->any_written = 1;
}

int xgo_regs_was_written(const xgo_regs_t *r, uint8_t addr)
{
    const unsigned s = slot(addr);
    XGO_ASSERT(addr < XGO_REGS_STORED);
    return (r->written[s >> 3] >> (s & 7u)) & 1u;
}

int xgo_regs_take_written(xgo_regs_t *r, uint8_t addr)
{
    const unsigned s = slot(addr);
    const uint8_t bit = (uint8_t)(1u << (s & 7u));
    const int was = (r->written[s >> 3] & bit) != 0;
    XGO_ASSERT(addr < XGO_REGS_STORED);
    r->written[s >> 3] = (uint8_t)(r->written[s >> 3] & ~bit);
    return was;
}

/* Mask of the bits of written[byte] that lie in slots [first, last]. */
static uint8_t range_mask(unsigned byte, unsigned first, unsigned last)
{
    const unsigned lo = byte == (first >> 3u) ? (first & 7u) : 0u;
    const unsigned hi = byte == (last >> 3u) ? (last & 7u) : 7u;
    return (uint8_t)((0xFFu << lo) & (0xFFu >> (7u - hi)));
}

/* A byte of flags at a time: the motion core asks for whole register
 * groups every tick (about 50 single flags otherwise). */
int xgo_regs_take_written_range(xgo_regs_t *r, uint8_t first_addr, uint8_t last_addr)
{
    const unsigned first = slot(first_addr), last = slot(last_addr);
    unsigned byte;
    int any = 0;
    for (byte = first >> 3u; byte <= (unsigned)(last >> 3u); byte++) {
        const uint8_t mask = range_mask(byte, first, last);
        any |= (r->written[byte] & mask) != 0;
        r->written[byte] = (uint8_t)(r->written[byte] & ~mask);
    }
    return any;
}

int xgo_regs_was_written_range(const xgo_regs_t *r, uint8_t first_addr, uint8_t last_addr)
{
    const unsigned first = slot(first_addr), last = slot(last_addr);
    unsigned byte;
    for (byte = first >> 3u; byte <= (unsigned)(last >> 3u); byte++) {
        if (r->written[byte] & range_mask(byte, first, last)) {
            return 1;
        }
    }
    return 0;
}

/* The firmware string (up to 10 ASCII characters, NUL padded) into the
 * flat image of its window, every byte but 0x09 (gait type): that one is
 * kept apart for the view at 0x07. */
static void store_firmware(xgo_regs_t *r, const char *firmware)
{
    unsigned i, end = 0;
    for (i = 0; i < XGO_FIRMWARE_LEN; i++) {
        const char c = firmware != NULL && i == end && firmware[i] != '\0' ? firmware[i] : '\0';
        end += c != '\0';
        if (XGO_REG_FIRMWARE + i == XGO_REG_GAIT_TYPE) {
            r->firmware_at_gait = c;
        } else {
            r->mem[XGO_REG_FIRMWARE + i] = (uint8_t)c;
        }
    }
}

/* The joint registers read where the joints are (the board forms those
 * bytes on read: board.c, read_joints; the image keeps its initial ones);
 * what a host writes there is a servo-mode command, kept apart in
 * servo_cmd so that no read ever returns it (docs/registers.md). */
static int is_servo_reg(unsigned addr)
{
    return addr >= XGO_REG_SERVO11 && addr <= XGO_REG_SERVO43;
}

static void load_initial(xgo_regs_t *r, int power_up)
{
    size_t i;
    memset(r->servo_cmd, xgo_reg_find(XGO_REG_SERVO11)->initial, sizeof r->servo_cmd);
    for (i = 0; i < REG_TABLE_SIZE; i++) {
        const xgo_reg_desc_t *d = &k_regs[i];
        if ((d->flags & XGO_REGF_COMPUTED) != 0 || d->access == XGO_ACCESS_R ||
            !for_model(d, r->arm)) {
            continue;
        }
        if (!power_up && ((d->flags & XGO_REGF_NONVOLATILE) != 0 || is_servo_reg(d->addr))) {
            continue; /* a reset keeps the name (the joints' image bytes are never read: board.c forms them) */
        }
        memset(&r->mem[slot(d->addr)], d->initial, d->width);
    }
#if XGO_WITH_MINI2
    r->servo_speed = desc_at(r, XGO_REG_SERVO_SPEED)->initial;
#endif
}

void xgo_regs_init(xgo_regs_t *r, const char *firmware, uint8_t version)
{
    size_t i;
    static const char k_default_name[] = "XGOMINI";

    memset(r, 0, sizeof *r);
    r->arm = XGO_WITH_MINI2 && version == XGO_VERSION_MINI2; /* else no arm rows (the gap) */
    load_initial(r, 1);
    for (i = 0; i < XGO_REGS_STORED; i++) {
        const xgo_reg_desc_t *d = desc_at(r, (unsigned)i);
        if (d != NULL && d->access == XGO_ACCESS_R && (d->flags & XGO_REGF_COMPUTED) == 0) {
            r->mem[slot((unsigned)i)] = d->initial;
        }
    }
    memcpy(&r->mem[XGO_REG_BT_NAME], k_default_name, sizeof k_default_name - 1);
    r->mem[XGO_REG_VERSION] = version;
    store_firmware(r, firmware);
    /* the bytes of a level attitude (xgo_regs_set_attitude writes only what changed) */
    r->mem[slot(XGO_REG_IMU_ROLL)] = r->mem[slot(XGO_REG_IMU_PITCH)] = r->mem[slot(XGO_REG_IMU_YAW)] =
        xgo_angle_to_byte(0);
}

void xgo_regs_restore_initial(xgo_regs_t *r)
{
    load_initial(r, 0);
    memset(r->written, 0, sizeof r->written);
}

uint8_t xgo_regs_get(const xgo_regs_t *r, uint8_t addr)
{
    XGO_ASSERT(addr < XGO_REGS_STORED);
    return r->mem[slot(addr)];
}

void xgo_regs_set(xgo_regs_t *r, uint8_t addr, uint8_t value)
{
    XGO_ASSERT(addr < XGO_REGS_STORED);
    r->mem[slot(addr)] = value;
}

const xgo_reg_desc_t *xgo_regs_find(const xgo_regs_t *r, uint8_t addr)
{
    return desc_at(r, addr);
}

/* Without the Mini2 no model publishes a claw at 0x5C: the image holds
 * the last value written there (or the initial one), so no copy is kept. */
uint8_t xgo_regs_servo_speed(const xgo_regs_t *r)
{
#if XGO_WITH_MINI2
    return r->servo_speed;
#else
    return r->mem[slot(XGO_REG_SERVO_SPEED)];
#endif
}

/* The turn command at 0x3F is two bytes wide but the foot register 0x40
 * follows it: inside a write frame, the byte after 0x3F belongs to the
 * command (docs/registers.md). */
static int turn_to_at(uint8_t addr, size_t i)
{
    return (unsigned)addr + (unsigned)i == XGO_REG_TURN_TO;
}

/* Pass 1 of a write: everything checked, nothing changed. */
static xgo_drop_reason_t validate_write(xgo_regs_t *r, uint8_t addr, const uint8_t *data, size_t n,
                                        int *unmapped)
{
    size_t i;
    for (i = 0; i < n; i++) {
        const unsigned a = (unsigned)addr + (unsigned)i;
        const xgo_reg_desc_t *d = desc_at(r, a);
        if (d == NULL) {
            *unmapped = 1;
            continue;
        }
        if ((d->access & XGO_ACCESS_W) == 0) {
            r->stats.rejected_read_only++;
            return XGO_DROP_READ_ONLY;
        }
        if (turn_to_at(addr, i)) {
            if (i + XGO_TURN_TO_LEN > n) { /* half a heading */
                r->stats.rejected_value++;
                return XGO_DROP_BAD_VALUE;
            }
            i += XGO_TURN_TO_LEN - 1u; /* any int16 is a heading */
            continue;
        }
        /* A multi-byte register is written from its first byte (a name
         * written from the middle has no meaning). */
        if ((d->width > 1 && a != d->addr && i == 0) || !xgo_reg_value_valid(d, data[i])) {
            r->stats.rejected_value++;
            return XGO_DROP_BAD_VALUE;
        }
    }
    return XGO_DROP_NONE;
}

/* Pass 2: apply a validated write. */
static void apply_write(xgo_regs_t *r, uint8_t addr, const uint8_t *data, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        const unsigned a = (unsigned)addr + (unsigned)i;
        const xgo_reg_desc_t *d = desc_at(r, a);
        if (d == NULL) {
            continue;
        }
        if (turn_to_at(addr, i)) {
            r->turn_to[0] = data[i];
            r->turn_to[1] = data[i + 1u];
            r->mem[slot(a)] = 0; /* turning, until the board says it is there */
            mark_written(r, (uint8_t)a);
            i += XGO_TURN_TO_LEN - 1u;
            continue;
        }
        if (is_servo_reg(a)) {
            r->servo_cmd[a - XGO_REG_SERVO11] = data[i];
            mark_written(r, (uint8_t)a);
            continue;
        }
        if (d->width > 1 && a == d->addr) {
            /* A shorter write sets the whole value: the rest is cleared. */
            memset(&r->mem[slot(a)], 0, d->width);
        }
        r->mem[slot(a)] = data[i];
        mark_written(r, (uint8_t)a);
#if XGO_WITH_MINI2
        if (a == XGO_REG_SERVO_SPEED) {
            r->servo_speed = data[i];
        }
#endif
    }
}

xgo_drop_reason_t xgo_regs_write(xgo_regs_t *r, uint8_t addr, const uint8_t *data, size_t n)
{
    int unmapped = 0;
    xgo_drop_reason_t why;

    if (n == 0 || n > XGO_FRAME_MAX_DATA || (size_t)addr + n > XGO_REG_COUNT) {
        return XGO_DROP_BAD_RANGE;
    }
    why = validate_write(r, addr, data, n, &unmapped);
    if (why != XGO_DROP_NONE) {
        return why;
    }
    apply_write(r, addr, data, n);
    if (unmapped) {
        r->stats.ignored_unmapped++;
    }
    r->stats.writes_ok++;
    return XGO_DROP_NONE;
}

uint8_t xgo_regs_servo_command(const xgo_regs_t *r, unsigned servo)
{
    return r->servo_cmd[servo % sizeof r->servo_cmd];
}

int16_t xgo_regs_turn_to_deg(const xgo_regs_t *r)
{
    return (int16_t)(uint16_t)(((unsigned)r->turn_to[0] << 8) | r->turn_to[1]);
}

static void put_u32_le(uint8_t *out, uint32_t v)
{
    out[0] = (uint8_t)v;
    out[1] = (uint8_t)(v >> 8);
    out[2] = (uint8_t)(v >> 16);
    out[3] = (uint8_t)(v >> 24);
}

static void put_u16_le(uint8_t *out, int16_t v)
{
    out[0] = (uint8_t)(uint16_t)v;
    out[1] = (uint8_t)((uint16_t)v >> 8);
}

/* The 0x65 view: acceleration x, y, z and angular rate x, y, z as int16
 * little-endian, then roll, pitch, yaw as float32 little-endian degrees. */
static void imu_block(const xgo_regs_imu_t *imu, uint8_t out[XGO_IMU_BLOCK_LEN])
{
    unsigned i;
    for (i = 0; i < 3; i++) {
#if XGO_WITH_INERTIAL
        put_u16_le(&out[2u * i], imu->accel[i]);
        put_u16_le(&out[6u + 2u * i], imu->gyro[i]);
#else
        put_u16_le(&out[2u * i], 0); /* no model: a port would put a real IMU's here */
        put_u16_le(&out[6u + 2u * i], 0);
#endif
        put_u32_le(&out[12u + 4u * i], xgo_mdeg_to_float32_bits(imu->attitude_mdeg[i]));
    }
}

/* Views chosen by the first address of a read; they replace the start of
 * the flat image's bytes (the rest of a longer read stays flat): the
 * firmware string (0x07), an angle's float32 (a read of four bytes or more
 * at 0x62..0x64: it covers what the window holds of 0x62..0x64), the block
 * (0x65), an angle's int16 (0x66..0x68). Under none of the IMU's, the
 * bytes at 0x62..0x64 in the window are formed from imu's angles (the
 * image's are a level attitude's). */
static void apply_read_views(const xgo_regs_t *r, const xgo_regs_imu_t *imu, uint8_t addr, size_t n,
                             uint8_t *out)
{
    uint8_t view[XGO_IMU_BLOCK_LEN];
    size_t len = 0, i;
    if (addr == XGO_REG_FIRMWARE) {
        memcpy(view, &r->mem[XGO_REG_FIRMWARE], XGO_FIRMWARE_LEN);
        view[XGO_REG_GAIT_TYPE - XGO_REG_FIRMWARE] = (uint8_t)r->firmware_at_gait;
        len = XGO_FIRMWARE_LEN;
    } else if (addr >= XGO_REG_IMU_ROLL && addr <= XGO_REG_IMU_YAW && n >= 4) {
        put_u32_le(view, xgo_mdeg_to_float32_bits(imu->attitude_mdeg[addr - XGO_REG_IMU_ROLL]));
        len = 4;
    } else if (addr == XGO_REG_IMU_BLOCK) {
        imu_block(imu, view);
        len = XGO_IMU_BLOCK_LEN;
    } else if (addr >= XGO_REG_IMU_ROLL16 && addr <= XGO_REG_IMU_YAW16) {
        const uint16_t v = (uint16_t)xgo_mdeg_to_centideg(imu->attitude_mdeg[addr - XGO_REG_IMU_ROLL16]);
        view[0] = (uint8_t)(v >> 8); /* big-endian, as read_imu_int16 decodes */
        view[1] = (uint8_t)v;
        len = 2;
    } else if (addr <= XGO_REG_IMU_YAW) {
        /* no view over them: the bytes at 0x62..0x64 in the window */
        for (i = 0; i < 3; i++) {
            const size_t at = (size_t)(XGO_REG_IMU_ROLL + i) - addr; /* wraps above n before addr */
            if (at < n) {
                out[at] = xgo_angle_to_byte(imu->attitude_mdeg[i]);
            }
        }
    }
    for (i = 0; i < n && i < len; i++) {
        out[i] = view[i];
    }
}

/* The flat image's n bytes at addr: what is stored in the runs between the
 * gaps, 0 in the gaps and above XGO_REGS_STORED (nothing was ever stored
 * there; the board forms the diagnostic block). */
static void image_read(const xgo_regs_t *r, unsigned addr, size_t n, uint8_t *out)
{
    const unsigned end = addr + (unsigned)n;
    unsigned i;
    memset(out, 0, n);
    for (i = 0; i < sizeof k_stored / sizeof k_stored[0]; i++) {
        const unsigned lo = addr > k_stored[i][0] ? addr : k_stored[i][0];
        const unsigned hi = end < k_stored[i][1] ? end : k_stored[i][1];
        if (lo < hi) {
            memcpy(&out[lo - addr], &r->mem[slot(lo)], hi - lo);
        }
    }
}

void xgo_regs_read_imu(const xgo_regs_t *r, const xgo_regs_imu_t *imu, uint8_t addr, size_t n,
                       uint8_t *out)
{
    image_read(r, addr, n, out);
    apply_read_views(r, imu, addr, n, out);
}

xgo_drop_reason_t xgo_regs_read(const xgo_regs_t *r, uint8_t addr, size_t n, uint8_t *out)
{
    xgo_regs_imu_t imu; /* the file's copy */
    if (n == 0 || n > XGO_FRAME_MAX_DATA || (size_t)addr + n > XGO_REG_COUNT) {
        return XGO_DROP_BAD_RANGE;
    }
    memcpy(imu.attitude_mdeg, r->attitude_mdeg, sizeof imu.attitude_mdeg);
#if XGO_WITH_INERTIAL
    memcpy(imu.accel, r->accel, sizeof imu.accel);
    memcpy(imu.gyro, r->gyro, sizeof imu.gyro);
#endif
    xgo_regs_read_imu(r, &imu, addr, n, out);
    return XGO_DROP_NONE;
}

/* One angle of the file's copy, and its byte at 0x62..0x64 (what
 * xgo_regs_get gives; a read forms the byte from the angle): the byte
 * encoded again only when the angle changed (it is a function of it, and
 * nothing else writes there: the registers are computed, read-only;
 * xgo_regs_init writes all three). The board no longer calls this every
 * tick: its reads form the IMU's registers from the motion core. */
XGO_INLINE_FAST void set_angle(xgo_regs_t *r, unsigned i, int32_t mdeg)
{
    if (r->attitude_mdeg[i] != mdeg) {
        r->attitude_mdeg[i] = mdeg;
        r->mem[slot(XGO_REG_IMU_ROLL + i)] = xgo_angle_to_byte(mdeg);
    }
}

void xgo_regs_set_attitude(xgo_regs_t *r, int32_t roll_mdeg, int32_t pitch_mdeg, int32_t yaw_mdeg)
{
    set_angle(r, 0, roll_mdeg);
    set_angle(r, 1, pitch_mdeg);
    set_angle(r, 2, yaw_mdeg);
}

/* Every counter has its slot in 0xC4..0xFF; a 16th needs a new block. */
typedef char xgo_regs_diag_fits_[(XGO_DIAG_COUNT <= XGO_DIAG_SLOTS &&
                                  XGO_REG_DIAG + 4u * XGO_DIAG_SLOTS == 0x100u) ? 1 : -1];
