/*
 * bench_view.c - what the live view (xgo-emu --view) costs the board.
 *
 * 1. pty reply latency (request written -> 20-byte reply read, the spec's
 *    servo read) and tick lateness (xgo-emu's counters at exit: how late
 *    each round of control ticks began) with --view and no view client,
 *    then with 4 clients reading /events at the default 30 Hz. The two runs
 *    alternate ROUNDS times (ABBA order) so machine load hits both alike.
 *    Also the view server's own work per loop turn (view_busy_*): the most
 *    it can hold back a pty byte or a tick, free of scheduling noise.
 * 2. xgo-emu's CPU share over 5 s: without --view, and with --view and one
 *    client reading /events (the host idle, then walking at full speed).
 *
 * usage: bench_view [REQUESTS [ROUNDS [HZ]]]
 *        (default 5000 requests, 3 rounds, --view-hz 30)
 * Prints numbers; never fails on timing. Exits 1 if the emulator does not
 * answer at all.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "http_client.h"
#include "serial_port.h"
#include "test_clock.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define CPU_SECONDS 5
#define MAX_CLIENTS 4

static const unsigned char k_request[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
#define REPLY_LEN 20u

typedef struct run_s {
    xgo_test_emu_t emu;
    unsigned port;
    int tty;
    pid_t reader; /* child reading the event streams, -1 none */
    char err_path[64];
} run_t;

static run_t g_run;
static const char *g_hz = "30"; /* --view-hz of the latency runs */

/* Starts xgo-emu with args (NULL-terminated), stderr to a file (its
 * counters at exit), opens the pty like pyserial; port from stdout. */
static int run_start(run_t *r, const char *const *args)
{
    long long deadline = xgo_test_now_ms() + 5000;
    snprintf(r->err_path, sizeof r->err_path, "/tmp/bench_view.%d.err", (int)getpid());
    xgo_test_emu_init(&r->emu);
    r->reader = -1;
    if (xgo_test_emu_spawn(&r->emu, XGO_EMU_PATH, args, r->err_path) != 0 ||
        xgo_test_emu_read_pty(&r->emu, 5000) != XGO_TEST_EMU_PTY_OK) {
        xgo_test_emu_kill(&r->emu);
        return -1;
    }
    while ((r->port = xgo_test_http_view_port(r->emu.out)) == 0 && args[0] != NULL &&
           strcmp(args[0], "--view") == 0 && xgo_test_now_ms() < deadline) {
        xgo_test_emu_wait(&r->emu, 20);
    }
    r->tty = xgo_test_port_open_like_pyserial(r->emu.pty, B115200);
    return r->tty >= 0 ? 0 : -1;
}

/* A child process that reads n event streams and throws the bytes away,
 * as browsers would, until it is killed. */
static int run_attach_clients(run_t *r, int n)
{
    static xgo_test_sse_t sse[MAX_CLIENTS];
    int i;
    for (i = 0; i < n; i++) {
        if (xgo_test_sse_open(&sse[i], r->port, 2000) != 0) {
            return -1;
        }
    }
    r->reader = fork();
    if (r->reader == 0) {
        static char sink[65536];
        for (;;) {
            for (i = 0; i < n; i++) { /* all streams tick together: round robin */
                if (read(sse[i].fd, sink, sizeof sink) == 0) {
                    _exit(0);
                }
            }
        }
    }
    for (i = 0; i < n; i++) {
        close(sse[i].fd); /* the child holds them */
    }
    xgo_test_sleep_ms(300); /* streams running */
    return r->reader > 0 ? 0 : -1;
}

/* Stops the emulator; returns what it printed on stderr (its counters). */
static const char *run_stop(run_t *r)
{
    static char text[16384];
    size_t n = 0;
    FILE *f;
    if (r->reader > 0) {
        kill(r->reader, SIGKILL);
        waitpid(r->reader, NULL, 0);
    }
    close(r->tty);
    xgo_test_emu_stop(&r->emu, SIGTERM, 5000);
    f = fopen(r->err_path, "r");
    if (f != NULL) {
        n = fread(text, 1, sizeof text - 1, f);
        fclose(f);
    }
    text[n] = '\0';
    return text;
}

/* A counter from the "  name value" lines at exit, -1 if absent. */
static long counter(const char *text, const char *name)
{
    const char *p = strstr(text, name);
    return p != NULL ? strtol(p + strlen(name), NULL, 10) : -1;
}

