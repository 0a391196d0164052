/*
 * xgo/regs.h - the register map of the board (the spec's MemTable): what a
 * host can read and write, and what the values mean. The one source of truth
 * for every tool and page: addresses, widths, access, initial values and
 * valid sets (XGO_REG_LIST), the diagnostic counters (XGO_DIAG_LIST) and the
 * value sets of the mode, action and unload registers. The register file
 * that holds the values is the core's (private, src/core/regfile.h).
 *
 * One descriptor per documented register (XGO_REG_LIST below) gives its
 * address, width, host access, initial value and valid set. The file is a flat
 * 256-byte image plus computed views that a flat array cannot give, each
 * chosen by the address a read starts at (docs/registers.md):
 *   - 0x07 firmware string: a read that starts at 0x07 returns the 10-byte
 *     string, although 0x09 on its own is the gait type register;
 *   - 0x62..0x64 roll/pitch/yaw: a read of 4+ bytes starting at one of them
 *     returns that angle as float32 little-endian degrees (built with integer
 *     arithmetic), a shorter read the one-byte encoding;
 *   - 0x65 IMU block: 24 bytes, acceleration and angular rate (int16 LE) and
 *     the three angles (float32 LE degrees), xgo_regs_set_inertial();
 *     a board forms 0x62..0x68 from its IMU's outputs when they are read
 *     (board.c), the register file alone from what was set;
 *   - 0x66..0x68 roll/pitch/yaw as int16 big-endian, 0.01 degree;
 *   - 0xC4..0xFF diagnostic counters, uint32 little-endian.
 * Two write views: 0x3F (turn to heading) takes two bytes, an int16
 * big-endian heading in degrees, as one command; the second byte does not go
 * to 0x40. A read of 0x3F gives 0 while turning, 1 when done. Writes to the
 * joint registers 0x50..0x5B are servo-mode commands kept apart: a read
 * there always gives the joints as they are, formed by the board from the
 * servos' angles when it is read (the register file's bytes there are not
 * read).
 *
 * A write is validated whole before anything changes (docs/decisions.md).
 * Checks: lookups take any address or value (unmapped: NULL / "-", outside a
 * set: 0); none asserts.
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_REGS_H
#define XGO_REGS_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

#define XGO_REG_COUNT 256u

/* Host access. R: writes rejected. W and RW: writable; W registers read back
 * their stored value (the real board's MemTable is a flat array). */
#define XGO_ACCESS_R 1u
#define XGO_ACCESS_W 2u
#define XGO_ACCESS_RW 3u

/* Flags */
#define XGO_REGF_AUTO_CLEAR 0x01u  /* the board acts on a write, then clears it to 0 */
#define XGO_REGF_COMPUTED 0x02u    /* value produced by the board on read */
#define XGO_REGF_NONVOLATILE 0x04u /* survives action 255 (reset) */
#define XGO_REGF_ARM 0x08u         /* only on a model with the arm (Mini2) */
#define XGO_REGF_NO_ARM 0x10u      /* only on a model without it (Mini, Lite) */
#define XGO_REGF_AUTO_CLEAR_NO_ARM (XGO_REGF_AUTO_CLEAR | XGO_REGF_NO_ARM)

/* Register 0x02: the model. The seed's MemTable gives 0x02 to the PRO, so
 * the Mini2 takes the next value. */
#define XGO_VERSION_MINI 0x00u
#define XGO_VERSION_LITE 0x01u
#define XGO_VERSION_MINI2 0x03u

/* The profile (XGO_PROFILE_*, xgo/profile.h) of a 0x02 value; unknown values
 * give the Mini's. */
unsigned xgo_version_profile(uint8_t version);

/* Valid sets */
typedef enum xgo_valid_e {
    XGO_VALID_ANY = 0,
    XGO_VALID_RANGE,  /* lo..hi inclusive */
    XGO_VALID_UNLOAD, /* xgo_unload_decode() accepts it */
    XGO_VALID_ACTION, /* 0..XGO_ACTION_LAST, XGO_ACTION_RESET (below) */
    XGO_VALID_ASCII   /* printable ASCII 0x20..0x7E */
} xgo_valid_t;

/*   X(ID, address, width, access, flags, initial, valid, lo, hi, "name")
 * Table order matters only where widths overlap: gait_type (0x09) comes before
 * the 10-byte firmware window (0x07..0x10) so 0x09 on its own is gait_type. */
