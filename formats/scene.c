#include "scene.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

void gb_material_set_default(gb_material *material, const char *name)
{
    memset(material, 0, sizeof *material);
    snprintf(material->name, sizeof material->name, "%s", name);
    material->Kd[0] = material->Kd[1] = material->Kd[2] = 0.8f;
}

void gb_scene_free(gb_scene *scene)
{
    free(scene->positions);
    free(scene->indices);
    free(scene->triangle_material);
    free(scene->corner_normals);
    free(scene->corner_texcoords);
    for (uint32_t i = 0; scene->materials && i < scene->material_count; ++i) {
        free(scene->materials[i].map_Kd);
        free(scene->materials[i].texture.rgb);
    }
    free(scene->materials);
    free(scene->emissive_triangles);
    free(scene->lights);
    free(scene->cameras);
    free(scene->environment_map);
    free(scene->environment_texture.rgb);
    free(scene->path);
    for (uint32_t i = 0; i < scene->input_count; ++i)
        free(scene->inputs[i]);
    free(scene->inputs);
    memset(scene, 0, sizeof *scene);
}

gb_result gb_scene_add_input(gb_scene *scene, const char *path, gb_error *error)
{
    for (uint32_t i = 0; i < scene->input_count; ++i)
        if (strcmp(scene->inputs[i], path) == 0)
            return GB_OK;
    char **grown = realloc(scene->inputs, (scene->input_count + 1u) * sizeof *grown);
    if (grown)
        scene->inputs = grown;
    if (!grown || !(scene->inputs[scene->input_count] = strdup(path)))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    scene->input_count++;
    return GB_OK;
}

double gb_triangle_area(const gb_scene *scene, uint32_t t)
{
    const uint32_t *v = &scene->indices[3 * (size_t)t];
    const float *a = &scene->positions[3 * (size_t)v[0]], *b = &scene->positions[3 * (size_t)v[1]],
                *c = &scene->positions[3 * (size_t)v[2]];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* ---- checks and clean-up of gb_scene_finish ------------------------------ */

static const char *scene_name(const gb_scene *scene)
{
    return scene->path ? scene->path : "scene";
}

static gb_result check_references(const gb_scene *scene, gb_error *error)
{
    if (scene->triangle_count && (!scene->indices || !scene->triangle_material))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: triangles without indices or materials",
                       scene_name(scene));
    for (size_t i = 0; i < 3 * (size_t)scene->triangle_count; ++i)
        if (scene->indices[i] >= scene->vertex_count)
            return gb_fail(error, GB_ERROR_INVALID, "%s: triangle %zu: vertex index %u out of "
                           "range (%u vertices)", scene_name(scene), i / 3,
                           scene->indices[i], scene->vertex_count);
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        if (scene->triangle_material[t] >= scene->material_count)
            return gb_fail(error, GB_ERROR_INVALID, "%s: triangle %u: material %u out of range "
                           "(%u materials)", scene_name(scene), t,
                           scene->triangle_material[t], scene->material_count);
    return GB_OK;
}

static gb_result check_finite(const gb_scene *scene, gb_error *error)
{
    for (size_t i = 0; i < 3 * (size_t)scene->vertex_count; ++i)
        if (!isfinite(scene->positions[i]))
            return gb_fail(error, GB_ERROR_INVALID, "%s: vertex %zu: coordinate is not finite",
                           scene_name(scene), i / 3 + 1);
    return GB_OK;
}

static int is_degenerate(const gb_scene *scene, uint32_t t)
{
    const uint32_t *v = &scene->indices[3 * (size_t)t];
    return v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || gb_triangle_area(scene, t) == 0.0;
}

