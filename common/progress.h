/* progress.h — the progress bar a tool prints on stderr during long work.
 *
 * Library code takes a gb_progress_callback (and its user pointer) and calls
 * it with the fraction done; it never prints. A tool's main() passes
 * gb_progress_report with a gb_progress of its own, which draws
 *     voxelize [##########          ] 50%  3 s left
 * on stderr, only when stderr is a terminal and --quiet was not given.
 * The caller owns the gb_progress (usually on its stack).
 */
#ifndef GB_PROGRESS_H
#define GB_PROGRESS_H

/* Returns nonzero to ask the work to stop (the work then fails cleanly). */
typedef int (*gb_progress_callback)(void *user, double fraction);

typedef struct gb_progress {
    const char *label;
    int enabled;
    double start_seconds;
    int last_permille;
} gb_progress;

void gb_progress_begin(gb_progress *progress, const char *label, int quiet);
/* gb_progress_begin, then a library's progress slots pointed at the bar:
 * *callback = gb_progress_report, *user = progress. */
void gb_progress_begin_for(gb_progress *progress, const char *label, int quiet,
                           gb_progress_callback *callback, void **user);
int gb_progress_report(void *progress, double fraction);
void gb_progress_end(gb_progress *progress);

/* One step's share [start, start + length] of a whole job's progress: give
 * the step gb_progress_span_report and a span as its callback and user, and
 * its fraction f reaches progress as start + length * f (a NULL progress
 * never stops). The caller owns the span, which outlives the step. */
typedef struct gb_progress_span {
    gb_progress_callback progress;
    void *user;
    double start, length;
} gb_progress_span;
int gb_progress_span_report(void *span, double fraction);

/* Seconds from an arbitrary start (monotonic clock). */
double gb_seconds(void);
/* CPU seconds the process has used, every thread counted. */
double gb_cpu_seconds(void);

#endif
