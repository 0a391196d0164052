/* link.c - create and remove the --link symlink (see link.h). */
#include "link.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int xgo_host_link_create(const char *link_path, const char *target, int *replaced, char *err,
                         size_t err_size)
{
    struct stat st;
    char tmp_path[4096];

    *replaced = 0;
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

    /* Replace via rename() so the path never disappears: a host retrying its
     * open during our start-up sees either the old link or the new one. */
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
    *replaced = 1;
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
