/* net.c - TCP plumbing (see net.h). */
#include "net.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

int xgo_host_net_nonblocking(int fd)
{
    int flags = fcntl(fd, F_GETFL);
    return (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0 ||
            fcntl(fd, F_SETFD, FD_CLOEXEC) != 0)
               ? -1
               : 0;
}

/* A whole decimal number 0..65535. */
static int xgo_host_net_port(const char *text, unsigned *port)
{
    char *end = NULL;
    unsigned long v;
    if (text[0] < '0' || text[0] > '9') {
        return 0;
    }
    errno = 0;
    v = strtoul(text, &end, 10);
    if (errno != 0 || *end != '\0' || v > 65535ul) {
        return 0;
    }
    *port = (unsigned)v;
    return 1;
}

int xgo_host_net_parse_endpoint(const char *value, uint32_t *addr, unsigned *port, char *err,
                                size_t err_size)
{
    const char *colon = strrchr(value, ':');
    struct in_addr a;
    a.s_addr = htonl(INADDR_LOOPBACK);
    if (colon != NULL) {
        char host[64];
        size_t n = (size_t)(colon - value);
        if (n == 0 || n >= sizeof host) {
            snprintf(err, err_size, "HOST must be an IPv4 address or localhost");
            return 0;
        }
        memcpy(host, value, n);
        host[n] = '\0';
        if (strcmp(host, "localhost") != 0 && inet_pton(AF_INET, host, &a) != 1) {
            snprintf(err, err_size, "HOST must be an IPv4 address or localhost");
            return 0;
        }
    }
    if (!xgo_host_net_port(colon != NULL ? colon + 1 : value, port)) {
        snprintf(err, err_size, "needs [HOST:]PORT with PORT 0..65535");
        return 0;
    }
    *addr = ntohl(a.s_addr);
    return 1;
}

int xgo_host_net_listen(uint32_t addr, unsigned port, int backlog, char *host, size_t host_size,
                        unsigned *bound)
{
    struct sockaddr_in sa;
    socklen_t len = sizeof sa;
    int one = 1;
    int fd;
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    sa.sin_addr.s_addr = htonl(addr);
    sa.sin_port = htons((uint16_t)port);
    inet_ntop(AF_INET, &sa.sin_addr, host, (socklen_t)host_size);
    fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        return -1;
    }
    if (xgo_host_net_nonblocking(fd) != 0 ||
        setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(fd, (struct sockaddr *)&sa, sizeof sa) != 0 || listen(fd, backlog) != 0 ||
        getsockname(fd, (struct sockaddr *)&sa, &len) != 0) {
        int saved = errno;
        close(fd);
        errno = saved;
        return -1;
    }
    *bound = ntohs(sa.sin_port);
    return fd;
}