/* Moves triangle from to place to (from >= to), with its corner data. */
static void move_triangle(gb_scene *scene, uint32_t from, uint32_t to)
{
    memmove(&scene->indices[3 * (size_t)to], &scene->indices[3 * (size_t)from],
            3 * sizeof *scene->indices);
    scene->triangle_material[to] = scene->triangle_material[from];
    if (scene->corner_normals)
        memmove(&scene->corner_normals[9 * (size_t)to], &scene->corner_normals[9 * (size_t)from],
                9 * sizeof(float));
    if (scene->corner_texcoords)
        memmove(&scene->corner_texcoords[6 * (size_t)to],
                &scene->corner_texcoords[6 * (size_t)from], 6 * sizeof(float));
}

static int emits(const gb_material *material)
{
    return material->Ke[0] > 0 || material->Ke[1] > 0 || material->Ke[2] > 0;
}

/* Counts the emissive ones too: a zero-area light is named when the scene
 * is found to have no light. */
static void drop_degenerate_triangles(gb_scene *scene)
{
    uint32_t kept = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        if (!is_degenerate(scene, t)) {
            move_triangle(scene, t, kept++);
        } else if (emits(&scene->materials[scene->triangle_material[t]])) {
            if (scene->dropped_emissive_count++ == 0)
                scene->dropped_emissive_material = scene->triangle_material[t];
        }
    }
    scene->dropped_triangle_count += scene->triangle_count - kept;
    scene->triangle_count = kept;
}

/* A triangle's three corner positions in lexicographic order: the same
 * three points give the same key whatever the winding or vertex indices. */
typedef struct triangle_key {
    float corner[3][3];
    uint32_t triangle;
} triangle_key;

static int compare_points(const float *a, const float *b)
{
    for (int k = 0; k < 3; ++k)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

static int compare_corners(const triangle_key *a, const triangle_key *b)
{
    for (int c = 0; c < 3; ++c) {
        int order = compare_points(a->corner[c], b->corner[c]);
        if (order)
            return order;
    }
    return 0;
}

/* Orders by corners, then by triangle: each run of equal keys starts with
 * the triangle that comes first in the file. */
static int compare_keys(const void *a, const void *b)
{
    const triangle_key *p = a, *q = b;
    int order = compare_corners(p, q);
    return order ? order : (p->triangle > q->triangle) - (p->triangle < q->triangle);
}

static void swap_corners(triangle_key *key, int i, int j)
{
    if (compare_points(key->corner[i], key->corner[j]) > 0)
        for (int k = 0; k < 3; ++k) {
            float swap = key->corner[i][k];
            key->corner[i][k] = key->corner[j][k];
            key->corner[j][k] = swap;
        }
}

static triangle_key key_of_triangle(const gb_scene *scene, uint32_t t)
{
    triangle_key key = {.triangle = t};
    for (int c = 0; c < 3; ++c)
        memcpy(key.corner[c], &scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + c]],
               sizeof key.corner[c]);
    swap_corners(&key, 0, 1);
    swap_corners(&key, 1, 2);
    swap_corners(&key, 0, 1);
    return key;
}

/* Drops every triangle whose three corners are those of an earlier one (a
 * surface laid twice, either way round): renderers that make a light or an
 * element of each triangle would count it twice. The first keeps its
 * material. */
static gb_result drop_duplicate_triangles(gb_scene *scene, gb_error *error)
{
    triangle_key *keys = malloc((size_t)scene->triangle_count * sizeof *keys);
    unsigned char *duplicate = calloc(scene->triangle_count, 1);
    if (!keys || !duplicate) {
        free(keys);
        free(duplicate);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_name(scene));
    }
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        keys[t] = key_of_triangle(scene, t);
    qsort(keys, scene->triangle_count, sizeof *keys, compare_keys);
    for (uint32_t i = 1; i < scene->triangle_count; ++i)
        duplicate[keys[i].triangle] = compare_corners(&keys[i], &keys[i - 1]) == 0;
    free(keys);
    uint32_t kept = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        if (!duplicate[t])
            move_triangle(scene, t, kept++);
    free(duplicate);
    scene->duplicate_triangle_count += scene->triangle_count - kept;
    scene->triangle_count = kept;
    return GB_OK;
}

