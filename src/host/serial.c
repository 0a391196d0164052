/* serial.c - raw 8N1 serial lines (see serial.h). */
#include "serial.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

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

#define XGO_HOST_SPEED_COUNT (sizeof xgo_host_speeds / sizeof xgo_host_speeds[0])

int xgo_host_serial_speed_code(uint32_t baud, speed_t *code)
{
    size_t i;
    for (i = 0; i < XGO_HOST_SPEED_COUNT; i++) {
        if (xgo_host_speeds[i].bits_per_s == baud) {
            *code = xgo_host_speeds[i].code;
            return 1;
        }
    }
    return 0;
}

uint32_t xgo_host_serial_baud_of(speed_t code)
{
    size_t i;
    for (i = 0; i < XGO_HOST_SPEED_COUNT; i++) {
        if (xgo_host_speeds[i].code == code) {
            return xgo_host_speeds[i].bits_per_s;
        }
    }
    return 0; /* B0 or a custom (BOTHER) rate we cannot see through termios */
}

int xgo_host_serial_make_raw(int fd, uint32_t baud)
{
    struct termios tio;
    speed_t code;
    if (!xgo_host_serial_speed_code(baud, &code)) {
        errno = EINVAL;
        return -1;
    }
    if (tcgetattr(fd, &tio) != 0) {
        return -1;
    }
    cfmakeraw(&tio); /* 8 bits, no parity, no echo, no mapping, no signals */
    tio.c_cflag &= (tcflag_t) ~(CSTOPB | PARENB);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_iflag &= (tcflag_t) ~(IXON | IXOFF | IXANY);
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    if (cfsetispeed(&tio, code) != 0 || cfsetospeed(&tio, code) != 0) {
        return -1;
    }
    return tcsetattr(fd, TCSANOW, &tio);
}

int xgo_host_serial_open(const char *path, uint32_t baud, char *err, size_t err_size)
{
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, err_size, "cannot open %s: %s", path, strerror(errno));
        return -1;
    }
    if (!isatty(fd)) {
        snprintf(err, err_size, "%s is not a serial port", path);
        close(fd);
        return -1;
    }
    if (xgo_host_serial_make_raw(fd, baud) != 0) {
        snprintf(err, err_size, "cannot set %s to raw 8N1 at %lu baud: %s", path,
                 (unsigned long)baud, strerror(errno));
        close(fd);
        return -1;
    }
    (void)tcflush(fd, TCIFLUSH); /* stale bytes are no reply to anything we send */
    return fd;
}
