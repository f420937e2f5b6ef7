/* light_octree_shading.h — the light octree's irradiance at a surface
 * point, on the CPU: the twin of runtime/octree/octree_irradiance.glsl's
 * interpolate(x, n, ng), which the octree display and the render into the
 * atlas evaluate on the GPU (vivianloc-2007 §4.2; the convention is
 * runtime/octree/octree.h's). `lightmap` bakes it per atlas texel; the
 * display's radiance is Kd / π times it.
 *
 * At x, the 8 leaf cells whose centres surround x (the cell grid shifted by
 * half a cell), each found from the root (δ node fetches); a cell that has
 * a leaf with VDLs gives
 *     sum = Σ E · c   over its VDLs with c > 0 and ng·ω > 0,
 *     c   = n·ω / max(|n_leaf·ω|, MIN_COS),
 * ω a VDL's direction (octahedral 2 x 16 bits, decoded as the GPU does),
 * E its irradiance. The result is Σ w sum / Σ w over those cells, w the
 * trilinear weight at least MIN_WEIGHT (the holes of Fig. 16c: cells
 * without a leaf or without VDLs get no weight); 0 when none of the 8 has
 * VDLs. Same constants, same order of operations, in float, as the shader:
 * the two agree to float rounding (tests/unit/test_light_octree_shading.c).
 *
 * An octree clustered with GB_LIGHT_OCTREE_SURFACE interpolation (cluster
 * --interpolation surface) also scales each w by its surface factor
 *     1 - trust (1 - max(1 - (s - s_min) / SURFACE_REACH, MIN_SURFACE)),
 *     s = |n_leaf·(x - centre) - plane| + 1 - |n_leaf·ng|   (cell edges),
 *     trust = clamp(2 - 2 s_min / SURFACE_REACH, 0, 1),
 * s_min the least s of the 8: a leaf of another surface (another plane, a
 * quarter of an edge off, or another orientation) lends x almost nothing
 * (issue 49: McGuire's light, 0.3 mm under a leaf boundary, read the
 * hidden ceiling 1 cm above it through the leaf above, and the boxes'
 * corners mixed walls and floor), as long as some leaf holds x: where
 * none is within half a reach (a window's reveal among leaves of the wall,
 * a table leg), the factors fade to 1, plain trilinear, by a whole reach.
 * Over 8 photon seeds (bench/octree_interpolation.sh) 11–27 % better than
 * trilinear on the Cornell boxes, 1–5 % on the living room and the
 * staircase, and on Sponza from 8 % better to 2 % worse (within the
 * seeds' spread): cluster's default (docs/figures.md, "light octree:
 * surface interpolation").
 *
 * Preconditions: the octree passed gb_light_octree_check; n (shading) and
 * ng (geometric) are unit, n on ng's side. Nothing is allocated; the
 * caller owns every argument. Thread-safe (reads only).
 */
#ifndef GB_LIGHT_OCTREE_SHADING_H
#define GB_LIGHT_OCTREE_SHADING_H

#include "light_octree.h"

#define GB_LIGHT_OCTREE_MIN_COS 0.25f       /* bounds a grazing VDL's gain (x4) */
#define GB_LIGHT_OCTREE_MIN_WEIGHT 1e-6f    /* a leaf centre without VDLs is not black */
#define GB_LIGHT_OCTREE_SURFACE_REACH 0.25f /* cell edges: past it, another surface's leaf */
#define GB_LIGHT_OCTREE_MIN_SURFACE 1e-3f   /* a point far from every leaf's surface is not black */

/* c of a VDL from the unit direction w in a leaf of normal leaf_normal, at
 * a surface of normal n: n.w / max(|leaf_normal.w|, MIN_COS). The VDL's
 * irradiance E (on the leaf's surface) brings E c there where c > 0. The
 * shading below and cluster's choice of the VDL count (tools/cluster/vdl.h)
 * both weigh a VDL by it. */
float gb_light_octree_vdl_gain(const float n[3], const float leaf_normal[3], const float w[3]);

/* out_rgb = the irradiance (W/m^2, linear RGB) the octree gives at x. */
void gb_light_octree_irradiance(const gb_light_octree *octree, const float x[3],
                                const float n[3], const float ng[3], float out_rgb[3]);

#endif
