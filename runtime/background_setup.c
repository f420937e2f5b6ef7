/* background_setup.c — a method's prepare on a pthread (background_setup.h).
 * The thread and the caller share only the atomics below: the fraction (in
 * millionths, an integer so that every platform stores it without a lock),
 * the cancel request and the finished flag; prepare's result and error are
 * the thread's until it has finished, the caller's after the join. */
#include "background_setup.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>

#define MILLIONTHS 1000000.0

struct gb_background_setup {
    const gb_indirect_method *method;
    gb_indirect_setup setup;            /* the caller's, its progress the job's */
    gb_progress_callback forward;       /* the caller's progress, or NULL */
    void *forward_user;
    int threaded;                       /* 0: no prepare, no thread */
    pthread_t thread;
    atomic_uint fraction;               /* millionths */
    atomic_int cancelled, finished;
    gb_result result;                   /* prepare's, once finished */
    void *prepared;
    gb_error error;
};

/* prepare's progress callback: records, forwards, says whether to stop. */
static int job_progress(void *user, double fraction)
{
    gb_background_setup *job = user;
    double clamped = fraction > 0.0 ? (fraction < 1.0 ? fraction : 1.0) : 0.0;
    atomic_store(&job->fraction, (unsigned)(clamped * MILLIONTHS));
    int stop = job->forward && job->forward(job->forward_user, fraction);
    return stop || atomic_load(&job->cancelled);
}

static void *run(void *user)
{
    gb_background_setup *job = user;
    job->result = job->method->prepare(&job->setup, &job->prepared, &job->error);
    atomic_store(&job->finished, 1);
    return NULL;
}

gb_result gb_background_setup_start(const gb_indirect_method *method,
                                    const gb_indirect_setup *setup,
                                    gb_background_setup **job, gb_error *error)
{
    *job = NULL;
    gb_background_setup *j = calloc(1, sizeof *j);
    if (!j)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "background setup: out of memory");
    j->method = method;
    j->setup = *setup;
    j->setup.prepared = NULL;
    j->setup.progress = job_progress;
    j->setup.progress_user = j;
    j->forward = setup->progress;
    j->forward_user = setup->progress_user;
    if (!method->prepare) {
        atomic_store(&j->fraction, (unsigned)MILLIONTHS);
        atomic_store(&j->finished, 1);
    } else if (pthread_create(&j->thread, NULL, run, j) != 0) {
        free(j);
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "background setup: no thread to prepare on");
    } else {
        j->threaded = 1;
    }
    *job = j;
    return GB_OK;
}

double gb_background_setup_progress(gb_background_setup *job, int *finished)
{
    *finished = atomic_load(&job->finished);
    return atomic_load(&job->fraction) / MILLIONTHS;
}

static void join(gb_background_setup *job)
{
    if (job->threaded)
        pthread_join(job->thread, NULL);
    job->threaded = 0;
}

gb_result gb_background_setup_finish(gb_background_setup *job, void **prepared,
                                     gb_error *error)
{
    join(job);
    gb_result result = job->result;
    *prepared = result == GB_OK ? job->prepared : NULL;
    if (result != GB_OK && error)
        *error = job->error;
    free(job);
    return result;
}

void gb_background_setup_cancel(gb_background_setup *job)
{
    if (!job)
        return;
    atomic_store(&job->cancelled, 1);
    join(job);
    if (job->result == GB_OK && job->prepared && job->method->discard)
        job->method->discard(job->prepared);
    free(job);
}
