/*
 * semihost.c - ARM semihosting calls (see semihost.h). On ARMv6-M and
 * ARMv7-M a request is BKPT 0xAB with the operation in r0 and a pointer to
 * its argument block in r1; the result comes back in r0.
 */
#include "semihost.h"

#include <stdint.h>

enum {
    SYS_OPEN = 0x01,
    SYS_CLOSE = 0x02,
    SYS_WRITE0 = 0x04,
    SYS_WRITE = 0x05,
    SYS_READ = 0x06,
    SYS_GET_CMDLINE = 0x15,
    SYS_EXIT_EXTENDED = 0x20
};

#define ADP_STOPPED_APPLICATION_EXIT 0x20026u
/* SYS_OPEN modes (ISO C fopen): 1 = "rb", 5 = "wb". */
#define OPEN_MODE_RB 1u
#define OPEN_MODE_WB 5u

static int32_t sh_call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

void xgo_sh_write0(const char *s)
{
    (void)sh_call(SYS_WRITE0, s);
}

void xgo_sh_exit(int code)
{
    uint32_t block[2];
    block[0] = ADP_STOPPED_APPLICATION_EXIT;
    block[1] = (uint32_t)code;
    (void)sh_call(SYS_EXIT_EXTENDED, block);
    for (;;) {
        /* no debugger: stay here */
    }
}

int xgo_sh_cmdline(char *buf, size_t size)
{
    uint32_t block[2];
    block[0] = (uint32_t)(uintptr_t)buf;
    block[1] = (uint32_t)size;
    return size > 0 && sh_call(SYS_GET_CMDLINE, block) == 0;
}

int xgo_sh_open(const char *path, const char *mode)
{
    uint32_t block[3];
    size_t len = 0;
    while (path[len] != '\0') {
        len++;
    }
    block[0] = (uint32_t)(uintptr_t)path;
    block[1] = mode[0] == 'w' ? OPEN_MODE_WB : OPEN_MODE_RB;
    block[2] = (uint32_t)len;
    return (int)sh_call(SYS_OPEN, block);
}

/* SYS_READ and SYS_WRITE return the number of bytes NOT transferred. */
static size_t transfer(uint32_t op, int handle, const void *buf, size_t n)
{
    uint32_t block[3];
    int32_t left;
    block[0] = (uint32_t)handle;
    block[1] = (uint32_t)(uintptr_t)buf;
    block[2] = (uint32_t)n;
    left = sh_call(op, block);
    return left < 0 || (size_t)left > n ? 0 : n - (size_t)left;
}

size_t xgo_sh_read(int handle, void *buf, size_t n)
{
    return transfer(SYS_READ, handle, buf, n);
}

size_t xgo_sh_write(int handle, const void *buf, size_t n)
{
    return transfer(SYS_WRITE, handle, buf, n);
}

int xgo_sh_close(int handle)
{
    uint32_t block[1];
    block[0] = (uint32_t)handle;
    return (int)sh_call(SYS_CLOSE, block);
}
