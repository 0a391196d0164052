/* pty.c - pseudo-terminal setup for xgo-emu (see pty.h). */
#include "pty.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

/* The slave's settings: what a freshly powered board's UART would look like
 * to a host that opens it without configuring anything. */
static int xgo_host_pty_make_raw(int fd)
{
    struct termios tio;
    if (tcgetattr(fd, &tio) != 0) {
        return -1;
    }
    cfmakeraw(&tio); /* no echo, no CR/NL mapping, no XON/XOFF, no signals */
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (cfsetispeed(&tio, B115200) != 0 || cfsetospeed(&tio, B115200) != 0) {
        return -1;
    }
    return tcsetattr(fd, TCSANOW, &tio);
}

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
    if (xgo_host_pty_make_raw(slave_fd) != 0) {
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

typedef struct xgo_host_speed_s {
    speed_t code;
    uint32_t bits_per_s;
} xgo_host_speed_t;

/* speed_t is an opaque code on Linux (B115200 != 115200): map the ones a
 * host may plausibly choose. */
static const xgo_host_speed_t xgo_host_speeds[] = {
    {B50, 50},         {B75, 75},         {B110, 110},       {B134, 134},
    {B150, 150},       {B200, 200},       {B300, 300},       {B600, 600},
    {B1200, 1200},     {B1800, 1800},     {B2400, 2400},     {B4800, 4800},
    {B9600, 9600},     {B19200, 19200},   {B38400, 38400},
#ifdef B57600
    {B57600, 57600},
#endif
#ifdef B115200
    {B115200, 115200},
#endif
#ifdef B230400
    {B230400, 230400},
#endif
#ifdef B460800
    {B460800, 460800},
#endif
#ifdef B500000
    {B500000, 500000},
#endif
#ifdef B576000
    {B576000, 576000},
#endif
#ifdef B921600
    {B921600, 921600},
#endif
#ifdef B1000000
    {B1000000, 1000000},
#endif
#ifdef B1500000
    {B1500000, 1500000},
#endif
#ifdef B2000000
    {B2000000, 2000000},
#endif
#ifdef B3000000
    {B3000000, 3000000},
#endif
#ifdef B4000000
    {B4000000, 4000000},
#endif
};

uint32_t xgo_host_pty_host_baud(const xgo_host_pty_t *pty)
{
    struct termios tio;
    speed_t code;
    size_t i;
    if (tcgetattr(pty->master_fd, &tio) != 0) {
        return 0;
    }
    code = cfgetospeed(&tio);
    for (i = 0; i < sizeof xgo_host_speeds / sizeof xgo_host_speeds[0]; i++) {
        if (xgo_host_speeds[i].code == code) {
            return xgo_host_speeds[i].bits_per_s;
        }
    }
    return 0; /* B0 or a custom (BOTHER) rate we cannot see through termios */
}

void xgo_host_pty_discard_unread(const xgo_host_pty_t *pty)
{
    int fd = open(pty->slave_path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd >= 0) {
        tcflush(fd, TCIFLUSH);
        close(fd);
    }
}
