/*
 * state_file.c - the --state file: format, parse, atomic save, and keeping a
 * running board's non-volatile data saved (see state_file.h).
 *
 * Why the save is atomic: rename() replaces the directory entry in one step,
 * so any reader (or the next start after a crash) finds either the old file
 * or the complete new one. The new file's data is fsync'ed before the rename,
 * so after a power loss the entry never points at a file whose blocks were
 * not written yet; the directory is fsync'ed after it, so the rename itself
 * is durable once the save returns. The CRC line catches anything the
 * storage mangles anyway, and a damaged file is refused, never overwritten.
 */
#include "state_file.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#define XGO_HOST_STATE_HEADER "xgo-state "
#define XGO_HOST_STATE_KEY_NAME "bt_name="
#define XGO_HOST_STATE_KEY_OFFSETS "zero_offsets_mdeg="
#define XGO_HOST_STATE_KEY_CRC "crc32="
/* "crc32=" + 8 hex digits + "\n" */
#define XGO_HOST_STATE_CRC_LINE_LEN 15u
#define XGO_HOST_STATE_TMP_INFIX ".tmp."
/* Paths longer than this are refused (Linux's PATH_MAX). */
#define XGO_HOST_STATE_PATH_MAX 4096u

/* CRC-32 as zlib, Python's zlib.crc32 and `gzip` compute it (reflected
 * 0xEDB88320), so a file can be checked or re-signed with standard tools.
 * Bitwise: the file is ~150 bytes and saved rarely. */
static uint32_t xgo_host_crc32(const char *p, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    while (n-- > 0) {
        int k;
        crc ^= (uint8_t)*p++;
        for (k = 0; k < 8; k++) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return crc ^ 0xFFFFFFFFu;
}

/* Did snprintf's output (n) fit in room bytes? */
static int xgo_host_fits(int n, size_t room)
{
    return n >= 0 && (size_t)n < room;
}

size_t xgo_host_state_format(const xgo_board_nv_t *nv, char *buf, size_t size)
{
    size_t name_len = 0;
    size_t at;
    unsigned i;
    int n;
    while (name_len < XGO_BT_NAME_LEN && nv->bt_name[name_len] != '\0') {
        name_len++;
    }
    n = snprintf(buf, size, XGO_HOST_STATE_HEADER "%d\n" XGO_HOST_STATE_KEY_NAME "%.*s\n"
                 XGO_HOST_STATE_KEY_OFFSETS, XGO_HOST_STATE_VERSION, (int)name_len, nv->bt_name);
    if (!xgo_host_fits(n, size)) {
        return 0;
    }
    at = (size_t)n;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        n = snprintf(buf + at, size - at, "%s%ld\n", i == 0 ? "" : " ",
                     (long)nv->zero_offset_mdeg[i]);
        if (!xgo_host_fits(n, size - at)) {
            return 0;
        }
        at += (size_t)n - 1; /* the newline stays only after the last value */
    }
    at++;
    n = snprintf(buf + at, size - at, XGO_HOST_STATE_KEY_CRC "%08lx\n",
                 (unsigned long)xgo_host_crc32(buf, at));
    if (!xgo_host_fits(n, size - at)) {
        return 0;
    }
    return at + (size_t)n;
}

/* ----------------------------------------------------------------- parse */

/* Cuts the next '\n'-terminated line off [*p, end). */
static int xgo_host_next_line(const char **p, const char *end, const char **line, size_t *len)
{
    const char *nl = memchr(*p, '\n', (size_t)(end - *p));
    if (nl == NULL) {
        return 0;
    }
    *line = *p;
    *len = (size_t)(nl - *p);
    *p = nl + 1;
    return 1;
}

static int xgo_host_has_prefix(const char *line, size_t len, const char *prefix)
{
    size_t n = strlen(prefix);
    return len >= n && memcmp(line, prefix, n) == 0;
}

/* Lower case only, as written: one spelling per file, so any flipped bit
 * is caught. */
static int xgo_host_hex_digit(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    return -1;
}

/* The last line must be the CRC of everything before it. *body_end: where
 * that line starts. */
