/* test_background_setup.c — a method's prepare on a thread
 * (runtime/background_setup.h). With a stand-in method whose prepare
 * reports quarters and waits at a gate the test opens: the fraction seen
 * while it runs, the result handed over, the stop asked by the caller's
 * progress callback, a cancel while it waits (prepare stops, nothing is
 * discarded) and after it finished (its result discarded, once), a method
 * without prepare. With implicit visibility on the Cornell box (found
 * through $GB_ROOT, default "."): prepared on a job then created, the same
 * image bytes as a plain create; a cancel during the links stops them
 * within a report or two, before they are made. The sanitizer build checks
 * that nothing leaks. */

#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../../runtime/background_setup.h"
#include "../../runtime/implicit/implicit.h"
#include "headless_render.h"
#include "method_frames.h"
#include "tap.h"

enum { SIZE = 64, STAND_IN_RESULT = 42, GATE_WAIT_MS = 5000 };

static void sleep_ms(long ms)
{
    struct timespec t = {ms / 1000, ms % 1000 * 1000000L};
    nanosleep(&t, NULL);
}

/* The stand-in method: what its prepare did, for the test to read. */
static struct {
    atomic_int gate;            /* prepare reports quarter q once gate >= q */
    atomic_int discarded;
    gb_result returned;         /* prepare's result, once it returned */
} stand_in;

/* Reports 0, then quarter q once the gate lets it, reporting the last
 * quarter again each millisecond while it waits (as work that reports
 * often); stops when told to, or after GATE_WAIT_MS (a stop never
 * heard). */
static gb_result stand_in_prepare(const gb_indirect_setup *setup, void **prepared,
                                  gb_error *error)
{
    *prepared = NULL;
    gb_result result = GB_OK;
    for (int q = 0; q <= 4 && result == GB_OK; ++q) {
        for (int waited = 0; atomic_load(&stand_in.gate) < q && result == GB_OK; ++waited) {
            if (setup->progress(setup->progress_user, (q - 1) / 4.0))
                result = gb_fail(error, GB_ERROR_INTERRUPTED, "stand-in: stopped");
            else if (waited == GATE_WAIT_MS)
                result = gb_fail(error, GB_ERROR_INVALID, "stand-in: the gate never opened");
            else
                sleep_ms(1);
        }
        if (result == GB_OK && setup->progress(setup->progress_user, q / 4.0))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "stand-in: stopped");
    }
    int *value = result == GB_OK ? malloc(sizeof *value) : NULL;
    if (value)
        *value = STAND_IN_RESULT;
    *prepared = value;
    stand_in.returned = result;
    return result;
}

static void stand_in_discard(void *prepared)
{
    atomic_fetch_add(&stand_in.discarded, 1);
    free(prepared);
}

static const gb_indirect_method stand_in_method = {
    .prepare = stand_in_prepare,
    .discard = stand_in_discard,
};

static void stand_in_reset(int gate)
{
    atomic_store(&stand_in.gate, gate);
    atomic_store(&stand_in.discarded, 0);
    stand_in.returned = GB_ERROR_INVALID;
}

/* Polls job until its fraction reaches at least fraction; 0 if it never
 * does within GATE_WAIT_MS. */
static int wait_for(gb_background_setup *job, double fraction)
{
    int finished;
    for (int waited = 0; waited < GATE_WAIT_MS; ++waited) {
        if (gb_background_setup_progress(job, &finished) >= fraction)
            return 1;
        sleep_ms(1);
    }
    return 0;
}

static void wait_finished(gb_background_setup *job)
{
    int finished = 0;
    while (gb_background_setup_progress(job, &finished), !finished)
        sleep_ms(1);
}

