/* octree_atlas.h — the light octree shown through the lightmap atlas
 * (vivianloc-2007 §4.2.3 and Figure 1, "Atlas LSCM parametrisation and
 * render-to-texture stages"): rendered into the atlas once, then the scene
 * drawn with one texture fetch per pixel instead of the octree walk's 8
 * walks of δ node fetches. runtime/octree/octree_atlas.c; the octree method
 * (octree.h) uses it when it has an atlas (NAME.atlas from `atlas`).
 *
 * create  renders the octree's irradiance (octree_irradiance.glsl, the
 *         display's own) into an RGBA32F texture of the atlas's size, two
 *         layers, one for each side of the surfaces (the walk turns the
 *         normals toward the viewer, so either side may be seen): each
 *         triangle drawn at its atlas UVs, its edges pushed out by
 *         gb_atlas_reach (√2 texels at the default padding), and every
 *         texel whose centre lies within that distance of it evaluated on
 *         its plane there (barycentric weights extended past the edges), the
 *         nearest triangle keeping the texel: the covered texels and all
 *         the others a bilinear read inside a triangle weighs hold the
 *         chart's own field, so chart borders show no seam, and a chart too
 *         small to cover a texel centre still gets its texels. In layer 0
 *         the face normal (the side the winding faces) is the geometric
 *         normal, in layer 1 its opposite; the corner normals are turned to
 *         it. Then the rest of the gutter
 *         (FORMATS.md, "Atlas"): padding - 1 rounds, every unfilled texel
 *         the mean of its 8 neighbours filled before the round. The caller
 *         binds the octree's node, leaf and VDL buffers (octree.c's SSBO
 *         bindings 0, 1, 2) before the call.
 * draw    the atlas UV and the side seen at each pixel (a geometry pass into
 *         a target of its own, redrawn only when the view or the size
 *         changes), then one full-screen pass: Kd / π · texture(atlas, uv)
 *         in that side's layer, one bilinear fetch.
 *
 * The caller owns the state: create → draw each frame → destroy (also NULL).
 * The scene and the atlas are only read during create. Needs a current
 * context.
 */
#ifndef GB_OCTREE_ATLAS_H
#define GB_OCTREE_ATLAS_H

#include <epoxy/gl.h>

#include "atlas.h"
#include "indirect_method.h"
#include "light_octree.h"
#include "result.h"
#include "scene.h"

typedef struct gb_octree_atlas gb_octree_atlas;

gb_result gb_octree_atlas_create(const gb_scene *scene, const gb_atlas *atlas,
                                 const gb_light_octree_header *octree,
                                 gb_octree_atlas **state, gb_error *error);
void gb_octree_atlas_draw(gb_octree_atlas *state, const gb_indirect_frame *frame);
void gb_octree_atlas_destroy(gb_octree_atlas *state);

#endif
