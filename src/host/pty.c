/* pty.c - pseudo-terminal setup for xgo-emu (see pty.h). */
#include "pty.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "serial.h"

static int xgo_host_pty_set_flags(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    int fdfl = fcntl(fd, F_GETFD);
    if (fl < 0 || fdfl < 0) {
        return -1;
    }
    if (fcntl(fd, F_SETFL, fl | O_NONBLOCK) != 0) {
        return -1;
    }
    return fcntl(fd, F_SETFD, fdfl | FD_CLOEXEC);
}

int xgo_host_pty_open(xgo_host_pty_t *pty, char *err, size_t err_size)
{
    const char *name;
    int slave_fd;

    memset(pty, 0, sizeof *pty);
    pty->master_fd = posix_openpt(O_RDWR | O_NOCTTY);
    if (pty->master_fd < 0) {
        snprintf(err, err_size, "posix_openpt: %s", strerror(errno));
        return -1;
    }
    if (grantpt(pty->master_fd) != 0 || unlockpt(pty->master_fd) != 0) {
        snprintf(err, err_size, "grantpt/unlockpt: %s", strerror(errno));
        goto fail;
    }
    name = ptsname(pty->master_fd);
    if (name == NULL || strlen(name) >= sizeof pty->slave_path) {
        snprintf(err, err_size, "ptsname: %s", name == NULL ? strerror(errno) : "path too long");
        goto fail;
    }
    strcpy(pty->slave_path, name);

    /* Configure through a slave fd: portable (the master's termios is the
     * slave's only on some systems). The settings outlive this fd because
     * the master keeps the tty alive; closing it leaves the master in the
     * "no host" state, which the event loop handles anyway. */
    slave_fd = open(pty->slave_path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (slave_fd < 0) {
        snprintf(err, err_size, "open %s: %s", pty->slave_path, strerror(errno));
        goto fail;
    }
    /* What a freshly powered board's UART looks like to a host that opens
     * the port without configuring anything. */
    if (xgo_host_serial_make_raw(slave_fd, XGO_HOST_DEFAULT_BAUD) != 0) {
        snprintf(err, err_size, "raw mode on %s: %s", pty->slave_path, strerror(errno));
        close(slave_fd);
        goto fail;
    }
    close(slave_fd);

    if (xgo_host_pty_set_flags(pty->master_fd) != 0) {
        snprintf(err, err_size, "fcntl on the pty master: %s", strerror(errno));
        goto fail;
    }
    return 0;

fail:
    close(pty->master_fd);
    pty->master_fd = -1;
    return -1;
}

void xgo_host_pty_close(xgo_host_pty_t *pty)
{
    if (pty->master_fd >= 0) {
        close(pty->master_fd);
        pty->master_fd = -1;
    }
}

uint32_t xgo_host_pty_host_baud(const xgo_host_pty_t *pty)
{
    struct termios tio;
    if (tcgetattr(pty->master_fd, &tio) != 0) {
        return 0;
    }
    return xgo_host_serial_baud_of(cfgetospeed(&tio));
}

void xgo_host_pty_discard_unread(const xgo_host_pty_t *pty)
{
    int fd = open(pty->slave_path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd >= 0) {
        tcflush(fd, TCIFLUSH);
        close(fd);
    }
}
