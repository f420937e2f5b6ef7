/* lightmap.c — the octree's irradiance at every covered texel, then the
 * gutter (lightmap.h). */
#include "lightmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gutter.h"
#include "light_octree_shading.h"
#include "texel_cover.h"
#include "work_queue.h"

typedef struct bake_job {
    const gb_scene *scene;
    const gb_atlas *atlas;
    const gb_light_octree *octree;
    const gb_texel_cover *cover;
    gb_image *image;
} bake_job;

static void normalize3(float v[3])
{
    float length = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k)
        v[k] = length > 0.0f ? v[k] / length : 0.0f;
}

/* cross(v1 - v0, v2 - v0), unit (z for a degenerate triangle). */
static void face_normal(const gb_scene *scene, uint32_t t, float out[3])
{
    const float *p[3];
    for (int c = 0; c < 3; ++c)
        p[c] = scene->positions + 3 * (size_t)scene->indices[3 * (size_t)t + c];
    float e1[3], e2[3];
    for (int k = 0; k < 3; ++k)
        e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
    out[0] = e1[1] * e2[2] - e1[2] * e2[1];
    out[1] = e1[2] * e2[0] - e1[0] * e2[2];
    out[2] = e1[0] * e2[1] - e1[1] * e2[0];
    normalize3(out);
    if (out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f)
        out[2] = 1.0f;
}

/* The point, shading normal n and geometric normal ng of triangle t at
 * barycentric weights w (lightmap.h, "Decided here"). */
static void surface_at(const gb_scene *scene, uint32_t t, const double w[3], float x[3],
                       float n[3], float ng[3])
{
    face_normal(scene, t, ng);
    for (int k = 0; k < 3; ++k) {
        double sum = 0.0, normal = 0.0;
        for (int c = 0; c < 3; ++c) {
            sum += w[c] * scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + c] + k];
            if (scene->corner_normals)
                normal += w[c] * scene->corner_normals[9 * (size_t)t + 3 * c + k];
        }
        x[k] = (float)sum;
        n[k] = (float)normal;
    }
    normalize3(n);
    if (!scene->corner_normals || (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f))
        memcpy(n, ng, 3 * sizeof *n);
    if (n[0] * ng[0] + n[1] * ng[1] + n[2] * ng[2] < 0.0f)
        for (int k = 0; k < 3; ++k)
            n[k] = -n[k];
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
        float x[3], n[3], ng[3];
        gb_texel_barycentric(job->atlas, t, i, j, w);
        surface_at(job->scene, t, w, x, n, ng);
        gb_light_octree_irradiance(job->octree, x, n, ng,
                                   job->image->pixels + 3 * ((size_t)j * width + i));
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

/* The gutter around the covered texels; counts filled into stats. */
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
    int64_t gutter = gb_gutter_fill(image, filled, atlas->header.padding);
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
        result = gb_texel_cover_make(atlas, &cover, error);
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