static double round_trip(int fd)
{
    unsigned char reply[REPLY_LEN];
    double t0 = xgo_test_now_us_f();
    if (xgo_test_port_write(fd, k_request, sizeof k_request, 1000) != 0 ||
        xgo_test_port_read(fd, reply, REPLY_LEN, 1000) != REPLY_LEN) {
        return -1;
    }
    return xgo_test_now_us_f() - t0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct figures_s {
    double p50, p99;
    long late_p50, late_p99;
    long busy_p99, busy_max; /* the view's own work per loop turn */
} figures_t;

/* One run: xgo-emu --view 0 with `clients` event streams; n round trips. */
static int measure(int clients, size_t n, double *lat, figures_t *out)
{
    const char *args[5] = {"--view", "0", "--view-hz", NULL, NULL};
    size_t i;
    args[3] = g_hz;
    if (run_start(&g_run, args) != 0 ||
        (clients > 0 && run_attach_clients(&g_run, clients) != 0)) {
        fprintf(stderr, "bench_view: cannot start %s with %d clients\n", XGO_EMU_PATH, clients);
        return -1;
    }
    for (i = 0; i < 200; i++) {
        round_trip(g_run.tty);
    }
    for (i = 0; i < n; i++) {
        lat[i] = round_trip(g_run.tty);
        if (lat[i] < 0) {
            fprintf(stderr, "bench_view: no reply to request %lu\n", (unsigned long)i);
            run_stop(&g_run);
            return -1;
        }
    }
    qsort(lat, n, sizeof *lat, cmp_double);
    out->p50 = lat[n / 2];
    out->p99 = lat[(n * 99) / 100];
    {
        const char *text = run_stop(&g_run);
        out->late_p50 = counter(text, "tick_late_p50_us");
        out->late_p99 = counter(text, "tick_late_p99_us");
        out->busy_p99 = counter(text, "view_busy_p99_us");
        out->busy_max = counter(text, "view_busy_max_us");
    }
    return 0;
}

#define MAX_ROUNDS 64

/* Median of n values (sorted in place). */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* The medians over the rounds of each figure, for 0 and 4 clients. */
static void print_medians(figures_t f[2][MAX_ROUNDS], int rounds)
{
    int c, r;
    for (c = 0; c < 2; c++) {
        double p50[MAX_ROUNDS], p99[MAX_ROUNDS], l50[MAX_ROUNDS], l99[MAX_ROUNDS];
        for (r = 0; r < rounds; r++) {
            p50[r] = f[c][r].p50;
            p99[r] = f[c][r].p99;
            l50[r] = (double)f[c][r].late_p50;
            l99[r] = (double)f[c][r].late_p99;
        }
        printf("  median of %d rounds, %d view clients: reply p50 %6.1f us  p99 %7.1f us   "
               "tick lateness p50 %5.0f us  p99 %5.0f us\n",
               rounds, c * MAX_CLIENTS, median(p50, rounds), median(p99, rounds),
               median(l50, rounds), median(l99, rounds));
    }
}

static double cpu_percent(pid_t pid, int tty, int walking)
{
    long hz = sysconf(_SC_CLK_TCK);
    long before, after;
    const unsigned char full = 0xFF;
    if (walking) {
        xgo_test_write_regs(tty, 0x30, &full, 1, 1000);
    }
    before = xgo_test_cpu_ticks(pid);
    xgo_test_sleep_ms(CPU_SECONDS * 1000L);
    after = xgo_test_cpu_ticks(pid);
    return before < 0 || after < 0 ? -1 : 100.0 * (double)(after - before) / (double)(hz * CPU_SECONDS);
}

static void measure_cpu(void)
{
    static const char *const k_plain[] = {NULL};
    static const char *const k_view[] = {"--view", "0", NULL};
    double plain_idle, plain_walk, view_idle, view_walk;
    if (run_start(&g_run, k_plain) != 0) {
        return;
    }
    plain_idle = cpu_percent(g_run.emu.pid, g_run.tty, 0);
    plain_walk = cpu_percent(g_run.emu.pid, g_run.tty, 1);
    run_stop(&g_run);
    if (run_start(&g_run, k_view) != 0 || run_attach_clients(&g_run, 1) != 0) {
        return;
    }
    view_idle = cpu_percent(g_run.emu.pid, g_run.tty, 0);
    view_walk = cpu_percent(g_run.emu.pid, g_run.tty, 1);
    run_stop(&g_run);
    printf("  CPU over %d s (of one core):  no --view: idle %.1f %%, walking %.1f %%   "
           "--view + 1 client at 30 Hz: idle %.1f %%, walking %.1f %%\n",
           CPU_SECONDS, plain_idle, plain_walk, view_idle, view_walk);
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? (size_t)strtoul(argv[1], NULL, 10) : 5000;
    int rounds = argc > 2 ? atoi(argv[2]) : 3;
    g_hz = argc > 3 ? argv[3] : g_hz;
    static figures_t all[2][MAX_ROUNDS];
    double *lat;
    int r;
    signal(SIGPIPE, SIG_IGN);
    if (n == 0 || rounds <= 0 || rounds > MAX_ROUNDS) {
        fprintf(stderr, "usage: bench_view [REQUESTS [ROUNDS [HZ]]]\n");
        return 2;
    }
    lat = malloc(n * sizeof *lat);
    if (lat == NULL) {
        return 1;
    }
    printf("bench_view: pty reply latency and tick lateness, xgo-emu --view 0 --view-hz %s, "
           "%lu requests a run\n",
           g_hz, (unsigned long)n);
    for (r = 0; r < rounds; r++) {
        int k;
        for (k = 0; k < 2; k++) {
            /* 0 then 4 clients, then 4 then 0: load drifting over time hits
             * both alike */
            int clients = (k == (r % 2)) ? 0 : MAX_CLIENTS;
            figures_t f;
            if (measure(clients, n, lat, &f) != 0) {
                free(lat);
                return 1;
            }
            all[clients != 0][r] = f;
            printf("  round %d, %d view clients: reply p50 %6.1f us  p99 %7.1f us   "
                   "tick lateness p50 %4ld us  p99 %5ld us   view work/turn p99 %3ld us  max %5ld us\n",
                   r + 1, clients, f.p50, f.p99, f.late_p50, f.late_p99, f.busy_p99, f.busy_max);
        }
    }
    free(lat);
    print_medians(all, rounds);
    measure_cpu();
    unlink(g_run.err_path);
    return 0;
}
