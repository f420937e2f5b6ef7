/* index_queue.h — a first-in first-out queue of indices that grows as it
 * fills: the front of a breadth-first flood over a grid (voxelize's empty
 * space), which holds a few slices of the grid rather than
 * the region. The caller owns the queue: zeroed, it is empty; release it
 * with gb_index_queue_free. */
#ifndef GB_INDEX_QUEUE_H
#define GB_INDEX_QUEUE_H

#include <stddef.h>

typedef struct gb_index_queue {
    size_t *items;              /* circular */
    size_t capacity, head, count;
} gb_index_queue;

/* Appends index; 0 when the queue could not grow (it is left as it was). */
int gb_index_queue_push(gb_index_queue *queue, size_t index);
/* The oldest index, removed; the queue must not be empty. */
size_t gb_index_queue_pop(gb_index_queue *queue);
void gb_index_queue_free(gb_index_queue *queue);

#endif
