/* work_queue.c — gb_work_queue_run (work_queue.h), on gb_run_threads. */
#include "work_queue.h"

#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>
#if defined(__SSE__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

#include "threads.h"

enum { MAX_THREADS = 64 };

/* next_item and stop change only under the lock, and progress is called
 * under it, so a stop asked for when item k is handed out is seen by every
 * thread before item k + 1 can start: which items run does not depend on
 * scheduling. Items are coarse (tiles, chunks), so one lock per item is
 * nothing beside the item itself. */
typedef struct queue_run {
    const gb_work_queue *queue;
    gb_work_item_function function;
    void *context;
    pthread_mutex_t lock;
    uint64_t next_item;
    int stop;
    atomic_uint_fast64_t items_done;
} queue_run;

static unsigned flush_denormals(void)
{
#if defined(__SSE__)
    unsigned saved = _mm_getcsr();
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    return saved;
#else
    return 0;
#endif
}

static void restore_denormals(unsigned saved)
{
#if defined(__SSE__)
    _mm_setcsr(saved);
#else
    (void)saved;
#endif
}

/* The next item to run, or item_count when none is left or the queue
 * stopped. The progress callback sees the fraction of items started and may
 * stop the queue before this item starts (a queue of no items has no
 * fraction: it is not called). */
static uint64_t take_item(queue_run *run)
{
    const gb_work_queue *queue = run->queue;
    pthread_mutex_lock(&run->lock);
    uint64_t item = queue->item_count;
    if (!run->stop && queue->progress && queue->item_count > 0 &&
        queue->progress(queue->progress_user, (double)run->next_item / (double)queue->item_count))
        run->stop = 1;
    if (!run->stop && run->next_item < queue->item_count)
        item = run->next_item++;
    pthread_mutex_unlock(&run->lock);
    return item;
}

static void ask_to_stop(queue_run *run)
{
    pthread_mutex_lock(&run->lock);
    run->stop = 1;
    pthread_mutex_unlock(&run->lock);
}

static void work(void *context, int thread, int thread_count)
{
    (void)thread, (void)thread_count;
    queue_run *run = context;
    unsigned saved = flush_denormals();
    for (uint64_t item; (item = take_item(run)) < run->queue->item_count;) {
        if (run->function(run->context, item))
            ask_to_stop(run);
        atomic_fetch_add(&run->items_done, 1);
    }
    restore_denormals(saved);
}

static int thread_count(const gb_work_queue *queue)
{
    long threads = queue->threads > 0 ? queue->threads : sysconf(_SC_NPROCESSORS_ONLN);
    if (threads < 1)
        threads = 1;
    if (threads > MAX_THREADS)
        threads = MAX_THREADS;
    if ((uint64_t)threads > queue->item_count)
        threads = queue->item_count ? (long)queue->item_count : 1;
    return (int)threads;
}

gb_result gb_work_queue_run(const gb_work_queue *queue, gb_work_item_function function,
                            void *context, int *threads_used)
{
    queue_run run = {.queue = queue, .function = function, .context = context};
    pthread_mutex_init(&run.lock, NULL);
    int threads = thread_count(queue);
    gb_run_threads(work, &run, threads);
    pthread_mutex_destroy(&run.lock);
    if (threads_used)
        *threads_used = threads;
    return atomic_load(&run.items_done) == queue->item_count && !run.stop
               ? GB_OK
               : GB_ERROR_INTERRUPTED;
}
