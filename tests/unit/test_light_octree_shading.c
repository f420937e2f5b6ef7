/* test_light_octree_shading.c — gb_light_octree_irradiance
 * (common/light_octree_shading.h), the CPU twin of the octree display's
 * interpolate() (runtime/octree/octree_irradiance.glsl), on a hand-made
 * octree over a floor whose leaves each hold three VDLs: one lit from
 * above (irradiance growing across the leaves), one grazing (|n_leaf·ω|
 * below MIN_COS = 0.25), one from just below the floor (n·ω > 0 for the
 * tilted shading normal, but ng·ω < 0: dropped), a leaf normal tilted off
 * the floor, and holes (missing leaves, leaves without VDLs):
 *
 *  The octree is clustered for surface interpolation (floor_octree.h):
 *  each leaf's plane is the floor's, seen along the tilted leaf normal, so
 *  the leaves' surface factors differ a little across the floor.
 *  1. Values worked out by hand: between four lit leaves, the mean of their
 *     sums weighted by their surface factors; at the centre of a missing
 *     leaf, the same over its three lit neighbours (MIN_WEIGHT); no light
 *     from behind ng.
 *  2. Against a direct evaluation written another way (every leaf's
 *     tent weight Π (1 - |d|) and surface factor over the leaves
 *     themselves, no tree walk, in double) at 2000 points of the floor.
 *  3. Against the GPU: the display of the floor (gbview --method octree
 *     --terms indirect, the runtime's own shader) at every pixel against
 *     Kd / π times gb_light_octree_irradiance at the pixel's world point
 *     (common/camera.h's ray through the pixel's centre, met with the
 *     floor).
 *  4. The lightmap (tools/lightmap/lightmap.h) of a hand-made atlas of the
 *     floor: the chart's texels and the first ring around it within the
 *     triangles' reach, each exactly gb_light_octree_irradiance at the
 *     point the test maps it to (the floor's plane, extended past its edge
 *     for the ring), the second ring the mean of its filled neighbours, 0
 *     beyond.
 *  5. That lightmap against the runtime's render into the same atlas
 *     (gbview --method octree --atlas FILE): the atlas display at every
 *     pixel against Kd / π times the CPU lightmap read bilinearly at the
 *     pixel's UV, and the same with the lightmap encoded as the glTF
 *     export embeds it (what a glTF viewer shows of the export; issue 19's
 *     bound: 10^-3 relative MSE).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/indirect_method.h"
#include "../../tools/lightmap/lightmap.h"
#include "../../tools/lightmap/png_bytes.h"
#include "camera.h"
#include "floor_octree.h"
#include "light_octree_shading.h"
#include "photon_map.h"
#include "random.h"
#include "tap.h"

#define PI 3.14159265358979323846

/* The floor (floor_octree.h) and its hand-made octree, three VDLs a lit
 * leaf. */
#define VDLS 3u

/* The three VDLs' directions (unit after normalize3), the leaves' normal,
 * and the floor's shading normal, tilted so that the third VDL has
 * n·ω > 0 but ng·ω < 0. */
static float from_above[3] = {0.3f, 1.0f, 0.2f};
static float grazing[3] = {1.0f, 0.1f, 0.0f};
static float from_below[3] = {-1.0f, -0.1f, 0.3f};
static float leaf_normal[3] = {0.1f, 1.0f, -0.05f};
static float tilted[3] = {-0.3f, 1.0f, 0.1f};
static const float up[3] = {0.0f, 1.0f, 0.0f};

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

static void normalize_directions(void)
{
    normalize3(from_above);
    normalize3(grazing);
    normalize3(from_below);
    normalize3(leaf_normal);
    normalize3(tilted);
}

/* VDL v's irradiance at leaf (i, k), channel c: the first grows across the
 * leaves, the others are constant. */
