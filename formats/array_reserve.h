/* array_reserve.h — room in an array that grows by doubling (git's
 * ALLOC_GROW): the one way the tree grows its lists.
 *
 *   if (!gb_array_reserve(&list->items, &list->capacity, list->count + 1,
 *                         sizeof *list->items))
 *       return out_of_memory;
 *   list->items[list->count++] = item;
 *
 * The caller owns the array (from malloc or realloc, or NULL with capacity
 * 0) and frees it with free().
 */
#ifndef GB_ARRAY_RESERVE_H
#define GB_ARRAY_RESERVE_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Makes the array at *items_address (a T ** passed as void *) hold at least
 * needed items of item_size bytes, doubling *capacity (from 16) until it
 * does. Returns 1, or 0 when out of memory or past SIZE_MAX bytes, with the
 * array and *capacity as they were. */
static inline int gb_array_reserve(void *items_address, size_t *capacity, size_t needed,
                                   size_t item_size)
{
    if (needed <= *capacity)
        return 1;
    size_t grown = *capacity ? *capacity : 16;
    while (grown < needed) {
        if (grown > SIZE_MAX / 2)
            return 0;
        grown *= 2;
    }
    if (grown > SIZE_MAX / item_size)
        return 0;
    void *items;
    memcpy(&items, items_address, sizeof items);
    items = realloc(items, grown * item_size);
    if (!items)
        return 0;
    memcpy(items_address, &items, sizeof items);
    *capacity = grown;
    return 1;
}

#endif
