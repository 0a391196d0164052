/* clock.c - CLOCK_MONOTONIC in microseconds (see clock.h). */
#include "clock.h"

#include <time.h>

uint64_t xgo_host_clock_us(void)
{
    struct timespec ts;
    /* CLOCK_MONOTONIC cannot fail with a valid pointer on POSIX systems
     * that define it, so there is no error path worth carrying around. */
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

uint32_t xgo_host_clock_ms32(uint64_t now_us)
{
    return (uint32_t)(now_us / 1000u);
}
