/*
 * regfile.h - the register file itself (private to the core; the register
 * map, its descriptors and the values' meanings are public: xgo/regs.h).
 * Implemented in regs.c with the table it is built from.
 *
 * The file is a flat 256-byte image plus the computed views xgo/regs.h lists;
 * a host write is validated whole before anything changes and every refusal
 * is counted (expected input). The board side (motion core) sets and takes
 * registers without validation.
 * Checks: host writes and reads are expected input (refused with a reason,
 * counted); the board side's own calls are trusted (no checks).
 *
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_CORE_REGFILE_H
#define XGO_CORE_REGFILE_H

#include <stddef.h>
#include <stdint.h>

#include "compiler.h"         /* XGO_ALWAYS_INLINE */
#include "xgo/board_state.h" /* xgo_regs_t */
#include "xgo/regs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* firmware: up to 10 ASCII chars; version: XGO_VERSION_* (the Mini2's also
 * selects the arm's rows of the table). */
void xgo_regs_init(xgo_regs_t *r, const char *firmware, uint8_t version);

/* Restore every writable, volatile register to its initial value (action 255). */
void xgo_regs_restore_initial(xgo_regs_t *r);

/* Host write of n bytes at addr, validated whole: returns XGO_DROP_NONE and
 * applies it, or returns the reason and changes nothing (counted). */
xgo_drop_reason_t xgo_regs_write(xgo_regs_t *r, uint8_t addr, const uint8_t *data, size_t n);

/* Host read of n bytes at addr into out (computed views applied). Returns
 * XGO_DROP_NONE, or XGO_DROP_BAD_RANGE for n == 0, n > 247 or addr + n > 256. */
xgo_drop_reason_t xgo_regs_read(const xgo_regs_t *r, uint8_t addr, size_t n, uint8_t *out);

/* The IMU's outputs a read forms its registers from: the angles (the bytes
 * at 0x62..0x64, the float32 views there, the block's floats, the int16
 * views at 0x66..0x68) and, with the model, the block's acceleration and
 * angular rate. */
typedef struct {
    int32_t attitude_mdeg[3]; /* roll, pitch, yaw */
#if XGO_WITH_INERTIAL
    int16_t accel[3];
    int16_t gyro[3];
#endif
} xgo_regs_imu_t;

/* xgo_regs_read with the IMU's registers formed from imu, not from the
 * file's copy (xgo_regs_set_attitude, xgo_regs_set_inertial): the board's
 * reads, which take them from the motion core's state as it is now, so that
 * a tick stores none of them. The caller checked the range (xgo_regs_read's
 * rule). */
void xgo_regs_read_imu(const xgo_regs_t *r, const xgo_regs_imu_t *imu, uint8_t addr, size_t n,
                       uint8_t *out);

/* Board-side access: no validation, no counting; addr below
 * XGO_REGS_STORED (the diagnostic block is the board's, formed on read). */
uint8_t xgo_regs_get(const xgo_regs_t *r, uint8_t addr);
void xgo_regs_set(xgo_regs_t *r, uint8_t addr, uint8_t value);

/* Where a stored address in no gap (board_state.h) sits in mem, as regs.c's
 * slot() finds it, but a constant expression for a constant address. */
#define XGO_REGS_SLOT(a)                                                                       \
    ((unsigned)(a) -                                                                           \
     ((unsigned)(a) >= XGO_REGS_GAP1_END ? XGO_REGS_GAP1_END - XGO_REGS_GAP1_START : 0u) -     \
     ((unsigned)(a) >= XGO_REGS_GAP2_END ? XGO_REGS_GAP2_END - XGO_REGS_GAP2_START : 0u) -     \
     ((unsigned)(a) >= XGO_REGS_GAP3_END ? XGO_REGS_GAP3_END - XGO_REGS_GAP3_START : 0u))
/* xgo_regs_set for a constant addr: the store itself, no call (the status
 * bytes the motion core publishes every tick). */
XGO_ALWAYS_INLINE void xgo_regs_put(xgo_regs_t *r, unsigned addr, uint8_t value)
{
    r->mem[XGO_REGS_SLOT(addr)] = value;
}
/* xgo_regs_get for a constant addr: the load itself. */
XGO_ALWAYS_INLINE uint8_t xgo_regs_at(const xgo_regs_t *r, unsigned addr)
{
    return r->mem[XGO_REGS_SLOT(addr)];
}

/* True (once) if the host wrote addr (< XGO_REGS_STORED: nothing above is
 * writable) since the last call for it. */
int xgo_regs_take_written(xgo_regs_t *r, uint8_t addr);
/* The same without consuming the flag. */
int xgo_regs_was_written(const xgo_regs_t *r, uint8_t addr);
/* True if the host wrote any address in [first, last] (first <= last);
 * the take_ form clears all their flags. */
int xgo_regs_take_written_range(xgo_regs_t *r, uint8_t first, uint8_t last);
int xgo_regs_was_written_range(const xgo_regs_t *r, uint8_t first, uint8_t last);
/* True (once) if the host wrote anything since the last call: a reader that
 * takes every flag it looks at may skip looking when nothing was written. */
XGO_ALWAYS_INLINE int xgo_regs_take_any_written(xgo_regs_t *r) /* inline: every tick */
{
    const int was = r->any_written;
    r->any_written = 0;
    return was;
}

/* The file's copy of the IMU's outputs, what xgo_regs_read forms the IMU's
 * registers from (a register file without a board: the tests; the board
 * reads them from the motion core instead, xgo_regs_read_imu). */
void xgo_regs_set_attitude(xgo_regs_t *r, int32_t roll_mdeg, int32_t pitch_mdeg, int32_t yaw_mdeg);
/* The IMU block's acceleration (16384 LSB = 1 g) and angular rate (16.4 LSB
 * = 1 deg/s), body axes x forward, y left, z up (docs/motion.md). */
XGO_ALWAYS_INLINE void xgo_regs_set_inertial(xgo_regs_t *r, const int16_t accel[3], const int16_t gyro[3])
{
#if XGO_WITH_INERTIAL
    r->accel[0] = accel[0];
    r->accel[1] = accel[1];
    r->accel[2] = accel[2];
    r->gyro[0] = gyro[0];
    r->gyro[1] = gyro[1];
    r->gyro[2] = gyro[2];
#else /* without the model they are 0 (xgo/config.h) */
    (void)r;
    (void)accel;
    (void)gyro;
#endif
}

/* The heading of the last turn command written to 0x3F, in degrees. */
int16_t xgo_regs_turn_to_deg(const xgo_regs_t *r);

/* The servo speed the host set at 0x5C. */
uint8_t xgo_regs_servo_speed(const xgo_regs_t *r);

/* The descriptor at addr for this register file's model (the Mini2 has the
 * arm's registers where the Mini has others); NULL when unmapped. */
const xgo_reg_desc_t *xgo_regs_find(const xgo_regs_t *r, uint8_t addr);

/* The last servo-mode command byte written to 0x50 + servo (servo 0..11),
 * the initial 0x80 until then and after a reset. A host cannot read it: a
 * read of 0x50..0x5B gives the joints where they are (the board forms
 * those bytes; the image keeps its initial ones there). */
uint8_t xgo_regs_servo_command(const xgo_regs_t *r, unsigned servo);

#ifdef __cplusplus
}
#endif

#endif /* XGO_CORE_REGFILE_H */