static void compute_bounds(gb_scene *scene)
{
    for (int k = 0; k < 3; ++k) {
        scene->bounds_min[k] = INFINITY;
        scene->bounds_max[k] = -INFINITY;
    }
    for (size_t i = 0; i < 3 * (size_t)scene->triangle_count; ++i) {
        const float *p = &scene->positions[3 * (size_t)scene->indices[i]];
        for (int k = 0; k < 3; ++k) {
            scene->bounds_min[k] = fminf(scene->bounds_min[k], p[k]);
            scene->bounds_max[k] = fmaxf(scene->bounds_max[k], p[k]);
        }
    }
}

static gb_result list_emissive_triangles(gb_scene *scene, gb_error *error)
{
    free(scene->emissive_triangles);
    scene->emissive_triangles = NULL;
    scene->emissive_count = 0;
    uint32_t count = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        count += emits(&scene->materials[scene->triangle_material[t]]);
    if (count == 0)
        return GB_OK;
    scene->emissive_triangles = malloc(count * sizeof *scene->emissive_triangles);
    if (!scene->emissive_triangles)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_name(scene));
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        if (emits(&scene->materials[scene->triangle_material[t]]))
            scene->emissive_triangles[scene->emissive_count++] = t;
    return GB_OK;
}

/* Looks at the centre of the bounds from +z, far enough for the bounding
 * sphere to fit the 45 degree square view. */
static gb_result add_default_camera(gb_scene *scene, gb_error *error)
{
    scene->cameras = calloc(1, sizeof *scene->cameras);
    if (!scene->cameras)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_name(scene));
    scene->camera_count = 1;
    gb_camera *camera = &scene->cameras[0];
    double radius = 0;
    for (int k = 0; k < 3; ++k) {
        double half = 0.5 * ((double)scene->bounds_max[k] - scene->bounds_min[k]);
        camera->target[k] = (float)(0.5 * ((double)scene->bounds_min[k] + scene->bounds_max[k]));
        radius += half * half;
    }
    radius = radius > 0 ? sqrt(radius) : 1;
    camera->fov_y = 45;
    camera->width = camera->height = 512;
    double distance = radius / sin(0.5 * camera->fov_y * M_PI / 180);
    memcpy(camera->position, camera->target, sizeof camera->position);
    camera->position[2] = (float)(camera->target[2] + distance);
    camera->up[1] = 1;
    return GB_OK;
}

/* ---- content hash: FNV-1a 64 over little-endian bytes ----------------------- */

enum { FNV_OFFSET = 0, FNV_PRIME = 1 };
static const uint64_t fnv[2] = {0xcbf29ce484222325ull, 0x100000001b3ull};

static uint64_t hash_bytes(uint64_t h, const void *bytes, size_t n)
{
    const unsigned char *b = bytes;
    for (size_t i = 0; i < n; ++i)
        h = (h ^ b[i]) * fnv[FNV_PRIME];
    return h;
}

static uint64_t hash_u32(uint64_t h, uint32_t value)
{
    unsigned char b[4] = {(unsigned char)value, (unsigned char)(value >> 8),
                          (unsigned char)(value >> 16), (unsigned char)(value >> 24)};
    return hash_bytes(h, b, 4);
}

/* The float's bits, with -0 as +0. */
static uint64_t hash_floats(uint64_t h, const float *values, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        float value = values[i] == 0 ? 0.0f : values[i];
        uint32_t bits;
        memcpy(&bits, &value, 4);
        h = hash_u32(h, bits);
    }
    return h;
}

static uint64_t hash_u32s(uint64_t h, const uint32_t *values, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        h = hash_u32(h, values[i]);
    return h;
}