static int xgo_host_check_crc(const char *text, size_t len, size_t *body_end, char *err,
                              size_t err_size)
{
    const char *line;
    uint32_t want = 0;
    uint32_t got;
    unsigned i;
    if (len < XGO_HOST_STATE_CRC_LINE_LEN + 1 || text[len - 1] != '\n') {
        snprintf(err, err_size, "incomplete (no crc32 line at the end)");
        return 0;
    }
    line = text + len - XGO_HOST_STATE_CRC_LINE_LEN;
    if (line[-1] != '\n' || memcmp(line, XGO_HOST_STATE_KEY_CRC, 6) != 0) {
        snprintf(err, err_size, "incomplete or damaged (no crc32 line at the end)");
        return 0;
    }
    for (i = 0; i < 8; i++) {
        int d = xgo_host_hex_digit(line[6 + i]);
        if (d < 0) {
            snprintf(err, err_size, "damaged (crc32 is not 8 lower-case hex digits)");
            return 0;
        }
        want = (want << 4) | (uint32_t)d;
    }
    got = xgo_host_crc32(text, (size_t)(line - text));
    if (got != want) {
        snprintf(err, err_size, "damaged or edited (crc32 says %08lx, contents give %08lx)",
                 (unsigned long)want, (unsigned long)got);
        return 0;
    }
    *body_end = (size_t)(line - text);
    return 1;
}

static int xgo_host_parse_name(const char *s, size_t len, char name[XGO_BT_NAME_LEN])
{
    size_t i;
    if (len == 0 || len > XGO_BT_NAME_LEN) {
        return 0;
    }
    memset(name, 0, XGO_BT_NAME_LEN);
    for (i = 0; i < len; i++) {
        if ((unsigned char)s[i] < 0x20 || (unsigned char)s[i] > 0x7E) {
            return 0;
        }
        name[i] = s[i];
    }
    return 1;
}

/* Exactly XGO_SERVO_COUNT decimal int32 values, single spaces between. */
static int xgo_host_parse_offsets(const char *s, size_t len, int32_t out[XGO_SERVO_COUNT])
{
    size_t at = 0;
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        int64_t v = 0;
        int neg = 0;
        unsigned digits = 0;
        if (i > 0) {
            if (at >= len || s[at] != ' ') {
                return 0;
            }
            at++;
        }
        if (at < len && s[at] == '-') {
            neg = 1;
            at++;
        }
        for (; at < len && s[at] >= '0' && s[at] <= '9'; at++) {
            if (++digits > 10) {
                return 0; /* beyond int32 anyway; keeps v from overflowing */
            }
            v = v * 10 + (s[at] - '0');
        }
        v = neg ? -v : v;
        if (digits == 0 || v < INT32_MIN || v > INT32_MAX) {
            return 0;
        }
        out[i] = (int32_t)v;
    }
    return at == len;
}

/* Up to 40 characters of a line for a message, control bytes as \xNN. */
static void xgo_host_quote(const char *s, size_t len, char *out, size_t size)
{
    size_t i, at = 0;
    out[0] = '\0';
    for (i = 0; i < len && i < 40 && at + 5 < size; i++) {
        const unsigned char c = (unsigned char)s[i];
        at += (size_t)snprintf(out + at, size - at, (c >= 0x20 && c < 0x7F) ? "%c" : "\\x%02X", c);
    }
}

