/* lightmap_error.c — a lightmap's error against a truth of the same atlas,
 * by the classes of texels issue 49 measures (bench/lightmap.sh).
 *
 *   lightmap_error SCENE NAME.atlas A.exr TRUTH.exr [CAMERA]
 *
 * Classes: "covered", the texels the lightmap fills (tools/lightmap/
 * texel_cover.h at the atlas's reach); "interior", the texels whose centre
 * a triangle covers and whose 9 x 9 neighbourhood lies in the same chart
 * (at least 5 texels from a chart's edge); "edge", the texels whose centre
 * a triangle covers but whose 3 x 3 neighbourhood leaves its chart (one
 * texel in from the edge); "dark", the covered texels whose truth is under
 * a tenth of the covered texels' mean (hidden ones: the floor under a box,
 * the ceiling above McGuire's light); "seen", the covered texels that
 * the scene's camera CAMERA (default 0; its own resolution) sees: each
 * pixel's centre ray traced with Embree, the hit's atlas UV giving the
 * texel (a pixel seeing a triangle's back counts too: the lightmap holds one
 * side a texel). For each, the count, the relative MSE
 *     mean over the texels and RGB of (a - b)^2 / (b^2 + 0.01 m^2),
 * m the truth's mean over the class (a floor scaled to the image, so the
 * figure does not depend on the light's units), and the ratio of means
 * mean(a) / mean(b) (a bias), as "NAME VALUE" lines; then, over the charts
 * of at least 64 interior texels, the ratio of means furthest from 1
 * (chart_worst_ratio) and its chart.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "atlas_inputs.h"
#include "camera.h"
#include "embree_scene.h"
#include "image.h"
#include "scene.h"
#include "../tools/lightmap/texel_cover.h"

enum { EDGE_TEXELS = 5 };

/* Whether texel (i, j)'s centre lies in a triangle of a chart that covers
 * every texel within r. */
static int within_chart(const gb_atlas *atlas, const gb_texel_cover *inside, long i, long j,
                        long r)
{
    long width = inside->width, height = inside->height;
    uint32_t t = inside->triangle[j * width + i];
    if (t == GB_TEXEL_NONE || i < r || j < r || i + r >= width || j + r >= height)
        return 0;
    for (long y = j - r; y <= j + r; ++y)
        for (long x = i - r; x <= i + r; ++x) {
            uint32_t u = inside->triangle[y * width + x];
            if (u == GB_TEXEL_NONE || atlas->charts[u] != atlas->charts[t])
                return 0;
        }
    return 1;
}

/* Marks seen[] the texels the camera's pixel centres see. */
static int mark_seen(const gb_scene *scene, const gb_atlas *atlas, int camera, uint8_t *seen,
                     gb_error *error)
{
    const gb_camera *c = &scene->cameras[camera];
    gb_camera_frame frame;
    gb_embree_scene *rays = NULL;
    if (gb_camera_frame_make(c, c->width, c->height, &frame, error) ||
        gb_embree_scene_create(scene, 0, &rays, error))
        return 0;
    const gb_atlas_header *h = &atlas->header;
    uint64_t ray_count = 0;
    for (int y = 0; y < c->height; ++y)
        for (int x = 0; x < c->width; ++x) {
            gb_vec3 direction = gb_camera_direction(&frame, x + 0.5f, y + 0.5f);
            gb_hit hit;
            if (!gb_embree_intersect(rays, frame.position, direction, 0.0f, INFINITY, &hit,
                                     &ray_count))
                continue;
            const float *uv = atlas->uvs + 6 * (size_t)hit.triangle;
            double w0 = 1.0 - hit.u - hit.v;
            long i = (long)floor((w0 * uv[0] + hit.u * uv[2] + hit.v * uv[4]) * h->width);
            long j = (long)floor((w0 * uv[1] + hit.u * uv[3] + hit.v * uv[5]) * h->height);
            if (i >= 0 && j >= 0 && i < (long)h->width && j < (long)h->height)
                seen[(size_t)j * h->width + (size_t)i] = 1;
        }
    gb_embree_scene_destroy(rays);
    return 1;
}

/* The sum of texel k's RGB. */
static double rgb_sum(const gb_image *image, size_t k)
{
    const float *p = image->pixels + k * image->channels;
    return (double)p[0] + p[1] + p[2];
}

