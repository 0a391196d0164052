/* test_clock.c - see test_clock.h. */
#include "test_clock.h"

#include <errno.h>
#include <time.h>

static struct timespec now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts;
}

long long xgo_test_now_ms(void)
{
    struct timespec ts = now();
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

long long xgo_test_now_us(void)
{
    struct timespec ts = now();
    return (long long)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

double xgo_test_now_us_f(void)
{
    struct timespec ts = now();
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static void sleep_for(struct timespec ts)
{
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

void xgo_test_sleep_ms(long ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (ms % 1000) * 1000000L;
    sleep_for(ts);
}

void xgo_test_sleep_us(long us)
{
    struct timespec ts;
    ts.tv_sec = us / 1000000;
    ts.tv_nsec = (us % 1000000) * 1000L;
    sleep_for(ts);
}