static void test_stand_in_runs(void)
{
    stand_in_reset(2);
    gb_indirect_setup setup = {0};
    gb_background_setup *job;
    gb_error error;
    if (!CHECK(gb_background_setup_start(&stand_in_method, &setup, &job, &error) == GB_OK,
               "stand-in: the job starts"))
        return;
    int half = wait_for(job, 0.5), finished = 1;
    double fraction = gb_background_setup_progress(job, &finished);
    CHECK(half && fraction == 0.5 && !finished,
          "stand-in: the job shows 1/2 while prepare waits at the gate, not finished");
    atomic_store(&stand_in.gate, 4);
    wait_finished(job);
    CHECK(gb_background_setup_progress(job, &finished) == 1.0 && finished,
          "stand-in: finished, at 1");
    void *prepared = NULL;
    gb_result result = gb_background_setup_finish(job, &prepared, &error);
    CHECK(result == GB_OK && prepared && *(int *)prepared == STAND_IN_RESULT,
          "stand-in: finish hands prepare's result over");
    free(prepared);
}

/* The caller's progress: counts the calls, asks to stop at stop_at. */
typedef struct heard {
    atomic_int calls;
    double last, stop_at;
    atomic_int reached;         /* set at the first call, which then waits ... */
    atomic_int release;         /* ... for this, when hold is set */
    int hold;
} heard;

static int listen(void *user, double fraction)
{
    heard *h = user;
    h->last = fraction;
    if (atomic_fetch_add(&h->calls, 1) == 0 && h->hold) {
        atomic_store(&h->reached, 1);
        while (!atomic_load(&h->release))
            sleep_ms(1);
    }
    return fraction >= h->stop_at;
}

static void test_stand_in_stopped_by_progress(void)
{
    stand_in_reset(4);
    heard h = {.stop_at = 0.5};
    gb_indirect_setup setup = {.progress = listen, .progress_user = &h};
    gb_background_setup *job;
    gb_error error;
    memset(&error, 0, sizeof error);
    if (!CHECK(gb_background_setup_start(&stand_in_method, &setup, &job, &error) == GB_OK,
               "stand-in, stop asked: the job starts"))
        return;
    void *prepared = &h;
    gb_result result = gb_background_setup_finish(job, &prepared, &error);
    CHECK(result == GB_ERROR_INTERRUPTED && !prepared && strstr(error.message, "stopped"),
          "stand-in: the caller's progress asks to stop: interrupted, prepare's error, no result");
    CHECK(h.last == 0.5 && atomic_load(&h.calls) == 3,
          "stand-in: the caller heard 0, 1/4, 1/2, and no more");
}

static void test_stand_in_cancelled(void)
{
    stand_in_reset(1);
    gb_indirect_setup setup = {0};
    gb_background_setup *job;
    gb_error error;
    if (!CHECK(gb_background_setup_start(&stand_in_method, &setup, &job, &error) == GB_OK,
               "stand-in, cancel: the job starts"))
        return;
    wait_for(job, 0.25);
    gb_background_setup_cancel(job);
    CHECK(stand_in.returned == GB_ERROR_INTERRUPTED,
          "stand-in: cancelled while waiting at the gate, prepare was told to stop");
    CHECK_EQ_INT(atomic_load(&stand_in.discarded), 0, "stand-in: a failed prepare: no discard");

    stand_in_reset(4);
    if (!CHECK(gb_background_setup_start(&stand_in_method, &setup, &job, &error) == GB_OK,
               "stand-in, cancel after the end: the job starts"))
        return;
    wait_finished(job);
    gb_background_setup_cancel(job);
    CHECK_EQ_INT(atomic_load(&stand_in.discarded), 1,
                 "stand-in: cancelled once finished, its result discarded once");
    gb_background_setup_cancel(NULL);
}

static void test_no_prepare(void)
{
    static const gb_indirect_method none = {0};
    gb_indirect_setup setup = {0};
    gb_background_setup *job;
    gb_error error;
    if (!CHECK(gb_background_setup_start(&none, &setup, &job, &error) == GB_OK,
               "no prepare: the job starts"))
        return;
    int finished = 0;
    double fraction = gb_background_setup_progress(job, &finished);
    void *prepared = &error;
    gb_result result = gb_background_setup_finish(job, &prepared, &error);
    CHECK(finished && fraction == 1.0 && result == GB_OK && !prepared,
          "no prepare: finished at once, no result (create does it all)");
}

