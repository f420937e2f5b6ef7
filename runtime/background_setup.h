/* background_setup.h — a GI method's prepare (indirect_method.h) run on a
 * thread of its own, so that the window keeps drawing while a method's long
 * CPU setup (implicit's links) runs, shows how far it is, and can drop it.
 *
 *   gb_background_setup *job;
 *   if (gb_background_setup_start(method, &setup, &job, &error) != GB_OK) ...
 *   each frame: fraction = gb_background_setup_progress(job, &finished);
 *   once finished: gb_background_setup_finish(job, &prepared, &error), then
 *                  setup.prepared = prepared; method->create(&setup, ...);
 *   or at any time: gb_background_setup_cancel(job)   (the user left)
 *
 * Ownership. The job copies the setup, but not what it points to (the
 * scene, the parameters ...): those outlive the job. finish and cancel free
 * the job; finish hands prepare's result to the caller, who gives it to
 * create (which takes it over) or to the method's discard; cancel
 * discards it. A method without prepare gives a job finished at once,
 * whose result is NULL: create then does all of its setup.
 *
 * Threads. prepare runs on the job's thread (and the threads it starts);
 * setup->progress, when not NULL, is called there, one call at a time. The
 * other functions are for the one thread that started the job.
 */
#ifndef GB_BACKGROUND_SETUP_H
#define GB_BACKGROUND_SETUP_H

#include "indirect_method.h"
#include "result.h"

typedef struct gb_background_setup gb_background_setup;

/* Starts method->prepare(setup) on a thread. The job's own progress
 * callback records the fraction, forwards it to setup->progress (which may
 * also ask to stop) and asks prepare to stop once the job is cancelled.
 * Fails (nothing started, *job NULL) when memory or a thread is lacking. */
gb_result gb_background_setup_start(const gb_indirect_method *method,
                                    const gb_indirect_setup *setup,
                                    gb_background_setup **job, gb_error *error);

/* The fraction prepare last reported, in [0, 1]; *finished nonzero once
 * prepare returned. Never blocks. */
double gb_background_setup_progress(gb_background_setup *job, int *finished);

/* Waits for prepare (at once when finished), frees the job and gives
 * prepare's result in *prepared (the caller's), or NULL and prepare's
 * error (GB_ERROR_INTERRUPTED when it was asked to stop). */
gb_result gb_background_setup_finish(gb_background_setup *job, void **prepared,
                                     gb_error *error);

/* Asks prepare to stop, waits for it (until its next progress report),
 * discards its result and frees the job; nothing on NULL. */
void gb_background_setup_cancel(gb_background_setup *job);

#endif
