/*
 * emu_process.h - an xgo-emu child process for the programs that drive it
 * end to end (test_pty_integration, test_host_state, bench_latency).
 *
 * One child at a time per xgo_test_emu_t: fork/exec with stdout on a pipe
 * (its first line is the pty path, the rest is kept in `out`) and stderr
 * either captured through a pipe into `err` or sent to a file. Every wait is
 * bounded by a timeout, so a broken emulator fails the caller instead of
 * hanging it. Nothing here asserts: results are return codes, and the Unity
 * tests assert on them while the bench just reports.
 */
#ifndef XGO_TEST_EMU_PROCESS_H
#define XGO_TEST_EMU_PROCESS_H

#include <stddef.h>
#include <sys/types.h>

#define XGO_TEST_EMU_OUT_CAP 65536u /* stdout kept (the path, --help, a program's output) */
#define XGO_TEST_EMU_ERR_CAP 65536u /* stderr kept (traces, counters at exit) */

typedef struct xgo_test_emu_s {
    pid_t pid;    /* -1: none running (never started, or reaped) */
    int out_fd;   /* read end of its stdout, -1 once at EOF or closed */
    int err_fd;   /* read end of its stderr when captured, else -1 */
    char pty[256]; /* the first stdout line, once xgo_test_emu_read_pty saw it */
    char out[XGO_TEST_EMU_OUT_CAP]; /* stdout so far, NUL-terminated */
    size_t out_len;
    char err[XGO_TEST_EMU_ERR_CAP]; /* captured stderr so far, NUL-terminated */
    size_t err_len;
    int status; /* waitpid status once reaped */
} xgo_test_emu_t;

/* Results of xgo_test_emu_read_pty. */
#define XGO_TEST_EMU_PTY_OK 1
#define XGO_TEST_EMU_PTY_CLOSED 0    /* stdout closed (it exited) before a line */
#define XGO_TEST_EMU_PTY_TIMEOUT -1  /* no whole line within the timeout */
#define XGO_TEST_EMU_PTY_TOO_LONG -2 /* the line does not fit `pty` */

/* Nothing running, no descriptors: call once before first use (a zeroed
 * struct would name descriptor 0). */
void xgo_test_emu_init(xgo_test_emu_t *emu);

/* Starts exe with argv[1..] = args (NULL-terminated, at most 30 used).
 * stderr goes to a pipe read into emu->err when err_path is NULL, else to
 * the file err_path (created or truncated, mode 0644). Output of a previous
 * child is forgotten. Returns 0, or -1 if pipe() or fork() failed. */
int xgo_test_emu_spawn(xgo_test_emu_t *emu, const char *exe, const char *const *args,
                       const char *err_path);

/* Waits up to timeout_ms for the first stdout line (the pty path) and
 * copies it into emu->pty; returns XGO_TEST_EMU_PTY_*. */
int xgo_test_emu_read_pty(xgo_test_emu_t *emu, long timeout_ms);

/* Waits up to timeout_ms for the child to exit, capturing its output
 * meanwhile; once it has, collects what it left in the pipes (up to 1 s more
 * for EOF), closes them and returns 1 with emu->status set. 0: still running
 * at the timeout. 1 at once when no child is running. */
int xgo_test_emu_wait(xgo_test_emu_t *emu, long timeout_ms);

/* Sends sig and waits up to timeout_ms as xgo_test_emu_wait does; returns 1
 * if the child exited. If kill() fails returns 0 and leaves the child alone;
 * if it is still running at the timeout, it is killed (SIGKILL), reaped and
 * forgotten, and 0 is returned. */
int xgo_test_emu_stop(xgo_test_emu_t *emu, int sig, long timeout_ms);

/* SIGKILL and reap a running child, then xgo_test_emu_reset. */
void xgo_test_emu_kill(xgo_test_emu_t *emu);

/* Forgets an exited child: closes what is left of its pipes, clears the
 * captured output. */
void xgo_test_emu_reset(xgo_test_emu_t *emu);

/* CPU time (user + system) process pid has used, in clock ticks
 * (sysconf(_SC_CLK_TCK)); -1 when /proc/PID/stat is not available. */
long xgo_test_cpu_ticks(pid_t pid);

#endif /* XGO_TEST_EMU_PROCESS_H */