static double vdl_irradiance(int v, double i, double k, int c)
{
    static const double tint[VDLS][3] = {{1.0, 0.8, 0.6}, {0.1, 0.2, 0.3}, {0.5, 0.5, 0.5}};
    return v == 0 ? (1.0 + 0.05 * i + 0.03 * k) * tint[0][c] : tint[v][c];
}

/* Leaf (i, k)'s three VDLs. */
static uint32_t fill_vdls(uint32_t i, uint32_t k, gb_light_octree_vdl *vdls)
{
    const float *directions[VDLS] = {from_above, grazing, from_below};
    for (uint32_t v = 0; v < VDLS; ++v) {
        for (int c = 0; c < 3; ++c)
            vdls[v].irradiance[c] = (float)vdl_irradiance((int)v, i, k, c);
        vdls[v].direction = gb_photon_pack_direction(directions[v]);
    }
    return VDLS;
}

static void make_octree(floor_octree *h, const gb_scene *scene, gb_light_octree *octree)
{
    floor_octree_punch_holes(h);
    floor_octree_make(h, leaf_normal, VDLS, fill_vdls, scene, octree);
}

/* The floor, its corner normals all `tilted`, a camera above it. */
static void build_floor(gb_scene *scene)
{
    floor_scene_begin(scene, up);
    scene->corner_normals = malloc(9 * scene->triangle_count * sizeof *scene->corner_normals);
    for (uint32_t c = 0; c < 3 * scene->triangle_count; ++c)
        memcpy(scene->corner_normals + 3 * c, tilted, 3 * sizeof(float));
    scene_done(scene);
}

/* ---- 1. by hand ----------------------------------------------------------- */

