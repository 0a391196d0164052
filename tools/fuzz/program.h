/*
 * program.h - the fuzz input format: a small program that drives one board.
 *
 * Byte 0 configures the board (bit 0: Lite instead of Mini; bits 1-2: the
 * silence timeout 0, 5, 20 or 200 ms; bit 3: run it inside the device layer
 * through a port; bits 4-6: the initial battery, 0..7 -> 0..100 %; bit 7:
 * a Mini2 with its arm, whatever bit 0 says).
 * The rest is a sequence of operations, each an op byte (taken modulo
 * FUZZ_OP_COUNT) followed by its operands; a program that ends inside an
 * operand reads zeros. Well-formed frames are built by the core's encoder,
 * so the fuzzer reaches every register handler without having to guess
 * checksums, while FUZZ_OP_RAW keeps the wire open to any byte.
 *
 * Shared by the fuzz target (fuzz_board.c) and the seed corpus (seeds.c).
 */
#ifndef XGO_FUZZ_PROGRAM_H
#define XGO_FUZZ_PROGRAM_H

typedef enum fuzz_op_e {
    FUZZ_OP_RAW = 0,    /* n: 1 + n % 64 bytes follow, fed as they are */
    FUZZ_OP_WRITE,      /* addr, n: 1 + (n & 15) data bytes follow (n & 0x80: legacy TYPE 0x01) */
    FUZZ_OP_READ,       /* addr, count: a read request (count 0 or > 247 is refused) */
    FUZZ_OP_TICKS,      /* k: 1 + 8k control ticks, 2 ms each */
    FUZZ_OP_SILENCE,    /* k: the line is quiet for k ms (the parser's timeout) */
    FUZZ_OP_HANGUP,     /* the host hangs up */
    FUZZ_OP_TILT,       /* roll, pitch: int8 x 500 mdeg, the ground's tilt */
    FUZZ_OP_BATTERY,    /* pct: the battery's charge (> 100 too) */
    FUZZ_OP_PUSH,       /* roll, pitch: int8 x 500 mdeg, a shove */
    FUZZ_OP_VIEW_WRITE, /* addr, n: n data bytes (0 and bad ranges too), xgo_board_write */
    FUZZ_OP_NV,         /* 10 name bytes, 12 offsets int8 x 3000 mdeg: xgo_board_set_nv */
    FUZZ_OP_COUNT
} fuzz_op_t;

#define FUZZ_CONFIG_DEVICE 0x08u /* byte 0: through xgo/port.h */
#define FUZZ_CONFIG_MINI2 0x80u  /* byte 0: the Mini2 (the arm) */

/* Ticks run by FUZZ_OP_TICKS k. */
#define FUZZ_TICKS(k) (1u + 8u * (unsigned)(k))

/* At most this many ticks per input (20 s of board time): keeps each run
 * short enough for many runs per second. */
#define FUZZ_MAX_TICKS 10000u

#endif /* XGO_FUZZ_PROGRAM_H */
