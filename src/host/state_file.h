/*
 * state_file.h - xgo-emu --state FILE: the board's non-volatile data (the
 * Bluetooth name and the servo zero offsets, xgo_board_nv_t) kept in a small
 * text file across restarts.
 *
 * The file (docs/xgo-emu.md, "State file"):
 *
 *   xgo-state 1
 *   bt_name=XGOMINI
 *   zero_offsets_mdeg=0 0 0 0 0 0 0 0 0 0 0 0
 *   crc32=1c2b3a4d
 *
 * The last line is the CRC-32 (zlib's) of every byte before it, so a file
 * that is damaged or cut short is recognised, never half-applied.
 *
 * Saving is atomic: the new text goes to a fresh FILE.tmp.<pid>.XXXXXX in the
 * same directory (created exclusively, mode 0600: nothing planted there is
 * ever opened), is fsync'ed, renamed over FILE, and the directory is
 * fsync'ed. A crash at any moment leaves the old file or the new one.
 */
#ifndef XGO_HOST_STATE_FILE_H
#define XGO_HOST_STATE_FILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "xgo/board.h"

/* Far more than a valid file needs (about 150 bytes); anything longer is not
 * a state file. */
#define XGO_HOST_STATE_MAX_BYTES 1024u

/* The format version in the first line. */
#define XGO_HOST_STATE_VERSION 1

/* Writes the file's text for nv into buf. Returns its length, or 0 if it
 * does not fit in size bytes. */
size_t xgo_host_state_format(const xgo_board_nv_t *nv, char *buf, size_t size);

/* Parses a whole file's text (len bytes, need not be NUL-terminated).
 * Returns 0 and fills nv, or -1 with a one-line reason in err. Checks the
 * layout and the CRC; whether the values are acceptable is the board's call
 * (xgo_board_set_nv). */
int xgo_host_state_parse(const char *text, size_t len, xgo_board_nv_t *nv, char *err,
                         size_t err_size);

typedef enum xgo_host_state_load_e {
    XGO_HOST_STATE_LOADED = 0, /* nv filled from the file */
    XGO_HOST_STATE_MISSING,    /* no file at path */
    XGO_HOST_STATE_BAD         /* unreadable or not a valid state file: see err */
} xgo_host_state_load_t;

xgo_host_state_load_t xgo_host_state_load(const char *path, xgo_board_nv_t *nv, char *err,
                                          size_t err_size);

/* Replaces the file at path atomically (see above). Returns 0, or -1 with a
 * one-line reason in err (the old file, if any, is then untouched). */
int xgo_host_state_save(const char *path, const xgo_board_nv_t *nv, char *err, size_t err_size);

/* Removes PATH.tmp.<pid>.XXXXXX (and older PATH.tmp.<pid>) files left
 * behind by processes that no longer exist (killed in the middle of a save):
 * only regular files owned by us. Returns how many were removed. */
int xgo_host_state_remove_stale(const char *path);

/* --- Keeping a running board's data saved ------------------------------
 * xgo-emu's port (port_posix.c) is the board's flash: the device layer
 * restores the data through xgo_port_nv_load at start and saves it through
 * xgo_port_nv_save once it has settled (XGO_PORT_NV_SETTLE_TICKS, 200 ms),
 * retrying a failed save each settle period. */

typedef struct xgo_host_state_s {
    const char *path;
    xgo_board_nv_t saved;     /* what the file holds */
    int loaded;               /* the file existed at start: saved is its content */
    xgo_board_nv_t failed_nv; /* what the last failed save tried to write */
    int failed;               /* the last save failed (and was reported) */
} xgo_host_state_t;

/* Start-up, before the board exists: removes stale temporary files and
 * loads path, if there is a file. Returns 0, or -1 with a one-line reason in
 * err: the file is unreadable or damaged (it is then left as it was). */
int xgo_host_state_open(xgo_host_state_t *s, const char *path, char *err, size_t err_size);

/* xgo_port_nv_load: 1 and the file's data in nv, or 0 when there was no
 * file. */
int xgo_host_state_loaded(const xgo_host_state_t *s, xgo_board_nv_t *nv);

/* After the board took (or refused) the loaded data: -1 with a reason in err
 * when it refused the file's values (it keeps its defaults then); without a
 * file, saves the board's defaults there at once (so a path that cannot be
 * written is reported now, not at exit). Returns 0 when serving may start. */
int xgo_host_state_check(xgo_host_state_t *s, const xgo_board_t *b, char *err, size_t err_size);

/* xgo_port_nv_save: saves nv if it differs from the file (or the last save
 * failed). A failure is reported on log once for the same data. Returns 0
 * when the file is up to date, -1 when it is not. */
int xgo_host_state_store(xgo_host_state_t *s, const xgo_board_nv_t *nv, FILE *log);

/* At exit: saves if the board's data differs from the file (a change not
 * yet settled, or a failed save). Returns 0 when the file is up to date, -1
 * (reported on log) when it is not. */
int xgo_host_state_close(xgo_host_state_t *s, const xgo_board_t *b, FILE *log);

#endif /* XGO_HOST_STATE_FILE_H */
