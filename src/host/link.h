/*
 * link.h - the --link symlink: a stable path (say /tmp/xgo) for a pty whose
 * own name (/dev/pts/N) changes every run.
 */
#ifndef XGO_HOST_LINK_H
#define XGO_HOST_LINK_H

#include <stddef.h>

/* Makes link_path a symlink to target. An existing symlink there (a stale
 * one from an earlier run, typically) is replaced atomically; anything else
 * (file, directory, ...) is refused. Returns 0, or -1 with a message in err.
 * *replaced is set to 1 when an old symlink was replaced. */
int xgo_host_link_create(const char *link_path, const char *target, int *replaced, char *err,
                         size_t err_size);

/* Removes link_path only if it is still a symlink to target: if someone
 * re-pointed it meanwhile (another emulator, say), it is theirs now.
 * Returns 1 if removed, 0 if left alone. */
int xgo_host_link_remove_if_ours(const char *link_path, const char *target);

#endif /* XGO_HOST_LINK_H */
