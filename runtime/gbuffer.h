/* gbuffer.h — the geometry pass and its G-buffer (Noël & Biri 2014, V.A):
 * per pixel,
 *   normal      RGBA32F  view space, octahedral: xy the shading normal, zw
 *                        the geometric normal, both turned toward the viewer
 *                        (common/brdf.h, "Sides")
 *   depth       DEPTH32F reversed (mat4.h): view z = -near / depth; 0 where
 *                        no surface was drawn
 *   diffuse     RGBA16F  Kd, times the diffuse texture
 *   glossy      RGBA16F  rgb Ks, a the Phong exponent Ns
 *   clusters    RG32UI   x the visibility cluster, y the geometry cluster
 *                        (V.A); GB_NO_CLUSTER until a GI method fills them
 *   emission    RGBA16F  Ke where the emitting (front) face is seen: the
 *                        radiance of emitters seen directly, which the
 *                        paper leaves out and the reference's direct mode has
 * Readers bind them with gb_gbuffer_bind (units GB_UNIT_GBUFFER_*), decode
 * normals with gbuffer_octahedral.glsl and fetch with texelFetch;
 * gbuffer_surface.glsl and gbuffer_world_position.glsl read a pixel back
 * into world space. The pass itself: gbuffer.vert.glsl, gbuffer.frag.glsl.
 *
 * Create → resize / draw each frame → destroy (also on a zeroed one).
 */
#ifndef GB_GBUFFER_H
#define GB_GBUFFER_H

#include <epoxy/gl.h>

#include "gpu_scene.h"
#include "mat4.h"
#include "result.h"
#include "view.h"

#define GB_NO_CLUSTER 0xffffffffu

enum {
    GB_UNIT_GBUFFER_NORMAL = 1,
    GB_UNIT_GBUFFER_DEPTH,
    GB_UNIT_GBUFFER_DIFFUSE,
    GB_UNIT_GBUFFER_GLOSSY,
    GB_UNIT_GBUFFER_CLUSTERS,
    GB_UNIT_GBUFFER_EMISSION,
};

typedef struct gb_gbuffer {
    int width, height;
    GLuint framebuffer;
    GLuint normal, depth, diffuse, glossy, clusters, emission;
    GLuint program;
} gb_gbuffer;

gb_result gb_gbuffer_create(int width, int height, gb_gbuffer *gbuffer, gb_error *error);
/* Reallocates the textures when the size changed. */
gb_result gb_gbuffer_resize(gb_gbuffer *gbuffer, int width, int height, gb_error *error);
/* The geometry pass: clears, then draws the scene seen through view and
 * projection. */
void gb_gbuffer_draw(gb_gbuffer *gbuffer, const gb_gpu_scene *scene, const gb_mat4 *view,
                     const gb_mat4 *projection);
void gb_gbuffer_bind(const gb_gbuffer *gbuffer);
/* Sets the uniforms gbuffer_textures.glsl declares for reading a pixel back
 * into world space (view_to_world, tan_half_fov, near) on program. */
void gb_gbuffer_set_view(GLuint program, const float view_to_world[16],
                         const float tan_half_fov[2], float near);
/* The same for view seen in a width x height target. */
void gb_gbuffer_set_view_of(GLuint program, const gb_view *view, int width, int height);
void gb_gbuffer_destroy(gb_gbuffer *gbuffer);

#endif
