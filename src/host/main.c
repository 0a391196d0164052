/*
 * main.c - xgo-emu: the XGO-Mini driver board on a pseudo-terminal.
 *
 * Start-up order matters to scripts: the pty is configured (raw) and the
 * --link symlink is in place before the slave path is printed, so whoever
 * reads the first stdout line can open the port at once. The --state file is
 * loaded before any of that, so a damaged one stops us before a pty or link
 * exists.
 */
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "capture.h"
#include "clock.h"
#include "link.h"
#include "loop.h"
#include "options.h"
#include "pty.h"
#include "record.h"
#include "state_file.h"
#include "tcp_bridge.h"
#include "trace.h"
#include "view_server.h"
#include "xgo/board.h"
#include "xgo/emulator.h"

#define XGO_EXIT_OK 0
#define XGO_EXIT_RUNTIME 1
#define XGO_EXIT_USAGE 2

static volatile sig_atomic_t xgo_host_stop_requested;

/* Only sets the flag: the loop notices within one tick (poll() is not
 * restarted: SA_RESTART is deliberately left out). */
static void xgo_host_on_stop_signal(int sig)
{
    (void)sig;
    xgo_host_stop_requested = 1;
}

static int xgo_host_install_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = xgo_host_on_stop_signal;
    sigemptyset(&sa.sa_mask);
    /* SIGHUP too: a closed terminal should still get the link cleaned up. */
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0 ||
        sigaction(SIGHUP, &sa, NULL) != 0) {
        return -1;
    }
    /* A script that read our first line and closed the pipe must not kill
     * us with SIGPIPE later. */
    sa.sa_handler = SIG_IGN;
    return sigaction(SIGPIPE, &sa, NULL);
}

/* --view and --record: opened before the pty exists, so a port in use or
 * an uncreatable file stops us before anything is visible to a host. */
static int xgo_host_open_outputs(const xgo_host_options_t *opts, xgo_host_view_t *view,
                                 xgo_host_record_t *record, const xgo_board_t *board, char *err,
                                 size_t err_size)
{
    if (opts->view) {
        if (xgo_host_view_open(view, opts->view_addr, opts->view_port, opts->view_hz, err,
                               err_size) != 0) {
            return -1;
        }
        if ((opts->view_addr >> 24) != 127u) {
            fprintf(stderr, "xgo-emu: warning: --view on %s is reachable from other machines; "
                            "anyone who can connect can drive the robot\n",
                    view->host);
        }
    }
    if (opts->record_path != NULL &&
        xgo_host_record_open(record, opts->record_path, opts->record_hz, board, err, err_size) !=
            0) {
        return -1;
    }
    return 0;
}

/* --capture and --tcp: what passes the serial line, kept and bridged. The
 * capture opens before the pty (its first note holds the board as loaded);
 * the bridge needs the pty's path. */
static xgo_host_capture_t xgo_host_capture;
static xgo_host_tcp_t xgo_host_tcp;

static int xgo_host_open_line_extras(const xgo_host_options_t *opts, const xgo_board_t *board,
                                     const xgo_host_pty_t *pty, const xgo_host_loop_t *loop,
                                     char *err, size_t err_size)
{
    if (pty == NULL) {
        return opts->capture_path == NULL
                   ? 0
                   : xgo_host_capture_open(&xgo_host_capture, opts->capture_path, board, err, err_size);
    }
    xgo_host_tcp.listen_fd = -1;
    return opts->tcp ? xgo_host_tcp_open(&xgo_host_tcp, opts->tcp_addr, opts->tcp_port,
                                         pty->slave_path, loop, err, err_size)
                     : 0;
}

static int xgo_host_close_line_extras(const xgo_host_options_t *opts)
{
    int rc = 0;
    if (opts->capture_path != NULL && xgo_host_capture_close(&xgo_host_capture, stderr) != 0) {
        rc = -1;
    }
    if (opts->tcp) {
        xgo_host_tcp_print_counters(&xgo_host_tcp, stderr);
        xgo_host_tcp_close(&xgo_host_tcp);
    }
    return rc;
}

