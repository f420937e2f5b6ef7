/* glb_export.c — the scene, its materials and the lightmap as glTF JSON and
 * a binary chunk (glb_export.h). */
#include "glb_export.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "byte_buffer.h"
#include "corner_vertices.h"
#include "glb_camera.h"
#include "glb_builder.h"
#include "glb_images.h"
#include "gltf_binary.h"
#include "progress.h"
#include "scene_triangles.h"

#define NONE 0xFFFFFFFFu

enum { SAMPLER_LIGHTMAP = 0, SAMPLER_TEXTURE = 1 };

typedef struct export_state {
    const gb_scene *scene;
    const gb_atlas *atlas;
    gb_glb_builder builder;
    gb_byte_buffer primitives, materials, images, textures;
    uint32_t *material_texture;     /* per material: its baseColorTexture, or NONE */
    uint32_t texture_count;
    gb_glb_export_stats *stats;
    int emissive_strength;          /* KHR_materials_emissive_strength used */
} export_state;

/* A JSON string of ASCII text: quotes and backslashes escaped, other
 * bytes outside printable ASCII replaced by '_'. */
static void print_string(gb_byte_buffer *json, const char *text)
{
    gb_byte_buffer_printf(json, "\"");
    for (const char *c = text; *c; ++c) {
        if (*c == '"' || *c == '\\')
            gb_byte_buffer_printf(json, "\\%c", *c);
        else
            gb_byte_buffer_printf(json, "%c", *c >= 0x20 && *c < 0x7F ? *c : '_');
    }
    gb_byte_buffer_printf(json, "\"");
}

/* ---- images and textures ---- */

static uint32_t add_image(export_state *s, uint32_t view, const char *mime, const char *name,
                          int sampler)
{
    uint32_t index = s->texture_count++;
    gb_byte_buffer_printf(&s->images, "%s{\"bufferView\":%u,\"mimeType\":\"%s\",\"name\":",
                          index ? "," : "", view, mime);
    print_string(&s->images, name);
    gb_byte_buffer_printf(&s->images, "}");
    gb_byte_buffer_printf(&s->textures, "%s{\"source\":%u,\"sampler\":%d}", index ? "," : "",
                          index, sampler);
    return index;
}

/* The lightmap: image and texture 0. */
static gb_result add_lightmap(export_state *s, const gb_image *lightmap, gb_error *error)
{
    uint32_t view;
    gb_result result = gb_glb_add_lightmap(&s->builder, lightmap, &view, &s->stats->scale,
                                           &s->stats->png_relative_mse, error);
    if (result == GB_OK)
        add_image(s, view, "image/png", "lightmap", SAMPLER_LIGHTMAP);
    return result;
}

/* Each map_Kd file once, however many materials name it. */
static gb_result add_textures(export_state *s, gb_error *error)
{
    const gb_scene *scene = s->scene;
    for (uint32_t m = 0; m < scene->material_count; ++m) {
        const char *path = scene->materials[m].map_Kd;
        s->material_texture[m] = NONE;
        if (!path)
            continue;
        for (uint32_t earlier = 0; earlier < m && s->material_texture[m] == NONE; ++earlier)
            if (scene->materials[earlier].map_Kd &&
                !strcmp(scene->materials[earlier].map_Kd, path))
                s->material_texture[m] = s->material_texture[earlier];
        if (s->material_texture[m] != NONE)
            continue;
        uint32_t view;
        const char *mime;
        gb_result result = gb_glb_add_texture(&s->builder, path, &view, &mime, error);
        if (result != GB_OK)
            return result;
        const char *slash = strrchr(path, '/');
        s->material_texture[m] = add_image(s, view, mime, slash ? slash + 1 : path,
                                           SAMPLER_TEXTURE);
    }
    return GB_OK;
}

/* ---- primitives ---- */

/* Corner c of triangle t: position, unit normal (scene_triangles.h: the
 * mesh's, else the face's), texcoord 0 (glTF's v), atlas UV. */
static void make_corner(const export_state *s, uint32_t t, int c, float *out)
{
    const gb_scene *scene = s->scene;
    gb_vec3_store(gb_triangle_corner(scene, t, c), out);
    gb_vec3_store(gb_corner_normal(scene, t, c, gb_triangle_normal(scene, t)), out + 3);
    const float *texcoord = scene->corner_texcoords
                                ? scene->corner_texcoords + 6 * (size_t)t + 2 * c : NULL;
    out[6] = texcoord ? texcoord[0] : 0.0f;
    out[7] = texcoord ? 1.0f - texcoord[1] : 0.0f;
    memcpy(out + 8, s->atlas->uvs + 6 * (size_t)t + 2 * c, 2 * sizeof *out);
}

