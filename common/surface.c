#include "surface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_triangles.h"

/* 2^-21: 4 to 8 float ulps of the corners' magnitude. A hit point
 * v0 + u e1 + v e2 is off its plane by at most about 2 ulps, the offset
 * origin rounds by half of one more, Embree's test by about 1. Larger
 * offsets step over thin gaps far from the origin: 2^-16 (500 ulps, 15 mm at
 * 1e6) let rays start below the Cornell box's light, 0.5 mm under the
 * ceiling; the box moved by 1e6 mm gave relative MSE 0.015 against the
 * unmoved box (64x64, 8 spp), 0.0005 with this scale (48x48, 64 spp). */
#define GB_RAY_OFFSET_SCALE 0x1p-21f

float gb_ray_offset(float magnitude)
{
    return GB_RAY_OFFSET_SCALE * fmaxf(magnitude, 1e-20f);
}

/* How far to move a ray origin off triangle t: gb_ray_offset of the largest
 * coordinate magnitude of its corners, which bounds the float error of any
 * point computed on it (robust offsets scaled by the point's magnitude). */
static float triangle_ray_offset(const gb_scene *scene, uint32_t t)
{
    return gb_ray_offset(fmaxf(gb_vec3_max_abs(gb_triangle_corner(scene, t, 0)),
                               fmaxf(gb_vec3_max_abs(gb_triangle_corner(scene, t, 1)),
                                     gb_vec3_max_abs(gb_triangle_corner(scene, t, 2)))));
}

/* An earlier material with the same texture file and size, or m itself. */
static uint32_t first_with_texture(const gb_scene *scene, uint32_t m)
{
    const gb_material *a = &scene->materials[m];
    for (uint32_t i = 0; i < m && a->map_Kd && a->texture.rgb; ++i) {
        const gb_material *b = &scene->materials[i];
        if (b->map_Kd && b->texture.rgb && strcmp(a->map_Kd, b->map_Kd) == 0 &&
            a->texture.width == b->texture.width && a->texture.height == b->texture.height)
            return i;
    }
    return m;
}

/* Packs each texture file once, however many materials use it. */
static gb_result pack_textures(const gb_scene *scene, gb_surface_table *table,
                               gb_error *error)
{
    table->textures = calloc(scene->material_count ? scene->material_count : 1,
                             sizeof *table->textures);
    if (!table->textures)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "surface table: out of memory");
    for (uint32_t m = 0; m < scene->material_count; ++m) {
        const gb_texture *texture = &scene->materials[m].texture;
        uint32_t first = first_with_texture(scene, m);
        if (first != m) {
            gb_packed_texture_share(&table->textures[first], texture, &table->textures[m]);
            continue;
        }
        gb_result result = gb_packed_texture_make(texture, &table->textures[m], error);
        if (result != GB_OK)
            return result;
    }
    return GB_OK;
}

gb_result gb_surface_table_build(const gb_scene *scene, gb_surface_table *table,
                                 gb_error *error)
{
    size_t count = scene->triangle_count ? scene->triangle_count : 1;
    *table = (gb_surface_table){.scene = scene};
    table->records = aligned_alloc(_Alignof(gb_triangle_record),
                                   count * sizeof *table->records);
    gb_result result = table->records ? pack_textures(scene, table, error)
                                      : gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                                                "surface table: out of memory");
    if (result != GB_OK) {
        gb_surface_table_free(table);
        return result;
    }
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        gb_triangle_record *r = &table->records[t];
        gb_vec3 a = gb_triangle_corner(scene, t, 0);
        gb_vec3_store(a, r->v0);
        gb_vec3_store(gb_vec3_sub(gb_triangle_corner(scene, t, 1), a), r->e1);
        gb_vec3_store(gb_vec3_sub(gb_triangle_corner(scene, t, 2), a), r->e2);
        gb_vec3_store(gb_triangle_normal(scene, t), r->normal);
        r->offset = triangle_ray_offset(scene, t);
        r->material = scene->triangle_material[t];
        if (scene->corner_texcoords)
            memcpy(r->texcoords, &scene->corner_texcoords[6 * (size_t)t], sizeof r->texcoords);
        if (scene->corner_normals)
            memcpy(r->corner_normals, &scene->corner_normals[9 * (size_t)t],
                   sizeof r->corner_normals);
    }
    return GB_OK;
}

