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
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#ifndef XGO_EMU_PATH
#error "XGO_EMU_PATH must name the xgo-emu executable"
#endif

#define REPLY_TIMEOUT_MS 1000
#define IDLE_SECONDS 2

static const unsigned char k_request[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
#define REPLY_LEN 20u

typedef struct emu_s {
    pid_t pid;
    char slave[256];
} emu_t;

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static void sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

/* Starts xgo-emu with one optional extra option; reads the pty path from its
 * first stdout line. Its stderr (counters at exit) is discarded. */
static int emu_start(emu_t *emu, const char *option)
{
    int out_pipe[2];
    size_t len = 0;
    double deadline;
    if (pipe(out_pipe) != 0) {
        return -1;
    }
    emu->pid = fork();
    if (emu->pid < 0) {
        return -1;
    }
    if (emu->pid == 0) {
        int devnull = open("/dev/null", O_WRONLY);
        dup2(out_pipe[1], STDOUT_FILENO);
        if (devnull >= 0) {
            dup2(devnull, STDERR_FILENO);
        }
        close(out_pipe[0]);
        close(out_pipe[1]);
        execl(XGO_EMU_PATH, XGO_EMU_PATH, option, (char *)NULL);
        _exit(127);
    }
    close(out_pipe[1]);
    deadline = now_us() + 5e6;
    while (len < sizeof emu->slave - 1) {
        struct pollfd pfd;
        ssize_t n;
        pfd.fd = out_pipe[0];
        pfd.events = POLLIN;
        if (now_us() > deadline || poll(&pfd, 1, 100) < 0) {
            break;
        }
        if (pfd.revents == 0) {
            continue;
        }
        n = read(out_pipe[0], emu->slave + len, 1);
        if (n <= 0) {
            break;
        }
        if (emu->slave[len] == '\n') {
            emu->slave[len] = '\0';
            close(out_pipe[0]);
            return 0;
        }
        len++;
    }
    close(out_pipe[0]);
    return -1;
}

static void emu_stop(emu_t *emu)
{
    int i;
    if (emu->pid <= 0) {
        return;
    }
    kill(emu->pid, SIGTERM);
    for (i = 0; i < 500; i++) {
        if (waitpid(emu->pid, NULL, WNOHANG) == emu->pid) {
            emu->pid = -1;
            return;
        }
        sleep_ms(10);
    }
    kill(emu->pid, SIGKILL);
    waitpid(emu->pid, NULL, 0);
    emu->pid = -1;
}

/* pyserial's settings: raw 8N1, no flow control, non-blocking. */
static int port_open(const char *path)
{
    struct termios tio;
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0 || tcgetattr(fd, &tio) != 0) {
        return -1;
    }
    cfmakeraw(&tio);
    tio.c_cflag |= (tcflag_t)(CLOCAL | CREAD);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    cfsetispeed(&tio, B115200);
    cfsetospeed(&tio, B115200);
    if (tcsetattr(fd, TCSANOW, &tio) != 0) {
        close(fd);
        return -1;
    }
    tcflush(fd, TCIOFLUSH);
    return fd;
}

/* One request -> reply round trip; returns microseconds or -1. */
static double round_trip(int fd)
{
    unsigned char reply[REPLY_LEN];
    size_t got = 0;
    double t0 = now_us();
    if (write(fd, k_request, sizeof k_request) != (ssize_t)sizeof k_request) {
        return -1;
    }
    while (got < REPLY_LEN) {
        struct pollfd pfd;
        ssize_t n;
        pfd.fd = fd;
        pfd.events = POLLIN;
        if (poll(&pfd, 1, REPLY_TIMEOUT_MS) <= 0) {
            return -1;
        }
        n = read(fd, reply + got, REPLY_LEN - got);
        if (n > 0) {
            got += (size_t)n;
        }
    }
    if (reply[2] != REPLY_LEN || reply[REPLY_LEN - 1] != 0xAA) {
        return -1;
    }
    return now_us() - t0;
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
    emu_t emu;
    double *lat;
    double sum = 0;
    size_t i;
    int fd;

    if (emu_start(&emu, option) != 0) {
        fprintf(stderr, "bench_latency: cannot start %s\n", XGO_EMU_PATH);
        return -1;
    }
    fd = port_open(emu.slave);
    lat = malloc(n * sizeof *lat);
    if (fd < 0 || lat == NULL) {
        fprintf(stderr, "bench_latency: cannot open %s\n", emu.slave);
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

/* utime + stime of pid in clock ticks, -1 without /proc. */
static long cpu_ticks(pid_t pid)
{
    char path[64];
    char buf[1024];
    const char *p;
    unsigned long utime, stime;
    size_t n;
    FILE *f;
    snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
    f = fopen(path, "r");
    if (f == NULL) {
        return -1;
    }
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    p = strrchr(buf, ')');
    if (p == NULL ||
        sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &utime, &stime) != 2) {
        return -1;
    }
    return (long)(utime + stime);
}

static double idle_cpu_percent(pid_t pid)
{
    long hz = sysconf(_SC_CLK_TCK);
    long before = cpu_ticks(pid);
    long after;
    sleep_ms(IDLE_SECONDS * 1000L);
    after = cpu_ticks(pid);
    if (before < 0 || after < 0 || hz <= 0) {
        return -1;
    }
    return 100.0 * (double)(after - before) / (double)(hz * IDLE_SECONDS);
}

static void measure_idle(void)
{
    emu_t emu;
    double attached, detached;
    int fd;
    if (emu_start(&emu, NULL) != 0) {
        return;
    }
    fd = port_open(emu.slave);
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
