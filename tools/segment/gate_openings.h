/* gate_openings.h — each visibility gate's disk fitted to the opening it
 * stands for, and a gate for every opening no edge crosses (beyond
 * noel-biri-2014 §IV.C, run when segment has the voxels: segment --voxels
 * --grid).
 *
 * The paper's disk (visibility_gates.h) has the radius of the smaller
 * maximal ball at the edge's ends, often far below the real separation
 * between the two clusters (a court cut at mid-height: the disk has the
 * radius of the court's half width, the opening is the whole court). The
 * paper names the result (darker images, §VI.B) and suggests matching the
 * shape of the separation better. The separation is known exactly once
 * every voxel has its cluster (gb_segmentation_voxel_clusters): the faces
 * between an empty voxel of cluster a and an empty voxel of cluster b.
 *
 *   a gate's disk: centre = the faces' centroid; normal = their mean normal,
 *   oriented from clusters[0] to clusters[1]; radius = sqrt(2 <r^2>), the
 *   disk with the faces' second moment in its plane (exact for faces that
 *   fill a disk), never below the paper's radius.
 *
 * Gates come from the segmented skeleton's edges, but the voxels decide
 * which clusters touch: the nearest-node partition often makes two clusters
 * meet with no edge between them (a room's corner near an opening belongs
 * to the skeleton outside). Such a pair gets an opening gate of its own
 * (edge GB_SEGMENTATION_NO_EDGE), fitted the same way, so that light crosses
 * every opening the voxels show.
 *
 * Decided here: a voxel voxelize flagged as surface is not empty, whatever
 * its node; each face goes to the gate between its two clusters whose
 * centre before fitting is nearest the face's centre (ties: the smaller
 * gate index); a gate without faces keeps the paper's disk; a disk whose
 * faces' normals cancel keeps its normal (an opening gate's starts as +x);
 * opening gates come after the edge gates, one per pair (a, b), a < b, in
 * increasing pairs.
 *
 *   uint32_t added, fitted;
 *   gb_gate_openings_add(&seg, voxel_clusters, voxels.surface, &added, &error);
 *   gb_gate_openings_fit(&seg, voxel_clusters, voxels.surface, &fitted, &error);
 *
 * voxel_clusters and surface are in the segmentation's voxel frame (x
 * fastest); surface may be NULL (every voxel with a cluster is empty). The
 * caller owns everything; the gates are changed in place.
 */
#ifndef GB_SEGMENT_GATE_OPENINGS_H
#define GB_SEGMENT_GATE_OPENINGS_H

#include <stdint.h>

#include "result.h"
#include "segmentation.h"

/* An opening gate (disk to be fitted) for every pair of clusters whose empty
 * voxels share a face but that no gate joins yet; *added of them. */
gb_result gb_gate_openings_add(gb_segmentation *segmentation, const int32_t *voxel_clusters,
                               const uint8_t *surface, uint32_t *added, gb_error *error);

/* Every gate's disk fitted to its faces, as above; *fitted: the gates that
 * had faces. */
gb_result gb_gate_openings_fit(gb_segmentation *segmentation, const int32_t *voxel_clusters,
                               const uint8_t *surface, uint32_t *fitted, gb_error *error);

#endif
