/* voxelize.c — scene triangles to surface voxels, conservatively (see
 * voxelize.h): for each triangle, the voxels near its plane inside its
 * bounding box are tested with the exact triangle/box test. */
#include "voxelize.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "threads.h"
#include "triangle_box_overlap.h"

/* Threads own interleaved slabs of this many z layers, so that each voxel is
 * written by one thread only. */
enum { SLAB_LAYERS = 16 };

/* Candidates along the dominant axis are widened by this (voxel units) to
 * cover the rounding of the plane equation; the exact test decides. */
static const double PLANE_MARGIN = 1e-6;

/* ------------------------------------------------------------- options */

static gb_result resolve_options(const gb_voxelize_options *given, gb_voxelize_options *options,
                                 gb_error *error)
{
    gb_voxelize_options zero = {0};
    *options = given ? *given : zero;
    if (options->resolution == 0)
        options->resolution = GB_VOXELIZE_DEFAULT_RESOLUTION;
    if (options->pad == 0)
        options->pad = GB_VOXELIZE_DEFAULT_PAD;
    else if (options->pad == GB_VOXELIZE_NO_PAD)
        options->pad = 0;
    if (options->thread_count == 0)
        options->thread_count = GB_VOXELIZE_DEFAULT_THREADS;
    if (options->resolution > GB_VOXELIZE_MAX_RESOLUTION)
        return gb_fail(error, GB_ERROR_ARGUMENT, "resolution %u is above the maximum %d",
                       options->resolution, GB_VOXELIZE_MAX_RESOLUTION);
    if (options->pad < 0 || options->pad > GB_VOXELIZE_MAX_PAD)
        return gb_fail(error, GB_ERROR_ARGUMENT, "pad %d is not in 0..%d", (int)options->pad,
                       GB_VOXELIZE_MAX_PAD);
    if (options->thread_count < 1 || options->thread_count > 64)
        return gb_fail(error, GB_ERROR_ARGUMENT, "thread count %d is not in 1..64",
                       (int)options->thread_count);
    return GB_OK;
}

/* ------------------------------------------------------------- input */

/* Checks indices and positions of the triangles and returns their bounds. */
static gb_result triangle_bounds(const float *positions, uint32_t vertex_count,
                                 const uint32_t *indices, uint32_t triangle_count,
                                 double lower[3], double upper[3], gb_error *error)
{
    if (triangle_count == 0)
        return gb_fail(error, GB_ERROR_INVALID, "no triangle to voxelize");
    for (int d = 0; d < 3; ++d) {
        lower[d] = INFINITY;
        upper[d] = -INFINITY;
    }
    for (uint32_t t = 0; t < triangle_count; ++t)
        for (int corner = 0; corner < 3; ++corner) {
            uint32_t v = indices[3 * (size_t)t + corner];
            if (v >= vertex_count)
                return gb_fail(error, GB_ERROR_INVALID,
                               "triangle %u: vertex index %u out of range (%u vertices)", t, v,
                               vertex_count);
            for (int d = 0; d < 3; ++d) {
                double x = positions[3 * (size_t)v + d];
                if (!isfinite(x))
                    return gb_fail(error, GB_ERROR_INVALID,
                                   "triangle %u: vertex %u is not finite", t, v);
                lower[d] = fmin(lower[d], x);
                upper[d] = fmax(upper[d], x);
            }
        }
    return GB_OK;
}

/* ------------------------------------------------------------- frame */

/* The frame for bounds lower..upper with resolved options. Each side is
 * computed as the vertices' voxel coordinates are, so that every vertex falls
 * inside the grid. */
static gb_result make_frame(const double lower[3], const double upper[3],
                            const gb_voxelize_options *options, gb_voxel_grid *frame,
                            gb_error *error)
{
    double longest = 0;
    for (int d = 0; d < 3; ++d)
        longest = fmax(longest, upper[d] - lower[d]);
    if (!(longest > 0) || !isfinite(longest))
        return gb_fail(error, GB_ERROR_INVALID,
                       "the triangles have zero extent: nothing to voxelize");
    double voxel_size = longest / options->resolution;
    if (!(voxel_size > 0))
        return gb_fail(error, GB_ERROR_INVALID, "the scene is too small (%g) to voxelize",
                       longest);
    memset(frame, 0, sizeof *frame);
    for (int d = 0; d < 3; ++d) {
        double voxels = ceil((upper[d] - lower[d]) / voxel_size);
        if (voxels < 1)
            voxels = 1;
        frame->size[d] = (int32_t)voxels + 2 * options->pad;
        frame->world_origin[d] = lower[d] - options->pad * voxel_size;
    }
    frame->voxel_size = voxel_size;
    frame->resolution = options->resolution;
    return GB_OK;
}

