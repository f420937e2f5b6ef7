/* thin.c — the steps of thin in order (see thin.h). */
#include "thin.h"

#include <malloc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cavities.h"
#include "collapse.h"
#include "cubical_complex.h"
#include "empty_voxels.h"
#include "nearest_node.h"
#include "persistence.h"
#include "skeleton_graph.h"

/* The share [start, start + length] of thin's progress. */
static gb_progress_span make_stage(const gb_thin_options *options, double start, double length)
{
    return (gb_progress_span){options->progress, options->progress_user, start, length};
}

static gb_thin_options resolved_options(const gb_thin_options *given)
{
    gb_thin_options options = {0};
    if (given)
        options = *given;
    if (options.persistence == 0.0)
        options.persistence = GB_THIN_DEFAULT_PERSISTENCE;
    else if (options.persistence < 0.0)
        options.persistence = 0.0;
    if (options.min_lifespan == 0.0)
        options.min_lifespan = GB_THIN_DEFAULT_MIN_LIFESPAN;
    else if (options.min_lifespan < 0.0)
        options.min_lifespan = 0.0;
    if (options.threads <= 0)
        options.threads = GB_THIN_DEFAULT_THREADS;
    if (options.threads > GB_THIN_MAX_THREADS)
        options.threads = GB_THIN_MAX_THREADS;
    return options;
}