#define XGO_REG_LIST(X)                                                                 \
    X(MODE, 0x00, 1, R, 0, 0x00, ANY, 0, 0, "mode")                                     \
    X(BATTERY, 0x01, 1, R, 0, 100, ANY, 0, 0, "battery")                                \
    X(VERSION, 0x02, 1, R, 0, 0x00, ANY, 0, 0, "version")                               \
    X(PERFORM, 0x03, 1, W, 0, 0x00, RANGE, 0, 1, "perform")                             \
    X(CALIBRATION, 0x04, 1, W, 0, 0x00, RANGE, 0, 1, "calibration")                     \
    X(UPGRADE, 0x05, 1, W, 0, 0x00, RANGE, 0, 1, "upgrade")                             \
    X(SET_ORIGIN, 0x06, 1, W, AUTO_CLEAR, 0x00, RANGE, 0, 1, "set_origin")              \
    X(GAIT_TYPE, 0x09, 1, RW, 0, 0x00, RANGE, 0, 3, "gait_type")                        \
    X(FIRMWARE, 0x07, 10, R, COMPUTED, 0x00, ANY, 0, 0, "firmware")                     \
    X(BT_NAME, 0x13, 10, W, NONVOLATILE, 0x00, ASCII, 0, 0, "bt_name")                  \
    X(UNLOAD, 0x20, 1, RW, 0, 0x00, UNLOAD, 0, 0, "unload")                             \
    X(SET_ZERO, 0x21, 1, W, AUTO_CLEAR, 0x00, RANGE, 0, 1, "set_zero")                  \
    X(VX, 0x30, 1, RW, 0, 0x80, ANY, 0, 0, "vx")                                        \
    X(VY, 0x31, 1, RW, 0, 0x80, ANY, 0, 0, "vy")                                        \
    X(VYAW, 0x32, 1, RW, 0, 0x80, ANY, 0, 0, "vyaw")                                    \
    X(BODY_X, 0x33, 1, RW, 0, 0x80, ANY, 0, 0, "body_x")                                \
    X(BODY_Y, 0x34, 1, RW, 0, 0x80, ANY, 0, 0, "body_y")                                \
    X(BODY_Z, 0x35, 1, RW, 0, 0x80, ANY, 0, 0, "body_z")                                \
    X(BODY_ROLL, 0x36, 1, RW, 0, 0x80, ANY, 0, 0, "body_roll")                          \
    X(BODY_PITCH, 0x37, 1, RW, 0, 0x80, ANY, 0, 0, "body_pitch")                        \
    X(BODY_YAW, 0x38, 1, RW, 0, 0x80, ANY, 0, 0, "body_yaw")                            \
    X(PERIOD_ROLL, 0x39, 1, RW, 0, 0x00, ANY, 0, 0, "period_roll")                      \
    X(PERIOD_PITCH, 0x3A, 1, RW, 0, 0x00, ANY, 0, 0, "period_pitch")                    \
    X(PERIOD_YAW, 0x3B, 1, RW, 0, 0x00, ANY, 0, 0, "period_yaw")                        \
    X(MARK_TIME, 0x3C, 1, RW, 0, 0x00, ANY, 0, 0, "mark_time")                          \
    X(MOVE_MODE, 0x3D, 1, RW, 0, 0x00, RANGE, 0, 2, "move_mode")                        \
    X(ACTION, 0x3E, 1, W, 0, 0x00, ACTION, 0, 0, "action")                              \
    X(TURN_TO, 0x3F, 1, RW, 0, 0x01, ANY, 0, 0, "turn_to")                              \
    X(LEG1_X, 0x40, 1, RW, 0, 0x80, ANY, 0, 0, "leg1_x")                                \
    X(LEG1_Y, 0x41, 1, RW, 0, 0x80, ANY, 0, 0, "leg1_y")                                \
    X(LEG1_Z, 0x42, 1, RW, 0, 0x80, ANY, 0, 0, "leg1_z")                                \
    X(LEG2_X, 0x43, 1, RW, 0, 0x80, ANY, 0, 0, "leg2_x")                                \
    X(LEG2_Y, 0x44, 1, RW, 0, 0x80, ANY, 0, 0, "leg2_y")                                \
    X(LEG2_Z, 0x45, 1, RW, 0, 0x80, ANY, 0, 0, "leg2_z")                                \
    X(LEG3_X, 0x46, 1, RW, 0, 0x80, ANY, 0, 0, "leg3_x")                                \
    X(LEG3_Y, 0x47, 1, RW, 0, 0x80, ANY, 0, 0, "leg3_y")                                \
    X(LEG3_Z, 0x48, 1, RW, 0, 0x80, ANY, 0, 0, "leg3_z")                                \
    X(LEG4_X, 0x49, 1, RW, 0, 0x80, ANY, 0, 0, "leg4_x")                                \
    X(LEG4_Y, 0x4A, 1, RW, 0, 0x80, ANY, 0, 0, "leg4_y")                                \
    X(LEG4_Z, 0x4B, 1, RW, 0, 0x80, ANY, 0, 0, "leg4_z")                                \
    X(SERVO11, 0x50, 1, RW, 0, 0x80, ANY, 0, 0, "servo11")                              \
    X(SERVO12, 0x51, 1, RW, 0, 0x80, ANY, 0, 0, "servo12")                              \
    X(SERVO13, 0x52, 1, RW, 0, 0x80, ANY, 0, 0, "servo13")                              \
    X(SERVO21, 0x53, 1, RW, 0, 0x80, ANY, 0, 0, "servo21")                              \
    X(SERVO22, 0x54, 1, RW, 0, 0x80, ANY, 0, 0, "servo22")                              \
    X(SERVO23, 0x55, 1, RW, 0, 0x80, ANY, 0, 0, "servo23")                              \
    X(SERVO31, 0x56, 1, RW, 0, 0x80, ANY, 0, 0, "servo31")                              \
    X(SERVO32, 0x57, 1, RW, 0, 0x80, ANY, 0, 0, "servo32")                              \
    X(SERVO33, 0x58, 1, RW, 0, 0x80, ANY, 0, 0, "servo33")                              \
    X(SERVO41, 0x59, 1, RW, 0, 0x80, ANY, 0, 0, "servo41")                              \
    X(SERVO42, 0x5A, 1, RW, 0, 0x80, ANY, 0, 0, "servo42")                              \
    X(SERVO43, 0x5B, 1, RW, 0, 0x80, ANY, 0, 0, "servo43")                              \
    X(SERVO_SPEED, 0x5C, 1, RW, 0, 0x80, ANY, 0, 0, "servo_speed")                      \
    X(STAND, 0x5D, 1, W, AUTO_CLEAR_NO_ARM, 0x00, RANGE, 0, 1, "stand")                 \
    X(ARM_ELBOW, 0x5D, 1, RW, ARM, 0x00, ANY, 0, 0, "servo52")                          \
    X(ARM_SHOULDER, 0x5E, 1, RW, ARM, 0x00, ANY, 0, 0, "servo53")                       \
    X(IMU_MODE, 0x61, 1, RW, 0, 0x00, RANGE, 0, 1, "imu_mode")                          \
    X(IMU_ROLL, 0x62, 1, R, COMPUTED, 0x80, ANY, 0, 0, "imu_roll")                      \
    X(IMU_PITCH, 0x63, 1, R, COMPUTED, 0x80, ANY, 0, 0, "imu_pitch")                    \
    X(IMU_YAW, 0x64, 1, R, COMPUTED, 0x80, ANY, 0, 0, "imu_yaw")                        \
    X(IMU_BLOCK, 0x65, 1, R, COMPUTED, 0x00, ANY, 0, 0, "imu_block")                    \
    X(IMU_ROLL16, 0x66, 1, R, COMPUTED, 0x00, ANY, 0, 0, "imu_roll16")                  \
    X(IMU_PITCH16, 0x67, 1, R, COMPUTED, 0x00, ANY, 0, 0, "imu_pitch16")                \
    X(IMU_YAW16, 0x68, 1, R, COMPUTED, 0x00, ANY, 0, 0, "imu_yaw16")                    \
    X(LED, 0x69, 3, RW, 0, 0x00, ANY, 0, 0, "led")                                      \
    X(CLAW, 0x71, 1, RW, ARM, 0x80, ANY, 0, 0, "claw")                                  \
    X(ARM_MODE, 0x72, 1, RW, ARM, 0x00, RANGE, 0, 1, "arm_mode")                        \
    X(ARM_X, 0x73, 1, RW, ARM, 0x00, ANY, 0, 0, "arm_x")                                \
    X(ARM_Z, 0x74, 1, RW, ARM, 0x00, ANY, 0, 0, "arm_z")                                \
    X(ARM_SPEED, 0x75, 1, RW, ARM, 0x80, ANY, 0, 0, "arm_speed")                        \
    X(ARM_THETA, 0x76, 1, RW, ARM, 0x00, ANY, 0, 0, "arm_theta")                        \
    X(ARM_R, 0x77, 1, RW, ARM, 0x00, ANY, 0, 0, "arm_r")                                \
    X(PERIOD_X, 0x80, 1, RW, 0, 0x00, ANY, 0, 0, "period_x")                            \
    X(PERIOD_Y, 0x81, 1, RW, 0, 0x00, ANY, 0, 0, "period_y")                            \
    X(PERIOD_Z, 0x82, 1, RW, 0, 0x00, ANY, 0, 0, "period_z")                            \
    X(ANALOG_OUT, 0x90, 1, RW, 0, 0x00, ANY, 0, 0, "analog_out")                        \
    X(DIGITAL_OUT, 0x91, 1, RW, 0, 0x00, ANY, 0, 0, "digital_out")                      \
    X(ANALOG_IN, 0x92, 1, RW, 0, 0x00, ANY, 0, 0, "analog_in")                          \
    X(DIGITAL_IN, 0x93, 1, RW, 0, 0x00, ANY, 0, 0, "digital_in")                        \
    X(DIAG, 0xC4, 60, R, COMPUTED, 0x00, ANY, 0, 0, "diag")

