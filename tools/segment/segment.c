/* segment.c — gb_segment: the steps of noel-biri-2014 §IV.B and §IV.C in
 * order (segment.h). */
#include "segment.h"

#include <stdlib.h>
#include <string.h>

#include "adjacency.h"
#include "coverage_nodes.h"
#include "curvature_nodes.h"
#include "gate_openings.h"
#include "lines.h"
#include "segmented_skeleton.h"
#include "topology_nodes.h"
#include "visibility_clusters.h"
#include "visibility_gates.h"

static double resolve_alpha(const gb_segment_options *options)
{
    if (!options || options->alpha == 0.0)
        return GB_SEGMENT_DEFAULT_ALPHA;
    return options->alpha < 0.0 ? 0.0 : options->alpha;
}

/* Lines between the classified nodes, computed again after a step added some. */
static gb_result refresh_lines(const gb_adjacency *graph, const uint8_t *node_class,
                               gb_lines *lines, gb_error *error)
{
    gb_lines_free(lines);
    return gb_lines_extract(graph, node_class, lines, error);
}

/* §IV.B.1: topology, loops, curvature, coverage; lines ends with the lines
 * between all the classified nodes. */
static gb_result classify_nodes(const gb_skeleton *skeleton, const gb_adjacency *graph,
                                uint8_t *node_class, gb_lines *lines, gb_segment_stats *stats,
                                gb_error *error)
{
    gb_result result = gb_topology_nodes(skeleton, graph, node_class, &stats->rings, error);
    if (!result)
        result = refresh_lines(graph, node_class, lines, error);
    if (result)
        return result;
    stats->lines = lines->count;
    stats->loops = gb_open_loops(skeleton, lines, node_class);
    if (stats->loops)
        result = refresh_lines(graph, node_class, lines, error);
    if (!result)
        result = gb_curvature_nodes(skeleton, lines, node_class, &stats->curvature_nodes, error);
    if (!result)
        result = refresh_lines(graph, node_class, lines, error);
    if (!result)
        result = gb_coverage_nodes(skeleton, lines, node_class, &stats->coverage_nodes, error);
    if (!result)
        result = refresh_lines(graph, node_class, lines, error);
    return result;
}

static void count_classes(const gb_segmentation *out, gb_segment_stats *stats)
{
    stats->topology_nodes = stats->curvature_nodes = stats->coverage_nodes = 0;
    for (uint32_t n = 0; n < out->node_count; ++n) {
        uint32_t c = out->nodes[n].node_class;
        stats->topology_nodes += c == GB_NODE_TOPOLOGY;
        stats->curvature_nodes += c == GB_NODE_CURVATURE;
        stats->coverage_nodes += c == GB_NODE_COVERAGE;
    }
}

static gb_result segment_skeleton(const gb_skeleton *skeleton, double alpha, gb_segmentation *out,
                                  gb_segment_stats *stats, gb_error *error)
{
    gb_adjacency graph;
    gb_lines lines = {0};
    gb_result result = gb_adjacency_build(skeleton->node_count, skeleton->edges,
                                          skeleton->edge_count, &graph, error);
    if (result)
        return result;
    uint8_t *node_class = calloc(skeleton->node_count ? skeleton->node_count : 1, 1);
    if (!node_class)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u nodes",
                         skeleton->node_count);
    if (!result)
        result = classify_nodes(skeleton, &graph, node_class, &lines, stats, error);
    if (!result)
        result = gb_segmented_skeleton(skeleton, node_class, &lines, out, error);
    out->alpha = alpha;
    if (!result)
        result = gb_visibility_clusters(out, alpha, error);
    if (!result)
        result = gb_visibility_gates(out, error);
    free(node_class);
    gb_lines_free(&lines);
    gb_adjacency_free(&graph);
    return result;
}

gb_result gb_segment(const gb_skeleton *skeleton, const gb_segment_options *options,
                     gb_segmentation *out, gb_segment_stats *stats, gb_error *error)
{
    memset(out, 0, sizeof *out);
    gb_segment_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    double start = gb_seconds();
    double alpha = resolve_alpha(options);
    if (!(alpha <= 100.0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "alpha %g is not in [0, 100]", alpha);
    gb_result result = gb_skeleton_validate(skeleton, "skeleton", error);
    if (!result)
        result = segment_skeleton(skeleton, alpha, out, stats, error);
    if (!result)
        result = gb_segmentation_validate(out, "segmentation", error);
    if (result) {
        gb_segmentation_free(out);
        return result;
    }
    count_classes(out, stats);
    stats->seconds = gb_seconds() - start;
    return GB_OK;
}

static int same_frame(const gb_segmentation *s, const gb_voxel_grid *voxels)
{
    return voxels->size[0] == s->grid_size[0] && voxels->size[1] == s->grid_size[1] &&
           voxels->size[2] == s->grid_size[2];
}

/* The openings' gates added, then every disk fitted. */
static gb_result fit_to_openings(gb_segmentation *s, const int32_t *voxel_clusters,
                                 const uint8_t *surface, gb_segment_stats *stats,
                                 gb_error *error)
{
    gb_result result = gb_gate_openings_add(s, voxel_clusters, surface, &stats->opening_gates,
                                            error);
    if (!result)
        result = gb_gate_openings_fit(s, voxel_clusters, surface, &stats->fitted_gates, error);
    return result;
}

gb_result gb_segment_fit_gates(gb_segmentation *s, const gb_voxel_grid *voxels,
                               const int32_t *nearest, gb_segment_stats *stats,
                               gb_error *error)
{
    gb_segment_stats local = {0};
    if (!stats)
        stats = &local;
    if (s->gates_fitted)
        return gb_fail(error, GB_ERROR_ARGUMENT, "the gates are fitted already");
    if (!same_frame(s, voxels))
        return gb_fail(error, GB_ERROR_ARGUMENT, "the voxels are not in the segmentation's frame");
    double start = gb_seconds();
    int32_t *voxel_clusters = gb_segmentation_voxel_clusters(s, nearest);
    if (!voxel_clusters)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for the voxels' clusters");
    gb_result result = fit_to_openings(s, voxel_clusters, voxels->surface, stats, error);
    free(voxel_clusters);
    s->gates_fitted = 1;
    if (!result)
        result = gb_segmentation_validate(s, "segmentation", error);
    stats->seconds += gb_seconds() - start;
    return result;
}
