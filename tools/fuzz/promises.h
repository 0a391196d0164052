/*
 * promises.h - what the board promises, checked while a fuzz program runs.
 * A broken promise prints what broke and aborts (the fuzzer keeps the input).
 *
 *   - every reply is a whole, well-formed frame (TYPE 0x12, checksum, tail,
 *     a host-side parser takes it without a drop) answering an accepted read
 *     (or an upgrade request), in order, with the bytes the board's read view
 *     showed; nothing answers a write or a rejected frame;
 *   - read-only registers never change through a host write (wire or view);
 *   - no joint moves more than 1.2 deg per tick (docs/motion.md), none leaves
 *     its limits; mode, action and battery hold documented values, the
 *     observers agree with the registers;
 *   - the counters add up: every byte fed is in a delivered frame, discarded
 *     or pending (nothing pending after a hang-up); frames_ok counts the delivered
 *     frames; each drop reason's counter equals its traced drops; counters
 *     never go back;
 *   - a written byte's physical value (reg_units) maps back to a byte with
 *     the same value, inside the register's range.
 */
#ifndef XGO_FUZZ_PROMISES_H
#define XGO_FUZZ_PROMISES_H

#include <stddef.h>
#include <stdint.h>

#include "xgo/board.h"

#define FUZZ_OWED_MAX 256u /* replies owed at once: far more than XGO_TX_BUFFER_SIZE holds */

typedef struct fuzz_promises_s {
    xgo_board_t *board;
    const xgo_profile_t *profile;      /* the board's model */
    uint8_t owed_addr[FUZZ_OWED_MAX]; /* replies owed, oldest first (a ring) */
    uint8_t owed_n[FUZZ_OWED_MAX];
    unsigned owed_head, owed_len;
    size_t wire_bytes;  /* fed through xgo_board_receive */
    size_t frame_bytes; /* in frames the parser delivered */
    uint32_t frames;    /* frames the parser delivered */
    uint32_t drops[XGO_DROP_REASON_COUNT]; /* traced drops per reason */
    uint32_t unmapped_writes;              /* accepted writes with bytes the model lacks */
    int upgrade_asked;                     /* the newest wire frame asked for an upgrade */
    uint32_t counters[XGO_DIAG_COUNT];     /* as last seen */
    int32_t joints[XGO_SERVO_COUNT];       /* as after the last tick */
    int32_t zeros[XGO_SERVO_COUNT];        /* the servos' zero offsets then */
    uint8_t read_only[XGO_REG_COUNT];      /* snapshot before a host write */
    xgo_parser_t host;                     /* parses the output like a host */
    uint32_t host_frames;
} fuzz_promises_t;

/* Starts watching b, a board of model `profile` (installs the trace hook). */
void fuzz_promises_init(fuzz_promises_t *p, xgo_board_t *b, const xgo_profile_t *profile);

/* n bytes are about to go through xgo_board_receive. */
void fuzz_promises_fed(fuzz_promises_t *p, size_t n);

/* Around a host write (frame or xgo_board_write): read-only registers. */
void fuzz_promises_before_write(fuzz_promises_t *p);
void fuzz_promises_after_write(fuzz_promises_t *p);

/* A written byte's physical meaning maps back to itself. */
void fuzz_promises_units(const fuzz_promises_t *p, uint8_t addr, const uint8_t *data, size_t n);

/* After each tick: joint steps and limits. */
void fuzz_promises_after_tick(fuzz_promises_t *p);

/* The joints' reference moved (new zero offsets set from outside). */
void fuzz_promises_rebase_joints(fuzz_promises_t *p);

/* The board's output since the last call (all of it: the board holds no
 * reply back), checked against the replies owed; then the observers and
 * the counters. */
void fuzz_promises_drain(fuzz_promises_t *p, const uint8_t *out, size_t n, uint32_t now_ms);

/* At the end, after a hang-up and a last drain: nothing is pending, every
 * owed reply has come. */
void fuzz_promises_finish(fuzz_promises_t *p);

/* Aborts with "broken promise: what" unless ok. */
void fuzz_check(int ok, const char *what);

#endif /* XGO_FUZZ_PROMISES_H */