gb_result gb_voxelize_frame(const double lower[3], const double upper[3],
                            const gb_voxelize_options *given, gb_voxel_grid *frame,
                            gb_error *error)
{
    gb_voxelize_options options;
    gb_result result = resolve_options(given, &options, error);
    if (result == GB_OK)
        result = make_frame(lower, upper, &options, frame, error);
    return result;
}

/* ------------------------------------------------------------- surface */

typedef struct surface_job {
    gb_voxel_grid *grid;
    const float *positions;
    const uint32_t *indices;
    uint32_t triangle_count;
    double reference[3], reference_voxel[3];
    const gb_voxelize_options *options;
    atomic_int stop;     /* set when the progress callback asks to stop */
} surface_job;

/* A triangle in voxel coordinates relative to the integer corner origin, and
 * the voxels of the grid its bounding box touches (inclusive). */
typedef struct placed_triangle {
    gb_triangle_boxes test;
    int origin[3];
    int lower[3], upper[3];
    int dominant;        /* axis of the largest normal component, -1 if none */
} placed_triangle;

/* Voxel coordinates of the triangle's vertices; its voxel range (a point at
 * an integer coordinate x touches voxels x-1 and x), clipped to the grid.
 * Returns 0 when the range is empty. */
static int place_triangle(const surface_job *job, uint32_t t, double vertex[3][3],
                          placed_triangle *placed)
{
    const gb_voxel_grid *grid = job->grid;
    for (int corner = 0; corner < 3; ++corner) {
        const float *p = job->positions + 3 * (size_t)job->indices[3 * (size_t)t + corner];
        for (int d = 0; d < 3; ++d)
            vertex[corner][d] = ((double)p[d] - job->reference[d]) / grid->voxel_size
                                + job->reference_voxel[d];
    }
    for (int d = 0; d < 3; ++d) {
        double low = fmin(vertex[0][d], fmin(vertex[1][d], vertex[2][d]));
        double high = fmax(vertex[0][d], fmax(vertex[1][d], vertex[2][d]));
        if (high < -1 || low > grid->size[d] + 1)
            return 0;
        /* Beyond the grid the range is clipped anyway: keep it in int. */
        low = fmax(low, -2.0);
        high = fmin(high, grid->size[d] + 2.0);
        placed->origin[d] = (int)ceil(low) - 1;
        placed->lower[d] = placed->origin[d] < 0 ? 0 : placed->origin[d];
        int top = (int)floor(high);
        placed->upper[d] = top >= grid->size[d] ? grid->size[d] - 1 : top;
        if (placed->lower[d] > placed->upper[d])
            return 0;
    }
    return 1;
}

/* Prepares the exact test on vertices relative to origin (exact: integer
 * shifts) and picks the dominant axis of the normal. */
static void prepare_triangle(double vertex[3][3], placed_triangle *placed)
{
    static const double half[3] = {0.5, 0.5, 0.5};
    for (int corner = 0; corner < 3; ++corner)
        for (int d = 0; d < 3; ++d)
            vertex[corner][d] -= placed->origin[d];
    gb_triangle_boxes_prepare(&placed->test, (const double(*)[3])vertex, half);
    const double *normal = placed->test.axis[0];
    placed->dominant = -1;
    double largest = 0;
    for (int d = 0; d < 3; ++d)
        if (fabs(normal[d]) > largest) {
            largest = fabs(normal[d]);
            placed->dominant = d;
        }
}

/* Range of voxels along the dominant axis d that the triangle's plane slab
 * crosses over the column of voxels (ia, ib) of the other axes a, b; local
 * coordinates. */