/* Register addresses: XGO_REG_VX == 0x30, ... */
enum xgo_reg_addr_e {
#define XGO_REG_ENUM_(id, addr, w, acc, fl, init, v, lo, hi, name) XGO_REG_##id = addr,
    XGO_REG_LIST(XGO_REG_ENUM_)
#undef XGO_REG_ENUM_
    XGO_REG_ADDR_END_ = 0x100
};

#define XGO_FIRMWARE_LEN 10u
#define XGO_BT_NAME_LEN 10u
#define XGO_IMU_BLOCK_LEN 24u  /* the 0x65 view */
#define XGO_TURN_TO_LEN 2u     /* the 0x3F write view */

/* Diagnostic block at 0xC4..0xFF: room for XGO_DIAG_SLOTS uint32 little-endian
 * counters, XGO_DIAG_COUNT of them used, in this order (docs/registers.md);
 * unused slots read 0. Read-only; counters wrap at 2^32. One row
 * per counter, the only list of them (enum, names and the board's mapping are
 * generated from it; new counters are appended, the order is the wire layout):
 *   X(ID, name, where the board keeps it: a member of xgo_board_t) */
#define XGO_DIAG_LIST(X)                                                               \
    X(FRAMES_OK, frames_ok, parser.stats.frames_ok)                                    \
    X(BAD_CHECKSUM, bad_checksum, parser.stats.bad_checksum)                           \
    X(BAD_TAIL, bad_tail, parser.stats.bad_tail)                                       \
    X(BAD_LENGTH, bad_length, parser.stats.bad_length)                                 \
    X(BAD_TYPE, bad_type, parser.stats.bad_type)                                       \
    X(BAD_RANGE, bad_range, parser.stats.bad_range)                                    \
    X(BYTES_DISCARDED, bytes_discarded, parser.stats.bytes_discarded)                  \
    X(TIMEOUTS, timeouts, parser.stats.timeouts)                                       \
    X(REJECTED_READ_ONLY, rejected_read_only, regs.stats.rejected_read_only)           \
    X(REJECTED_VALUE, rejected_value, regs.stats.rejected_value)                       \
    X(IGNORED_UNMAPPED, ignored_unmapped, regs.stats.ignored_unmapped)                 \
    X(TX_OVERFLOW, tx_overflow, tx_overflows)                                          \
    X(HANGUP_DISCARDS, hangup_discards, parser.stats.hangup_discards)                  \
    X(FRAMING_ERRORS, framing_errors, framing_errors)                                  \
    X(REACH_CLAMPED, reach_clamped, motion.reach_clamped_ticks)