void gb_surface_table_free(gb_surface_table *table)
{
    for (uint32_t m = 0; table->textures && m < table->scene->material_count; ++m)
        gb_packed_texture_free(&table->textures[m]);
    free(table->textures);
    free(table->records);
    table->textures = NULL;
    table->records = NULL;
}

/* Interpolated corner normal, or the geometric normal without corner normals. */
static gb_vec3 shading_normal(const gb_surface_table *table, const gb_triangle_record *r,
                              const gb_hit *hit, gb_vec3 ng)
{
    if (!table->scene->corner_normals)
        return ng;
    const float *c = r->corner_normals;
    float w = 1.0f - hit->u - hit->v;
    gb_vec3 n = gb_vec3_scale(gb_vec3_load(c), w);
    n = gb_vec3_madd(n, gb_vec3_load(c + 3), hit->u);
    n = gb_vec3_madd(n, gb_vec3_load(c + 6), hit->v);
    n = gb_vec3_normalize(n);
    if (gb_vec3_is_zero(n) || !isfinite(n.x + n.y + n.z))
        return ng;
    return gb_vec3_dot(n, ng) < 0.0f ? gb_vec3_negate(n) : n;
}

/* Where the texture of the material is read at the hit, if it has one. */
static void find_texcoord(const gb_surface_table *table, const gb_triangle_record *r,
                          const gb_hit *hit, gb_surface *surface)
{
    const gb_scene *scene = table->scene;
    const gb_texture *texture = &scene->materials[surface->material].texture;
    surface->textured = texture->rgb && texture->width > 0 && texture->height > 0 &&
                        scene->corner_texcoords;
    if (!surface->textured)
        return;
    const float *c = r->texcoords;
    float w = 1.0f - hit->u - hit->v;
    surface->texels = gb_packed_texture_prefetch(&table->textures[surface->material],
                                                 w * c[0] + hit->u * c[2] + hit->v * c[4],
                                                 w * c[1] + hit->u * c[3] + hit->v * c[5]);
}

const gb_brdf *gb_surface_brdf(const gb_surface_table *table, gb_surface *surface)
{
    if (surface->brdf_ready)
        return &surface->brdf;
    const gb_material *material = &table->scene->materials[surface->material];
    gb_vec3 kd = gb_vec3_load(material->Kd);
    if (surface->textured)
        kd = gb_vec3_mul(kd, gb_packed_texture_read(&table->textures[surface->material],
                                                    surface->texels));
    gb_vec3_store(kd, surface->brdf.Kd);
    for (int c = 0; c < 3; ++c)
        surface->brdf.Ks[c] = material->Ks[c];
    surface->brdf.Ns = fmaxf(material->Ns, 0.0f);
    surface->brdf_ready = 1;
    return &surface->brdf;
}

void gb_surface_at_hit(const gb_surface_table *table, const gb_hit *hit, gb_vec3 dir,
                       gb_surface *surface)
{
    const gb_triangle_record *r = &table->records[hit->triangle];
    __builtin_prefetch(r->corner_normals);  /* the record's second line, with the first */
    const gb_material *material = &table->scene->materials[r->material];
    gb_vec3 front_normal = gb_vec3_load(r->normal);
    gb_vec3 p = gb_vec3_madd(gb_vec3_load(r->v0), gb_vec3_load(r->e1), hit->u);
    surface->position = gb_vec3_madd(p, gb_vec3_load(r->e2), hit->v);
    surface->triangle = hit->triangle;
    surface->wo = gb_vec3_negate(dir);
    surface->front = gb_vec3_dot(front_normal, surface->wo) > 0.0f;
    surface->ng = surface->front ? front_normal : gb_vec3_negate(front_normal);
    surface->n = shading_normal(table, r, hit, surface->ng);
    surface->material = r->material;
    surface->brdf_ready = 0;
    find_texcoord(table, r, hit, surface);
    surface->emission = surface->front ? gb_vec3_load(material->Ke) : gb_vec3_make(0, 0, 0);
    surface->offset = r->offset;
}

gb_vec3 gb_surface_ray_origin(const gb_surface *surface, gb_vec3 dir)
{
    float side = gb_vec3_dot(dir, surface->ng) >= 0.0f ? 1.0f : -1.0f;
    return gb_vec3_madd(surface->position, surface->ng, side * surface->offset);
}