static double dot3(const float a[3], const float b[3])
{
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

/* The VDL term's factor n·ω / max(|n_leaf·ω|, 0.25), 0 when it or ng·ω is
 * not positive, for the direction stored (its 2 x 16-bit decoding). */
static double factor(const float *direction, const float n[3], const float ng[3])
{
    float w[3];
    gb_photon_unpack_direction(gb_photon_pack_direction(direction), w);
    double c = dot3(n, w) / fmax(fabs(dot3(leaf_normal, w)), 0.25);
    return c > 0.0 && dot3(ng, w) > 0.0 ? c : 0.0;
}

/* A lit leaf's sum at "leaf coordinates" (i, k), channel c. */
static double leaf_sum(double i, double k, const float n[3], const float ng[3], int c)
{
    const float *directions[VDLS] = {from_above, grazing, from_below};
    double sum = 0.0;
    for (int v = 0; v < (int)VDLS; ++v)
        sum += vdl_irradiance(v, i, k, c) * factor(directions[v], n, ng);
    return sum;
}

static double relative(double a, double b)
{
    return fabs(a - b) / fmax(fabs(b), 1e-30);
}

/* The distance of the floor point over (i, k) from leaf (li, lk)'s plane
 * in leaf edges, that plane through the floor under the leaf's centre
 * along the leaf's normal as stored (its height offset as stored too).
 * (The surface distance's normal term, 1 - |n_leaf.ng|, is the same for
 * every leaf here: it cancels in s - s_min.) */
static double plane_by_hand(double li, double lk, double i, double k)
{
    float n[3];
    gb_photon_unpack_direction(gb_photon_pack_direction(leaf_normal), n);
    double centre_height = (-2.1 + (FLOOR_LAYER + 0.5) * FLOOR_CELL) / FLOOR_CELL;
    double stored = lrint(-n[1] * centre_height * 32767.0) / 32767.0;
    return fabs(n[0] * (i - li) + n[1] * -centre_height + n[2] * (k - lk) - stored);
}

/* A leaf's surface factor, s its surface distance, s_min the least of the
 * point's 8 (light_octree_shading.h): max(1 - (s - s_min) / 0.25, 10^-3),
 * faded to 1 as s_min goes from 0.125 to 0.25. */
static double surface_factor(double s, double s_min)
{
    double trust = fmin(fmax(2.0 - 2.0 * s_min / 0.25, 0.0), 1.0);
    return 1.0 - trust * (1.0 - fmax(1.0 - (s - s_min) / 0.25, 1e-3));
}

/* The mean of leaf sums over leaves (li[j], lk[j]), j < count (the lit
 * ones among the point's 8, at equal trilinear weights), each weighted by
 * its surface factor at the floor point over (i, k). */
static double planed_mean(const double *li, const double *lk, int count, double i, double k,
                          const float n[3], const float ng[3], int c)
{
    double total = 0.0, weight = 0.0, nearest = INFINITY;
    for (int j = 0; j < count; ++j)
        nearest = fmin(nearest, plane_by_hand(li[j], lk[j], i, k));
    for (int j = 0; j < count; ++j) {
        double f = surface_factor(plane_by_hand(li[j], lk[j], i, k), nearest);
        total += f * leaf_sum(li[j], lk[j], n, ng, c);
        weight += f;
    }
    return total / weight;
}

/* The floor point over leaf coordinates (i, k) (leaf centres at integers). */
static void floor_point(double i, double k, float x[3])
{
    x[0] = (float)(-2.0 + FLOOR_CELL * (i + 0.5));
    x[1] = 0.0f;
    x[2] = (float)(-2.0 + FLOOR_CELL * (k + 0.5));
}

static void test_by_hand(const gb_light_octree *octree)
{
    float x[3], e[3];
    double worst = 0.0;
    /* Between the lit leaves (2..3) x (4..5): equal weights; layer 7 has no
     * leaf, so the weights renormalise over layer 8. */
    const double window_i[4] = {2, 3, 2, 3}, window_k[4] = {4, 4, 5, 5};
    floor_point(2.5, 4.5, x);
    gb_light_octree_irradiance(octree, x, up, up, e);
    for (int c = 0; c < 3; ++c)
        worst = fmax(worst, relative(e[c], planed_mean(window_i, window_k, 4, 2.5, 4.5, up,
                                                       up, c)));
    printf("# between four lit leaves: %.7g %.7g %.7g, relative error %.2g\n", e[0], e[1],
           e[2], worst);
    CHECK(worst < 1e-5, "between four lit leaves: their sums weighted by their plane factors");
    CHECK(fabs(dot3(leaf_normal, grazing)) < 0.25 && factor(grazing, up, up) > 0.0,
          "the grazing VDL counts, its |n_leaf.w| below MIN_COS (gain clamped at 4)");

    /* The centre of missing leaf (6, 6): its own weight is 1 but it has no
     * light; the others' weights are MIN_WEIGHT each: the mean of the lit
     * (7, 6), (6, 7), (7, 7). */
    const double around_i[3] = {7, 6, 7}, around_k[3] = {6, 7, 7};
    floor_point(6.0, 6.0, x);
    gb_light_octree_irradiance(octree, x, up, up, e);
    worst = 0.0;
    for (int c = 0; c < 3; ++c)
        worst = fmax(worst, relative(e[c], planed_mean(around_i, around_k, 3, 6, 6, up, up, c)));
    printf("# centre of a missing leaf: %.7g %.7g %.7g, relative error %.2g\n", e[0], e[1],
           e[2], worst);
    CHECK(worst < 1e-5, "centre of a missing leaf: the mean of its three lit neighbours");

    /* The light from below: with the tilted n it faces n (n·ω > 0) but not
     * ng, so it is dropped; with ng = n it would count. */
    CHECK(dot3(tilted, from_below) > 0.0 && dot3(up, from_below) < 0.0,
          "the third VDL is in front of the tilted n, behind ng");
    floor_point(2.5, 4.5, x);
    float both[3];
    gb_light_octree_irradiance(octree, x, tilted, up, e);
    double kept = planed_mean(window_i, window_k, 4, 2.5, 4.5, tilted, up, 0);
    gb_light_octree_irradiance(octree, x, tilted, tilted, both);
    double counted = planed_mean(window_i, window_k, 4, 2.5, 4.5, tilted, tilted, 0);
    printf("# tilted n: %.7g (by hand %.7g); with ng = n %.7g (by hand %.7g)\n", e[0], kept,
           both[0], counted);
    CHECK(relative(e[0], kept) < 1e-5 && relative(both[0], counted) < 1e-5 && counted > kept,
          "light from behind ng is dropped, and counts when ng allows it");

    /* Far from every leaf: black. */
    x[1] = 1.5f;
    gb_light_octree_irradiance(octree, x, up, up, e);
    CHECK(e[0] == 0.0f && e[1] == 0.0f && e[2] == 0.0f, "far from every leaf: 0");
}

/* ---- 2. a direct evaluation ----------------------------------------------- */

/* Leaf l as direct() sees it at x: lit and within one edge of x on every
 * axis (near), its tent weight Π (1 - |d|), its surface distance s. */
typedef struct leaf_view {
    int near;
    double tent, surface;
} leaf_view;

static leaf_view view_leaf(const gb_light_octree *octree, uint32_t l, const float x[3],
                           const float ng[3])
{
    const gb_light_octree_header *h = &octree->header;
    const gb_light_octree_leaf *leaf = &octree->leaves[l];
    double cell = h->size / (double)(1u << h->depth), off_plane = -leaf->plane / 32767.0;
    uint32_t leaf_cell[3];
    float normal[3];
    gb_light_octree_leaf_cell(leaf, leaf_cell);
    gb_light_octree_leaf_normal(leaf, normal);
    leaf_view v = {leaf->vdl_count > 0, 1.0, 0.0};
    for (int k = 0; k < 3; ++k) {
        double d = (x[k] - (h->origin[k] + (leaf_cell[k] + 0.5) * cell)) / cell;
        v.near &= fabs(d) < 1.0;
        v.tent *= 1.0 - fabs(d);
        off_plane += normal[k] * d;
    }
    v.surface = fabs(off_plane) + 1.0 - fabs(dot3(normal, ng));
    return v;
}

/* Σ w sum / Σ w over the leaves with VDLs whose centre is within one leaf
 * edge of x on every axis, w = max(Π (1 - |d|), 10^-6) max(1 - (s -
 * s_min) / 0.25, 10^-3), s the distance of x from the leaf's plane in leaf
 * edges plus 1 - |n_leaf.ng|, s_min the least over those leaves, in
 * double. */
static void direct(const gb_light_octree *octree, const float x[3], const float n[3],
                   const float ng[3], double out[3])
{
    const gb_light_octree_header *h = &octree->header;
    double total[3] = {0, 0, 0}, weight = 0.0, nearest = INFINITY;
    leaf_view *views = malloc(h->leaf_count * sizeof *views);
    for (uint32_t l = 0; l < h->leaf_count; ++l) {
        views[l] = view_leaf(octree, l, x, ng);
        if (views[l].near)
            nearest = fmin(nearest, views[l].surface);
    }
    for (uint32_t l = 0; l < h->leaf_count; ++l) {
        const gb_light_octree_leaf *leaf = &octree->leaves[l];
        if (!views[l].near)
            continue;
        float normal[3];
        gb_light_octree_leaf_normal(leaf, normal);
        double w = fmax(views[l].tent, 1e-6) * surface_factor(views[l].surface, nearest);
        for (uint32_t v = leaf->first_vdl; v < leaf->first_vdl + leaf->vdl_count; ++v) {
            float d[3];
            gb_photon_unpack_direction(octree->vdls[v].direction, d);
            double c = dot3(n, d) / fmax(fabs(dot3(normal, d)), 0.25);
            if (c > 0.0 && dot3(ng, d) > 0.0)
                for (int k = 0; k < 3; ++k)
                    total[k] += w * octree->vdls[v].irradiance[k] * c;
        }
        weight += w;
    }
    for (int k = 0; k < 3; ++k)
        out[k] = weight > 0.0 ? total[k] / weight : 0.0;
    free(views);
}

static void test_direct(const gb_light_octree *octree)
{
    gb_random rng = gb_random_make(19, 0);
    double worst = 0.0;
    for (int s = 0; s < 2000; ++s) {
        float x[3] = {-1.9f + 3.8f * gb_random_float(&rng), 0.0f,
                      -1.9f + 3.8f * gb_random_float(&rng)};
        const float *n = s % 2 ? tilted : up;
        float e[3];
        double expected[3];
        gb_light_octree_irradiance(octree, x, n, up, e);
        direct(octree, x, n, up, expected);
        for (int c = 0; c < 3; ++c)
            worst = fmax(worst, fabs(e[c] - expected[c]) / fmax(expected[c], 1e-3));
    }
    printf("# 2000 floor points against the direct evaluation: largest relative "
           "difference %.3g\n", worst);
    CHECK(worst < 1e-5, "2000 points of the floor: the direct evaluation within 10^-5");
}

/* ---- 3. the GPU display --------------------------------------------------- */

/* Where the ray through pixel (px, py)'s centre meets the floor. */
static int pixel_point(const gb_camera_frame *frame, int px, int py, float x[3])
{
    gb_vec3 d = gb_camera_direction(frame, (float)px + 0.5f, (float)py + 0.5f);
    if (!(d.y < 0.0f))
        return 0;
    float t = -frame->position.y / d.y;
    x[0] = frame->position.x + t * d.x;
    x[1] = 0.0f;
    x[2] = frame->position.z + t * d.z;
    return 1;
}

/* Measured: 3.4e-7 (the GPU's world point from its depth buffer against
 * the ray's, float rounding of the same sums). */
#define GPU_TOLERANCE 1e-4

static void test_gpu(const gb_scene *scene, const gb_light_octree *octree, const char *what)
{
    char text[160];
    gb_image image;
    gb_camera_frame frame;
    gb_error error;
    if (!CHECK(gb_camera_frame_make(&scene->cameras[0], FLOOR_IMAGE_SIZE, FLOOR_IMAGE_SIZE, &frame,
                                    &error) == GB_OK &&
                   floor_octree_render(scene, octree, NULL, FLOOR_IMAGE_SIZE, &image),
               "the octree display of the floor rendered headless"))
        return;
    double worst = 0.0, lowest = INFINITY;
    int compared = 0;
    for (int py = 0; py < FLOOR_IMAGE_SIZE; ++py)
        for (int px = 0; px < FLOOR_IMAGE_SIZE; ++px) {
            float x[3], e[3];
            if (!pixel_point(&frame, px, py, x))
                continue;
            gb_light_octree_irradiance(octree, x, tilted, up, e);
            for (int c = 0; c < 3; ++c) {
                double expected = FLOOR_KD / PI * e[c];
                double got = image.pixels[3 * ((size_t)py * FLOOR_IMAGE_SIZE + px) + c];
                worst = fmax(worst, relative(got, expected));
                lowest = fmin(lowest, expected);
            }
            ++compared;
        }
    printf("# %d pixels: the display against Kd/pi x the CPU port, largest relative "
           "difference %.3g (darkest expected %.4g)\n", compared, worst, lowest);
    CHECK(compared == FLOOR_IMAGE_SIZE * FLOOR_IMAGE_SIZE, "every pixel sees the floor");
    CHECK(lowest > 0.0, "no pixel expects black");
    snprintf(text, sizeof text, "%s: every pixel: Kd/pi x gb_light_octree_irradiance within 10^-4",
             what);
    CHECK(worst < GPU_TOLERANCE, text);
    gb_image_free(&image);
}

/* The same with every other leaf's normal turned 60 degrees about z: the
 * surface factor's normal term, 1 - |n_leaf.ng|, now differs between
 * leaves (with one normal it is the same for all and cancels). The leaves
 * are put back as they were. */
static void test_gpu_two_orientations(floor_octree *h, const gb_scene *scene,
                                      const gb_light_octree *octree)
{
    const float turned[3] = {0.8660254f, 0.5f, 0.0f};
    uint32_t kept[FLOOR_GRID * FLOOR_GRID];
    for (uint32_t i = 0; i < h->leaf_count; ++i) {
        kept[i] = h->leaves[i].normal;
        if (i % 2)
            h->leaves[i].normal = gb_photon_pack_direction(turned);
    }
    test_gpu(scene, octree, "leaves of two orientations");
    for (uint32_t i = 0; i < h->leaf_count; ++i)
        h->leaves[i].normal = kept[i];
}

/* ---- 4. the lightmap of a hand-made atlas --------------------------------- */

/* The floor laid flat in one chart (floor_octree.h's floor_atlas) of
 * SQUARE x SQUARE texels, PADDING texels of gutter around it. The quad's
 * diagonal runs through texel centres. */
#define SQUARE 60
#define PADDING 2
#define SIDE (SQUARE + 2 * PADDING)

/* The floor point at texel coordinates (tx, ty) of the atlas. */
static void atlas_point(const floor_atlas *a, double tx, double ty, float x[3])
{
    double s = (tx - PADDING) / SQUARE, r = (ty - PADDING) / SQUARE;
    x[0] = (float)(-FLOOR_HALF + 2.0 * FLOOR_HALF * (a->straight ? s : r));
    x[1] = 0.0f;
    x[2] = (float)(-FLOOR_HALF + 2.0 * FLOOR_HALF * (a->straight ? r : s));
}

static const float *texel(const gb_image *image, int i, int j)
{
    return image->pixels + 3 * ((size_t)j * image->width + i);
}

/* Gutter texel (i, j) of ring `ring` (1: next to the chart) against the
 * mean of its 8 neighbours filled before its round (the chart's texels and
 * the inner rings); the largest relative difference. */
static double ring_difference(const gb_image *image, int i, int j, int ring)
{
    double sum[3] = {0, 0, 0}, worst = 0.0;
    int count = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int x = i + dx, y = j + dy;
            int depth = (int)fmax(fmax(PADDING - x, x - (PADDING + SQUARE - 1)),
                                  fmax(PADDING - y, y - (PADDING + SQUARE - 1)));
            if (depth >= ring || x < 0 || y < 0 || x >= SIDE || y >= SIDE)
                continue;   /* not filled before this ring's round */
            for (int c = 0; c < 3; ++c)
                sum[c] += texel(image, x, y)[c];
            ++count;
        }
    for (int c = 0; c < 3; ++c)
        worst = fmax(worst, relative(texel(image, i, j)[c], sum[c] / count));
    return worst;
}

