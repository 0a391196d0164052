/* link.c - create and remove the --link symlink (see link.h). */
#include "link.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Is old_target a name in the directory that holds our pty (say
 * /dev/pts/7 next to our /dev/pts/3)? */
static int xgo_host_link_in_pty_dir(const char *old_target, const char *pty)
{
    const char *slash = strrchr(pty, '/');
    size_t dir_len;
    if (slash == NULL) {
        return 0;
    }
    dir_len = (size_t)(slash - pty) + 1; /* with the slash */
    return strncmp(old_target, pty, dir_len) == 0 && old_target[dir_len] != '\0' &&
           strchr(old_target + dir_len, '/') == NULL;
}

/* May the existing symlink at link_path be replaced? Only a stale one of an
 * emulator's: it points into the pty directory at a pty that no longer
 * exists (or already at ours). Anything else belongs to someone: a dotfile
 * link, another device's name, a running emulator's pty. */
static int xgo_host_link_may_replace(const char *link_path, const char *target, char *old,
                                     size_t old_size, char *err, size_t err_size)
{
    struct stat st;
    ssize_t n = readlink(link_path, old, old_size - 1);
    if (n < 0) {
        snprintf(err, err_size, "--link %s: %s", link_path, strerror(errno));
        return 0;
    }
    old[n] = '\0';
    if (strcmp(old, target) == 0) {
        return 1; /* our pty got the number of the one it named */
    }
    if (!xgo_host_link_in_pty_dir(old, target)) {
        snprintf(err, err_size,
                 "--link %s: is a symlink to %s, not to a pty; refusing to replace it", link_path,
                 old);
        return 0;
    }
    if (stat(link_path, &st) == 0 || errno != ENOENT) {
        snprintf(err, err_size,
                 "--link %s: is a symlink to %s, a pty that exists (another emulator or device "
                 "uses this name); refusing to replace it",
                 link_path, old);
        return 0;
    }
    return 1;
}

/* Replace via rename() so the path never disappears: a host retrying its
 * open during our start-up sees either the old link or the new one. */
static int xgo_host_link_replace(const char *link_path, const char *target, char *err,
                                 size_t err_size)
{
    char tmp_path[4096];
    struct stat st;
    if ((size_t)snprintf(tmp_path, sizeof tmp_path, "%s.xgo-emu-%ld.tmp", link_path,
                         (long)getpid()) >= sizeof tmp_path) {
        snprintf(err, err_size, "--link %s: path too long", link_path);
        return -1;
    }
    if (lstat(tmp_path, &st) == 0 && S_ISLNK(st.st_mode)) {
        unlink(tmp_path); /* leftover of a crashed run that had our pid */
    }
    if (symlink(target, tmp_path) != 0) {
        snprintf(err, err_size, "--link %s: cannot create symlink: %s", tmp_path,
                 strerror(errno));
        return -1;
    }
    if (rename(tmp_path, link_path) != 0) {
        snprintf(err, err_size, "--link %s: cannot replace symlink: %s", link_path,
                 strerror(errno));
        unlink(tmp_path);
        return -1;
    }
    return 0;
}

int xgo_host_link_create(const char *link_path, const char *target, char *replaced,
                         size_t replaced_size, char *err, size_t err_size)
{
    struct stat st;

    replaced[0] = '\0';
    if (symlink(target, link_path) == 0) {
        return 0;
    }
    if (errno != EEXIST) {
        snprintf(err, err_size, "--link %s: cannot create symlink: %s", link_path,
                 strerror(errno));
        return -1;
    }
    if (lstat(link_path, &st) != 0) {
        snprintf(err, err_size, "--link %s: %s", link_path, strerror(errno));
        return -1;
    }
    if (!S_ISLNK(st.st_mode)) {
        snprintf(err, err_size, "--link %s: exists and is not a symlink, refusing to replace it",
                 link_path);
        return -1;
    }
    if (!xgo_host_link_may_replace(link_path, target, replaced, replaced_size, err, err_size) ||
        xgo_host_link_replace(link_path, target, err, err_size) != 0) {
        replaced[0] = '\0';
        return -1;
    }
    return 0;
}

int xgo_host_link_remove_if_ours(const char *link_path, const char *target)
{
    char current[4096];
    ssize_t n = readlink(link_path, current, sizeof current - 1);
    if (n < 0) {
        return 0; /* gone already, or no longer a symlink */
    }
    current[n] = '\0';
    if (strcmp(current, target) != 0) {
        return 0;
    }
    return unlink(link_path) == 0;
}