int main(int argc, char **argv)
{
    static xgo_board_t board;   /* static: large, and lives as long as the process */
    static xgo_host_loop_t loop;
    static xgo_host_view_t view;     /* --view: 2.4 MB of client buffers */
    static xgo_host_record_t record; /* --record */
    xgo_host_options_t opts;
    xgo_host_pty_t pty;
    xgo_host_trace_t trace;
    xgo_host_state_t state;
    char err[8192]; /* room for messages that quote two long paths */
    char replaced[4096]; /* the target of a stale --link symlink we replaced */
    int rc;

    switch (xgo_host_options_parse(&opts, argc, argv, err, sizeof err)) {
    case XGO_HOST_PARSE_RUN:
        break;
    case XGO_HOST_PARSE_HELP:
        xgo_host_options_usage(stdout);
        return XGO_EXIT_OK;
    case XGO_HOST_PARSE_VERSION:
        printf("xgo-emu %s\n", XGO_EMU_VERSION);
        return XGO_EXIT_OK;
    case XGO_HOST_PARSE_ERROR:
        fprintf(stderr, "xgo-emu: %s\n", err);
        xgo_host_options_usage(stderr);
        return XGO_EXIT_USAGE;
    }

    if (xgo_host_install_signals() != 0) {
        perror("xgo-emu: sigaction");
        return XGO_EXIT_RUNTIME;
    }
    xgo_board_init(&board, &opts.board);
    xgo_board_set_ground_tilt(&board, opts.ground_roll_mdeg, opts.ground_pitch_mdeg);
    if (opts.state_path != NULL &&
        xgo_host_state_open(&state, opts.state_path, &board, err, sizeof err) != 0) {
        fprintf(stderr, "xgo-emu: %s\n", err);
        return XGO_EXIT_RUNTIME;
    }
    if (xgo_host_open_outputs(&opts, &view, &record, &board, err, sizeof err) != 0 ||
        xgo_host_open_line_extras(&opts, &board, NULL, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "xgo-emu: %s\n", err);
        return XGO_EXIT_RUNTIME;
    }
    if (xgo_host_pty_open(&pty, err, sizeof err) != 0) {
        fprintf(stderr, "xgo-emu: %s\n", err);
        return XGO_EXIT_RUNTIME;
    }
    if (xgo_host_open_line_extras(&opts, &board, &pty, &loop, err, sizeof err) != 0) {
        fprintf(stderr, "xgo-emu: %s\n", err);
        xgo_host_pty_close(&pty);
        return XGO_EXIT_RUNTIME;
    }
    if (opts.link_path != NULL) {
        if (xgo_host_link_create(opts.link_path, pty.slave_path, replaced, sizeof replaced, err,
                                 sizeof err) != 0) {
            fprintf(stderr, "xgo-emu: %s\n", err);
            xgo_host_pty_close(&pty);
            return XGO_EXIT_RUNTIME;
        }
        if (replaced[0] != '\0') {
            fprintf(stderr, "xgo-emu: replaced the stale symlink %s (it pointed at %s)\n",
                    opts.link_path, replaced);
        }
    }

    xgo_host_trace_init(&trace, stderr, xgo_host_clock_us());
    trace.arm = opts.board.model == XGO_MODEL_MINI2;
    if (opts.trace) {
        xgo_board_set_trace(&board, xgo_host_trace_event, &trace);
    }
    xgo_host_loop_init(&loop, &board, &pty, opts.trace ? &trace : NULL, opts.baud_pacing,
                       &xgo_host_stop_requested);
    xgo_host_loop_set_uart(&loop, opts.uart_baud);
    if (opts.state_path != NULL) {
        xgo_host_loop_set_state(&loop, &state);
    }
    if (opts.view) {
        (void)xgo_host_view_attach(&view, &board, (unsigned)opts.board.model, &loop,
                                   opts.trace ? &trace : NULL);
    }
    if (opts.record_path != NULL) {
        (void)xgo_host_loop_add_service(&loop, &record.service);
    }
    if (opts.capture_path != NULL) {
        (void)xgo_host_loop_add_service(&loop, &xgo_host_capture.service);
    }
    if (opts.tcp) {
        (void)xgo_host_loop_add_service(&loop, &xgo_host_tcp.service);
    }

    printf("%s\n", pty.slave_path);
    if (opts.tcp) {
        printf("tcp: %s:%u\n", xgo_host_tcp.host, xgo_host_tcp.port);
    }
    if (opts.view) {
        printf("view: http://%s:%u/\n", view.host, view.port);
    }
    fflush(stdout);

    rc = xgo_host_loop_run(&loop);

    /* A change the board received but never saved is a runtime error: the
     * user asked for it to be kept. */
    if (opts.state_path != NULL && xgo_host_state_close(&state, &board, stderr) != 0) {
        rc = -1;
    }
    if (opts.trace) {
        xgo_host_trace_flush(&trace); /* noise folded since the last line */
    }
    if (opts.record_path != NULL && xgo_host_record_close(&record, stderr) != 0) {
        rc = -1;
    }
    xgo_host_loop_print_counters(&loop, stderr);
    if (xgo_host_close_line_extras(&opts) != 0) {
        rc = -1;
    }
    if (opts.view) {
        xgo_host_view_print_counters(&view, stderr);
        xgo_host_view_close(&view);
    }
    if (opts.link_path != NULL) {
        xgo_host_link_remove_if_ours(opts.link_path, pty.slave_path);
    }
    xgo_host_pty_close(&pty);
    return rc == 0 ? XGO_EXIT_OK : XGO_EXIT_RUNTIME;
}