static void test_lightmap(const gb_scene *scene, const gb_light_octree *octree,
                          const floor_atlas *a, gb_image *lightmap)
{
    gb_lightmap_options options = {.threads = 2};
    gb_lightmap_stats stats;
    gb_error error;
    if (!CHECK(gb_atlas_check(&a->atlas, "floor atlas", &error) == GB_OK &&
                   gb_lightmap_bake(scene, &a->atlas, octree, &options, lightmap, &stats,
                                    &error) == GB_OK,
               "lightmap: the floor's atlas baked")) {
        printf("# %s\n", error.message);
        return;
    }
    CHECK_EQ_INT(stats.covered, (SQUARE + 2) * (SQUARE + 2),
                 "lightmap: the chart's texels and the first ring around it within the "
                 "triangles' reach (sqrt 2: the second ring's centres are 1.5 away)");
    double worst = 0.0, worst_ring = 0.0;
    int black_outside = 1;
    for (int j = 0; j < SIDE; ++j)
        for (int i = 0; i < SIDE; ++i) {
            int depth = (int)fmax(fmax(PADDING - i, i - (PADDING + SQUARE - 1)),
                                  fmax(PADDING - j, j - (PADDING + SQUARE - 1)));
            if (depth <= 1) {
                /* the chart, and the first ring on the plane of the chart's
                 * nearest triangle: the floor's plane, extended past its edge */
                float x[3], e[3];
                atlas_point(a, i + 0.5, j + 0.5, x);
                gb_light_octree_irradiance(octree, x, tilted, up, e);
                for (int c = 0; c < 3; ++c)
                    worst = fmax(worst, relative(texel(lightmap, i, j)[c], e[c]));
            } else if (depth <= PADDING) {
                worst_ring = fmax(worst_ring, ring_difference(lightmap, i, j, depth));
            } else {
                black_outside &= texel(lightmap, i, j)[0] == 0.0f;
            }
        }
    printf("# lightmap: within reach %llu, gutter %llu texels; covered texels and the first "
           "ring against the port %.3g, the second ring against its neighbours' mean %.3g\n",
           (unsigned long long)stats.covered, (unsigned long long)stats.gutter, worst,
           worst_ring);
    CHECK_EQ_INT(stats.gutter, (SQUARE + 4) * (SQUARE + 4) - (SQUARE + 2) * (SQUARE + 2),
                 "lightmap: the gutter's round fills the padding's second ring");
    CHECK(worst < 1e-5, "lightmap: each covered texel is the octree's irradiance at its point, "
                        "each of the first ring on the floor's plane past its edge");
    CHECK(worst_ring < 1e-6, "lightmap: a texel of a later ring is the mean of its filled "
                             "neighbours");
    CHECK(black_outside, "lightmap: beyond the padding, 0");
}

