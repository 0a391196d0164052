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
#include "port_posix.h"
#include "pty.h"
#include "record.h"
#include "state_file.h"
#include "tcp_bridge.h"
#include "trace.h"
#include "view_server.h"
#include "xgo/board.h"
#include "xgo/emulator.h"
#include "xgo/port.h"

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

/* Everything one xgo-emu process runs, in one place (static in main:
 * large, and it lives as long as the process). */
typedef struct xgo_host_emu_s {
    xgo_host_options_t opts;
    xgo_device_t device;        /* the board, driven through xgo/port.h */
    xgo_port_t port;            /* the pty as its UART, --state as its flash */
    xgo_host_loop_t loop;
    xgo_host_view_t view;       /* --view: 2.4 MB of client buffers */
    xgo_host_record_t record;   /* --record */
    xgo_host_capture_t capture; /* --capture */
    xgo_host_tcp_t tcp;         /* --tcp */
    xgo_host_pty_t pty;
    xgo_host_trace_t trace;
    xgo_host_state_t state;     /* --state */
    int pty_open;
    char err[8192]; /* room for messages that quote two long paths */
} xgo_host_emu_t;

/* --view and --record: opened before the pty exists, so a port in use or
 * an uncreatable file stops us before anything is visible to a host. */
static int xgo_host_open_outputs(xgo_host_emu_t *e)
{
    const xgo_host_options_t *opts = &e->opts;
    if (opts->view) {
        if (xgo_host_view_open(&e->view, opts->view_addr, opts->view_port, opts->view_hz, e->err,
                               sizeof e->err) != 0) {
            return -1;
        }
        if ((opts->view_addr >> 24) != 127u) {
            fprintf(stderr, "xgo-emu: warning: --view on %s is reachable from other machines; "
                            "anyone who can connect can drive the robot\n",
                    e->view.host);
        }
    }
    if (opts->record_path != NULL &&
        xgo_host_record_open(&e->record, opts->record_path, opts->record_hz,
                             xgo_device_board(&e->device), e->err, sizeof e->err) != 0) {
        return -1;
    }
    /* the capture's first note holds the board as loaded */
    return opts->capture_path == NULL ? 0
                                      : xgo_host_capture_open(&e->capture, opts->capture_path,
                                                              xgo_device_board(&e->device),
                                                              e->err, sizeof e->err);
}

/* The --state file, then the device on our port: the board starts with
 * what xgo_port_nv_load gives it, as firmware does from flash. */
static int xgo_host_emu_open_device(xgo_host_emu_t *e)
{
    const xgo_host_options_t *opts = &e->opts;
    xgo_host_state_t *state = opts->state_path != NULL ? &e->state : NULL;
    if (state != NULL && xgo_host_state_open(state, opts->state_path, e->err, sizeof e->err) != 0) {
        return -1;
    }
    xgo_host_port_init(&e->port, &e->pty, state);
    xgo_device_init(&e->device, &e->port, &opts->board);
    /* An emulator input: the ground a real robot stands on (board.h). */
    xgo_board_set_ground_tilt(xgo_device_board(&e->device), opts->ground_roll_mdeg,
                              opts->ground_pitch_mdeg);
    return state == NULL ? 0
                         : xgo_host_state_check(state, xgo_device_board(&e->device), e->err,
                                                sizeof e->err);
}

/* The device (and its saved state), the outputs, the pty, the TCP bridge
 * (it needs the pty's path) and the --link. Returns 0, or -1 with the
 * reason in e->err. */
static int xgo_host_emu_open(xgo_host_emu_t *e)
{
    const xgo_host_options_t *opts = &e->opts;
    char replaced[4096]; /* the target of a stale --link symlink we replaced */
    e->tcp.listen_fd = -1;
    if (xgo_host_emu_open_device(e) != 0 || xgo_host_open_outputs(e) != 0 ||
        xgo_host_pty_open(&e->pty, e->err, sizeof e->err) != 0) {
        return -1;
    }
    e->pty_open = 1;
    if (opts->tcp && xgo_host_tcp_open(&e->tcp, opts->tcp_addr, opts->tcp_port,
                                       e->pty.slave_path, &e->loop, e->err, sizeof e->err) != 0) {
        return -1;
    }
    if (opts->link_path != NULL) {
        if (xgo_host_link_create(opts->link_path, e->pty.slave_path, replaced, sizeof replaced,
                                 e->err, sizeof e->err) != 0) {
            return -1;
        }
        if (replaced[0] != '\0') {
            fprintf(stderr, "xgo-emu: replaced the stale symlink %s (it pointed at %s)\n",
                    opts->link_path, replaced);
        }
    }
    return 0;
}

