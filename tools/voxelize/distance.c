/* distance.c — exact Euclidean distance transform (see distance.h): three
 * separable passes of squared distances, x then y then z, each line by the
 * lower envelope of parabolas of Felzenszwalb & Huttenlocher. */
#include "distance.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "threads.h"

/* Squared distance of a voxel with no site yet on its lines: as stored in
 * the grid's floats, and in the integer work space. */
#define FAR_AWAY 1e30f
#define NO_SITE INT32_MAX

/* Lines of the y and z passes are processed BUNDLE at a time, adjacent in x,
 * so that each read of the grid uses whole cache lines. */
enum { BUNDLE = 32 };

enum { PASSES = 3 };

/* Work space of one thread for lines of up to length voxels. */
typedef struct line_space {
    int32_t *values;   /* BUNDLE * length, line b at values + b * length */
    int32_t *site;     /* parabolas of the lower envelope: their sites, */
    int64_t *height;   /* their values at their sites, */
    int64_t *numerator, *denominator; /* where each begins: a fraction */
    void *storage;     /* the one allocation they all view */
} line_space;

static int line_space_allocate(line_space *space, int length)
{
    size_t n = (size_t)length;
    /* the 8-byte arrays first, so that each stays aligned */
    space->storage = malloc(n * (3 * sizeof(int64_t) + (BUNDLE + 1) * sizeof(int32_t)));
    if (!space->storage)
        return 0;
    space->height = space->storage;
    space->numerator = space->height + n;
    space->denominator = space->numerator + n;
    space->values = (int32_t *)(void *)(space->denominator + n);
    space->site = space->values + BUNDLE * n;
    return 1;
}

static void line_space_free(line_space *space)
{
    free(space->storage);
    space->storage = NULL;
}

/* f[q] = min over sites p (f[p] != NO_SITE) of (q - p)^2 + f[p], in place:
 * F&H algorithm 1 restricted to finite sites, with the meeting points of
 * parabolas kept as exact fractions ((f[q] + q^2) - (f[p] + p^2)) / 2(q - p)
 * compared by cross-multiplication (below 2^40: exact in int64). */
static void transform_line(int32_t *f, int n, line_space *space)
{
    int32_t *site = space->site;
    int64_t *height = space->height, *numerator = space->numerator;
    int64_t *denominator = space->denominator;
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == NO_SITE)
            continue;
        int64_t level = (int64_t)f[q] + (int64_t)q * q, num = 0, den = 1;
        for (;;) {
            if (k < 0)
                break;
            num = level - (height[k] + (int64_t)site[k] * site[k]);
            den = 2 * (int64_t)(q - site[k]);
            /* Parabola k is hidden if q's meets it before k begins. */
            if (k > 0 && num * denominator[k] <= numerator[k] * den)
                --k;
            else
                break;
        }
        ++k;
        site[k] = q;
        height[k] = f[q];
        if (k > 0)
            numerator[k] = num, denominator[k] = den;
    }
    if (k < 0)
        return;
    int last = k;
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (k < last && numerator[k + 1] < (int64_t)q * denominator[k + 1])
            ++k;
        int64_t dq = q - site[k];
        f[q] = (int32_t)(dq * dq + height[k]);
    }
}

typedef struct distance_job {
    gb_voxel_grid *grid;
    const gb_voxelize_options *options;
    int pass;               /* 0: x, 1: y, 2: z (then world units) */
    line_space *spaces;     /* one per thread */
    atomic_int stop;        /* set when the progress callback asks to stop */
} distance_job;

/* Thread 0 reports progress; every thread stops soon after it is asked. */
static int should_stop(distance_job *job, int thread, size_t done, size_t total)
{
    if ((done & 63) != 0)
        return 0;
    if (thread == 0 && job->options->progress
        && job->options->progress(job->options->progress_user,
                                  (job->pass + (double)done / total) / PASSES))
        atomic_store(&job->stop, 1);
    return atomic_load(&job->stop);
}

/* Squared distance along the row to its nearest surface voxel (two sweeps),
 * FAR_AWAY when the row has none. */
static void row_distance(const uint8_t *surface, float *f, int n)
{
    int last = -1;
    for (int i = 0; i < n; ++i) {
        if (surface[i])
            last = i;
        f[i] = last < 0 ? FAR_AWAY : (float)(i - last) * (float)(i - last);
    }
    last = -1;
    for (int i = n - 1; i >= 0; --i) {
        if (surface[i])
            last = i;
        if (last >= 0) {
            float squared = (float)(last - i) * (float)(last - i);
            if (squared < f[i])
                f[i] = squared;
        }
    }
}

/* Rows along x: sites are the surface voxels. */
static void pass_x(distance_job *job, int thread, int thread_count)
{
    gb_voxel_grid *grid = job->grid;
    int nx = grid->size[0];
    size_t rows = (size_t)grid->size[1] * grid->size[2];
    size_t first = rows * thread / thread_count, end = rows * (thread + 1) / thread_count;
    for (size_t row = first; row < end; ++row) {
        if (should_stop(job, thread, row - first, end - first))
            return;
        row_distance(grid->surface + row * nx, grid->distance + row * nx, nx);
    }
}