/* One class's figures from its mask. */
static void print_class(const char *name, const uint8_t *mask, const gb_image *a,
                        const gb_image *b)
{
    size_t texels = (size_t)a->width * a->height, count = 0;
    double sum_a = 0.0, sum_b = 0.0, error = 0.0;
    for (size_t k = 0; k < texels; ++k)
        if (mask[k])
            for (int c = 0; c < 3; ++c, ++count) {
                sum_a += a->pixels[k * a->channels + c];
                sum_b += b->pixels[k * b->channels + c];
            }
    double m = count ? sum_b / count : 0.0, floor2 = 0.01 * m * m;
    for (size_t k = 0; k < texels; ++k)
        if (mask[k])
            for (int c = 0; c < 3; ++c) {
                double x = a->pixels[k * a->channels + c], y = b->pixels[k * b->channels + c];
                error += (x - y) * (x - y) / (y * y + floor2);
            }
    printf("%s_texels %zu\n%s_relative_mse %.6g\n%s_ratio_of_means %.6g\n", name, count / 3,
           name, count ? error / count : 0.0, name, sum_b > 0.0 ? sum_a / sum_b : 0.0);
}

/* The chart (of at least 64 texels of mask) whose ratio of means is
 * furthest from 1, in log. */
static void print_worst_chart(const gb_atlas *atlas, const gb_texel_cover *inside,
                              const uint8_t *mask, const gb_image *a, const gb_image *b)
{
    uint32_t charts = atlas->header.chart_count;
    double *sums = calloc(3 * (size_t)charts, sizeof *sums);
    if (!sums)
        return;
    for (size_t k = 0; k < (size_t)a->width * a->height; ++k) {
        if (!mask[k])
            continue;
        uint32_t chart = atlas->charts[inside->triangle[k]];
        sums[3 * chart] += 1.0;
        for (int c = 0; c < 3; ++c) {
            sums[3 * chart + 1] += a->pixels[k * a->channels + c];
            sums[3 * chart + 2] += b->pixels[k * b->channels + c];
        }
    }
    double worst = 1.0;
    uint32_t worst_chart = 0;
    for (uint32_t chart = 0; chart < charts; ++chart) {
        double ratio = sums[3 * chart + 2] > 0.0 ? sums[3 * chart + 1] / sums[3 * chart + 2]
                                                 : 1.0;
        if (sums[3 * chart] >= 64.0 && fabs(log(ratio)) > fabs(log(worst))) {
            worst = ratio;
            worst_chart = chart;
        }
    }
    printf("chart_worst_ratio %.6g\nchart_worst %u\n", worst, worst_chart);
    free(sums);
}

static int compare(const gb_scene *scene, const gb_atlas *atlas, const gb_image *a,
                   const gb_image *b, int camera, gb_error *error)
{
    gb_texel_cover covered = {0}, inside = {0};
    size_t texels = (size_t)a->width * a->height;
    uint8_t *masks = calloc(5, texels);
    int ok = masks && !gb_texel_cover_make(atlas, gb_atlas_reach(atlas->header.padding),
                                           &covered, error) &&
             !gb_texel_cover_make(atlas, 0.0, &inside, error) &&
             mark_seen(scene, atlas, camera, masks + 2 * texels, error);
    if (ok) {
        for (size_t k = 0; k < texels; ++k) {
            masks[k] = covered.triangle[k] != GB_TEXEL_NONE;
            long i = (long)(k % a->width), j = (long)(k / a->width);
            masks[texels + k] = within_chart(atlas, &inside, i, j, EDGE_TEXELS - 1);
            masks[3 * texels + k] = inside.triangle[k] != GB_TEXEL_NONE &&
                                    !within_chart(atlas, &inside, i, j, 1);
            masks[2 * texels + k] &= masks[k];
        }
        print_class("covered", masks, a, b);
        print_class("interior", masks + texels, a, b);
        print_class("seen", masks + 2 * texels, a, b);
        print_class("edge", masks + 3 * texels, a, b);
        double mean = 0.0;
        size_t count = 0;
        for (size_t k = 0; k < texels; ++k)
            if (masks[k])
                mean += rgb_sum(b, k), ++count;
        mean = count ? mean / count : 0.0;
        for (size_t k = 0; k < texels; ++k)
            masks[4 * texels + k] = masks[k] && rgb_sum(b, k) < 0.1 * mean;
        print_class("dark", masks + 4 * texels, a, b);
        print_worst_chart(atlas, &inside, masks + texels, a, b);
    }
    free(masks);
    gb_texel_cover_free(&covered);
    gb_texel_cover_free(&inside);
    return ok;
}

int main(int argc, char **argv)
{
    atlas_inputs in;
    int ok = atlas_inputs_read(&in, argc, argv, "lightmap_error");
    if (ok && (in.a.width != (int)in.atlas.header.width ||
               in.a.height != (int)in.atlas.header.height)) {
        fprintf(stderr, "lightmap_error: the images are not at the atlas's size\n");
        ok = 0;
    }
    gb_error error = {0};
    if (ok && !(ok = compare(&in.scene, &in.atlas, &in.a, &in.b, in.camera, &error)))
        fprintf(stderr, "lightmap_error: %s\n", error.message);
    atlas_inputs_free(&in);
    return ok ? 0 : 1;
}