/* Trace, loop and the services that ride on it. */
static void xgo_host_emu_attach(xgo_host_emu_t *e)
{
    const xgo_host_options_t *opts = &e->opts;
    xgo_host_trace_t *trace = opts->trace ? &e->trace : NULL;
    xgo_board_t *board = xgo_device_board(&e->device);
    xgo_host_trace_init(&e->trace, stderr, xgo_host_clock_us());
    e->trace.arm = opts->board.model == XGO_MODEL_MINI2;
    if (trace != NULL) {
        xgo_board_set_trace(board, xgo_host_trace_event, trace);
    }
    xgo_host_loop_init(&e->loop, &e->device, &e->port, trace, opts->baud_pacing, opts->uart_baud,
                       &xgo_host_stop_requested);
    if (opts->view) {
        (void)xgo_host_view_attach(&e->view, board, (unsigned)opts->board.model, &e->loop, trace);
    }
    if (opts->record_path != NULL) {
        (void)xgo_host_loop_add_service(&e->loop, &e->record.service);
    }
    if (opts->capture_path != NULL) {
        (void)xgo_host_loop_add_service(&e->loop, &e->capture.service);
    }
    if (opts->tcp) {
        (void)xgo_host_loop_add_service(&e->loop, &e->tcp.service);
    }
}

/* The first stdout line is the pty: scripts read it and open the port. */
static void xgo_host_emu_announce(const xgo_host_emu_t *e)
{
    printf("%s\n", e->pty.slave_path);
    if (e->opts.tcp) {
        printf("tcp: %s:%u\n", e->tcp.host, e->tcp.port);
    }
    if (e->opts.view) {
        printf("view: http://%s:%u/\n", e->view.host, e->view.port);
    }
    fflush(stdout);
}

/* Saves, flushes, counters, and every resource closed. Returns -1 when
 * something the user asked to be kept was not (state, record, capture). */
static int xgo_host_emu_close(xgo_host_emu_t *e, int served)
{
    const xgo_host_options_t *opts = &e->opts;
    int rc = 0;
    /* A change the board received but never saved is a runtime error. */
    if (served && opts->state_path != NULL &&
        xgo_host_state_close(&e->state, xgo_device_board(&e->device), stderr) != 0) {
        rc = -1;
    }
    if (served && opts->trace) {
        xgo_host_trace_flush(&e->trace); /* noise folded since the last line */
    }
    if (served && opts->record_path != NULL && xgo_host_record_close(&e->record, stderr) != 0) {
        rc = -1;
    }
    if (served) {
        xgo_host_loop_print_counters(&e->loop, stderr);
    }
    if (served && opts->capture_path != NULL &&
        xgo_host_capture_close(&e->capture, stderr) != 0) {
        rc = -1;
    }
    if (opts->tcp && e->tcp.listen_fd >= 0) {
        if (served) {
            xgo_host_tcp_print_counters(&e->tcp, stderr);
        }
        xgo_host_tcp_close(&e->tcp);
    }
    if (served && opts->view) {
        xgo_host_view_print_counters(&e->view, stderr);
        xgo_host_view_close(&e->view);
    }
    if (served && opts->link_path != NULL) {
        xgo_host_link_remove_if_ours(opts->link_path, e->pty.slave_path);
    }
    if (e->pty_open) {
        xgo_host_pty_close(&e->pty);
    }
    return rc;
}

int main(int argc, char **argv)
{
    static xgo_host_emu_t emu;
    int rc;

    switch (xgo_host_options_parse(&emu.opts, argc, argv, emu.err, sizeof emu.err)) {
    case XGO_HOST_PARSE_RUN:
        break;
    case XGO_HOST_PARSE_HELP:
        xgo_host_options_usage(stdout);
        return XGO_EXIT_OK;
    case XGO_HOST_PARSE_VERSION:
        printf("xgo-emu %s\n", XGO_EMU_VERSION);
        return XGO_EXIT_OK;
    case XGO_HOST_PARSE_ERROR:
        fprintf(stderr, "xgo-emu: %s\n", emu.err);
        xgo_host_options_usage(stderr);
        return XGO_EXIT_USAGE;
    }
    if (xgo_host_install_signals() != 0) {
        perror("xgo-emu: sigaction");
        return XGO_EXIT_RUNTIME;
    }
    if (xgo_host_emu_open(&emu) != 0) {
        fprintf(stderr, "xgo-emu: %s\n", emu.err);
        (void)xgo_host_emu_close(&emu, 0);
        return XGO_EXIT_RUNTIME;
    }
    xgo_host_emu_attach(&emu);
    xgo_host_emu_announce(&emu);
    rc = xgo_host_loop_run(&emu.loop);
    if (xgo_host_emu_close(&emu, 1) != 0) {
        rc = -1;
    }
    return rc == 0 ? XGO_EXIT_OK : XGO_EXIT_RUNTIME;
}
