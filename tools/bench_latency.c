/*
 * bench_latency.c - reply latency of xgo-emu over a real pty, and its idle
 * CPU use.
 *
 * Starts xgo-emu (XGO_EMU_PATH), opens its pty the way pyserial does, then
 * sends read requests one at a time (the spec's example: 12 servo bytes) and
 * times each from the write() of the request to the read() that completes
 * the 20-byte reply. Reports p50/p99/max/mean in microseconds, unpaced
 * (10,000 requests) and with --baud-pacing at 115200 (1,000 requests, where
 * the floor is the wire time of 9 + 20 bytes = 2.52 ms). Finally measures the
 * emulator's CPU use over 2 s idle, with a host attached and with none.
 *
 * usage: bench_latency [REQUESTS]   (default 10000)
 * Prints numbers; never fails on timing. Exits 1 only if the emulator does
 * not answer at all.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/types.h>
#include <termios.h>
#include <unistd.h>

#include "emu_process.h"
#include "serial_port.h"
#include "test_clock.h"

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define REPLY_TIMEOUT_MS 1000
#define EMU_START_TIMEOUT_MS 5000
#define EMU_STOP_TIMEOUT_MS 5000 /* then SIGKILL */
#define IDLE_SECONDS 2

static const unsigned char k_request[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
#define REPLY_LEN 20u

/* Starts xgo-emu with one optional extra option and reads the pty path from
 * its first stdout line (test/support). Its stderr (counters at exit) is
 * discarded. Returns 0, or -1 with nothing left running. */
static int emu_start(xgo_test_emu_t *emu, const char *option)
{
    const char *args[2];
    args[0] = option;
    args[1] = NULL;
    xgo_test_emu_init(emu);
    if (xgo_test_emu_spawn(emu, XGO_EMU_PATH, args, "/dev/null") != 0) {
        return -1;
    }
    if (xgo_test_emu_read_pty(emu, EMU_START_TIMEOUT_MS) != XGO_TEST_EMU_PTY_OK) {
        xgo_test_emu_kill(emu);
        return -1;
    }
    return 0;
}

static void emu_stop(xgo_test_emu_t *emu)
{
    xgo_test_emu_stop(emu, SIGTERM, EMU_STOP_TIMEOUT_MS);
}

/* One request -> reply round trip; returns microseconds or -1. */
static double round_trip(int fd)
{
    unsigned char reply[REPLY_LEN];
    double t0 = xgo_test_now_us_f();
    if (xgo_test_port_write(fd, k_request, sizeof k_request, REPLY_TIMEOUT_MS) != 0 ||
        xgo_test_port_read(fd, reply, REPLY_LEN, REPLY_TIMEOUT_MS) != REPLY_LEN) {
        return -1;
    }
    if (reply[2] != REPLY_LEN || reply[REPLY_LEN - 1] != 0xAA) {
        return -1;
    }
    return xgo_test_now_us_f() - t0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Runs n round trips after a short warm-up and prints the distribution. */
static int measure(const char *label, const char *option, size_t n)
{
    static xgo_test_emu_t emu; /* ~70 KB of captured output: not on the stack */
    double *lat;
    double sum = 0;
    size_t i;
    int fd;

    if (emu_start(&emu, option) != 0) {
        fprintf(stderr, "bench_latency: cannot start %s\n", XGO_EMU_PATH);
        return -1;
    }
    fd = xgo_test_port_open_like_pyserial(emu.pty, B115200);
    lat = malloc(n * sizeof *lat);
    if (fd < 0 || lat == NULL) {
        fprintf(stderr, "bench_latency: cannot open %s\n", emu.pty);
        emu_stop(&emu);
        free(lat);
        return -1;
    }
    for (i = 0; i < 100; i++) {
        if (round_trip(fd) < 0) {
            break;
        }
    }
    for (i = 0; i < n; i++) {
        lat[i] = round_trip(fd);
        if (lat[i] < 0) {
            fprintf(stderr, "bench_latency: no reply to request %zu\n", i);
            close(fd);
            emu_stop(&emu);
            free(lat);
            return -1;
        }
        sum += lat[i];
    }
    qsort(lat, n, sizeof *lat, cmp_double);
    printf("  %-22s n=%-6zu p50 %8.1f us   p99 %8.1f us   max %8.1f us   mean %8.1f us\n", label,
           n, lat[n / 2], lat[(n * 99) / 100], lat[n - 1], sum / (double)n);
    close(fd);
    emu_stop(&emu);
    free(lat);
    return 0;
}

static double idle_cpu_percent(pid_t pid)
{
    long hz = sysconf(_SC_CLK_TCK);
    long before = xgo_test_cpu_ticks(pid);
    long after;
    xgo_test_sleep_ms(IDLE_SECONDS * 1000L);
    after = xgo_test_cpu_ticks(pid);
    if (before < 0 || after < 0 || hz <= 0) {
        return -1;
    }
    return 100.0 * (double)(after - before) / (double)(hz * IDLE_SECONDS);
}

static void measure_idle(void)
{
    static xgo_test_emu_t emu; /* ~70 KB of captured output: not on the stack */
    double attached, detached;
    int fd;
    if (emu_start(&emu, NULL) != 0) {
        return;
    }
    fd = xgo_test_port_open_like_pyserial(emu.pty, B115200);
    attached = idle_cpu_percent(emu.pid);
    if (fd >= 0) {
        close(fd); /* from now on the master sees POLLHUP */
    }
    detached = idle_cpu_percent(emu.pid);
    emu_stop(&emu);
    if (attached < 0 || detached < 0) {
        printf("  idle CPU: not measured (no /proc)\n");
        return;
    }
    printf("  idle CPU over %d s: host attached %.1f %%, no host %.1f %% (of one core)\n",
           IDLE_SECONDS, attached, detached);
}

int main(int argc, char **argv)
{
    size_t n = 10000;
    signal(SIGPIPE, SIG_IGN);
    if (argc > 1) {
        n = (size_t)strtoul(argv[1], NULL, 10);
        if (n == 0) {
            fprintf(stderr, "usage: bench_latency [REQUESTS]\n");
            return 2;
        }
    }
    printf("bench_latency: xgo-emu over a pty, request written -> 20-byte reply read\n");
    if (measure("unpaced", NULL, n) != 0) {
        return 1;
    }
    if (measure("--baud-pacing 115200", "--baud-pacing", n / 10 > 0 ? n / 10 : 1) != 0) {
        return 1;
    }
    measure_idle();
    return 0;
}
