/*
 * assert_hosted.c - the default xgo_assert_failed() for hosted builds: a
 * caller broke one of the core's preconditions (xgo/config.h), so say which
 * and stop, as assert() would. Linked with xgo::core on hosted systems; a
 * program that defines its own xgo_assert_failed() keeps its own.
 */
#include <stdio.h>
#include <stdlib.h>

#include "xgo/config.h"

#if XGO_ASSERT_ENABLED
void xgo_assert_failed(const char *file, int line, const char *expr)
{
    fprintf(stderr, "%s:%d: xgo core check failed: %s (a caller's bug, see the header)\n", file,
            line, expr);
    fflush(stderr);
    abort();
}
#else
/* Checks are compiled out: nothing to provide (ISO C wants a declaration). */
typedef int xgo_assert_hosted_unused_;
#endif
