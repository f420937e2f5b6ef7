/* union_find.h — disjoint sets over the indices 0 .. n-1 in an array the
 * caller owns, parent[i] = i to start: each set's root is its least index,
 * so the roots do not depend on the order of the joins (atlas discs' glued
 * corners, implicit visibility's connected parts of a mesh). */
#ifndef GB_UNION_FIND_H
#define GB_UNION_FIND_H

#include <stdint.h>

/* The root of i's set (the path halved on the way). */
static inline uint32_t gb_union_find_root(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

/* Joins the sets of a and b under the lesser root. */
static inline void gb_union_find_join(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = gb_union_find_root(parent, a);
    b = gb_union_find_root(parent, b);
    if (a != b)
        parent[a < b ? b : a] = a < b ? a : b;
}

#endif
