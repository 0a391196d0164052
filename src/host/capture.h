/*
 * capture.h - xgo-emu --capture FILE.pcap: every byte of the serial line,
 * both directions, with its time and the board tick, written as it passes
 * (src/host/pcap.c; format in docs/capture.md). A service of the event loop
 * (on_line). The first record is a note with the board's settings
 * (profile, battery, parser timeout, ground tilt, non-volatile data), so
 * xgo-replay can start a board like this one.
 */
#ifndef XGO_HOST_CAPTURE_H
#define XGO_HOST_CAPTURE_H

#include <stdio.h>

#include "loop.h"
#include "pcap.h"
#include "xgo/board.h"
#include "xgo/emulator.h"

typedef struct xgo_host_capture_s {
    xgo_host_pcap_writer_t pcap;
    const char *path;
    const xgo_board_t *board;
    int reported;        /* a write failure was reported (once) */
    xgo_host_service_t service;
} xgo_host_capture_t;

/* Creates path, writes the settings note. Returns 0, or -1 with a one-line
 * message in err. */
int xgo_host_capture_open(xgo_host_capture_t *c, const char *path, const xgo_board_t *board,
                          char *err, size_t err_size);

/* Closes; returns 0, or -1 (message on out) if a record could not be
 * written. */
int xgo_host_capture_close(xgo_host_capture_t *c, FILE *out);

#endif /* XGO_HOST_CAPTURE_H */
