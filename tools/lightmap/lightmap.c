/* lightmap.c — the octree's irradiance at every covered texel, then the
 * gutter (lightmap.h). */
#include "lightmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gutter.h"
#include "light_octree_shading.h"
#include "scene_triangles.h"
#include "texel_cover.h"
#include "work_queue.h"

typedef struct bake_job {
    const gb_scene *scene;
    const gb_atlas *atlas;
    const gb_light_octree *octree;
    const gb_texel_cover *cover;
    gb_image *image;
} bake_job;

/* The point, shading normal n and geometric normal ng of side `side` (1:
 * the side the winding faces, -1 the back) of triangle t at barycentric
 * weights w (lightmap.h, "Decided here"): the corners' normals as the
 * runtime gives them (scene_triangles.h) interpolated, normalised, turned
 * to ng's side. */
static void surface_at(const gb_scene *scene, uint32_t t, const double w[3], float side,
                       float x[3], float n[3], float ng[3])
{
    gb_vec3 face = gb_vec3_scale(gb_triangle_normal(scene, t), side);
    gb_vec3 normal = {0.0f, 0.0f, 0.0f};
    double point[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
        gb_vec3 corner = gb_triangle_corner(scene, t, c);
        point[0] += w[c] * corner.x;
        point[1] += w[c] * corner.y;
        point[2] += w[c] * corner.z;
        normal = gb_vec3_madd(normal, gb_corner_normal(scene, t, c, face), (float)w[c]);
    }
    for (int k = 0; k < 3; ++k)
        x[k] = (float)point[k];
    normal = gb_vec3_length(normal) > 0.0f ? gb_vec3_normalize(normal) : face;
    if (gb_vec3_dot(normal, face) < 0.0f)
        normal = gb_vec3_negate(normal);
    gb_vec3_store(normal, n);
    gb_vec3_store(face, ng);
}

/* The irradiance of the brighter side of triangle t at weights w: a glTF
 * lightmap has one value a texel for both sides, and the side that light
 * reaches is the one seen (the other faces into a wall or a solid). */
static void brighter_side(const bake_job *job, uint32_t t, const double w[3], float out[3])
{
    float x[3], n[3], ng[3], back[3];
    surface_at(job->scene, t, w, 1.0f, x, n, ng);
    gb_light_octree_irradiance(job->octree, x, n, ng, out);
    surface_at(job->scene, t, w, -1.0f, x, n, ng);
    gb_light_octree_irradiance(job->octree, x, n, ng, back);
    if (back[0] + back[1] + back[2] > out[0] + out[1] + out[2])
        out[0] = back[0], out[1] = back[1], out[2] = back[2];
}

/* Row `item` of the atlas. */
static int bake_row(void *context, uint64_t item)
{
    const bake_job *job = context;
    uint32_t j = (uint32_t)item, width = job->cover->width;
    for (uint32_t i = 0; i < width; ++i) {
        uint32_t t = job->cover->triangle[(size_t)j * width + i];
        if (t == GB_TEXEL_NONE)
            continue;
        double w[3];
        gb_texel_barycentric(job->atlas, t, i, j, w);
        brighter_side(job, t, w, job->image->pixels + 3 * ((size_t)j * width + i));
    }
    return 0;
}

static gb_result bake_texels(bake_job *job, const gb_lightmap_options *options, int *threads,
                             gb_error *error)
{
    gb_work_queue queue = {.item_count = job->cover->height, .threads = options->threads,
                           .progress = options->progress,
                           .progress_user = options->progress_user};
    if (gb_work_queue_run(&queue, bake_row, job, threads) != GB_OK)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "lightmap: interrupted");
    return GB_OK;
}

/* The gutter past the triangles' reach; counts into stats. */
static gb_result fill_gutter(const gb_atlas *atlas, const gb_texel_cover *cover,
                             gb_image *image, gb_lightmap_stats *stats, gb_error *error)
{
    size_t texels = (size_t)cover->width * cover->height;
    uint8_t *filled = malloc(texels);
    if (!filled)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    for (size_t k = 0; k < texels; ++k) {
        filled[k] = cover->triangle[k] != GB_TEXEL_NONE;
        stats->covered += filled[k];
    }
    uint32_t padding = atlas->header.padding;
    int64_t gutter = padding > 1 ? gb_gutter_fill(image, filled, padding - 1) : 0;
    free(filled);
    if (gutter < 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    stats->gutter = (uint64_t)gutter;
    return GB_OK;
}

gb_result gb_lightmap_bake(const gb_scene *scene, const gb_atlas *atlas,
                           const gb_light_octree *octree, const gb_lightmap_options *options,
                           gb_image *image, gb_lightmap_stats *stats, gb_error *error)
{
    double start = gb_seconds();
    gb_lightmap_stats own;
    stats = stats ? stats : &own;
    memset(stats, 0, sizeof *stats);
    memset(image, 0, sizeof *image);
    if (atlas->header.triangle_count != scene->triangle_count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "lightmap: the atlas has %u triangles, the "
                       "scene %u", atlas->header.triangle_count, scene->triangle_count);
    gb_texel_cover cover = {0};
    gb_result result = gb_image_allocate(image, (int)atlas->header.width,
                                         (int)atlas->header.height, 3, error);
    if (result == GB_OK)
        result = gb_texel_cover_make(atlas, gb_atlas_reach(atlas->header.padding), &cover,
                                     error);
    bake_job job = {scene, atlas, octree, &cover, image};
    if (result == GB_OK)
        result = bake_texels(&job, options, &stats->threads, error);
    if (result == GB_OK)
        result = fill_gutter(atlas, &cover, image, stats, error);
    gb_texel_cover_free(&cover);
    if (result != GB_OK)
        gb_image_free(image);
    stats->seconds = gb_seconds() - start;
    return result;
}
