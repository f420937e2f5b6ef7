/* bisection.h — the one binary search of gibake: in a sequence sorted so
 * that a test holds for a leading run of its indices, the last index of that
 * run. Every "which interval holds u" asks it: picking by a cumulative
 * distribution (cumulative_distribution.h), a node by its cell in an
 * increasing list (tools/thin/skeleton_graph.c), the nearest code of a
 * decoding table (packed_texture.c).
 *
 *   static int at_or_below(const void *user, size_t i) { ... cdf[i] <= u ... }
 *   size_t i = gb_bisection_last(count, at_or_below, &context);
 *
 * Static inline so that the compiler calls the test in place; nothing is
 * kept, the caller owns the sequence.
 */
#ifndef GB_BISECTION_H
#define GB_BISECTION_H

#include <stddef.h>

/* Whether index i of the caller's sequence is still in the leading run. */
typedef int (*gb_bisection_test)(const void *user, size_t i);

/* The last i in [0, count) with in_run(user, i), for count >= 1 and a test
 * that holds for indices 0..k and fails after: index 0 is taken to be in
 * the run and never asked, so the answer is 0 when no other index is.
 * log2(count) tests. */
static inline size_t gb_bisection_last(size_t count, gb_bisection_test in_run, const void *user)
{
    size_t low = 0, high = count;   /* low in the run; high past it, or the end */
    while (high - low > 1) {
        size_t middle = low + (high - low) / 2;
        if (in_run(user, middle))
            low = middle;
        else
            high = middle;
    }
    return low;
}

#endif