/* implicit's prepare on a job, then its create: the same bytes as a plain
 * create, with parameters that are not the defaults (a job that lost them
 * would show). */
static void test_implicit_prepared(method_view *v)
{
    gb_method_parameters parameters = {.implicit = {.bins = 8, .bounces = 2}};
    gb_indirect_setup setup = method_view_setup(v, &parameters);
    gb_image plain, prepared_image;
    if (!CHECK(method_render(v, &gb_implicit_method, &setup, 1, 1, 0.0, &plain),
               "implicit: a plain create renders"))
        return;
    heard h = {.stop_at = 2.0};
    setup.progress = listen;
    setup.progress_user = &h;
    gb_background_setup *job;
    void *prepared = NULL;
    gb_error error;
    gb_result result = gb_background_setup_start(&gb_implicit_method, &setup, &job, &error);
    if (result == GB_OK) {
        wait_finished(job);
        result = gb_background_setup_finish(job, &prepared, &error);
    }
    if (CHECK(succeeded(result, &error) && prepared, "implicit: prepared on a job")) {
        CHECK(h.last == 1.0 && atomic_load(&h.calls) > 1,
              "implicit: the links reported to the caller through the job, up to 1");
        setup.progress = NULL;
        setup.prepared = prepared;
        if (CHECK(method_render(v, &gb_implicit_method, &setup, 1, 1, 0.0, &prepared_image),
                  "implicit: created from the prepared links, renders")) {
            CHECK(same_image(&plain, &prepared_image),
                  "implicit: prepared on a job, the same image bytes as a plain create");
            gb_image_free(&prepared_image);
        }
    }
    gb_image_free(&plain);
}

/* A cancel while the links run: the caller's progress holds the links at
 * their first report until the test has asked to cancel. */
static void test_implicit_cancelled(method_view *v)
{
    gb_method_parameters parameters = {0};
    heard h = {.stop_at = 2.0, .hold = 1};
    gb_indirect_setup setup = method_view_setup(v, &parameters);
    setup.progress = listen;
    setup.progress_user = &h;
    gb_background_setup *job;
    gb_error error;
    if (!CHECK(succeeded(gb_background_setup_start(&gb_implicit_method, &setup, &job, &error),
                         &error),
               "implicit, cancel: the job starts"))
        return;
    for (int waited = 0; !atomic_load(&h.reached) && waited < GATE_WAIT_MS; ++waited)
        sleep_ms(1);
    CHECK(atomic_load(&h.reached), "implicit, cancel: the links reported to the caller");
    atomic_store(&h.release, 1);
    gb_background_setup_cancel(job);
    printf("# cancelled links: %d reports, the last %.3f\n", atomic_load(&h.calls), h.last);
    CHECK(h.last < 1.0, "implicit: cancelled during the links, they were not made");
    CHECK(atomic_load(&h.calls) <= 2, "implicit: the links stopped within two reports");

    /* Cancelled at once: whatever prepare got to, the job ends, nothing leaks. */
    setup.progress = NULL;
    if (CHECK(gb_background_setup_start(&gb_implicit_method, &setup, &job, &error) == GB_OK,
              "implicit: a job cancelled right after its start starts"))
        gb_background_setup_cancel(job);
}

int main(void)
{
    test_stand_in_runs();
    test_stand_in_stopped_by_progress();
    test_stand_in_cancelled();
    test_no_prepare();
    gb_scene scene;
    if (!CHECK(load_cornell(&scene), "the Cornell box loads"))
        return tap_done();
    method_view v;
    if (CHECK(method_view_open(&scene, SIZE, SIZE, &v), "a headless view of the Cornell box")) {
        test_implicit_prepared(&v);
        test_implicit_cancelled(&v);
        method_view_close(&v);
    }
    gb_scene_free(&scene);
    return tap_done();
}
