/* gpu_scene.h — the scene on the GPU: one vertex buffer of triangle corners
 * (grouped by material so that a material's diffuse texture is bound once),
 * the materials in a shader storage buffer, the diffuse textures.
 *
 * Vertex attributes (locations): 0 position (world), 1 shading normal (the
 * corner normal, or the face normal when the mesh has none), 2 face normal
 * (cross(v1 - v0, v2 - v0), the side that emits), 3 texture coordinates,
 * 4 material index (integer).
 *
 * Materials, std430 at binding GB_SSBO_MATERIALS, in GLSL:
 *     struct Material { vec4 Kd_textured; vec4 Ks_Ns; vec4 Ke; };
 * Kd_textured.w is 1 when the material has a diffuse texture (map_Kd, loaded
 * with the scene), bound to texture unit GB_UNIT_MATERIAL_TEXTURE while its
 * triangles draw.
 *
 * Create → draw any number of times → destroy (which also works on a zeroed
 * gb_gpu_scene and after a failed create). Needs a current context.
 */
#ifndef GB_GPU_SCENE_H
#define GB_GPU_SCENE_H

#include <stdint.h>

#include <epoxy/gl.h>

#include "result.h"
#include "scene.h"

enum {
    GB_SSBO_MATERIALS = 0,
    GB_UNIT_MATERIAL_TEXTURE = 0,
};

typedef struct gb_gpu_range {
    uint32_t material;
    uint32_t first_vertex, vertex_count;
} gb_gpu_range;

typedef struct gb_gpu_scene {
    GLuint vertex_buffer, vertex_array, material_buffer;
    GLuint white_texture;       /* bound for materials without a texture */
    GLuint *textures;           /* material_count: 0 when the material has none */
    uint32_t material_count;
    uint32_t vertex_count;
    uint32_t range_count;       /* one per material that has triangles */
    gb_gpu_range *ranges;
} gb_gpu_scene;

gb_result gb_gpu_scene_create(const gb_scene *scene, gb_gpu_scene *gpu, gb_error *error);
/* Draws every triangle with the bound program; with_textures binds each
 * material's diffuse texture first (the geometry pass wants them, shadow
 * maps do not). */
void gb_gpu_scene_draw(const gb_gpu_scene *gpu, int with_textures);
void gb_gpu_scene_destroy(gb_gpu_scene *gpu);

#endif
