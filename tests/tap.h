/* tap.h — the tiny Test Anything Protocol harness of gibake's unit tests.
 *
 * A test file defines main(), calls its checks with the macros below, and
 * ends with `return tap_done();`. `prove` reads the output.
 *
 *   CHECK(cond, "what is checked")           ok / not ok
 *   CHECK_NEAR(a, b, tolerance, "what")      |a - b| <= tolerance
 *   CHECK_EQ_INT(a, b, "what")               a == b, shows both on failure
 */
#ifndef GB_TAP_H
#define GB_TAP_H

#include <math.h>
#include <stdio.h>

static int tap_count, tap_failed;

static inline int tap_check(int passed, const char *file, int line, const char *what)
{
    ++tap_count;
    if (!passed)
        ++tap_failed;
    printf("%s %d - %s\n", passed ? "ok" : "not ok", tap_count, what);
    if (!passed)
        printf("#   failed at %s:%d\n", file, line);
    fflush(stdout);
    return passed;
}

#define CHECK(cond, what) tap_check((cond) ? 1 : 0, __FILE__, __LINE__, (what))

#define CHECK_NEAR(a, b, tolerance, what)                                           \
    do {                                                                            \
        double tap_a_ = (double)(a), tap_b_ = (double)(b);                           \
        if (!tap_check(fabs(tap_a_ - tap_b_) <= (double)(tolerance), __FILE__,       \
                       __LINE__, (what)))                                           \
            printf("#   got %.9g, expected %.9g (tolerance %g)\n", tap_a_, tap_b_,  \
                   (double)(tolerance));                                            \
    } while (0)

#define CHECK_EQ_INT(a, b, what)                                                    \
    do {                                                                            \
        long long tap_a_ = (long long)(a), tap_b_ = (long long)(b);                  \
        if (!tap_check(tap_a_ == tap_b_, __FILE__, __LINE__, (what)))                \
            printf("#   got %lld, expected %lld\n", tap_a_, tap_b_);                  \
    } while (0)

static inline int tap_done(void)
{
    printf("1..%d\n", tap_count);
    return tap_failed ? 1 : 0;
}

#endif
