/* lightmap.h — the light octree baked into the atlas, on the CPU
 * (vivianloc-2007 §4.2.3, Figure 1: the render-to-texture stage, here
 * without a GPU, so that other engines can load the result):
 *
 *   texel_cover.c   which triangle's field each texel holds: each triangle
 *                   rasterised at its atlas UVs with its reach
 *                   (gb_atlas_reach), the nearest keeping a texel
 *   lightmap.c      per such texel, the indirect irradiance on its
 *                   triangle's plane at the texel's centre (texel_surface.h),
 *                   on a work queue of rows: the covered texels and every
 *                   other one a bilinear read inside a triangle weighs, so
 *                   chart borders show no seam. With quality 0 the octree
 *                   read there (light_octree_shading.h, as the runtime's
 *                   display); else a final gather of `quality` rays
 *                   (texel_gather.h, final_gather.h) that reads the octree,
 *                   or traces paths on, where its rays meet the scene, at
 *                   the texels texel_interpolation.c chooses, the others
 *                   interpolated between them
 *   gutter.c        the rest of the gutter filled from the filled texels
 *                   (padding - 1 rounds), so bilinear reads never reach
 *                   black
 *   glb_export.c    the scene with the lightmap as a glTF 2.0 binary
 *                   (formats/gltf_binary.h the container): its vertices
 *                   (corner_vertices.c), bufferViews and accessors
 *                   (glb_builder.c over byte_buffer.c), its images
 *                   (glb_images.c, PNG through png_bytes.c), its camera
 *                   (glb_camera.c)
 *
 * A texel holds the irradiance E, without Kd / π: the viewer multiplies the
 * albedo (textured or not) at display, so textures keep their resolution.
 *
 * Decided here: a texel has one value for both sides of its surface (a
 * glTF lightmap has no more). With gathers, each triangle keeps the side
 * that looks into the open, where a camera can be (texel_gather.h; a gap
 * narrower than GB_TEXEL_GATHER_NEAR_FRACTION of the scene's diagonal is
 * closed), the side its winding faces on a tie; without, each texel the
 * brighter side (the octree read at a point says nothing of what the side
 * faces). A side's geometric normal is the face normal of the triangle's
 * winding or its opposite, and the shading normal is turned to it
 * (texel_surface.h), as the runtime's render into the atlas does for each
 * of its two layers (runtime/octree/octree_atlas.h). The reach and the
 * gutter follow the runtime's too: after the triangles' reach, padding - 1
 * rounds, each giving an unfilled texel the mean of its filled 8
 * neighbours; texels further out stay 0.
 *
 * The image never depends on the number of threads (texel_gather.h says
 * which random streams a texel draws from).
 *
 * The caller owns the scene, the atlas, the octree (checked against the
 * scene before the call; NULL with options.paths, which reads none) and
 * the image it gets (gb_image_free).
 */
#ifndef GB_LIGHTMAP_H
#define GB_LIGHTMAP_H

#include <stdint.h>

#include "atlas.h"
#include "image.h"
#include "light_octree.h"
#include "progress.h"
#include "result.h"
#include "scene.h"

#define GB_LIGHTMAP_ACCURACY 0.2

typedef struct gb_lightmap_options {
    int threads;                    /* 0: every core */
    int quality;                    /* final gather rays per texel; 0: none */
    int paths;                      /* the gathers trace paths on, the octree unused */
    int bounces;                    /* reflections a gather traces before it reads the
                                       octree; 0: 1, the final gather */
    double accuracy;                /* Ward's a of the gathers (texel_interpolation.h); 0:
                                       GB_LIGHTMAP_ACCURACY, < 0: every texel gathers */
    uint64_t seed;                  /* of the gathers' random streams */
    gb_progress_callback progress;  /* may be NULL */
    void *progress_user;
} gb_lightmap_options;

typedef struct gb_lightmap_stats {
    uint64_t covered;               /* texels within a triangle's reach */
    uint64_t gutter;                /* texels the gutter's rounds filled */
    uint64_t rays;                  /* traced by the gathers */
    int threads;
    double seconds;
} gb_lightmap_stats;

/* image: width x height of the atlas, 3 channels (linear RGB irradiance,
 * W/m^2), row 0 the atlas's row 0. stats may be NULL. */
gb_result gb_lightmap_bake(const gb_scene *scene, const gb_atlas *atlas,
                           const gb_light_octree *octree, const gb_lightmap_options *options,
                           gb_image *image, gb_lightmap_stats *stats, gb_error *error);

#endif
