/* lightmap.c — the indirect irradiance at every covered texel, the octree
 * read there or gathered (texel_gather.h), then the gutter (lightmap.h). */
#include "lightmap.h"

#include <stdlib.h>
#include <string.h>

#include "gutter.h"
#include "light_octree_shading.h"
#include "texel_cover.h"
#include "texel_gather.h"
#include "texel_surface.h"
#include "work_queue.h"

typedef struct bake_job {
    const gb_scene *scene;
    const gb_atlas *atlas;
    const gb_light_octree *octree;
    const gb_texel_cover *cover;
    gb_image *image;
} bake_job;

static float sum3(gb_vec3 v)
{
    return v.x + v.y + v.z;
}

/* The octree's irradiance at side s. */
static gb_vec3 octree_irradiance(const gb_light_octree *octree, const gb_texel_surface *s)
{
    float x[3], n[3], ng[3], e[3];
    gb_vec3_store(s->x, x);
    gb_vec3_store(s->n, n);
    gb_vec3_store(s->ng, ng);
    gb_light_octree_irradiance(octree, x, n, ng, e);
    return gb_vec3_load(e);
}

/* The irradiance of the brighter side of triangle t at weights w, the
 * octree read there (lightmap.h, "Decided here"). */
static void brighter_side(const bake_job *job, uint32_t t, const double w[3], float out[3])
{
    gb_texel_surface front = gb_texel_surface_at(job->scene, t, w, 1.0f),
                     back = gb_texel_surface_at(job->scene, t, w, -1.0f);
    gb_vec3 e_front = octree_irradiance(job->octree, &front),
            e_back = octree_irradiance(job->octree, &back);
    gb_vec3_store(sum3(e_back) > sum3(e_front) ? e_back : e_front, out);
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

/* The octree read at every covered texel. */
static gb_result bake_octree_texels(bake_job *job, const gb_lightmap_options *options,
                                    int *threads, gb_error *error)
{
    gb_work_queue queue = {.item_count = job->cover->height, .threads = options->threads,
                           .progress = options->progress,
                           .progress_user = options->progress_user};
    if (gb_work_queue_run(&queue, bake_row, job, threads) != GB_OK)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "lightmap: interrupted");
    return GB_OK;
}

/* A final gather at every covered texel. */
static gb_result bake_gathered_texels(const bake_job *job, const gb_lightmap_options *options,
                                      gb_lightmap_stats *stats, gb_error *error)
{
    gb_texel_gather gather = {
        .scene = job->scene,
        .atlas = job->atlas,
        .cover = job->cover,
        .octree = options->paths ? NULL : job->octree,
        .rays = options->quality,
        .octree_bounces = options->bounces > 0 ? options->bounces : 1,
        .accuracy = options->accuracy == 0.0  ? GB_LIGHTMAP_ACCURACY
                    : options->accuracy < 0.0 ? 0.0
                                              : options->accuracy,
        .seed = options->seed,
        .threads = options->threads,
        .progress = options->progress,
        .progress_user = options->progress_user,
    };
    return gb_texel_gather_bake(&gather, job->image, &stats->rays, &stats->threads, error);
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
        result = options->quality > 0 ? bake_gathered_texels(&job, options, stats, error)
                                      : bake_octree_texels(&job, options, &stats->threads, error);
    if (result == GB_OK)
        result = fill_gutter(atlas, &cover, image, stats, error);
    gb_texel_cover_free(&cover);
    if (result != GB_OK)
        gb_image_free(image);
    stats->seconds = gb_seconds() - start;
    return result;
}
