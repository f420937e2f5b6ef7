/* work_queue.c — gb_work_queue_run (work_queue.h), on gb_run_threads. */
#include "work_queue.h"

#include <stdatomic.h>
#include <unistd.h>
#if defined(__SSE__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

#include "threads.h"

enum { MAX_THREADS = 64 };

typedef struct queue_run {
    const gb_work_queue *queue;
    gb_work_item_function function;
    void *context;
    atomic_uint_fast64_t next_item, items_done;
    atomic_int stop;
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

/* Runs the next item; 0 when none is left or the queue stopped. */
static int run_next_item(queue_run *run)
{
    if (atomic_load(&run->stop))
        return 0;
    uint64_t item = atomic_fetch_add(&run->next_item, 1);
    if (item >= run->queue->item_count)
        return 0;
    if (run->function(run->context, item))
        atomic_store(&run->stop, 1);
    atomic_fetch_add(&run->items_done, 1);
    return 1;
}

static void report_progress(queue_run *run)
{
    const gb_work_queue *queue = run->queue;
    double done = (double)atomic_load(&run->items_done) / (double)queue->item_count;
    if (queue->progress && queue->progress(queue->progress_user, done))
        atomic_store(&run->stop, 1);
}

static void work(void *context, int thread, int thread_count)
{
    (void)thread_count;
    queue_run *run = context;
    unsigned saved = flush_denormals();
    while (run_next_item(run))
        if (thread == 0)
            report_progress(run);
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
    int threads = thread_count(queue);
    gb_run_threads(work, &run, threads);
    if (threads_used)
        *threads_used = threads;
    return atomic_load(&run.items_done) == queue->item_count && !atomic_load(&run.stop)
               ? GB_OK
               : GB_ERROR_INTERRUPTED;
}
