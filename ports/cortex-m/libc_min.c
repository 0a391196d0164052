/*
 * libc_min.c - the four string.h functions the image needs, so it links with
 * -nostdlib (no newlib): the core uses memcpy, memset, memmove and memcmp;
 * GCC may emit memcpy/memset/memcmp for struct copies and initialisers.
 *
 * Built with -fno-tree-loop-distribute-patterns, or GCC would turn these
 * loops back into calls to themselves. The core's copies and compares are of
 * word-aligned int32_t arrays and structs (joint angles, poses, feet): those
 * go a word at a time (4x fewer iterations); anything else byte by byte
 * (a Cortex-M0 faults on an unaligned word access).
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

static int aligned2(const void *a, const void *b)
{
    return (((uintptr_t)a | (uintptr_t)b) & 3u) == 0;
}

void *memcpy(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (aligned2(d, s)) {
        for (; n >= 4u; n -= 4u, d += 4, s += 4) {
            *(uint32_t *)(void *)d = *(const uint32_t *)(const void *)s;
        }
    }
    while (n--) {
        *d++ = *s++;
    }
    return dst;
}

void *memmove(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (d < s) {
        while (n--) {
            *d++ = *s++;
        }
    } else if (d > s) {
        d += n;
        s += n;
        while (n--) {
            *--d = *--s;
        }
    }
    return dst;
}

void *memset(void *dst, int c, size_t n)
{
    unsigned char *d = dst;
    const uint32_t word = 0x01010101u * (unsigned char)c;
    for (; n > 0 && ((uintptr_t)d & 3u) != 0; n--) {
        *d++ = (unsigned char)c;
    }
    for (; n >= 4u; n -= 4u, d += 4) {
        *(uint32_t *)(void *)d = word;
    }
    while (n--) {
        *d++ = (unsigned char)c;
    }
    return dst;
}

int memcmp(const void *a, const void *b, size_t n)
{
    const unsigned char *x = a;
    const unsigned char *y = b;
    if (aligned2(x, y)) {
        /* Skip equal words; a differing one is compared byte by byte below. */
        for (; n >= 4u && *(const uint32_t *)(const void *)x == *(const uint32_t *)(const void *)y;
             n -= 4u, x += 4, y += 4) {
        }
    }
    for (; n; n--, x++, y++) {
        if (*x != *y) {
            return *x < *y ? -1 : 1;
        }
    }
    return 0;
}
