/* octree.h — the light octree (Vivianloc 2007, §3.2, §4.2) as a GI method
 * of the runtime (indirect_method.h); runtime/octree/octree.c.
 *
 * create  borrows the light octree (NAME.lot, from cluster) of the bake
 *         (runtime/bake.h), uploads its node pool, leaves and VDLs as
 *         shader storage buffers.
 * draw    one full-screen pass over the G-buffer (octree_display.frag.glsl):
 *         per pixel, the world point x, walked from the root to the leaves
 *         of the 8 leaf cells around it (δ node fetches each, Figure 6),
 *         their VDL sums interpolated trilinearly between the leaf centres
 *         (with surface interpolation, cluster's default, each weight also
 *         scaled by its leaf's surface factor: light_octree_shading.h).
 *         Neighbours without a leaf or without VDLs get no weight and the
 *         weights are renormalised over the rest (the paper's interpolation
 *         holes, Fig. 16c): no dark seams. Every weight is at least 10^-6, so a
 *         point at the centre of a leaf without VDLs (where the trilinear
 *         weights of the other 7 are 0) gets its neighbours' mean, not
 *         black. Only a point whose 8 neighbours all lack VDLs is black.
 *         tests/unit/test_octree_display.c checks this on a hand-made octree.
 *         With an atlas (--atlas, or the bake's NAME.atlas), the display
 *         goes through it instead (octree_atlas.h): create prepares it,
 *         draw renders it in slices at part 0 of each image until the
 *         frame's budget_ms is spent on them (all of it at the first image
 *         when budget_ms is 0), and shows the walk, returning nonzero
 *         (another image will be better), until the atlas is complete;
 *         then the display through it, returning 0.
 *
 * Convention: a VDL's irradiance E (cluster: Σ Φ / (π r²) over its
 * photons, a density on the leaf's surface) is the irradiance it gives the
 * leaf's own geometry, cosine included: on a surface facing ω it gives
 * E / |n_leaf·ω|. The reflected radiance is then
 *     Σ Kd / π · E · max(0, n·ω) / max(|n_leaf·ω|, 0.25)
 * over the VDLs, ω a VDL's direction (toward the light), n the pixel's
 * shading normal, n_leaf the leaf's normal; on the leaf's own plane that is
 * Σ Kd / π · E. The 0.25 bounds the gain of grazing VDLs (x4). Taking E
 * as the irradiance facing ω instead (no division) counts the cosine twice:
 * relative MSE 0.016 instead of 0.0058 on the Cornell box (tests/cli/octree.t).
 * Light from behind the geometric normal is dropped (brdf.h, "Sides").
 * Diffuse only.
 *
 * GPU layout: the file's arrays as they are (light_octree.h), 16 bytes a
 * VDL like the paper's one RGBA texel: irradiance as 3 x f32 (no
 * quantisation) and the direction octahedral 2 x 16 bits (photon_map.h),
 * decoded by octree_vdl_direction.glsl. Measured angular error of the
 * packing and this decode: max 0.0025°, mean 0.0012°; the paper's 8 + 8 bit
 * (θ, φ) gives max 0.78°, mean 0.35° (test_octree_display.c).
 */
#ifndef GB_OCTREE_H
#define GB_OCTREE_H

#include "indirect_method.h"

extern const gb_indirect_method gb_octree_method;

/* octree's gbview option (octree_options.c). */
typedef struct gb_octree_parameters {
    const char *atlas;          /* show it through this atlas file (--atlas);
                                   "none": the walk; NULL: the bake's NAME.atlas
                                   when it has one, else the walk */
} gb_octree_parameters;
extern const gb_method_option gb_octree_options[];

/* The atlas of a state gb_octree_method's create made (octree_atlas.h), or
 * NULL when it shows the walk: for tests. */
struct gb_octree_atlas;
struct gb_octree_atlas *gb_octree_atlas_of(void *state);

#endif
