/* threads.c — gb_run_threads (threads.h). */
#include "threads.h"

#include <pthread.h>

enum { MAX_THREADS = 64 };

typedef struct thread_start {
    gb_thread_function function;
    void *context;
    int thread, thread_count;
} thread_start;

static void *run_one(void *argument)
{
    thread_start *start = argument;
    start->function(start->context, start->thread, start->thread_count);
    return NULL;
}

void gb_run_threads(gb_thread_function function, void *context, int thread_count)
{
    if (thread_count < 1)
        thread_count = 1;
    if (thread_count > MAX_THREADS)
        thread_count = MAX_THREADS;
    pthread_t threads[MAX_THREADS];
    thread_start starts[MAX_THREADS];
    int started[MAX_THREADS] = {0};
    for (int t = 1; t < thread_count; ++t) {
        starts[t] = (thread_start){function, context, t, thread_count};
        started[t] = pthread_create(&threads[t], NULL, run_one, &starts[t]) == 0;
    }
    function(context, 0, thread_count);
    for (int t = 1; t < thread_count; ++t) {
        if (started[t])
            pthread_join(threads[t], NULL);
        else
            function(context, t, thread_count);
    }
}
