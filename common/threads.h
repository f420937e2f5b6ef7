/* threads.h — runs one function on a few threads and waits for all of them
 * (pthreads). Thread 0 is the calling thread, so it may report progress.
 * Work handed out item by item is work_queue.h, built on this. */
#ifndef GB_THREADS_H
#define GB_THREADS_H

#include "result.h"

typedef void (*gb_thread_function)(void *context, int thread, int thread_count);

/* Calls function(context, t, thread_count) for t in 0..thread_count-1, t = 0
 * on the calling thread; returns when all have returned. When a thread cannot
 * be started, the calling thread runs its share itself. */
void gb_run_threads(gb_thread_function function, void *context, int thread_count);

#endif
