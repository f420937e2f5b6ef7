#include "progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

enum { BAR_WIDTH = 30 };

double gb_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

double gb_cpu_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

void gb_progress_begin(gb_progress *progress, const char *label, int quiet)
{
    progress->label = label;
    progress->enabled = !quiet && isatty(STDERR_FILENO);
    progress->start_seconds = gb_seconds();
    progress->last_permille = -1;
}

void gb_progress_begin_for(gb_progress *progress, const char *label, int quiet,
                           gb_progress_callback *callback, void **user)
{
    gb_progress_begin(progress, label, quiet);
    *callback = gb_progress_report;
    *user = progress;
}

static void draw(const gb_progress *progress, double fraction)
{
    char bar[BAR_WIDTH + 1];
    int filled = (int)(fraction * BAR_WIDTH);
    for (int i = 0; i < BAR_WIDTH; ++i)
        bar[i] = i < filled ? '#' : ' ';
    bar[BAR_WIDTH] = '\0';
    double elapsed = gb_seconds() - progress->start_seconds;
    double left = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : -1.0;
    if (left >= 0.0)
        fprintf(stderr, "\r%s [%s] %3d%%  %.0f s left ", progress->label, bar,
                (int)(fraction * 100.0), left);
    else
        fprintf(stderr, "\r%s [%s] %3d%%", progress->label, bar, (int)(fraction * 100.0));
}

int gb_progress_span_report(void *user, double fraction)
{
    const gb_progress_span *span = user;
    return span->progress ? span->progress(span->user, span->start + span->length * fraction)
                          : 0;
}

int gb_progress_report(void *user, double fraction)
{
    gb_progress *progress = user;
    if (!progress || !progress->enabled)
        return 0;
    if (fraction < 0.0)
        fraction = 0.0;
    if (fraction > 1.0)
        fraction = 1.0;
    int permille = (int)(fraction * 1000.0);
    if (permille == progress->last_permille)
        return 0;
    progress->last_permille = permille;
    draw(progress, fraction);
    return 0;
}

void gb_progress_end(gb_progress *progress)
{
    if (progress->enabled && progress->last_permille >= 0)
        fprintf(stderr, "\r%s done in %.2f s%*s\n", progress->label,
                gb_seconds() - progress->start_seconds, BAR_WIDTH, "");
}