int xgo_host_state_parse(const char *text, size_t len, xgo_board_nv_t *nv, char *err,
                         size_t err_size)
{
    char quoted[4 * 40 + 1];
    const char *p = text;
    const char *end;
    const char *line;
    size_t line_len;
    size_t body_end;

    /* The header first: a file that is not ours at all deserves that
     * message rather than "bad crc". */
    if (!xgo_host_next_line(&p, text + len, &line, &line_len) ||
        !xgo_host_has_prefix(line, line_len, XGO_HOST_STATE_HEADER)) {
        snprintf(err, err_size, "not an xgo-emu state file (no 'xgo-state 1' first line)");
        return -1;
    }
    /* An editor that saved it with CR LF: say so, rather than quote a CR. */
    if (memchr(text, '\r', len) != NULL) {
        snprintf(err, err_size, "line endings must be LF, this file has CR LF (or a stray CR)");
        return -1;
    }
    if (line_len != strlen(XGO_HOST_STATE_HEADER) + 1 || line[line_len - 1] != '1') {
        xgo_host_quote(line, line_len, quoted, sizeof quoted);
        snprintf(err, err_size, "unsupported format '%s' (this xgo-emu reads 'xgo-state 1')",
                 quoted);
        return -1;
    }
    if (!xgo_host_check_crc(text, len, &body_end, err, err_size)) {
        return -1;
    }
    end = text + body_end;
    if (!xgo_host_next_line(&p, end, &line, &line_len) ||
        !xgo_host_has_prefix(line, line_len, XGO_HOST_STATE_KEY_NAME) ||
        !xgo_host_parse_name(line + 8, line_len - 8, nv->bt_name)) {
        snprintf(err, err_size, "line 2 must be bt_name= and 1..10 printable ASCII characters");
        return -1;
    }
    if (!xgo_host_next_line(&p, end, &line, &line_len) ||
        !xgo_host_has_prefix(line, line_len, XGO_HOST_STATE_KEY_OFFSETS) ||
        !xgo_host_parse_offsets(line + 18, line_len - 18, nv->zero_offset_mdeg)) {
        snprintf(err, err_size, "line 3 must be zero_offsets_mdeg= and 12 whole numbers");
        return -1;
    }
    if (p != end) {
        snprintf(err, err_size, "unexpected lines before the crc32 line");
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ file I/O */

/* "a FIFO", "a directory", ... for a message. */
static const char *xgo_host_file_kind(const struct stat *st)
{
    if (S_ISFIFO(st->st_mode)) {
        return "a FIFO";
    }
    if (S_ISDIR(st->st_mode)) {
        return "a directory";
    }
    if (S_ISCHR(st->st_mode)) {
        return "a character device";
    }
    if (S_ISBLK(st->st_mode)) {
        return "a block device";
    }
    if (S_ISSOCK(st->st_mode)) {
        return "a socket";
    }
    return "not a file";
}

xgo_host_state_load_t xgo_host_state_load(const char *path, xgo_board_nv_t *nv, char *err,
                                          size_t err_size)
{
    char buf[XGO_HOST_STATE_MAX_BYTES + 1];
    size_t len = 0;
    struct stat st;
    /* O_NONBLOCK: opening a FIFO for reading would wait for a writer. */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) {
        if (errno == ENOENT) {
            return XGO_HOST_STATE_MISSING;
        }
        snprintf(err, err_size, "cannot open: %s", strerror(errno));
        return XGO_HOST_STATE_BAD;
    }
    if (fstat(fd, &st) != 0) {
        snprintf(err, err_size, "cannot stat: %s", strerror(errno));
        close(fd);
        return XGO_HOST_STATE_BAD;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(err, err_size, "not a regular file (%s)", xgo_host_file_kind(&st));
        close(fd);
        return XGO_HOST_STATE_BAD;
    }
    while (len < sizeof buf) {
        ssize_t n = read(fd, buf + len, sizeof buf - len);
        if (n == 0) {
            break;
        }
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            snprintf(err, err_size, "cannot read: %s", strerror(errno));
            close(fd);
            return XGO_HOST_STATE_BAD;
        }
        len += (size_t)n;
    }
    close(fd);
    if (len > XGO_HOST_STATE_MAX_BYTES) {
        snprintf(err, err_size, "too large to be an xgo-emu state file");
        return XGO_HOST_STATE_BAD;
    }
    return xgo_host_state_parse(buf, len, nv, err, err_size) == 0 ? XGO_HOST_STATE_LOADED
                                                             : XGO_HOST_STATE_BAD;
}

/* The directory part of path (into dir) and the last component. NULL if the
 * path is too long. */
static const char *xgo_host_split_path(const char *path, char *dir, size_t size)
{
    const char *slash = strrchr(path, '/');
    int n;
    if (slash == NULL) {
        n = snprintf(dir, size, ".");
    } else if (slash == path) {
        n = snprintf(dir, size, "/");
    } else {
        n = snprintf(dir, size, "%.*s", (int)(slash - path), path);
    }
    if (n < 0 || (size_t)n >= size) {
        return NULL;
    }
    return slash == NULL ? path : slash + 1;
}

