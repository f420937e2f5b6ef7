/* implicit.h — implicit visibility (Dong, Kautz, Theobalt, Seidel 2007),
 * Algorithm 1, on the CPU; runtime/implicit/implicit.c shows it (gb_implicit_method).
 * One file a step, each with its header:
 *   implicit_elements.c   CreateSurfels: discs at the vertices (4.1)
 *   implicit_hierarchy.c  CreateGeometricHierarchy: segments, a quadtree a
 *                         segment (4.1)
 *   implicit_small_segments.c  segments smaller than an element regrouped
 *                         (an addition: scenes finer than the bins)
 *   implicit_update.c     UpdateElements: nodes refitted to the vertices (4.2.1)
 *   implicit_bins.c       the cube map of 6 x N x N bins (4.2.2)
 *   implicit_links.c      CreateHierarchicalLinks, RefineHierarchicalLinks,
 *                         PushdownLinks (4.2.2 - 4.2.4)
 *   implicit_bounce.c     ComputeIlluminateLeafNodes, PullupEnergy (4.3, 4.4)
 *   implicit_environment.c  a lat-long environment map into the bins (4.4)
 *   implicit_hidden.c     sides of elements under another surface, and the
 *                         element displayed in their place (an addition)
 *
 * Elements. The paper's models are tessellated finely; scenes here are not
 * (the Cornell box has 4 vertices a wall), so each triangle is first cut
 * into n x n smaller ones (n = ceil(longest edge / element size)) and the
 * elements are the vertices of that finer mesh, welded within a segment. A
 * vertex where segments meet (a box's corner) is one element in each. A
 * scene finer than that gets one element a grid cell of half the element
 * size and segment, a segment smaller than such a cell is regrouped with
 * the small ones of its material in its cell (implicit_small_segments.h;
 * Sponza: 16 238 elements, 41 591 before), and one tree over the segments'
 * roots stands for the paper's pairs of charts.
 *
 * Segments stand for the paper's UV charts, which scene files do not have:
 * triangles grown from a seed across shared edges while they have the
 * seed's material and a normal within GB_IMPLICIT_SEGMENT_DEGREES of it.
 *
 * Per frame (Algorithm 1, steps 4-11): gb_implicit_update_elements,
 * gb_implicit_create_links (Create, Refine, PushdownLinks), then
 * gb_implicit_illuminate; gb_implicit_model_create (steps 1-2) runs once.
 * bench/implicit_steps.c times each step on a deforming model; the runtime
 * (implicit.c) rebuilds the links each image of a frame with no budget
 * while that costs less than GB_IMPLICIT_FRAME_SECONDS (gbview's scenes do
 * not move, so above it the links of the last build, identical, are kept),
 * and in the window solves the first image only (implicit.c says why).
 *
 * Light is diffuse (Kd of the material, no texture average, no gloss). The
 * display term of an element is its incident radiance E / pi from the
 * environment and the bounces (what the direct pass does not draw), the
 * renderer multiplies it by the pixel's Kd.
 */
#ifndef GB_IMPLICIT_H
#define GB_IMPLICIT_H

#include <stdint.h>

#include "implicit_bins.h"
#include "implicit_bounce.h"
#include "implicit_elements.h"
#include "implicit_environment.h"
#include "implicit_hidden.h"
#include "implicit_hierarchy.h"
#include "implicit_links.h"
#include "implicit_model.h"
#include "implicit_update.h"
#include "indirect_method.h"

/* implicit.c: the GI method listed in methods.c. It runs steps 4-7 again
 * each frame while they took under this (the paper's frames: 0.11-0.22 s). */
#define GB_IMPLICIT_FRAME_SECONDS 0.25

/* Milliseconds of each step summed over the images solved (implicit.c). */
typedef struct gb_implicit_step_times {
    uint32_t frames, rebuilds;  /* images solved (each image without a budget,
                                   the first with one), of which links rebuilt */
    double update_ms, create_ms, refine_ms, illuminate_ms;
} gb_implicit_step_times;
void gb_implicit_times(const void *method_state, gb_implicit_step_times *times);

extern const gb_indirect_method gb_implicit_method;

/* implicit's gbview options (implicit_options.c), which flc-iv reads too;
 * zero fields: the defaults. */
typedef struct gb_implicit_parameters {
    int bins;                   /* cube-map bins per face edge (--bins; 12) */
    int bounces;                /* 1 or 2 (--bounces; 1) */
    int paper_rules;            /* 1: the links by the paper's rules alone,
                                   faster and coarser (--paper-rules) */
} gb_implicit_parameters;
extern const gb_method_option gb_implicit_options[];

#endif