/* The last pass writes distances in world units: voxel_size * sqrt(n). */
static void scatter_world_units(const int32_t *values, int n, int width, float *base,
                                size_t stride, double voxel_size)
{
    for (int p = 0; p < n; ++p)
        for (int b = 0; b < width; ++b)
            base[p * stride + b] =
                (float)(sqrt((double)values[(size_t)b * n + p]) * voxel_size);
}

/* Lines along y (axis 1) or z (axis 2), BUNDLE adjacent in x at a time:
 * gather, transform, scatter (in world units after z). */
static void pass_across(distance_job *job, int axis, int thread, int thread_count,
                        line_space *space)
{
    gb_voxel_grid *grid = job->grid;
    int nx = grid->size[0], ny = grid->size[1], nz = grid->size[2];
    int n = grid->size[axis], other = axis == 1 ? nz : ny;
    size_t stride = axis == 1 ? (size_t)nx : (size_t)nx * ny;
    size_t step_other = axis == 1 ? (size_t)nx * ny : (size_t)nx;
    int bundles = (nx + BUNDLE - 1) / BUNDLE;
    size_t items = (size_t)bundles * other;
    size_t first = items * thread / thread_count, end = items * (thread + 1) / thread_count;
    for (size_t item = first; item < end; ++item) {
        if (should_stop(job, thread, item - first, end - first))
            return;
        int i0 = (int)(item % bundles) * BUNDLE, width = nx - i0 < BUNDLE ? nx - i0 : BUNDLE;
        float *base = grid->distance + (item / bundles) * step_other + i0;
        int32_t *values = space->values;
        for (int p = 0; p < n; ++p)
            for (int b = 0; b < width; ++b) {
                float squared = base[p * stride + b];
                values[(size_t)b * n + p] = squared >= FAR_AWAY ? NO_SITE : (int32_t)squared;
            }
        for (int b = 0; b < width; ++b)
            transform_line(values + (size_t)b * n, n, space);
        if (axis == 2)
            scatter_world_units(values, n, width, base, stride, grid->voxel_size);
        else
            for (int p = 0; p < n; ++p)
                for (int b = 0; b < width; ++b) {
                    int32_t squared = values[(size_t)b * n + p];
                    base[p * stride + b] = squared == NO_SITE ? FAR_AWAY : (float)squared;
                }
    }
}

static void run_pass(void *context, int thread, int thread_count)
{
    distance_job *job = context;
    if (job->pass == 0)
        pass_x(job, thread, thread_count);
    else
        pass_across(job, job->pass, thread, thread_count, &job->spaces[thread]);
}

gb_result gb_distance_transform(gb_voxel_grid *grid, const gb_voxelize_options *given,
                                gb_error *error)
{
    gb_voxelize_options options = {0};
    if (given)
        options = *given;
    if (options.thread_count <= 0)
        options.thread_count = GB_VOXELIZE_DEFAULT_THREADS;
    double farthest = 0;
    for (int d = 0; d < 3; ++d)
        farthest += ((double)grid->size[d] - 1) * ((double)grid->size[d] - 1);
    if (farthest >= 16777216.0)
        return gb_fail(error, GB_ERROR_ARGUMENT,
                       "distance: grid %d x %d x %d too large for exact squared distances",
                       (int)grid->size[0], (int)grid->size[1], (int)grid->size[2]);
    size_t count = (size_t)grid->size[0] * grid->size[1] * grid->size[2];
    if (!memchr(grid->surface, 1, count))
        return gb_fail(error, GB_ERROR_INVALID, "distance: the grid has no surface voxel");
    int longest = grid->size[0] > grid->size[1] ? grid->size[0] : grid->size[1];
    longest = longest > grid->size[2] ? longest : grid->size[2];
    line_space *spaces = calloc((size_t)options.thread_count, sizeof *spaces);
    int allocated = spaces != NULL;
    for (int t = 0; allocated && t < options.thread_count; ++t)
        allocated = line_space_allocate(&spaces[t], longest);
    int stopped = 0;
    if (allocated) {
        distance_job job = {grid, &options, 0, spaces, 0};
        for (job.pass = 0; job.pass < PASSES && !atomic_load(&job.stop); ++job.pass)
            gb_run_threads(run_pass, &job, options.thread_count);
        stopped = atomic_load(&job.stop);
    }
    for (int t = 0; spaces && t < options.thread_count; ++t)
        line_space_free(&spaces[t]);
    free(spaces);
    if (!allocated)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "distance: out of memory");
    if (stopped || (options.progress && options.progress(options.progress_user, 1.0)))
        return gb_fail(error, GB_ERROR_INTERRUPTED, "distance: interrupted");
    return GB_OK;
}
