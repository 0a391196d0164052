/* serial_port.c - see serial_port.h. */
#include "serial_port.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include "test_clock.h"
#include "xgo/protocol.h"

#define PORT_WRITE_RETRY_US 500 /* pause while the port is full */

int xgo_test_port_open(const char *path)
{
    return open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
}

int xgo_test_port_open_like_pyserial(const char *path, speed_t speed)
{
    struct termios tio;
    int fd = xgo_test_port_open(path);
    if (fd < 0) {
        return -1;
    }
    if (tcgetattr(fd, &tio) != 0) {
        close(fd);
        return -1;
    }
    /* pyserial's Serial._reconfigure_port, flag for flag */
    tio.c_cflag |= (tcflag_t)(CLOCAL | CREAD);
    tio.c_lflag &= (tcflag_t) ~(ICANON | ECHO | ECHOE | ECHOK | ECHONL | ISIG | IEXTEN);
    tio.c_oflag &= (tcflag_t) ~(OPOST | ONLCR | OCRNL);
    tio.c_iflag &= (tcflag_t) ~(INLCR | IGNCR | ICRNL | IGNBRK | INPCK | ISTRIP | IXON | IXOFF);
    tio.c_cflag &= (tcflag_t) ~(CSIZE | PARENB | CSTOPB);
    tio.c_cflag |= CS8;
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    cfsetispeed(&tio, speed);
    cfsetospeed(&tio, speed);
    if (tcsetattr(fd, TCSANOW, &tio) != 0) {
        close(fd);
        return -1;
    }
    tcflush(fd, TCIFLUSH); /* pyserial's reset_input_buffer() at open */
    return fd;
}

int xgo_test_port_write(int fd, const void *bytes, size_t n, long timeout_ms)
{
    const uint8_t *p = bytes;
    long long deadline = xgo_test_now_ms() + timeout_ms;
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(fd, p + done, n - done);
        if (w > 0) {
            done += (size_t)w;
            continue;
        }
        if (!(w < 0 && (errno == EAGAIN || errno == EINTR)) || xgo_test_now_ms() >= deadline) {
            return -1;
        }
        xgo_test_sleep_us(PORT_WRITE_RETRY_US);
    }
    return 0;
}

size_t xgo_test_port_read(int fd, void *buf, size_t n, long timeout_ms)
{
    uint8_t *p = buf;
    long long deadline = xgo_test_now_ms() + timeout_ms;
    size_t got = 0;
    while (got < n) {
        struct pollfd pfd;
        long long left = deadline - xgo_test_now_ms();
        ssize_t r;
        if (left <= 0) {
            break;
        }
        pfd.fd = fd;
        pfd.events = POLLIN;
        if (poll(&pfd, 1, (int)left) <= 0) {
            continue;
        }
        r = read(fd, p + got, n - got);
        if (r > 0) {
            got += (size_t)r;
        }
    }
    return got;
}

size_t xgo_test_port_silence(int fd, long ms)
{
    uint8_t buf[512];
    return xgo_test_port_read(fd, buf, sizeof buf, ms);
}

size_t xgo_test_read_request(uint8_t addr, uint8_t count, uint8_t *out)
{
    return xgo_frame_encode(XGO_TYPE_READ, addr, &count, 1, out, XGO_READ_REQUEST_LEN);
}

size_t xgo_test_read_reply(int fd, uint8_t addr, uint8_t count, uint8_t *reply, long timeout_ms)
{
    uint8_t req[XGO_READ_REQUEST_LEN];
    if (xgo_test_read_request(addr, count, req) != sizeof req ||
        xgo_test_port_write(fd, req, sizeof req, timeout_ms) != 0) {
        return 0;
    }
    return xgo_test_port_read(fd, reply, (size_t)count + XGO_FRAME_OVERHEAD, timeout_ms);
}

int xgo_test_write_regs(int fd, uint8_t addr, const void *values, size_t n, long timeout_ms)
{
    uint8_t frame[XGO_FRAME_MAX_LEN];
    size_t len = xgo_frame_encode(XGO_TYPE_WRITE, addr, values, n, frame, sizeof frame);
    if (len == 0) {
        return -1;
    }
    return xgo_test_port_write(fd, frame, len, timeout_ms);
}
