/* tap_printf.h — tap.h's CHECK and CHECK_EQ_INT with the message made as
 * printf makes it, for a check run once per case, so that a test does not
 * write the message into a buffer of its own before each check:
 *
 *   CHECKF(cond, "%s: thin succeeds", name)          ok / not ok
 *   CHECK_EQ_INTF(a, b, "%s: b0 = %ld", name, b0)    a == b, both shown on failure
 *
 * Both return whether the check passed, as CHECK does; the message is cut
 * at 511 bytes.
 */
#ifndef GB_TAP_PRINTF_H
#define GB_TAP_PRINTF_H

#include <stdarg.h>
#include <stdio.h>

#include "tap.h"

static inline int tap_vcheck(int passed, const char *file, int line, const char *format,
                             va_list arguments)
{
    char what[512];
    vsnprintf(what, sizeof what, format, arguments);
    return tap_check(passed, file, line, what);
}

__attribute__((format(printf, 4, 5))) static inline int
tap_checkf(int passed, const char *file, int line, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    int ok = tap_vcheck(passed, file, line, format, arguments);
    va_end(arguments);
    return ok;
}

__attribute__((format(printf, 5, 6))) static inline int
tap_check_eq_intf(long long a, long long b, const char *file, int line, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    int ok = tap_vcheck(a == b, file, line, format, arguments);
    va_end(arguments);
    if (!ok)
        printf("#   got %lld, expected %lld\n", a, b);
    return ok;
}

#define CHECKF(cond, ...) tap_checkf((cond) ? 1 : 0, __FILE__, __LINE__, __VA_ARGS__)

#define CHECK_EQ_INTF(a, b, ...)                                                            \
    tap_check_eq_intf((long long)(a), (long long)(b), __FILE__, __LINE__, __VA_ARGS__)

#endif
