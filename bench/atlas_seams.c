/* atlas_seams.c — where the atlas's seams are, and how two images differ
 * there and elsewhere (bench/octree_atlas.sh).
 *
 *   atlas_seams SCENE NAME.atlas A.exr B.exr [CAMERA]
 *
 * Each pixel's centre ray (the scene's camera CAMERA, default 0, at the
 * images' size; common/camera.h) is traced with Embree; the triangle hit
 * and its barycentrics give the pixel's atlas UV, as the display reads it.
 * A pixel is on a seam when any of the four texels its bilinear fetch
 * weighs is not covered by its own chart: a texel is covered by a chart when
 * its centre lies in one of the chart's triangles (tools/lightmap/
 * texel_cover.h with no reach; the others hold the reach and the gutter). A pixel that sees the
 * back of its triangle (the side its winding does not face, which the atlas
 * does not hold: octree_atlas.h) is counted apart. Prints, for the seam
 * pixels, the back-facing ones and the others, their count and the
 * relative MSE of A against B as imgdiff defines it (image_error.h: the
 * mean over their RGB values of (a - b)² / (b² + 0.01)), as "NAME VALUE"
 * lines.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "atlas_inputs.h"
#include "camera.h"
#include "embree_scene.h"
#include "image.h"
#include "scene.h"
#include "scene_triangles.h"
#include "../tools/lightmap/texel_cover.h"

/* Whether the bilinear fetch at the hit's UV weighs a texel its chart does
 * not cover. */
static int on_seam(const gb_atlas *atlas, const gb_texel_cover *cover, const gb_hit *hit)
{
    const gb_atlas_header *h = &atlas->header;
    const float *uv = atlas->uvs + 6 * (size_t)hit->triangle;
    double w0 = 1.0 - hit->u - hit->v;
    double x = (w0 * uv[0] + hit->u * uv[2] + hit->v * uv[4]) * h->width - 0.5;
    double y = (w0 * uv[1] + hit->u * uv[3] + hit->v * uv[5]) * h->height - 0.5;
    long i0 = (long)floor(x), j0 = (long)floor(y);
    for (long j = j0; j <= j0 + 1; ++j)
        for (long i = i0; i <= i0 + 1; ++i) {
            long ci = i < 0 ? 0 : i >= (long)h->width ? (long)h->width - 1 : i;
            long cj = j < 0 ? 0 : j >= (long)h->height ? (long)h->height - 1 : j;
            uint32_t t = cover->triangle[(size_t)cj * h->width + (size_t)ci];
            if (t == GB_TEXEL_NONE || atlas->charts[t] != atlas->charts[hit->triangle])
                return 1;
        }
    return 0;
}

typedef struct pixel_class {
    long count;
    double relative_squared_error;  /* summed over the class's RGB values */
} pixel_class;

static void add_pixel(pixel_class *c, const float *a, const float *b)
{
    ++c->count;
    for (int k = 0; k < 3; ++k)
        c->relative_squared_error += ((double)a[k] - b[k]) * ((double)a[k] - b[k]) /
                                     ((double)b[k] * b[k] + 0.01);
}

static int compare(const gb_scene *scene, const gb_atlas *atlas, const gb_image *a,
                   const gb_image *b, int camera, gb_error *error)
{
    gb_camera_frame frame;
    gb_embree_scene *rays = NULL;
    gb_texel_cover cover = {0};
    if (gb_texel_cover_make(atlas, 0.0, &cover, error) ||
        gb_camera_frame_make(&scene->cameras[camera], a->width, a->height, &frame, error) ||
        gb_embree_scene_create(scene, 0, &rays, error)) {
        gb_texel_cover_free(&cover);
        return 0;
    }
    pixel_class seam = {0}, back = {0}, inside = {0};
    uint64_t ray_count = 0;
    for (int y = 0; y < a->height; ++y)
        for (int x = 0; x < a->width; ++x) {
            gb_vec3 direction = gb_camera_direction(&frame, x + 0.5f, y + 0.5f);
            gb_hit hit;
            if (!gb_embree_intersect(rays, frame.position, direction, 0.0f, INFINITY, &hit,
                                     &ray_count))
                continue;
            size_t i = ((size_t)y * a->width + x) * (size_t)a->channels;
            pixel_class *c = gb_vec3_dot(gb_triangle_normal(scene, hit.triangle), direction) > 0.0f
                                 ? &back
                                 : on_seam(atlas, &cover, &hit) ? &seam : &inside;
            add_pixel(c, a->pixels + i, b->pixels + i);
        }
    const pixel_class *classes[3] = {&seam, &back, &inside};
    static const char *const names[3] = {"seam", "back", "other"};
    for (int k = 0; k < 3; ++k)
        printf("%s_pixels %ld\n%s_relative_mse %.6g\n", names[k], classes[k]->count, names[k],
               classes[k]->relative_squared_error / fmax(3.0 * classes[k]->count, 1.0));
    gb_embree_scene_destroy(rays);
    gb_texel_cover_free(&cover);
    return 1;
}

int main(int argc, char **argv)
{
    atlas_inputs in;
    int ok = atlas_inputs_read(&in, argc, argv, "atlas_seams");
    gb_error error = {0};
    if (ok && !(ok = compare(&in.scene, &in.atlas, &in.a, &in.b, in.camera, &error)))
        fprintf(stderr, "atlas_seams: %s\n", error.message);
    atlas_inputs_free(&in);
    return ok ? 0 : 1;
}