/* XGO_DIAG_FRAMES_OK == 0, ... */
typedef enum xgo_diag_e {
#define XGO_DIAG_ENUM_(id, name, member) XGO_DIAG_##id,
    XGO_DIAG_LIST(XGO_DIAG_ENUM_)
#undef XGO_DIAG_ENUM_
    XGO_DIAG_COUNT
} xgo_diag_t;

/* Slots in the block (0xC4 + 4 * 15 = 0x100): at most this many counters. */
#define XGO_DIAG_SLOTS 15u

typedef struct xgo_reg_desc_s {
    uint8_t addr;
    uint8_t width;
    uint8_t access;
    uint8_t flags;
    uint8_t initial;
    uint8_t valid; /* xgo_valid_t */
    uint8_t lo, hi;
#if XGO_WITH_NAMES /* xgo/config.h */
    const char *name;
#endif
} xgo_reg_desc_t;

/* The descriptor table and lookups. */
size_t xgo_reg_table_size(void);
const xgo_reg_desc_t *xgo_reg_table_entry(size_t i);
const xgo_reg_desc_t *xgo_reg_find(uint8_t addr); /* the Mini's; NULL when it lacks addr */
/* The same for a model with (arm = 1: the Mini2) or without the arm. */
const xgo_reg_desc_t *xgo_reg_find_model(uint8_t addr, int arm);
/* 1 if the table row d exists on a model with (arm = 1) or without the arm:
 * rows flagged XGO_REGF_ARM / XGO_REGF_NO_ARM are on one of them only. */