/* ---- 5. the CPU lightmap against the GPU's render into the atlas ---------- */

static void sample_bilinear(const gb_image *image, double u, double v, double out[3])
{
    double x = u * image->width - 0.5, y = v * image->height - 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double ax = x - x0, ay = y - y0;
    for (int c = 0; c < 3; ++c) {
        double t[2][2];
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                int i = x0 + dx < 0 ? 0 : x0 + dx >= image->width ? image->width - 1 : x0 + dx;
                int j = y0 + dy < 0 ? 0 : y0 + dy >= image->height ? image->height - 1 : y0 + dy;
                t[dy][dx] = texel(image, i, j)[c];
            }
        out[c] = (1 - ay) * ((1 - ax) * t[0][0] + ax * t[0][1]) +
                 ay * ((1 - ax) * t[1][0] + ax * t[1][1]);
    }
}

/* Measured: 1.3e-6 (float rounding; the GPU's bilinear weights are fixed
 * point, the field changes little over a texel). */
#define ATLAS_TOLERANCE 1e-4

/* The atlas display (image) against Kd/pi x map read bilinearly at each
 * pixel's UV: the largest relative difference and the relative MSE
 * (imgdiff's: mean of (a - b)^2 / (b^2 + 0.01), b the display). */
static void against_display(const gb_image *image, const gb_camera_frame *frame,
                            const floor_atlas *a, const gb_image *map, double *worst,
                            double *relative_mse)
{
    double sum = 0.0;
    int count = 0;
    *worst = 0.0;
    for (int py = 0; py < FLOOR_IMAGE_SIZE; ++py)
        for (int px = 0; px < FLOOR_IMAGE_SIZE; ++px) {
            float x[3];
            if (!pixel_point(frame, px, py, x))
                continue;
            double s = (x[a->straight ? 0 : 2] + FLOOR_HALF) / (2.0 * FLOOR_HALF);
            double r = (x[a->straight ? 2 : 0] + FLOOR_HALF) / (2.0 * FLOOR_HALF);
            double e[3];
            sample_bilinear(map, (PADDING + s * SQUARE) / SIDE, (PADDING + r * SQUARE) / SIDE,
                            e);
            for (int c = 0; c < 3; ++c) {
                double shown = image->pixels[3 * ((size_t)py * FLOOR_IMAGE_SIZE + px) + c];
                *worst = fmax(*worst, relative(FLOOR_KD / PI * e[c], shown));
                sum += (FLOOR_KD / PI * e[c] - shown) * (FLOOR_KD / PI * e[c] - shown) /
                       (shown * shown + 0.01);
                ++count;
            }
        }
    *relative_mse = count ? sum / count : INFINITY;
}

