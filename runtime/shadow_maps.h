/* shadow_maps.h — the scene's light sources on the GPU, each with its shadow
 * map (Noël & Biri 2014, V.E: "primary light sources with shadow maps"):
 *   point lights and the area lights' point emitters (area_lights.h): cube
 *     maps (one cube-map-array texture) of the distance to the light
 *     divided by its range;
 *   spot lights (perspective over the cone) and directional lights
 *     (orthographic, fitted to the scene's bounds): 2-D maps (one array
 *     texture) of reversed depth;
 *   the scene's own directional lights (not those standing for the
 *     environment, common/environment_lights.h) also get
 *     GB_SHADOW_CASCADES maps fitted to the view (shadow_cascades.h; one
 *     more array texture), which the direct pass reads; the scene-wide map
 *     stays for what lights the whole scene (FLC's VPLs).
 * Both textures compare in the sampler (GL_TEXTURE_COMPARE_MODE) with
 * bilinear filtering: 2x2 percentage-closer filtering.
 *
 * Lights, std430, in GLSL (bound by gb_shadow_maps_bind):
 *   binding GB_SSBO_POINT_LIGHTS:
 *     struct PointLight { vec4 position_range; vec4 intensity_one_sided;
 *                         vec4 normal; };
 *     intensity in W/sr; one_sided 1 for an area light's emitter, whose
 *     intensity is times max(0, dot(normal, w)) and whose 1/r^2 is
 *     1/(r^2 + normal.w), normal.w its area / pi (area_lights.h; 0 for a
 *     point light); range: the stored distance is distance / range.
 *   binding GB_SSBO_PLANE_LIGHTS:
 *     struct PlaneLight { mat4 world_to_clip; vec4 position_kind;
 *                         vec4 direction_texel; vec4 intensity;
 *                         vec4 cone; };
 *     kind 0 spot (intensity W/sr), 1 directional (irradiance, W/m^2);
 *     direction: the way light travels; texel: the world size of a texel at
 *     distance 1 (spot) or everywhere (directional); cone: x the cone
 *     half-angle, y the fall-off half-angle, degrees (common/brdf.h), z
 *     the light's cascades (layers z * GB_SHADOW_CASCADES on), -1: none.
 *   binding GB_SSBO_SHADOW_CASCADES:
 *     struct Cascade { mat4 world_to_clip; vec4 far_texel; };
 *     far: the view depth where the cascade ends; texel: its world size;
 *     z: 1 / the world length of its depth range.
 * Textures at units GB_UNIT_SHADOW_CUBES (samplerCubeArrayShadow),
 * GB_UNIT_SHADOW_PLANES and GB_UNIT_SHADOW_CASCADES (sampler2DArrayShadow).
 *
 * The scene and its lights are static: the maps are drawn once, by the
 * first gb_shadow_maps_draw; the cascades again whenever the view changes
 * (gb_shadow_maps_fit_view). Create → draw → fit to the view → bind each
 * frame → destroy.
 */
#ifndef GB_SHADOW_MAPS_H
#define GB_SHADOW_MAPS_H

#include <stdint.h>

#include <epoxy/gl.h>

#include "gpu_scene.h"
#include "result.h"
#include "scene.h"
#include "view.h"

enum {
    GB_SSBO_POINT_LIGHTS = 1,
    GB_SSBO_PLANE_LIGHTS = 2,
    GB_SSBO_SHADOW_CASCADES = 3,
    GB_UNIT_SHADOW_CUBES = 8,
    GB_UNIT_SHADOW_PLANES = 9,
    GB_UNIT_SHADOW_CASCADES = 11,
    GB_DEFAULT_SHADOW_SIZE = 1024,
    GB_DEFAULT_CASCADE_SIZE = 2048,
    GB_DEFAULT_AREA_SAMPLES = 16,
};

typedef struct gb_shadow_options {
    int size;                   /* 2-D maps' side; cube faces get half; 0: 1024 */
    int area_samples;           /* point emitters for all the area lights; 0: 16;
                                   negative: none */
    int cascade_size;           /* side of a cascade's map; 0: 2048; negative:
                                   no cascades (the scene-wide map) */
} gb_shadow_options;

typedef struct gb_shadow_maps {
    uint32_t point_count, plane_count;
    int plane_size, cube_size;
    GLuint point_buffer, plane_buffer;
    GLuint cube_array, plane_array;
    GLuint framebuffer;
    GLuint cube_program, plane_program;
    int drawn;
    /* CPU copies used to draw the maps */
    float *point_data;          /* point_count * 12 floats */
    float *plane_data;          /* plane_count * 32 floats */
    /* the cascades of cascaded_count directional lights, and the view
       (eye, size) they were fitted to */
    uint32_t cascaded_count;
    int cascade_size;
    GLuint cascade_array, cascade_buffer;
    float *cascade_data;        /* cascaded_count * GB_SHADOW_CASCADES * 20 floats */
    gb_view fitted_view;
    int fitted_width, fitted_height;
} gb_shadow_maps;

gb_result gb_shadow_maps_create(const gb_scene *scene, const gb_shadow_options *options,
                                gb_shadow_maps *maps, gb_error *error);
/* Draws the maps if they are not yet (restores the framebuffer binding to 0). */
void gb_shadow_maps_draw(gb_shadow_maps *maps, const gb_gpu_scene *scene);
/* Fits the cascades to view (an image width x height) and draws them, unless
 * they were fitted to that view last (restores the framebuffer binding to 0). */
void gb_shadow_maps_fit_view(gb_shadow_maps *maps, const gb_scene *scene,
                             const gb_gpu_scene *gpu_scene, const gb_view *view, int width,
                             int height);
void gb_shadow_maps_bind(const gb_shadow_maps *maps);
/* The cascades too, for the direct pass alone (their binding is another
 * pass's buffer elsewhere: FLC's triangles). */
void gb_shadow_maps_bind_cascades(const gb_shadow_maps *maps);
void gb_shadow_maps_destroy(gb_shadow_maps *maps);

#endif