/* The corners of the count triangles listed, in order. */
static float *corners_of(const export_state *s, const uint32_t *triangles, uint32_t count)
{
    float *corners = malloc(((size_t)count * 3 + 1) * GB_VERTEX_FLOATS * sizeof *corners);
    for (uint32_t k = 0; corners && k < count; ++k)
        for (int c = 0; c < 3; ++c)
            make_corner(s, triangles[k], c, corners + ((size_t)k * 3 + c) * GB_VERTEX_FLOATS);
    return corners;
}

/* The triangles grouped by material, each group in scene order:
 * triangles[first[m] .. first[m + 1]) are material m's. */
static int group_by_material(const gb_scene *scene, uint32_t **triangles, uint32_t **first)
{
    *triangles = malloc(((size_t)scene->triangle_count + 1) * sizeof **triangles);
    *first = calloc((size_t)scene->material_count + 2, sizeof **first);
    if (!*triangles || !*first)
        return 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        ++(*first)[scene->triangle_material[t] + 2];
    for (uint32_t m = 0; m < scene->material_count; ++m)
        (*first)[m + 2] += (*first)[m + 1];
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        (*triangles)[(*first)[scene->triangle_material[t] + 1]++] = t;
    return 1;
}

static void add_primitive(export_state *s, uint32_t m, const gb_corner_vertices *v,
                          uint32_t corner_count)
{
    gb_glb_builder *b = &s->builder;
    uint32_t position = gb_glb_add_floats(b, v->vertices, v->count, 3, GB_VERTEX_FLOATS, 1);
    uint32_t normal = gb_glb_add_floats(b, v->vertices + 3, v->count, 3, GB_VERTEX_FLOATS, 0);
    uint32_t texcoord1 = gb_glb_add_floats(b, v->vertices + 8, v->count, 2, GB_VERTEX_FLOATS, 0);
    /* glTF wants TEXCOORD_0 before a TEXCOORD_1: without texture
     * coordinates, the atlas's accessor serves as both. */
    uint32_t texcoord0 = s->scene->corner_texcoords
                             ? gb_glb_add_floats(b, v->vertices + 6, v->count, 2,
                                                 GB_VERTEX_FLOATS, 0)
                             : texcoord1;
    uint32_t indices = gb_glb_add_indices(b, v->indices, corner_count);
    gb_byte_buffer_printf(&s->primitives, "%s{\"attributes\":{\"POSITION\":%u,\"NORMAL\":%u,",
                          s->stats->primitives ? "," : "", position, normal);
    gb_byte_buffer_printf(&s->primitives, "\"TEXCOORD_0\":%u,\"TEXCOORD_1\":%u},"
                          "\"indices\":%u,\"material\":%u,\"mode\":4}", texcoord0, texcoord1,
                          indices, m);
    s->stats->primitives++;
    s->stats->vertices += v->count;
}

static gb_result add_primitives(export_state *s, gb_error *error)
{
    uint32_t *triangles = NULL, *first = NULL;
    gb_result result = GB_OK;
    if (!group_by_material(s->scene, &triangles, &first))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    for (uint32_t m = 0; result == GB_OK && m < s->scene->material_count; ++m) {
        uint32_t count = first[m + 1] - first[m];
        if (!count)
            continue;
        float *corners = corners_of(s, triangles + first[m], count);
        gb_corner_vertices vertices = {0};
        result = corners ? gb_corner_vertices_make(corners, 3 * count, &vertices, error)
                         : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
        if (result == GB_OK)
            add_primitive(s, m, &vertices, 3 * count);
        gb_corner_vertices_free(&vertices);
        free(corners);
    }
    free(triangles);
    free(first);
    return result;
}

/* ---- materials ---- */