/* The lightmap as the glTF export holds it (glb_images.h): an 8-bit sRGB
 * PNG of lightmap / its largest value, decoded and scaled back. */
static int exported(const gb_image *lightmap, gb_image *decoded)
{
    size_t n = (size_t)lightmap->width * lightmap->height * 3;
    float scale = 0.0f;
    for (size_t i = 0; i < n; ++i)
        scale = fmaxf(scale, lightmap->pixels[i]);
    gb_image scaled;
    gb_error error;
    void *bytes = NULL;
    size_t size;
    if (gb_image_allocate(&scaled, lightmap->width, lightmap->height, 3, &error) != GB_OK)
        return 0;
    for (size_t i = 0; i < n; ++i)
        scaled.pixels[i] = lightmap->pixels[i] / scale;
    int ok = gb_png_bytes(&scaled, &bytes, &size, decoded, &error) == GB_OK;
    for (size_t i = 0; ok && i < n; ++i)
        decoded->pixels[i] *= scale;
    if (!ok)
        printf("# %s\n", error.message);
    free(bytes);
    gb_image_free(&scaled);
    return ok;
}

static void test_against_gpu_atlas(const gb_scene *scene, const gb_light_octree *octree,
                                   const floor_atlas *a, const gb_image *lightmap)
{
    gb_image image, png;
    gb_camera_frame frame;
    gb_error error;
    if (!CHECK(gb_camera_frame_make(&scene->cameras[0], FLOOR_IMAGE_SIZE, FLOOR_IMAGE_SIZE, &frame,
                                    &error) == GB_OK &&
                   floor_octree_render(scene, octree, &a->atlas, FLOOR_IMAGE_SIZE, &image),
               "the octree through the floor's atlas rendered headless"))
        return;
    double worst, mse;
    against_display(&image, &frame, a, lightmap, &worst, &mse);
    printf("# the runtime's atlas display against Kd/pi x the CPU lightmap, bilinear at "
           "each pixel's UV: largest relative difference %.3g, relative MSE %.3g\n", worst, mse);
    CHECK(worst < ATLAS_TOLERANCE,
          "the runtime's atlas display: Kd/pi x the CPU lightmap within 10^-4");
    if (CHECK(exported(lightmap, &png), "the lightmap encoded as the glTF export does")) {
        against_display(&image, &frame, a, &png, &worst, &mse);
        printf("# the same with the exported PNG: largest relative difference %.3g, "
               "relative MSE %.3g\n", worst, mse);
        CHECK(mse < 1e-3, "the exported PNG at each pixel's UV: the atlas display within "
                          "10^-3 relative MSE");
        gb_image_free(&png);
    }
    gb_image_free(&image);
}

int main(void)
{
    normalize_directions();
    gb_scene scene;
    build_floor(&scene);
    floor_octree *h = calloc(1, sizeof *h);
    gb_light_octree octree;
    if (!h)
        return 1;
    make_octree(h, &scene, &octree);
    gb_error error;
    CHECK(gb_light_octree_check(&octree, "hand-made", &error) == GB_OK,
          "the hand-made octree passes the reader's checks");
    CHECK_EQ_INT(h->leaf_count, FLOOR_GRID * FLOOR_GRID - 2, "two leaves missing");
    test_by_hand(&octree);
    test_direct(&octree);
    test_gpu(&scene, &octree, "one leaf normal");
    test_gpu_two_orientations(h, &scene, &octree);
    floor_atlas atlas;
    gb_image lightmap = {0};
    floor_atlas_make(&scene, SQUARE, PADDING, 1, &atlas);
    test_lightmap(&scene, &octree, &atlas, &lightmap);
    if (lightmap.pixels)
        test_against_gpu_atlas(&scene, &octree, &atlas, &lightmap);
    gb_image_free(&lightmap);
    free(h);
    gb_scene_free(&scene);
    return tap_done();
}
