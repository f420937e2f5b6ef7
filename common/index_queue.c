#include "index_queue.h"

#include <stdlib.h>
#include <string.h>

int gb_index_queue_push(gb_index_queue *queue, size_t index)
{
    if (queue->count == queue->capacity) {
        size_t capacity = queue->capacity ? 2 * queue->capacity : 4096;
        size_t *items = malloc(capacity * sizeof *items);
        if (!items)
            return 0;
        for (size_t n = 0; n < queue->count; ++n)
            items[n] = queue->items[(queue->head + n) % queue->capacity];
        free(queue->items);
        queue->items = items;
        queue->capacity = capacity;
        queue->head = 0;
    }
    queue->items[(queue->head + queue->count++) % queue->capacity] = index;
    return 1;
}

size_t gb_index_queue_pop(gb_index_queue *queue)
{
    size_t index = queue->items[queue->head];
    queue->head = (queue->head + 1) % queue->capacity;
    --queue->count;
    return index;
}

void gb_index_queue_free(gb_index_queue *queue)
{
    free(queue->items);
    memset(queue, 0, sizeof *queue);
}