static void plane_range(const placed_triangle *placed, int a, int b, int ia, int ib,
                        int *first, int *last)
{
    const gb_triangle_boxes *test = &placed->test;
    int d = placed->dominant;
    double n[3] = {test->axis[0][0], test->axis[0][1], test->axis[0][2]};
    double slack = test->slack[0] * (test->magnitude + 2);
    double w_low = test->low[0] - slack, w_high = test->high[0] + slack;
    if (n[d] < 0) {
        for (int k = 0; k < 3; ++k)
            n[k] = -n[k];
        double swap = w_low;
        w_low = -w_high;
        w_high = -swap;
    }
    /* x_d = (w - n_a x_a - n_b x_b) / n_d over the closed column. */
    double xa0 = ia, xa1 = ia + 1.0, xb0 = ib, xb1 = ib + 1.0;
    double most = fmax(n[a] * xa0, n[a] * xa1) + fmax(n[b] * xb0, n[b] * xb1);
    double least = fmin(n[a] * xa0, n[a] * xa1) + fmin(n[b] * xb0, n[b] * xb1);
    double low = (w_low - most) / n[d], high = (w_high - least) / n[d];
    *first = (int)floor(low - PLANE_MARGIN);
    *last = (int)floor(high + PLANE_MARGIN);
}

/* Tests the voxels of the triangle's range whose z is in [z_first, z_last]
 * and marks those it touches. */
static void mark_triangle(gb_voxel_grid *grid, const placed_triangle *placed, int z_first,
                          int z_last)
{
    int lower[3] = {placed->lower[0], placed->lower[1], z_first};
    int upper[3] = {placed->upper[0], placed->upper[1], z_last};
    int d = placed->dominant < 0 ? 2 : placed->dominant;
    int a = (d + 1) % 3, b = (d + 2) % 3;
    const int *o = placed->origin;
    for (int ib = lower[b]; ib <= upper[b]; ++ib)
        for (int ia = lower[a]; ia <= upper[a]; ++ia) {
            int first = lower[d], last = upper[d];
            if (placed->dominant >= 0) {
                int plane_first, plane_last;
                plane_range(placed, a, b, ia - o[a], ib - o[b], &plane_first, &plane_last);
                if (plane_first + o[d] > first)
                    first = plane_first + o[d];
                if (plane_last + o[d] < last)
                    last = plane_last + o[d];
            }
            int voxel[3];
            voxel[a] = ia;
            voxel[b] = ib;
            for (voxel[d] = first; voxel[d] <= last; ++voxel[d]) {
                size_t index = gb_voxel_index(grid, voxel[0], voxel[1], voxel[2]);
                if (grid->surface[index])
                    continue;
                double centre[3] = {voxel[0] - o[0] + 0.5, voxel[1] - o[1] + 0.5,
                                    voxel[2] - o[2] + 0.5};
                if (gb_triangle_boxes_overlap(&placed->test, centre))
                    grid->surface[index] = 1;
            }
        }
}

/* Thread 0 reports progress; every thread stops soon after it is asked. */
static int should_stop(surface_job *job, int thread, uint32_t t)
{
    if ((t & 1023) != 0)
        return 0;
    if (thread == 0 && job->options->progress
        && job->options->progress(job->options->progress_user, (double)t / job->triangle_count))
        atomic_store(&job->stop, 1);
    return atomic_load(&job->stop);
}

/* Thread `thread` marks the voxels of the slabs it owns, for every triangle. */
static void mark_slabs(void *context, int thread, int thread_count)
{
    surface_job *job = context;
    for (uint32_t t = 0; t < job->triangle_count; ++t) {
        if (should_stop(job, thread, t))
            return;
        double vertex[3][3];
        placed_triangle placed;
        if (!place_triangle(job, t, vertex, &placed))
            continue;
        int prepared = 0;
        for (int slab = placed.lower[2] / SLAB_LAYERS; slab <= placed.upper[2] / SLAB_LAYERS;
             ++slab) {
            if (slab % thread_count != thread)
                continue;
            if (!prepared) {
                prepare_triangle(vertex, &placed);
                prepared = 1;
            }
            int z_first = slab * SLAB_LAYERS, z_last = z_first + SLAB_LAYERS - 1;
            mark_triangle(job->grid, &placed, z_first > placed.lower[2] ? z_first : placed.lower[2],
                          z_last < placed.upper[2] ? z_last : placed.upper[2]);
        }
    }
}