/* An image's file name (not its folder: moving the scene keeps the hash). */
static uint64_t hash_texture_name(uint64_t h, const char *path)
{
    if (!path)
        return hash_u32(h, 0);
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    h = hash_u32(h, (uint32_t)strlen(name));
    return hash_bytes(h, name, strlen(name));
}

static uint64_t hash_geometry(uint64_t h, const gb_scene *scene)
{
    h = hash_u32(h, scene->vertex_count);
    h = hash_floats(h, scene->positions, 3 * (size_t)scene->vertex_count);
    h = hash_u32(h, scene->triangle_count);
    h = hash_u32s(h, scene->indices, 3 * (size_t)scene->triangle_count);
    h = hash_u32s(h, scene->triangle_material, scene->triangle_count);
    h = hash_u32(h, scene->corner_normals != NULL);
    if (scene->corner_normals)
        h = hash_floats(h, scene->corner_normals, 9 * (size_t)scene->triangle_count);
    h = hash_u32(h, scene->corner_texcoords != NULL);
    if (scene->corner_texcoords)
        h = hash_floats(h, scene->corner_texcoords, 6 * (size_t)scene->triangle_count);
    return h;
}

static uint64_t hash_materials_and_lights(uint64_t h, const gb_scene *scene)
{
    h = hash_u32(h, scene->material_count);
    for (uint32_t i = 0; i < scene->material_count; ++i) {
        const gb_material *m = &scene->materials[i];
        h = hash_floats(h, m->Kd, 3);
        h = hash_floats(h, m->Ks, 3);
        h = hash_floats(h, &m->Ns, 1);
        h = hash_floats(h, m->Ke, 3);
        h = hash_texture_name(h, m->map_Kd);
    }
    h = hash_u32(h, scene->light_count);
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        const gb_light *light = &scene->lights[i];
        h = hash_u32(h, (uint32_t)light->type);
        h = hash_floats(h, light->position, 3);
        h = hash_floats(h, light->direction, 3);
        h = hash_floats(h, light->intensity, 3);
        h = hash_floats(h, &light->cone_angle, 1);
        h = hash_floats(h, &light->falloff_angle, 1);
    }
    if (scene->environment_map)     /* only then: older hashes stay valid */
        h = hash_texture_name(h, scene->environment_map);
    return hash_floats(h, scene->environment, 3);
}

static uint64_t scene_hash(const gb_scene *scene)
{
    static const char tag[] = "gibake scene hash 1";
    uint64_t h = hash_bytes(fnv[FNV_OFFSET], tag, sizeof tag - 1);
    h = hash_geometry(h, scene);
    return hash_materials_and_lights(h, scene);
}

static gb_result give_default_material(gb_scene *scene, gb_error *error)
{
    scene->materials = malloc(sizeof *scene->materials);
    scene->triangle_material = calloc((size_t)scene->triangle_count + 1, sizeof(uint32_t));
    if (!scene->materials || !scene->triangle_material)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_name(scene));
    scene->material_count = 1;
    gb_material_set_default(&scene->materials[0], "default");
    return GB_OK;
}

gb_result gb_scene_finish(gb_scene *scene, gb_error *error)
{
    gb_result result = GB_OK;
    if (!scene->triangle_material && scene->material_count == 0)
        result = give_default_material(scene, error);
    if (result == GB_OK)
        result = check_references(scene, error);
    if (result == GB_OK)
        result = check_finite(scene, error);
    if (result != GB_OK)
        return result;
    drop_degenerate_triangles(scene);
    if (scene->triangle_count == 0)
        return gb_fail(error, GB_ERROR_INVALID, "%s: no triangles (empty mesh%s)",
                       scene_name(scene), scene->dropped_triangle_count ? ", all degenerate"
                                                                        : "");
    result = drop_duplicate_triangles(scene, error);
    if (result != GB_OK)
        return result;
    compute_bounds(scene);
    result = list_emissive_triangles(scene, error);
    if (result == GB_OK && scene->camera_count == 0)
        result = add_default_camera(scene, error);
    scene->hash = scene_hash(scene);
    return result;
}

