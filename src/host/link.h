/*
 * link.h - the --link symlink: a stable path (say /tmp/xgo) for a pty whose
 * own name (/dev/pts/N) changes every run.
 */
#ifndef XGO_HOST_LINK_H
#define XGO_HOST_LINK_H

#include <stddef.h>

/* Makes link_path a symlink to target (our pty). An existing symlink there
 * is replaced (atomically) only when it is stale: it points into the pty
 * directory (target's) at a pty that no longer exists, as one left by a
 * killed emulator does. A symlink to anything else (a dotfile, another
 * device) or to a pty that exists (another emulator uses that name) is
 * refused, and so is anything that is not a symlink. Returns 0, or -1 with
 * a message naming what is there in err. On a replacement, replaced
 * (replaced_size bytes) gets the old link's target, else "". */
int xgo_host_link_create(const char *link_path, const char *target, char *replaced,
                         size_t replaced_size, char *err, size_t err_size);

/* Removes link_path only if it is still a symlink to target: if someone
 * re-pointed it meanwhile (another emulator, say), it is theirs now.
 * Returns 1 if removed, 0 if left alone. */
int xgo_host_link_remove_if_ours(const char *link_path, const char *target);

#endif /* XGO_HOST_LINK_H */
