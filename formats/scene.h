/* scene.h — a static triangle scene in memory: the mesh, its materials,
 * lights and cameras, as every gibake tool and the runtime see it.
 *
 * gb_scene_load reads a .scene file (formats/FORMATS.md, "Scene file") or a
 * mesh directly (.obj with its .mtl, .obj.gz, .ply, .off, .stl). Polygons are
 * triangulated, degenerate (zero-area) triangles are dropped and counted,
 * so are duplicates (the three corners of an earlier triangle, either way
 * round: a surface laid twice would be lit twice by methods that make a
 * light or an element of each triangle),
 * triangles whose material emits (Ke > 0) are the scene's area lights.
 * Positions are indexed (shared between triangles); normals and texture
 * coordinates, when the file has them, are stored per triangle corner.
 *
 * The caller owns the gb_scene and releases it with gb_scene_free (which
 * also works on a zeroed scene and after a failed load).
 */
#ifndef GB_SCENE_H
#define GB_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"

typedef struct gb_texture {
    int width, height;          /* 0 when not loaded */
    float *rgb;                 /* width*height*3 linear RGB, row 0 at the top */
} gb_texture;

typedef struct gb_material {
    char name[64];
    float Kd[3];                /* diffuse reflectance */
    float Ks[3];                /* glossy (Phong) reflectance */
    float Ns;                   /* Phong exponent */
    float Ke[3];                /* emitted radiance */
    char *map_Kd;               /* resolved path of the diffuse texture, or NULL */
    gb_texture texture;         /* its pixels, if the options asked for them */
} gb_material;

typedef enum gb_light_type {
    GB_LIGHT_POINT,
    GB_LIGHT_SPOT,
    GB_LIGHT_DIRECTIONAL,
} gb_light_type;

typedef struct gb_light {
    gb_light_type type;
    float position[3];          /* point, spot */
    float direction[3];         /* spot, directional: the way light travels, unit */
    float intensity[3];         /* point, spot: W/sr; directional: irradiance W/m^2 */
    float cone_angle;           /* spot: half-angle of the cone, degrees */
    float falloff_angle;        /* spot: half-angle where falloff starts, degrees */
} gb_light;

typedef struct gb_camera {
    float position[3];
    float target[3];
    float up[3];
    float fov_y;                /* vertical field of view, degrees */
    int width, height;          /* image resolution, pixels */
} gb_camera;

typedef struct gb_scene {
    uint32_t vertex_count;
    float *positions;           /* vertex_count * 3 */
    uint32_t triangle_count;
    uint32_t *indices;          /* triangle_count * 3, into positions */
    uint32_t *triangle_material;/* triangle_count, into materials */
    float *corner_normals;      /* triangle_count * 9, or NULL */
    float *corner_texcoords;    /* triangle_count * 6, or NULL */

    uint32_t material_count;
    gb_material *materials;

    uint32_t emissive_count;    /* area lights: the triangles whose Ke > 0 */
    uint32_t *emissive_triangles;

    uint32_t light_count;       /* point, spot and directional lights */
    gb_light *lights;
    uint32_t environment_light_count; /* of them, the last that stand for the
                                   environment (common/environment_lights.h;
                                   0 as loaded): the scene's own are the
                                   first light_count - environment_light_count */
    uint32_t camera_count;      /* at least 1: a default is derived from the bounds */
    gb_camera *cameras;
    float environment[3];       /* radiance of the background (no map) */
    char *environment_map;      /* resolved path of a lat-long image, or NULL
                                   (common/environment.h reads it) */
    gb_texture environment_texture; /* its pixels, if the options asked for them */

    float bounds_min[3], bounds_max[3];
    uint64_t hash;              /* content hash: geometry, materials, lights */
    uint32_t dropped_triangle_count; /* degenerate triangles dropped at load */
    uint32_t dropped_emissive_count; /* of them, triangles of an emissive material */
    uint32_t dropped_emissive_material; /* the material of the first of those */
    uint32_t duplicate_triangle_count; /* triangles with the corners of an earlier
                                          one, dropped at load (the first kept) */
    char *path;                 /* the file loaded */
    char **inputs;              /* every file the load read, each once: the
                                   scene file, the mesh, its MTL files, and
                                   with load_textures its images (--depfile) */
    uint32_t input_count;
    uint32_t undefined_material_count; /* OBJ usemtl names that no MTL defines:
                                          each got the default material */
} gb_scene;

/* The scene's own lights, lights[0 .. this): those the scene file named. */
static inline uint32_t gb_scene_own_light_count(const gb_scene *scene)
{
    return scene->light_count - scene->environment_light_count;
}

typedef struct gb_scene_options {
    int load_textures;          /* 0 (default): check map_Kd and the environment
                                   map exist, do not decode */
} gb_scene_options;

/* options may be NULL for the defaults. */
gb_result gb_scene_load(const char *path, const gb_scene_options *options,
                        gb_scene *scene, gb_error *error);
void gb_scene_free(gb_scene *scene);

/* Appends path to scene->inputs unless it is there already. */
gb_result gb_scene_add_input(gb_scene *scene, const char *path, gb_error *error);

/* Sets material to the default of meshes without materials: name, Kd 0.8
 * grey, no gloss (Ks 0, Ns 0), no emission, no texture. */
void gb_material_set_default(gb_material *material, const char *name);

/* Area of triangle t (world units squared). */
double gb_triangle_area(const gb_scene *scene, uint32_t t);

/* Whether anything in the scene gives light: an emissive triangle of nonzero
 * power, a point, spot or directional light of nonzero intensity, or an
 * environment that is not black (a map counts unless its pixels were loaded
 * and are all black). The one place that decides it: every tool asks here.
 * Returns 1 if so. If not, returns 0 and, when why is not NULL, writes the
 * reason into why (size bytes, truncated): "no light (no emissive material,
 * point, spot or directional light, black environment)", then what was
 * found that gives none, e.g. ": 2 zero-area triangles of emissive material
 * 'lamp' dropped; 1 point light of zero intensity". A scene with no light is
 * valid: its right answer is black. */
int gb_scene_has_light(const gb_scene *scene, char *why, size_t size);

/* The warning about the triangles gb_scene_finish dropped, e.g. "3
 * degenerate triangles dropped (2 of emissive material 'lamp'); 1 duplicate
 * triangle dropped (the corners of an earlier one)", into
 * text (size bytes, truncated). Returns 0 and writes "" when none was. */
int gb_scene_dropped_warning(const gb_scene *scene, char *text, size_t size);

/* Recomputes bounds, emissive triangles and hash after a caller built or
 * changed a scene in memory (tests do this). Also what gb_scene_load does
 * after reading: checks indices, materials and finite positions, drops
 * degenerate and duplicate triangles (counting them), fails on an empty mesh, adds the
 * default camera when there is none. A scene built with no materials
 * (material_count 0, triangle_material NULL) gets the default material. */
gb_result gb_scene_finish(gb_scene *scene, gb_error *error);

#endif
