/* octree_atlas.h — the light octree shown through the lightmap atlas
 * (vivianloc-2007 §4.2.3 and Figure 1, "Atlas LSCM parametrisation and
 * render-to-texture stages"): rendered into the atlas once (in slices, so
 * that a large atlas does not hold up the window), then the scene
 * drawn with one texture fetch per pixel instead of the octree walk's 8
 * walks of δ node fetches. runtime/octree/octree_atlas.c; the octree method
 * (octree.h) uses it when it has an atlas (NAME.atlas from `atlas`).
 *
 * create  uploads the triangles' corners and builds the passes' programs;
 *         renders nothing.
 * render  renders the octree's irradiance (octree_irradiance.glsl, the
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
 *         it. Then, once both layers are done, the rest of the gutter
 *         (FORMATS.md, "Atlas"): padding - 1 rounds, every unfilled texel
 *         the mean of its 8 neighbours filled before the round.
 *         It works in slices, bands of rows of one layer drawn with the
 *         scissor on them, until budget_ms is spent (timed with glFinish
 *         after each slice; at least one slice a call), and goes on where
 *         it stopped at the next call; budget_ms 0: all of it at once. The
 *         atlas is the same bytes whatever the slices. Returns 1 once the
 *         atlas is complete (and does nothing when it already was), else 0.
 *         The caller binds
 *         the octree's node, leaf and VDL buffers (octree.c's SSBO bindings
 *         0, 1, 2) before the call; the framebuffers, viewport, scissor,
 *         blending, depth test and culling are left as the caller had them.
 * draw    once the atlas is complete: the atlas UV and the side seen at
 *         each pixel (a geometry pass over the whole view into a target of
 *         its own, the scissor off, redrawn only when the view or the size
 *         changes), then one full-screen pass into the caller's framebuffer,
 *         within its scissor and with its blending: Kd / π · texture(atlas,
 *         uv) in that side's layer, one bilinear fetch.
 *
 * The caller owns the state: create → render until it returns 1 → draw
 * each frame → destroy (also NULL, also before the atlas is complete). The
 * scene and the atlas are only read during create. Needs a current context.
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
int gb_octree_atlas_render(gb_octree_atlas *state, double budget_ms);
int gb_octree_atlas_complete(const gb_octree_atlas *state);
void gb_octree_atlas_draw(gb_octree_atlas *state, const gb_indirect_frame *frame);
/* The atlas texture (RGBA32F, a 2-D array of two layers), complete once
 * render returned 1: for tests. */
GLuint gb_octree_atlas_texture(const gb_octree_atlas *state);
void gb_octree_atlas_destroy(gb_octree_atlas *state);

/* The uniforms octree_irradiance.glsl reads from the octree's header
 * (origin, cell_size, depth, surface_interpolation), set on program: the
 * walk's display and the render into the atlas both call it. */
void gb_octree_set_irradiance_uniforms(GLuint program, const gb_light_octree_header *h);

#endif