/* gb_voxelize_surface with resolved options. */
static gb_result mark_surface(gb_voxel_grid *grid, const double reference[3],
                              const double reference_voxel[3], const float *positions,
                              uint32_t vertex_count, const uint32_t *indices,
                              uint32_t triangle_count, const gb_voxelize_options *options,
                              gb_error *error)
{
    if (!grid || !grid->surface || !(grid->voxel_size > 0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "voxelize: the grid is not allocated");
    double lower[3], upper[3];
    gb_result result = triangle_bounds(positions, vertex_count, indices, triangle_count,
                                       lower, upper, error);
    if (result != GB_OK)
        return result;
    surface_job job = {grid, positions, indices, triangle_count, {0}, {0}, options, 0};
    memcpy(job.reference, reference, sizeof job.reference);
    memcpy(job.reference_voxel, reference_voxel, sizeof job.reference_voxel);
    gb_run_threads(mark_slabs, &job, options->thread_count);
    if (atomic_load(&job.stop))
        return gb_fail(error, GB_ERROR_INTERRUPTED, "voxelize: interrupted");
    if (options->progress && options->progress(options->progress_user, 1.0))
        return gb_fail(error, GB_ERROR_INTERRUPTED, "voxelize: interrupted");
    return GB_OK;
}

gb_result gb_voxelize_surface(gb_voxel_grid *grid, const double reference[3],
                              const double reference_voxel[3], const float *positions,
                              uint32_t vertex_count, const uint32_t *indices,
                              uint32_t triangle_count, const gb_voxelize_options *given,
                              gb_error *error)
{
    gb_voxelize_options options;
    gb_result result = resolve_options(given, &options, error);
    if (result == GB_OK)
        result = mark_surface(grid, reference, reference_voxel, positions, vertex_count,
                              indices, triangle_count, &options, error);
    return result;
}

/* ------------------------------------------------------------- all steps */

/* Options whose progress reports into span (when there is a progress). */
static gb_voxelize_options step_options(const gb_voxelize_options *options,
                                        gb_progress_span *span, double start,
                                        double length)
{
    gb_voxelize_options step = *options;
    *span = (gb_progress_span){options->progress, options->progress_user, start, length};
    if (options->progress) {
        step.progress = gb_progress_span_report;
        step.progress_user = span;
    }
    return step;
}

gb_result gb_voxelize_triangles(const float *positions, uint32_t vertex_count,
                                const uint32_t *indices, uint32_t triangle_count,
                                const gb_voxelize_options *given, gb_voxel_grid *grid,
                                gb_error *error)
{
    gb_voxelize_options options;
    gb_result result = resolve_options(given, &options, error);
    if (result != GB_OK)
        return result;
    double lower[3], upper[3];
    result = triangle_bounds(positions, vertex_count, indices, triangle_count, lower, upper,
                             error);
    gb_voxel_grid frame;
    if (result == GB_OK)
        result = make_frame(lower, upper, &options, &frame, error);
    if (result == GB_OK) {
        int32_t size[3] = {frame.size[0], frame.size[1], frame.size[2]};
        result = gb_voxel_grid_allocate(&frame, size, error);
    }
    if (result != GB_OK)
        return result;
    double pad[3] = {options.pad, options.pad, options.pad};
    gb_progress_span span;
    gb_voxelize_options step = step_options(&options, &span, 0, 1);
    result = mark_surface(&frame, lower, pad, positions, vertex_count, indices,
                          triangle_count, &step, error);
    if (result != GB_OK) {
        gb_voxel_grid_free(&frame);
        return result;
    }
    *grid = frame;
    return GB_OK;
}

gb_result gb_voxelize_scene(const gb_scene *scene, const gb_voxelize_options *options,
                            gb_voxel_grid *grid, gb_error *error)
{
    gb_result result = gb_voxelize_triangles(scene->positions, scene->vertex_count,
                                             scene->indices, scene->triangle_count, options,
                                             grid, error);
    if (result == GB_OK)
        grid->scene_hash = scene->hash;
    return result;
}
