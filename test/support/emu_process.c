/* emu_process.c - see emu_process.h. */
#include "emu_process.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_clock.h"

#define EMU_ARGV_MAX 32
#define EMU_EXIT_POLL_MS 2  /* how often a wait checks whether the child is gone */
#define EMU_EOF_WAIT_MS 1000 /* after it is gone, how long its pipes may take to reach EOF */

void xgo_test_emu_init(xgo_test_emu_t *emu)
{
    memset(emu, 0, sizeof *emu);
    emu->pid = -1;
    emu->out_fd = -1;
    emu->err_fd = -1;
}

static void close_pipes(xgo_test_emu_t *emu)
{
    if (emu->out_fd >= 0) {
        close(emu->out_fd);
        emu->out_fd = -1;
    }
    if (emu->err_fd >= 0) {
        close(emu->err_fd);
        emu->err_fd = -1;
    }
}

void xgo_test_emu_reset(xgo_test_emu_t *emu)
{
    close_pipes(emu);
    xgo_test_emu_init(emu);
}

/* Appends whatever is readable now on fd (non-blocking) to buf, keeping it
 * NUL-terminated and dropping what does not fit. Returns 0 at EOF, 1
 * otherwise. */
static int drain_fd(int fd, char *buf, size_t cap, size_t *len)
{
    for (;;) {
        char tmp[4096];
        ssize_t n = read(fd, tmp, sizeof tmp);
        if (n > 0) {
            size_t keep = (size_t)n;
            if (keep > cap - 1 - *len) {
                keep = cap - 1 - *len;
            }
            memcpy(buf + *len, tmp, keep);
            *len += keep;
            buf[*len] = '\0';
            continue;
        }
        if (n == 0) {
            return 0;
        }
        if (errno == EINTR) {
            continue;
        }
        return 1; /* EAGAIN */
    }
}

/* Reads both pipes as far as they go now; a pipe at EOF is closed. */
static void drain(xgo_test_emu_t *emu)
{
    if (emu->err_fd >= 0 && !drain_fd(emu->err_fd, emu->err, sizeof emu->err, &emu->err_len)) {
        close(emu->err_fd);
        emu->err_fd = -1;
    }
    if (emu->out_fd >= 0 && !drain_fd(emu->out_fd, emu->out, sizeof emu->out, &emu->out_len)) {
        close(emu->out_fd);
        emu->out_fd = -1;
    }
}

/* Our ends of the pipes: non-blocking (drain never waits) and not inherited
 * by later children. */
static void set_read_end(int fd)
{
    fcntl(fd, F_SETFL, O_NONBLOCK);
    fcntl(fd, F_SETFD, FD_CLOEXEC);
}

int xgo_test_emu_spawn(xgo_test_emu_t *emu, const char *exe, const char *const *args,
                       const char *err_path)
{
    int out_pipe[2];
    int err_pipe[2] = {-1, -1};
    const char *argv[EMU_ARGV_MAX];
    size_t argc = 0;

    xgo_test_emu_reset(emu);
    argv[argc++] = exe;
    while (*args != NULL && argc < EMU_ARGV_MAX - 1) {
        argv[argc++] = *args++;
    }
    argv[argc] = NULL;

    if (pipe(out_pipe) != 0) {
        return -1;
    }
    if (err_path == NULL && pipe(err_pipe) != 0) {
        close(out_pipe[0]);
        close(out_pipe[1]);
        return -1;
    }
    emu->pid = fork();
    if (emu->pid == 0) {
        dup2(out_pipe[1], STDOUT_FILENO);
        close(out_pipe[0]);
        close(out_pipe[1]);
        if (err_path == NULL) {
            dup2(err_pipe[1], STDERR_FILENO);
            close(err_pipe[0]);
            close(err_pipe[1]);
        } else {
            int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (err >= 0) {
                dup2(err, STDERR_FILENO);
                if (err != STDERR_FILENO) {
                    close(err);
                }
            }
        }
        execv(exe, (char *const *)argv);
        _exit(127);
    }
    close(out_pipe[1]);
    if (err_pipe[1] >= 0) {
        close(err_pipe[1]);
    }
    if (emu->pid < 0) {
        close(out_pipe[0]);
        if (err_pipe[0] >= 0) {
            close(err_pipe[0]);
        }
        emu->pid = -1;
        return -1;
    }
    emu->out_fd = out_pipe[0];
    emu->err_fd = err_pipe[0];
    set_read_end(emu->out_fd);
    if (emu->err_fd >= 0) {
        set_read_end(emu->err_fd);
    }
    return 0;
}

int xgo_test_emu_read_pty(xgo_test_emu_t *emu, long timeout_ms)
{
    long long deadline = xgo_test_now_ms() + timeout_ms;
    char *nl;
    while ((nl = strchr(emu->out, '\n')) == NULL) {
        struct pollfd pfd;
        if (xgo_test_now_ms() >= deadline) {
            return XGO_TEST_EMU_PTY_TIMEOUT;
        }
        if (emu->out_fd < 0) {
            return XGO_TEST_EMU_PTY_CLOSED;
        }
        pfd.fd = emu->out_fd;
        pfd.events = POLLIN;
        poll(&pfd, 1, 50);
        drain(emu);
    }
    if ((size_t)(nl - emu->out) >= sizeof emu->pty) {
        return XGO_TEST_EMU_PTY_TOO_LONG;
    }
    memcpy(emu->pty, emu->out, (size_t)(nl - emu->out));
    emu->pty[nl - emu->out] = '\0';
    return XGO_TEST_EMU_PTY_OK;
}

int xgo_test_emu_wait(xgo_test_emu_t *emu, long timeout_ms)
{
    long long deadline = xgo_test_now_ms() + timeout_ms;
    while (emu->pid > 0) {
        int status;
        pid_t r = waitpid(emu->pid, &status, WNOHANG);
        drain(emu);
        if (r == emu->pid) {
            emu->status = status;
            emu->pid = -1;
            break;
        }
        if (xgo_test_now_ms() > deadline) {
            return 0;
        }
        xgo_test_sleep_ms(EMU_EXIT_POLL_MS);
    }
    /* Collect the rest of its output (EOF comes quickly once it is gone). */
    deadline = xgo_test_now_ms() + EMU_EOF_WAIT_MS;
    while ((emu->err_fd >= 0 || emu->out_fd >= 0) && xgo_test_now_ms() < deadline) {
        drain(emu);
        xgo_test_sleep_ms(EMU_EXIT_POLL_MS);
    }
    close_pipes(emu);
    return 1;
}

int xgo_test_emu_stop(xgo_test_emu_t *emu, int sig, long timeout_ms)
{
    if (emu->pid <= 0 || kill(emu->pid, sig) != 0) {
        return 0;
    }
    if (xgo_test_emu_wait(emu, timeout_ms)) {
        return 1;
    }
    xgo_test_emu_kill(emu);
    return 0;
}

void xgo_test_emu_kill(xgo_test_emu_t *emu)
{
    if (emu->pid > 0) {
        kill(emu->pid, SIGKILL);
        waitpid(emu->pid, NULL, 0);
    }
    xgo_test_emu_reset(emu);
}

long xgo_test_cpu_ticks(pid_t pid)
{
    char path[64];
    char buf[1024];
    const char *p;
    unsigned long utime, stime;
    FILE *f;
    size_t n;
    snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
    f = fopen(path, "r");
    if (f == NULL) {
        return -1;
    }
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    p = strrchr(buf, ')'); /* the command name may contain spaces */
    if (p == NULL ||
        sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &utime, &stime) != 2) {
        return -1;
    }
    return (long)(utime + stime);
}
