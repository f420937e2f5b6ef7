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
 * normals with GB_GLSL_OCTAHEDRAL and fetch with texelFetch; GB_GLSL_SURFACE
 * and GB_GLSL_WORLD_POSITION read a pixel back into world space.
 *
 * Create → resize / draw each frame → destroy (also on a zeroed one).
 */
#ifndef GB_GBUFFER_H
#define GB_GBUFFER_H

#include <epoxy/gl.h>

#include "gpu_scene.h"
#include "mat4.h"
#include "result.h"

#define GB_NO_CLUSTER 0xffffffffu

enum {
    GB_UNIT_GBUFFER_NORMAL = 1,
    GB_UNIT_GBUFFER_DEPTH,
    GB_UNIT_GBUFFER_DIFFUSE,
    GB_UNIT_GBUFFER_GLOSSY,
    GB_UNIT_GBUFFER_CLUSTERS,
    GB_UNIT_GBUFFER_EMISSION,
};

/* GLSL: oct_encode(vec3 unit) -> vec2 in [-1, 1]^2, oct_decode(vec2) -> unit. */
#define GB_GLSL_OCTAHEDRAL                                                        \
    "vec2 sign_not_zero(vec2 v) {\n"                                              \
    "    return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);\n"       \
    "}\n"                                                                         \
    "vec2 oct_encode(vec3 n) {\n"                                                 \
    "    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));\n"                      \
    "    return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * sign_not_zero(p);\n"          \
    "}\n"                                                                         \
    "vec3 oct_decode(vec2 p) {\n"                                                 \
    "    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));\n"                          \
    "    if (n.z < 0.0)\n"                                                        \
    "        n.xy = (1.0 - abs(n.yx)) * sign_not_zero(n.xy);\n"                   \
    "    return normalize(n);\n"                                                  \
    "}\n"

/* GLSL: world_position(pixel, size, depth), the world point that pixel of a
 * size-pixel target shows at G-buffer depth (reversed, mat4.h). Needs the
 * uniforms view_to_world, tan_half_fov and near. */
#define GB_GLSL_WORLD_POSITION                                                    \
    "vec3 world_position(ivec2 pixel, ivec2 size, float depth) {\n"              \
    "    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(size) - 1.0;\n"            \
    "    float z = -near / depth;\n"                                            \
    "    return (view_to_world * vec4(ndc * tan_half_fov * -z, z, 1.0)).xyz;\n"  \
    "}\n"

/* GLSL: struct Surface and surface_at(pixel, depth), everything the
 * G-buffer says of a pixel, in world space (wo toward the eye). Needs
 * GB_GLSL_OCTAHEDRAL, the samplers gbuffer_normal, gbuffer_depth,
 * gbuffer_diffuse and gbuffer_glossy, and the uniforms of
 * GB_GLSL_WORLD_POSITION. */
#define GB_GLSL_SURFACE                                                           \
    "struct Surface { vec3 position, n, ng, wo, Kd, Ks; float Ns; };\n"          \
    "Surface surface_at(ivec2 pixel, float depth) {\n"                           \
    "    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(textureSize(gbuffer_depth, 0)) - 1.0;\n" \
    "    float z = -near / depth;\n"                                            \
    "    vec3 view_position = vec3(ndc * tan_half_fov * -z, z);\n"               \
    "    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);\n"                 \
    "    mat3 rotation = mat3(view_to_world);\n"                                 \
    "    Surface s;\n"                                                           \
    "    s.position = (view_to_world * vec4(view_position, 1.0)).xyz;\n"         \
    "    s.n = normalize(rotation * oct_decode(normals.xy));\n"                  \
    "    s.ng = normalize(rotation * oct_decode(normals.zw));\n"                 \
    "    s.wo = normalize(rotation * -view_position);\n"                         \
    "    s.Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;\n"                    \
    "    vec4 glossy = texelFetch(gbuffer_glossy, pixel, 0);\n"                  \
    "    s.Ks = glossy.rgb;\n"                                                   \
    "    s.Ns = glossy.a;\n"                                                     \
    "    return s;\n"                                                            \
    "}\n"

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
void gb_gbuffer_destroy(gb_gbuffer *gbuffer);

#endif
