/*
 * options.h - xgo-emu's command line. The parser is table-driven (options.c):
 * adding an option means adding one row and one small apply function, and
 * the usage text follows automatically.
 */
#ifndef XGO_HOST_OPTIONS_H
#define XGO_HOST_OPTIONS_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

#include "xgo/board.h"

#define XGO_EMU_VERSION "0.1.0"

typedef struct xgo_host_options_s {
    const char *link_path;    /* --link, NULL = no symlink */
    int trace;                /* --trace */
    int baud_pacing;          /* --baud-pacing */
    uint32_t uart_baud;       /* --uart-baud: the board's UART speed, 0 = no line model */
    const char *state_path;   /* --state, NULL = nothing kept across runs */
    int32_t ground_roll_mdeg; /* --ground-tilt, 0,0 = level */
    int32_t ground_pitch_mdeg;
    xgo_board_config_t board; /* --profile, --battery, --timeout-ms */
    int view;                 /* --view given */
    uint32_t view_addr;       /* its IPv4 address, host byte order (127.0.0.1) */
    unsigned view_port;       /* 0 = any free port */
    unsigned view_hz;         /* --view-hz, events a second */
    int tcp;                  /* --tcp given */
    uint32_t tcp_addr;        /* its IPv4 address, host byte order (127.0.0.1) */
    unsigned tcp_port;        /* 0 = any free port */
    const char *capture_path; /* --capture, NULL = no capture */
    const char *record_path;  /* --record, NULL = no motion log */
    unsigned record_hz;       /* --record-hz, 0 = a row every tick */
} xgo_host_options_t;

typedef enum xgo_host_parse_result_e {
    XGO_HOST_PARSE_RUN = 0, /* options are valid: start serving */
    XGO_HOST_PARSE_HELP,    /* --help given: print usage, exit 0 */
    XGO_HOST_PARSE_VERSION, /* --version given: print version, exit 0 */
    XGO_HOST_PARSE_ERROR    /* misuse: `error` holds a one-line message */
} xgo_host_parse_result_t;

/* Fills opts with the defaults, then applies argv[1..argc-1]. On
 * XGO_HOST_PARSE_ERROR, error (error_size bytes) says what was wrong, without
 * the "xgo-emu: " prefix or a newline. */
xgo_host_parse_result_t xgo_host_options_parse(xgo_host_options_t *opts, int argc, char **argv,
                                               char *error, size_t error_size);

/* The usage text, generated from the option table. */
void xgo_host_options_usage(FILE *out);

#endif /* XGO_HOST_OPTIONS_H */
