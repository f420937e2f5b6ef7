/* work_queue.h — items 0 .. item_count-1 handed out one at a time to a few
 * threads, for work whose items differ in cost: the reference renderer's
 * tiles, the photon tracer's chunks. The calling thread works too. Before an
 * item is handed out, the progress callback is called (one call at a time,
 * from whichever thread takes the item) with the fraction of items started;
 * once it or an item asks to stop, no further item starts, so a stop asked
 * for when item k is handed out means items k and later never run, whatever
 * the scheduling. Every worker flushes
 * denormals to zero, as Embree advises for speed; all threads alike, so no
 * result depends on the thread count.
 *
 *   gb_work_queue queue = {.item_count = n, .threads = 0, .progress = cb, ...};
 *   gb_result r = gb_work_queue_run(&queue, do_item, context, &threads_used);
 *
 * The caller owns the queue and the context; nothing is allocated.
 */
#ifndef GB_WORK_QUEUE_H
#define GB_WORK_QUEUE_H

#include <stdint.h>

#include "progress.h"
#include "result.h"

/* Does item; returns nonzero to stop the queue (no new item is started). */
typedef int (*gb_work_item_function)(void *context, uint64_t item);

typedef struct gb_work_queue {
    uint64_t item_count;
    int threads;                    /* 0: one per processor */
    gb_progress_callback progress;  /* may be NULL; nonzero stops the queue;
                                       called under the queue's lock */
    void *progress_user;
} gb_work_queue;

/* GB_OK when every item ran; GB_ERROR_INTERRUPTED when an item or the
 * progress callback stopped the queue. threads_used may be NULL. */
gb_result gb_work_queue_run(const gb_work_queue *queue, gb_work_item_function function,
                            void *context, int *threads_used);

#endif