/* ---- what the tools warn about ------------------------------------------------ */

static int any_positive(const float colour[3])
{
    return colour[0] > 0 || colour[1] > 0 || colour[2] > 0;
}

static int environment_gives_light(const gb_scene *scene)
{
    if (!scene->environment_map)
        return any_positive(scene->environment);
    const gb_texture *map = &scene->environment_texture;
    if (!map->rgb)
        return 1;               /* not read: it may be bright */
    for (size_t i = 0; i < (size_t)map->width * (size_t)map->height; ++i)
        if (any_positive(&map->rgb[3 * i]))
            return 1;
    return 0;
}

static uint32_t lights_of_no_power(const gb_scene *scene, gb_light_type type)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < scene->light_count; ++i)
        count += scene->lights[i].type == type && !any_positive(scene->lights[i].intensity);
    return count;
}

static const char *plural(uint32_t count)
{
    return count == 1 ? "" : "s";
}

/* Appends ": " before the first detail, "; " before the others. */
static void append_detail(char *why, size_t size, int *details, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

static void append_detail(char *why, size_t size, int *details, const char *format, ...)
{
    size_t used = strlen(why);
    if (used + 1 >= size)
        return;
    snprintf(why + used, size - used, "%s", (*details)++ ? "; " : ": ");
    used = strlen(why);
    va_list list;
    va_start(list, format);
    vsnprintf(why + used, size - used, format, list);
    va_end(list);
}

int gb_scene_has_light(const gb_scene *scene, char *why, size_t size)
{
    /* gb_scene_finish dropped the zero-area ones: those left have power */
    if (scene->emissive_count || environment_gives_light(scene))
        return 1;
    for (uint32_t i = 0; i < scene->light_count; ++i)
        if (any_positive(scene->lights[i].intensity))
            return 1;
    if (!why || size == 0)
        return 0;
    snprintf(why, size, "no light (no emissive material, point, spot or directional light, "
             "black environment)");
    int details = 0;
    if (scene->dropped_emissive_count)
        append_detail(why, size, &details, "%u zero-area triangle%s of emissive material '%s' "
                      "dropped", scene->dropped_emissive_count,
                      plural(scene->dropped_emissive_count),
                      scene->materials[scene->dropped_emissive_material].name);
    static const char *const names[] = {"point", "spot", "directional"};
    for (int type = GB_LIGHT_POINT; type <= GB_LIGHT_DIRECTIONAL; ++type) {
        uint32_t count = lights_of_no_power(scene, (gb_light_type)type);
        if (count)
            append_detail(why, size, &details, "%u %s light%s of zero intensity", count,
                          names[type], plural(count));
    }
    if (scene->environment_map)
        append_detail(why, size, &details, "environment-map %s is black everywhere",
                      scene->environment_map);
    return 0;
}

int gb_scene_dropped_warning(const gb_scene *scene, char *text, size_t size)
{
    if (size)
        text[0] = '\0';
    if ((!scene->dropped_triangle_count && !scene->duplicate_triangle_count) || size == 0)
        return 0;
    if (scene->dropped_triangle_count)
        snprintf(text, size, "%u degenerate triangle%s dropped", scene->dropped_triangle_count,
                 plural(scene->dropped_triangle_count));
    if (scene->dropped_emissive_count)
        snprintf(text + strlen(text), size - strlen(text), " (%u of emissive material '%s')",
                 scene->dropped_emissive_count,
                 scene->materials[scene->dropped_emissive_material].name);
    if (scene->duplicate_triangle_count)
        snprintf(text + strlen(text), size - strlen(text),
                 "%s%u duplicate triangle%s dropped (the corners of an earlier one)",
                 scene->dropped_triangle_count ? "; " : "", scene->duplicate_triangle_count,
                 plural(scene->duplicate_triangle_count));
    return 1;
}
