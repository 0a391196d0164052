/*
 * nv_file.h - the board's non-volatile data (xgo_board_nv_t) in a host file
 * through semihosting: QEMU's stand-in for the flash page a real board
 * would program (QEMU models neither chip's flash controller). The file's
 * path is the second word of the semihosting command line
 * (tools/mcu/serve.sh --state FILE); without one the data lives in RAM only
 * and is lost at power-off, like xgo-emu without --state.
 *
 * The file is one 72-byte record, the same an MCU would keep in flash:
 *   0  "XGNV"          4  version 1, 3 zero bytes
 *   8  bt_name[10]     18 2 zero bytes
 *   20 12 x int32 LE zero offsets (mdeg, register order)
 *   68 CRC-32 (zlib's) of bytes 0..67, LE
 * A record that is short, damaged or of another version is not loaded.
 */
#ifndef XGO_PORT_NV_FILE_H
#define XGO_PORT_NV_FILE_H

#include "xgo/board.h"

#define XGO_NV_FILE_PATH_MAX 160u
#define XGO_NV_FILE_RECORD_SIZE 72u

typedef struct xgo_nv_file_s {
    char path[XGO_NV_FILE_PATH_MAX]; /* "" = RAM only */
    xgo_board_nv_t ram;              /* the last save without a file */
    int ram_valid;
} xgo_nv_file_t;

/* Reads the path from the semihosting command line. */
void xgo_nv_file_init(xgo_nv_file_t *f);

/* xgo_port_nv_load / xgo_port_nv_save for a port that keeps its data here. */
int xgo_nv_file_load(xgo_nv_file_t *f, xgo_board_nv_t *nv);
int xgo_nv_file_save(xgo_nv_file_t *f, const xgo_board_nv_t *nv);

/* The record for nv into out; decoding it back (1 when it is valid). */
void xgo_nv_record_encode(const xgo_board_nv_t *nv, uint8_t out[XGO_NV_FILE_RECORD_SIZE]);
int xgo_nv_record_decode(const uint8_t in[XGO_NV_FILE_RECORD_SIZE], xgo_board_nv_t *nv);

#endif /* XGO_PORT_NV_FILE_H */
