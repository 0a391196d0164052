/*
 * check.h - XGO_ASSERT(cond): the core's check for a caller's bug (private).
 *
 * TinyUSB keeps TU_ASSERT apart from TU_VERIFY; so do we: expected failures
 * (bad bytes from the wire, values out of range from a host) are handled
 * where they happen - dropped, counted, clamped - and never reach
 * XGO_ASSERT. A failed XGO_ASSERT means code calling the core broke a
 * documented precondition, or a path the code rules out was taken; with
 * XGO_ASSERT_ENABLED it calls the application's xgo_assert_failed()
 * (xgo/config.h), without it it compiles to nothing and the code after it
 * behaves as documented for release builds (a clamp, a default).
 */
#ifndef XGO_CORE_CHECK_H
#define XGO_CORE_CHECK_H

#include "xgo/config.h"

#if XGO_ASSERT_ENABLED
#define XGO_ASSERT(cond) ((cond) ? (void)0 : xgo_assert_failed(__FILE__, __LINE__, #cond))
#else
#define XGO_ASSERT(cond) ((void)0)
#endif

#endif /* XGO_CORE_CHECK_H */
