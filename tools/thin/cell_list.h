/* cell_list.h — a growable array of cell indices (the border lists and
 * breadth-first fronts of thin). Zero-initialise, push, free. */
#ifndef GB_CELL_LIST_H
#define GB_CELL_LIST_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "array_reserve.h"
#include "result.h"

typedef struct gb_cell_list {
    uint32_t *items;
    size_t count, capacity;
} gb_cell_list;

static inline gb_result gb_cell_list_push(gb_cell_list *list, size_t cell, gb_error *error)
{
    if (!gb_array_reserve(&list->items, &list->capacity, list->count + 1, sizeof *list->items))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for a list of %zu cells",
                       list->count + 1);
    list->items[list->count++] = (uint32_t)cell;
    return GB_OK;
}

static inline void gb_cell_list_free(gb_cell_list *list)
{
    free(list->items);
    list->items = NULL;
    list->count = list->capacity = 0;
}

#endif