static gb_result check_input(const gb_voxel_grid *grid, const gb_thin_options *options,
                             gb_error *error)
{
    if (!grid || !grid->surface)
        return gb_fail(error, GB_ERROR_ARGUMENT, "no voxel grid");
    for (int a = 0; a < 3; ++a)
        if (grid->size[a] <= 0 || !isfinite(grid->world_origin[a]))
            return gb_fail(error, GB_ERROR_ARGUMENT, "bad grid frame");
    if (!isfinite(grid->voxel_size) || !(grid->voxel_size > 0.0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "voxel size %g is not positive",
                       grid->voxel_size);
    if (!isfinite(options->persistence) || !isfinite(options->min_lifespan))
        return gb_fail(error, GB_ERROR_ARGUMENT, "persistence parameters are not finite");
    return GB_OK;
}

/* Collapse, then open the cavities it stops on and collapse again, until no
 * 2-cycle is left. */
static gb_result thin_complex(gb_cubical_complex *complex, gb_persistence *persistence,
                              const gb_thin_options *options, gb_thin_stats *stats,
                              gb_error *error)
{
    gb_collapse collapse;
    gb_result result = gb_collapse_init(&collapse, complex, persistence, options->threads, error);
    if (result)
        return result;
    gb_progress_span s = make_stage(options, 0.15, 0.45);
    uint32_t opened = 1;
    while (!result && opened) {
        result = gb_collapse_run(&collapse, gb_progress_span_report, &s, error);
        if (!result)
            result = gb_open_cavities(complex, &collapse, &stats->squares_left, &opened, error);
        stats->cavities_opened += opened;
    }
    stats->iterations = collapse.iteration;
    stats->shared_iterations = collapse.shared_iterations;
    stats->empty_voxels = collapse.cubes;
    stats->cells_examined = collapse.cells_examined;
    stats->pairs_removed = collapse.pairs_removed;
    gb_collapse_free(&collapse);
    return result;
}

/* The complex and the empty voxels, all thin reads of the surface: then
 * the surface is given back if it is thin's to free, before the maps. */
static gb_result build_maps(const gb_voxel_grid *grid, uint8_t **surface_to_free,
                            const gb_thin_options *options, gb_cubical_complex *complex,
                            gb_empty_voxels *empty, gb_persistence *persistence,
                            gb_error *error)
{
    gb_result result = gb_cubical_complex_build(complex, grid, error);
    if (!result)
        result = gb_empty_voxels_of(grid, empty, error);
    if (surface_to_free) {
        free(*surface_to_free);
        *surface_to_free = NULL;
    }
    if (result)
        return result;
    gb_progress_span s = make_stage(options, 0.0, 0.15);
    return gb_persistence_init(persistence, complex, options->persistence,
                               options->min_lifespan, options->threads,
                               gb_progress_span_report, &s, error);
}

static void describe(gb_skeleton *skeleton, const gb_voxel_grid *grid,
                     const gb_thin_options *options, const gb_thin_stats *stats)
{
    skeleton->voxel_size = grid->voxel_size;
    memcpy(skeleton->world_origin, grid->world_origin, sizeof skeleton->world_origin);
    memcpy(skeleton->grid_size, grid->size, sizeof skeleton->grid_size);
    skeleton->resolution = grid->resolution;
    skeleton->scene_hash = grid->scene_hash;
    skeleton->persistence = options->persistence;
    skeleton->min_lifespan = options->min_lifespan;
    skeleton->iterations = stats->iterations;
    skeleton->cavities_broken = stats->cavities_opened;
}

static gb_result compute_nearest(const gb_voxel_grid *grid, const gb_empty_voxels *empty,
                                 const gb_cubical_complex *complex,
                                 const uint32_t *node_cells, uint32_t node_count,
                                 const gb_thin_options *options, int32_t **nearest,
                                 gb_error *error)
{
    gb_progress_span s = make_stage(options, 0.65, 0.35);
    gb_nearest_options nearest_options = {GB_NEAREST_SWEEP_PAIRS, options->threads,
                                          gb_progress_span_report, &s};
    return gb_nearest_node(grid, empty, complex, node_cells, node_count, &nearest_options,
                           nearest, error);
}

/* gb_thin; with surface_to_free (&grid->surface), that too once read. */
static gb_result thin_grid(const gb_voxel_grid *grid, uint8_t **surface_to_free,
                           const gb_thin_options *given_options, gb_skeleton *skeleton,
                           int32_t **nearest, gb_thin_stats *stats_out, gb_error *error)
{
    gb_thin_options options = resolved_options(given_options);
    memset(skeleton, 0, sizeof *skeleton);
    if (nearest)
        *nearest = NULL;
    gb_result result = check_input(grid, &options, error);
    if (result)
        return result;
    gb_thin_stats stats = {0};
    gb_cubical_complex complex = {0};
    gb_empty_voxels empty = {0};
    gb_persistence persistence = {0};
    uint32_t *node_cells = NULL;
    double start = gb_seconds(), cpu_start = gb_cpu_seconds();
    result = build_maps(grid, surface_to_free, &options, &complex, &empty, &persistence, error);
    double maps_done = gb_seconds();
    if (!result)
        result = thin_complex(&complex, &persistence, &options, &stats, error);
    double collapse_done = gb_seconds();
    gb_persistence_free(&persistence);
    if (!result)
        result = gb_skeleton_graph_build(&complex, grid, &empty, skeleton, &node_cells, error);
    double graph_done = gb_seconds(), cpu_graph_done = gb_cpu_seconds();
    /* the faces are done with: only the lattice's frame is used from here */
    free(complex.faces);
    complex.faces = NULL;
    /* the collapse's lists grew on the heap, which glibc keeps once freed: give it back
     * before the nearest-node grid takes its 6 bytes a cell */
    malloc_trim(0);
    if (!result && nearest)
        result = compute_nearest(grid, &empty, &complex, node_cells, skeleton->node_count,
                                 &options, nearest, error);
    double nearest_done = gb_seconds(), cpu_nearest_done = gb_cpu_seconds();
    gb_cubical_complex_free(&complex);
    gb_empty_voxels_free(&empty);
    free(node_cells);
    if (result) {
        gb_skeleton_free(skeleton);
        return result;
    }
    stats.seconds_maps = maps_done - start;
    stats.seconds_collapse = collapse_done - maps_done;
    stats.seconds_graph = graph_done - collapse_done;
    stats.seconds_nearest = nearest_done - graph_done;
    stats.cpu_seconds_skeleton = cpu_graph_done - cpu_start;
    stats.cpu_seconds_nearest = cpu_nearest_done - cpu_graph_done;
    describe(skeleton, grid, &options, &stats);
    if (stats_out)
        *stats_out = stats;
    return GB_OK;
}

gb_result gb_thin(const gb_voxel_grid *grid, const gb_thin_options *options,
                  gb_skeleton *skeleton, int32_t **nearest, gb_thin_stats *stats,
                  gb_error *error)
{
    return thin_grid(grid, NULL, options, skeleton, nearest, stats, error);
}

gb_result gb_thin_and_free(gb_voxel_grid *grid, const gb_thin_options *options,
                           gb_skeleton *skeleton, int32_t **nearest, gb_thin_stats *stats,
                           gb_error *error)
{
    gb_result result = thin_grid(grid, grid ? &grid->surface : NULL, options, skeleton,
                                 nearest, stats, error);
    if (grid) {
        free(grid->surface);
        grid->surface = NULL;
    }
    return result;
}
