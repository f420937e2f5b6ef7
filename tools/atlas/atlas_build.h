/* atlas_build.h — a scene's lightmap atlas (vivianloc-2007 §4.2.3, Figure
 * 1: "Atlas LSCM parametrisation"), the steps in order:
 *   charts.h        charts grown over shared edges within a normal cone
 *   discs.h         each cut until it is a topological disc
 *   parameterize.h  each disc mapped by LSCM (lscm.h, CGAL), split again on a fold
 *   merge.h         small charts joined to a neighbour when that packs smaller
 *   packing.h       turned, scaled to one texel density, packed by shape
 *                   (chart_mask.h, occupancy.h) with a gutter
 *   overlap.h       the exact test that no two triangles overlap in UV
 * into a gb_atlas (formats/atlas.h) that gb_atlas_check accepts.
 *
 * Decided here:
 * - UVs are fixed point before they are floats: u = round(x / width *
 *   2^24) / 2^24 (x the texel coordinate), exactly a float, so that the
 *   overlap test and the sign of every triangle's area are exact, and the
 *   file holds what was tested. Rounding moves a corner by at most half a
 *   unit, side / 2^25 texels; the packer rasters the charts before
 *   rounding with a margin of twice that (side / 2^24, the side being
 *   --size, or 16384 at a density asked for), so that the file's padded
 *   masks (formats/atlas_mask.h), rastered after, are apart too.
 * - A triangle whose area rounds to zero or below in fixed point (a tiny
 *   triangle of a large chart at a low density) leaves its chart for a
 *   chart of its own, laid flat; its old chart, split into its connected
 *   parts, keeps its UVs. Two triangles of one chart found overlapping
 *   (LSCM is not injective on every disc) send the chart back to be split
 *   and mapped again. Either means packing again, until neither happens
 *   (at most GB_ATLAS_BUILD_ROUNDS rounds, else the build fails saying
 *   so). Triangles of different charts never overlap: their padded masks
 *   share no texel; should the test find such a pair the build fails. Each
 *   round after the first tries the last round's density first.
 * - Angle distortion is measured on the UVs written (texel units): per
 *   corner |UV angle - 3-D angle|, over the corners whose two edges are
 *   at least GB_ATLAS_MEASURED_EDGE UV steps long (a step: 2^-24 of the
 *   atlas side, what a float UV in [0.5, 1) resolves). A shorter edge's
 *   direction is not in the file: the staircase's needle triangles, with
 *   an edge of 3e-5 texel beside two of half a texel, get UV angles of
 *   anything from 0 to 180 degrees at their short edge (86.8 degrees off
 *   at 1024^2), while every corner that the UVs can hold is within the
 *   25 degrees of GB_ATLAS_MAX_DISTORTION. Needle corners are counted.
 * - fill ratio = (sum over triangles of their UV area in texels) /
 *   (atlas width * height): the share of the atlas the triangles cover.
 * - The default cone (70 degrees) and the waste limit (GB_ATLAS_MAX_WASTE
 *   with GB_MIN_RECT_FILL, parameterize.h) were chosen by the charts, fill
 *   ratio and distortion they give on Sponza and the staircase; the sweeps
 *   are in docs/figures.md, "atlas: the default cone and the waste limit".
 *   The fill ratio is bounded by the file's rule that charts' padded
 *   masks share no texel: every chart costs the texels its triangles
 *   overlap and a gutter of P texels around them.
 *
 * On GB_OK the caller owns *atlas (gb_atlas_free). Single-threaded and
 * deterministic: the same scene and options give the same bytes (from one
 * build of the tool: a compiler that fuses multiply-adds, as clang does,
 * may round a normal on a cone's edge the other way).
 */
#ifndef GB_ATLAS_BUILD_H
#define GB_ATLAS_BUILD_H

#include <stdint.h>

#include "atlas.h"
#include "progress.h"
#include "result.h"
#include "scene.h"

#define GB_ATLAS_BUILD_ROUNDS 16
/* A chart whose smallest rectangle wastes more than this share of the
 * scene's area is split (parameterize.h, max_waste). */
#define GB_ATLAS_MAX_WASTE 0.0005
/* No corner of an LSCM chart, nor of a merged one, is distorted by more
 * than this (degrees; parameterize.h, merge.h). */
#define GB_ATLAS_MAX_DISTORTION 25.0
/* The shortest UV edge, in UV steps (2^-24 of the side: GB_OVERLAP_ONE),
 * whose corners' angles are measured: rounding moves each end of an edge
 * of 4 steps by at most 0.71 of one, turning it by at most 20 degrees. */
#define GB_ATLAS_MEASURED_EDGE 4.0

typedef struct gb_atlas_options {
    double cone_degrees;        /* 0: the default, GB_ATLAS_DEFAULT_CONE */
    double texels_per_unit;     /* > 0: this density; 0: chosen for size */
    uint32_t size;              /* 0: the default, 1024 */
    uint32_t padding;           /* texels; use GB_ATLAS_DEFAULT_PADDING */
    gb_progress_callback progress;
    void *progress_user;
} gb_atlas_options;

#define GB_ATLAS_DEFAULT_CONE 70.0
#define GB_ATLAS_DEFAULT_SIZE 1024
#define GB_ATLAS_DEFAULT_PADDING 2

typedef struct gb_atlas_stats {
    uint32_t grown_charts;      /* charts of the normal cone, before cutting */
    uint32_t charts;            /* in the file */
    uint32_t lone_triangles;    /* charts of one triangle */
    uint32_t lscm_failures, splits, folded, overlapping, wasteful, distorted; /* parameterize.h */
    uint32_t merged;            /* joins of small charts (merge.h) */
    uint32_t collapsed, self_overlaps;
    uint32_t rounds;            /* packings */
    double fill_ratio;
    double max_angle_distortion, mean_angle_distortion; /* degrees, over the corners
                                   measured (GB_ATLAS_MEASURED_EDGE) */
    uint64_t needle_corners;    /* corners not measured: an edge under GB_ATLAS_MEASURED_EDGE */
    double seconds;
} gb_atlas_stats;

gb_result gb_atlas_build(const gb_scene *scene, const gb_atlas_options *options,
                         gb_atlas *atlas, gb_atlas_stats *stats, gb_error *error);

#endif