int xgo_reg_for_model(const xgo_reg_desc_t *d, int arm);
/* Name of the register at addr ("vx", "bt_name[3]" style is the caller's job);
 * "-" when unmapped. */
const char *xgo_reg_name(uint8_t addr);
int xgo_reg_value_valid(const xgo_reg_desc_t *d, uint8_t value);

/* ------------------------------------------------------------ values
 * What some registers' values mean: the one definition of each set, used by
 * the board, the register file's validation and the host's tools. */

/* Register 0x00 (mode, read-only). */
typedef enum xgo_mode_e {
    XGO_MODE_WHOLE_UNIT = 0x00, /* gait, body pose, periodic motions */
    XGO_MODE_LEG = 0x01,        /* feet follow 0x40..0x4B */
    XGO_MODE_SERVO = 0x02,      /* joints follow 0x50..0x5B at the speed of 0x5C */
    XGO_MODE_DEBUG = 0x03,      /* after a write to 0x20: joints hold, some may be limp */
    XGO_MODE_ACTION = 0x04,     /* a preset action (0x3E) is running */
    XGO_MODE_CALIBRATION = 0x05 /* 0x04 = 1: all joints limp, 0x21 records zeros */
} xgo_mode_t;

/* Register 0x3E (action): 0 stops; 1..19 are the spec's list; 20..24 are
 * our own motions, named after the XGO family's action lists (the Mini's
 * protocol document has no names for them; docs/actions.md); 255 is the
 * reset (1 s in the stance). Valid values: 0..XGO_ACTION_LAST and
 * XGO_ACTION_RESET. */
#define XGO_ACTION_NONE 0u
#define XGO_ACTION_LIE_DOWN 1u
#define XGO_ACTION_STAND_UP 2u
#define XGO_ACTION_CREEP 3u
#define XGO_ACTION_CIRCLE 4u
#define XGO_ACTION_STEP 5u
#define XGO_ACTION_SQUAT 6u
#define XGO_ACTION_ROLL 7u
#define XGO_ACTION_PITCH 8u
#define XGO_ACTION_YAW 9u
#define XGO_ACTION_THREE_AXIS 10u
#define XGO_ACTION_PEE 11u
#define XGO_ACTION_SIT 12u
#define XGO_ACTION_BECKON 13u
#define XGO_ACTION_STRETCH 14u
#define XGO_ACTION_WAVE 15u
#define XGO_ACTION_SWAY 16u
#define XGO_ACTION_BEG 17u
#define XGO_ACTION_SEARCH 18u
#define XGO_ACTION_SHAKE_HANDS 19u
#define XGO_ACTION_CHICKEN_HEAD 20u
#define XGO_ACTION_PUSH_UP 21u
#define XGO_ACTION_LOOK_AROUND 22u
#define XGO_ACTION_DANCE 23u
#define XGO_ACTION_NAUGHTY 24u
#define XGO_ACTION_LAST 24u /* highest preset id */
#define XGO_ACTION_RESET 255u

/* English name of an action ("lie down", ..., "reset"); NULL for 0 and for
 * an id without a table. */
const char *xgo_action_name(uint8_t id);

/* Length of action id in control ticks (the vendor library's wait in
 * seconds x XGO_TICK_HZ): register 0x3E reads the action that long. 0 for
 * an id without a table. */
uint32_t xgo_action_duration_ticks(uint8_t id);

/* Register 0x20 (unload): 0x00 load all, 0x01 unload all, 0x11..0x14 unload
 * leg 1..4, 0x21..0x24 load leg 1..4 - the one definition of that set. */
typedef struct xgo_unload_s {
    uint8_t load; /* 1: the joints hold (load), 0: they go limp (unload) */
    uint8_t leg;  /* leg index 0..3, or XGO_UNLOAD_ALL_LEGS */
} xgo_unload_t;
#define XGO_UNLOAD_ALL_LEGS 0xFFu

/* Returns 1 and fills *out for a value of the set; 0 (out untouched) else. */
int xgo_unload_decode(uint8_t value, xgo_unload_t *out);

#ifdef __cplusplus
}
#endif

#endif /* XGO_REGS_H */