static float unit(float x)
{
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

static void add_emission(export_state *s, const gb_material *material)
{
    float strength = fmaxf(material->Ke[0], fmaxf(material->Ke[1], material->Ke[2]));
    if (!(strength > 0.0f))
        return;
    float divide = strength > 1.0f ? strength : 1.0f;
    gb_byte_buffer_printf(&s->materials, ",\"emissiveFactor\":[%.9g,%.9g,%.9g]",
                          (double)(material->Ke[0] / divide), (double)(material->Ke[1] / divide),
                          (double)(material->Ke[2] / divide));
    if (strength > 1.0f) {
        gb_byte_buffer_printf(&s->materials, ",\"extensions\":{\"KHR_materials_emissive_"
                              "strength\":{\"emissiveStrength\":%.9g}}", (double)strength);
        s->emissive_strength = 1;
    }
}

static void add_material(export_state *s, uint32_t m)
{
    const gb_material *material = &s->scene->materials[m];
    gb_byte_buffer_printf(&s->materials, "%s{\"name\":", m ? "," : "");
    print_string(&s->materials, material->name);
    gb_byte_buffer_printf(&s->materials, ",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                          "[%.9g,%.9g,%.9g,1],\"metallicFactor\":0,\"roughnessFactor\":1",
                          (double)unit(material->Kd[0]), (double)unit(material->Kd[1]),
                          (double)unit(material->Kd[2]));
    if (s->material_texture[m] != NONE)
        gb_byte_buffer_printf(&s->materials, ",\"baseColorTexture\":{\"index\":%u,"
                              "\"texCoord\":0}", s->material_texture[m]);
    gb_byte_buffer_printf(&s->materials, "},\"doubleSided\":true");
    add_emission(s, material);
    gb_byte_buffer_printf(&s->materials, ",\"extras\":{\"lightmap\":{\"texture\":0,"
                          "\"texCoord\":1,\"scale\":%.9g,\"encoding\":\"srgb\"}}}",
                          (double)s->stats->scale);
}

/* ---- the file ---- */

/* A buffer's text, "" when nothing was appended. */
static const char *text(const gb_byte_buffer *b)
{
    return b->data ? b->data : "";
}

static void print_document(const export_state *s, gb_byte_buffer *json)
{
    gb_byte_buffer camera_node = {0}, cameras = {0};
    int camera = gb_glb_print_camera(s->scene, &camera_node, &cameras);
    gb_byte_buffer_printf(json, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"gibake "
                          "lightmap\"},");
    if (s->emissive_strength)
        gb_byte_buffer_printf(json, "\"extensionsUsed\":[\"KHR_materials_emissive_"
                              "strength\"],");
    gb_byte_buffer_printf(json, "\"scene\":0,\"scenes\":[{\"nodes\":[0%s]}],\"nodes\":[{"
                          "\"mesh\":0,\"name\":\"scene\"}%s],", camera ? ",1" : "",
                          text(&camera_node));
    if (camera)
        gb_byte_buffer_printf(json, "\"cameras\":%s,", text(&cameras));
    gb_byte_buffer_printf(json, "\"meshes\":[{\"primitives\":[%s]}],\"materials\":[%s],"
                          "\"images\":[%s],\"textures\":[%s],", text(&s->primitives),
                          text(&s->materials), text(&s->images), text(&s->textures));
    gb_byte_buffer_printf(json, "\"samplers\":[{\"magFilter\":9729,\"minFilter\":9729,"
                          "\"wrapS\":33071,\"wrapT\":33071},{\"magFilter\":9729,"
                          "\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}],");
    gb_byte_buffer_printf(json, "\"accessors\":[%s],\"bufferViews\":[%s],\"buffers\":[{"
                          "\"byteLength\":%zu}]}", text(&s->builder.accessors),
                          text(&s->builder.views), s->builder.bin.size);
    json->failed |= camera_node.failed || cameras.failed;
    gb_byte_buffer_free(&camera_node);
    gb_byte_buffer_free(&cameras);
}

static int any_failed(const export_state *s)
{
    return gb_glb_builder_failed(&s->builder) || s->primitives.failed || s->materials.failed ||
           s->images.failed || s->textures.failed;
}

static gb_result write_file(const char *path, export_state *s, gb_error *error)
{
    gb_byte_buffer json = {0};
    print_document(s, &json);
    gb_result result = json.failed || any_failed(s)
                           ? gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path)
                           : gb_gltf_binary_write(path, json.data, json.size, s->builder.bin.data,
                                                  s->builder.bin.size, error);
    gb_byte_buffer_free(&json);
    return result;
}

static void free_state(export_state *s)
{
    gb_glb_builder_free(&s->builder);
    gb_byte_buffer_free(&s->primitives);
    gb_byte_buffer_free(&s->materials);
    gb_byte_buffer_free(&s->images);
    gb_byte_buffer_free(&s->textures);
    free(s->material_texture);
}

gb_result gb_glb_export(const char *path, const gb_scene *scene, const gb_atlas *atlas,
                        const gb_image *lightmap, gb_glb_export_stats *stats, gb_error *error)
{
    double start = gb_seconds();
    gb_glb_export_stats own;
    stats = stats ? stats : &own;
    memset(stats, 0, sizeof *stats);
    export_state s = {.scene = scene, .atlas = atlas, .stats = stats};
    s.material_texture = malloc((scene->material_count + 1) * sizeof *s.material_texture);
    if (!s.material_texture)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    gb_result result = add_lightmap(&s, lightmap, error);
    if (result == GB_OK)
        result = add_textures(&s, error);
    if (result == GB_OK)
        result = add_primitives(&s, error);
    for (uint32_t m = 0; result == GB_OK && m < scene->material_count; ++m)
        add_material(&s, m);
    if (result == GB_OK)
        result = write_file(path, &s, error);
    free_state(&s);
    stats->seconds = gb_seconds() - start;
    return result;
}