static int xgo_host_write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w <= 0) {
            if (w == 0) {
                errno = EIO;
            }
            return -1;
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

/* The rename is only durable once the directory is on disk too. Some file
 * systems cannot fsync a directory (EINVAL): nothing more can be done there. */
static int xgo_host_sync_dir(const char *path)
{
    char dir[XGO_HOST_STATE_PATH_MAX];
    int fd;
    int rc;
    if (xgo_host_split_path(path, dir, sizeof dir) == NULL) {
        errno = ENAMETOOLONG;
        return -1;
    }
    fd = open(dir, O_RDONLY | O_CLOEXEC | O_DIRECTORY);
    if (fd < 0) {
        return -1;
    }
    rc = fsync(fd);
    if (rc != 0 && errno == EINVAL) {
        rc = 0;
    }
    close(fd);
    return rc;
}

/* Creates the temporary file: a fresh name (tmp: "PATH.tmp.<pid>.XXXXXX",
 * filled in) that nobody else can have prepared, mode 0600. mkstemp opens
 * with O_CREAT | O_EXCL, so whatever sits at a name it tries (a FIFO, a
 * symlink, another user's file) is never opened: it tries another name. */
static int xgo_host_create_tmp(char *tmp)
{
    int fd = mkstemp(tmp);
    int fl;
    if (fd < 0) {
        return -1;
    }
    fl = fcntl(fd, F_GETFD);
    if (fl >= 0) {
        (void)fcntl(fd, F_SETFD, fl | FD_CLOEXEC);
    }
    return fd;
}

/* Writes, flushes and closes the temporary file. A replaced regular file
 * keeps its permission bits (best effort); a new file, or one replacing a
 * symlink or anything else, stays 0600. lstat: a symlink's target is not
 * ours to copy from. */
static int xgo_host_write_tmp(int fd, const char *path, const char *text, size_t len)
{
    struct stat st;
    int saved;
    if (lstat(path, &st) == 0 && S_ISREG(st.st_mode)) {
        (void)fchmod(fd, st.st_mode & 0777);
    }
    if (xgo_host_write_all(fd, text, len) != 0 || fsync(fd) != 0) {
        saved = errno;
        close(fd);
        errno = saved;
        return -1;
    }
    return close(fd);
}

int xgo_host_state_save(const char *path, const xgo_board_nv_t *nv, char *err, size_t err_size)
{
    char text[XGO_HOST_STATE_MAX_BYTES];
    char tmp[XGO_HOST_STATE_PATH_MAX];
    size_t len = xgo_host_state_format(nv, text, sizeof text);
    int n = snprintf(tmp, sizeof tmp, "%s" XGO_HOST_STATE_TMP_INFIX "%ld.XXXXXX", path,
                     (long)getpid());
    int fd;
    if (len == 0 || n < 0 || (size_t)n >= sizeof tmp) {
        snprintf(err, err_size, "path too long");
        return -1;
    }
    fd = xgo_host_create_tmp(tmp);
    if (fd < 0) {
        snprintf(err, err_size, "cannot create a temporary file next to it: %s", strerror(errno));
        return -1;
    }
    if (xgo_host_write_tmp(fd, path, text, len) != 0) {
        snprintf(err, err_size, "cannot write %s: %s", tmp, strerror(errno));
        (void)unlink(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        snprintf(err, err_size, "cannot rename %s over it: %s", tmp, strerror(errno));
        (void)unlink(tmp);
        return -1;
    }
    if (xgo_host_sync_dir(path) != 0) {
        snprintf(err, err_size, "saved, but cannot fsync its directory: %s", strerror(errno));
        return -1;
    }
    return 0;
}

/* Is name "<base>.tmp.<pid>.XXXXXX" (or "<base>.tmp.<pid>", as earlier
 * versions named it)? */
static int xgo_host_tmp_pid(const char *name, const char *base, long *pid)
{
    size_t base_len = strlen(base);
    const char *p;
    long v = 0;
    unsigned digits = 0;
    if (strncmp(name, base, base_len) != 0 ||
        strncmp(name + base_len, XGO_HOST_STATE_TMP_INFIX, 5) != 0) {
        return 0;
    }
    for (p = name + base_len + 5; *p >= '0' && *p <= '9'; p++) {
        if (++digits > 9) {
            return 0;
        }
        v = v * 10 + (*p - '0');
    }
    if (digits == 0 || (*p != '\0' && (*p != '.' || strlen(p + 1) != 6))) {
        return 0;
    }
    *pid = v;
    return v > 0;
}

int xgo_host_state_remove_stale(const char *path)
{
    char dir[XGO_HOST_STATE_PATH_MAX];
    char full[XGO_HOST_STATE_PATH_MAX];
    const char *base = xgo_host_split_path(path, dir, sizeof dir);
    struct dirent *e;
    struct stat st;
    DIR *d;
    int removed = 0;
    if (base == NULL || *base == '\0' || (d = opendir(dir)) == NULL) {
        return 0;
    }
    while ((e = readdir(d)) != NULL) {
        long pid;
        int n;
        if (!xgo_host_tmp_pid(e->d_name, base, &pid)) {
            continue;
        }
        /* A live process (or one we may not signal: EPERM) may be in the
         * middle of its own save: not ours to remove. */
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) {
            continue;
        }
        n = snprintf(full, sizeof full, "%s/%s", dir, e->d_name);
        /* Only what a save of ours can have left: a regular file we own. */
        if (n > 0 && (size_t)n < sizeof full && lstat(full, &st) == 0 && S_ISREG(st.st_mode) &&
            st.st_uid == geteuid() && unlink(full) == 0) {
            removed++;
        }
    }
    closedir(d);
    return removed;
}

/* ------------------------------------------------ keeping a board saved */

/* Field by field: the struct has padding. */
static int xgo_host_nv_equal(const xgo_board_nv_t *a, const xgo_board_nv_t *b)
{
    return memcmp(a->bt_name, b->bt_name, sizeof a->bt_name) == 0 &&
           memcmp(a->zero_offset_mdeg, b->zero_offset_mdeg, sizeof a->zero_offset_mdeg) == 0;
}

int xgo_host_state_open(xgo_host_state_t *s, const char *path, char *err, size_t err_size)
{
    char why[XGO_HOST_STATE_PATH_MAX + 128];
    memset(s, 0, sizeof *s);
    s->path = path;
    (void)xgo_host_state_remove_stale(path);
    switch (xgo_host_state_load(path, &s->saved, why, sizeof why)) {
    case XGO_HOST_STATE_LOADED:
        s->loaded = 1;
        break;
    case XGO_HOST_STATE_MISSING:
        break;
    case XGO_HOST_STATE_BAD:
        snprintf(err, err_size, "--state %s: %s; refusing to start, fix or remove the file", path,
                 why);
        return -1;
    }
    return 0;
}

int xgo_host_state_loaded(const xgo_host_state_t *s, xgo_board_nv_t *nv)
{
    if (s->loaded) {
        *nv = s->saved;
    }
    return s->loaded;
}

int xgo_host_state_check(xgo_host_state_t *s, const xgo_board_t *b, char *err, size_t err_size)
{
    char why[XGO_HOST_STATE_PATH_MAX + 128];
    xgo_board_nv_t nv;
    xgo_board_get_nv(b, &nv);
    if (s->loaded) {
        if (!xgo_host_nv_equal(&nv, &s->saved)) { /* the board kept its defaults */
            snprintf(err, err_size,
                     "--state %s: values out of range (bt_name 1..10 printable ASCII, zero "
                     "offsets within +-360000 mdeg); refusing to start, fix or remove the file",
                     s->path);
            return -1;
        }
        return 0;
    }
    if (xgo_host_state_save(s->path, &nv, why, sizeof why) != 0) {
        snprintf(err, err_size, "--state %s: %s", s->path, why);
        return -1;
    }
    s->saved = nv;
    return 0;
}

static int xgo_host_state_save_nv(xgo_host_state_t *s, const xgo_board_nv_t *nv, FILE *log,
                                  const char *after_failure)
{
    char why[XGO_HOST_STATE_PATH_MAX + 128];
    if (xgo_host_state_save(s->path, nv, why, sizeof why) != 0) {
        if (!s->failed || !xgo_host_nv_equal(nv, &s->failed_nv)) {
            fprintf(log, "xgo-emu: --state %s: %s (%s)\n", s->path, why, after_failure);
        }
        s->failed = 1;
        s->failed_nv = *nv;
        return -1;
    }
    s->failed = 0;
    s->saved = *nv;
    return 0;
}

int xgo_host_state_store(xgo_host_state_t *s, const xgo_board_nv_t *nv, FILE *log)
{
    if (!s->failed && xgo_host_nv_equal(nv, &s->saved)) {
        return 0;
    }
    return xgo_host_state_save_nv(s, nv, log, "retrying while serving and at exit");
}

int xgo_host_state_close(xgo_host_state_t *s, const xgo_board_t *b, FILE *log)
{
    xgo_board_nv_t nv;
    xgo_board_get_nv(b, &nv);
    if (!s->failed && xgo_host_nv_equal(&nv, &s->saved)) {
        return 0;
    }
    s->failed = 0; /* the last word: always reported */
    return xgo_host_state_save_nv(s, &nv, log, "the last changes are lost");
}
