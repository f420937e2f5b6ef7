/* lightmap's interpolation between gathered texels
 * (tools/lightmap/texel_interpolation.h) against brute force and against
 * the gather at every texel:
 *  1. strides: every texel's, against the definition (the largest power
 *     of two up to the top that divides both coordinates), by search;
 *  2. corners: at every texel of an odd-sized atlas, the corners' weights
 *     sum to 1, lie on the 2 s lattice and reproduce an affine function of
 *     the texel's coordinates exactly (bilinear interpolation does); a
 *     texel whose cell leaves the atlas has none;
 *  3. Ward's error by hand;
 *  4. a block resting on a floor, lit by a point light (the issue's
 *     contact case): `lightmap --paths` with the default accuracy against
 *     the unbiased gather at every texel with 16 times the rays: the
 *     block's footprint stays dark (no light interpolated into it from
 *     outside), the rim just outside it within 5 % of the truth, the
 *     texels within 1.5 texels of its walls (turned so that they cross the
 *     texels at every offset) no worse than gathered at every texel, the
 *     floor's error no larger than the same rays' gather at every texel,
 *     for less than a third of the rays.
 */
#include <math.h>
#include <string.h>

#include "scene_builder.h"
#include "tap_printf.h"
#include "../../tools/atlas/atlas_build.h"
#include "../../tools/lightmap/lightmap.h"
#include "../../tools/lightmap/texel_cover.h"
#include "../../tools/lightmap/texel_interpolation.h"

static int stride_by_search(uint32_t i, uint32_t j, int top)
{
    for (int s = top; s > 1; s /= 2)
        if (i % (uint32_t)s == 0 && j % (uint32_t)s == 0)
            return s;
    return 1;
}

static void test_strides(void)
{
    int wrong = 0;
    for (uint32_t j = 0; j < 70; ++j)
        for (uint32_t i = 0; i < 70; ++i)
            wrong += gb_texel_stride(i, j, GB_TEXEL_TOP_STRIDE) !=
                     stride_by_search(i, j, GB_TEXEL_TOP_STRIDE);
    CHECKF(wrong == 0, "strides of 70 x 70 texels: the largest power of two <= %d dividing both "
          "(%d wrong)", GB_TEXEL_TOP_STRIDE, wrong);
    CHECK(gb_texel_stride(16, 48, 1) == 1, "top stride 1: every texel its own");
}

static double affine(double i, double j)
{
    return 3.0 + 2.0 * i - 5.0 * j;
}

static void test_corners(void)
{
    enum { WIDTH = 37, HEIGHT = 29 };
    int wrong = 0, interpolated = 0, outside = 0;
    for (uint32_t j = 0; j < HEIGHT; ++j)
        for (uint32_t i = 0; i < WIDTH; ++i) {
            int s = gb_texel_stride(i, j, GB_TEXEL_TOP_STRIDE);
            if (s == GB_TEXEL_TOP_STRIDE)
                continue;
            gb_texel_corner c[4];
            int count = gb_texel_corners(i, j, s, WIDTH, HEIGHT, c);
            uint32_t cell = 2u * (uint32_t)s;
            int leaves = (i % cell && i - i % cell + cell >= WIDTH) ||
                         (j % cell && j - j % cell + cell >= HEIGHT);
            if (count == 0) {
                outside += leaves;
                wrong += !leaves;
                continue;
            }
            double sum = 0.0, value = 0.0;
            for (int k = 0; k < count; ++k) {
                sum += c[k].weight;
                value += c[k].weight * affine(c[k].i, c[k].j);
                wrong += c[k].i % cell != 0 || c[k].j % cell != 0 || c[k].weight <= 0.0;
            }
            wrong += leaves || (count != 2 && count != 4) || fabs(sum - 1.0) > 1e-12 ||
                     fabs(value - affine(i, j)) > 1e-9;
            ++interpolated;
        }
    CHECKF(wrong == 0 && interpolated > 900 && outside > 0,
          "corners of %d texels of 37 x 29: on the 2 s lattice, weights > 0 summing to 1, an "
          "affine function reproduced; %d whose cell leaves the atlas have none (%d wrong)",
          interpolated, outside, wrong);
}

static void test_ward_error(void)
{
    gb_vec3 x = {0.0f, 0.0f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
    gb_vec3 x_k = {3.0f, 4.0f, 0.0f}, tilted = {0.0f, 0.5f, 0.8660254f};
    double flat = gb_ward_error(x, up, x_k, up, 10.0f);
    double turned = gb_ward_error(x, up, x, tilted, 10.0f);
    CHECKF(fabs(flat - 0.5) < 1e-6, "Ward's error: 5 away at R 10, same normal: 0.5 (%.7f)", flat);
    CHECKF(fabs(turned - sqrt(0.5)) < 1e-6,
          "Ward's error: same point, normals 60 degrees apart: sqrt(1 - cos 60) (%.7f)", turned);
}

/* ---- a block resting on a floor ---- */

enum { FLOOR_TRIANGLES = 2 };
static const float HALF_FLOOR = 2.0f, HALF_BLOCK = 0.5f, BLOCK_HEIGHT = 1.0f;
/* The block turned about the vertical, so that its walls cross the atlas's
 * texels at every offset. */
static const double BLOCK_TURN = 0.12;

/* Point (x, z) of the floor turned by angle about the vertical. */
static void turn(double angle, double *x, double *z)
{
    double c = cos(angle), s = sin(angle), turned = c * *x - s * *z;
    *z = s * *x + c * *z;
    *x = turned;
}

/* Point p turned by BLOCK_TURN about the vertical, into turned. */
static void turn_point(const float p[3], float turned[3])
{
    double x = p[0], z = p[2];
    turn(BLOCK_TURN, &x, &z);
    turned[0] = (float)x;
    turned[1] = p[1];
    turned[2] = (float)z;
}

/* The floor (triangles 0 and 1, front up) and a block standing on it,
 * turned by BLOCK_TURN, its five faces out (no bottom: it rests on the
 * floor); grey 0.5; a point light above one corner. */
static void build_block_on_floor(gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    uint32_t grey = add_grey(scene, 0.5f, 0.0f);
    const float f = HALF_FLOOR, b = HALF_BLOCK, h = BLOCK_HEIGHT;
    const float floor_quad[4][3] = {{-f, 0, -f}, {f, 0, -f}, {f, 0, f}, {-f, 0, f}};
    const float above[3] = {0.0f, 10.0f, 0.0f};
    add_quad_facing(scene, floor_quad, above, grey);
    const float faces[5][4][3] = {
        {{-b, h, -b}, {b, h, -b}, {b, h, b}, {-b, h, b}},   /* top */
        {{-b, 0, -b}, {b, 0, -b}, {b, h, -b}, {-b, h, -b}}, /* z = -b */
        {{-b, 0, b}, {b, 0, b}, {b, h, b}, {-b, h, b}},     /* z = +b */
        {{-b, 0, -b}, {-b, 0, b}, {-b, h, b}, {-b, h, -b}}, /* x = -b */
        {{b, 0, -b}, {b, 0, b}, {b, h, b}, {b, h, -b}},     /* x = +b */
    };
    const float outward[5][3] = {{0, 10, 0}, {0, 0.5f, -10}, {0, 0.5f, 10}, {-10, 0.5f, 0},
                                 {10, 0.5f, 0}};
    for (int k = 0; k < 5; ++k) {
        float face[4][3], facing[3];
        for (int c = 0; c < 4; ++c)
            turn_point(faces[k][c], face[c]);
        turn_point(outward[k], facing);
        add_quad_facing(scene, face, facing, grey);
    }
    const float light[3] = {1.2f, 2.5f, 0.8f}, intensity[3] = {20.0f, 20.0f, 20.0f};
    add_point_light(scene, GB_LIGHT_POINT, light, NULL, intensity);
    const float eye[3] = {0.0f, 4.0f, 6.0f}, target[3] = {0.0f, 0.0f, 0.0f};
    set_camera(scene, eye, target, 40.0f, 64, 64);
    scene_done(scene);
}

/* Sums over a class of the floor's texels. */
typedef struct texel_sums {
    double bake, truth;         /* of the mean irradiance over RGB */
    double squared_error;       /* of the bake: (a - b)^2 / (b^2 + 0.01 mean^2), summed */
    double gathered_squared_error; /* the same of the gather at every texel */
    int texels;
} texel_sums;

typedef struct floor_classes {
    texel_sums footprint, rim, wall, floor;
} floor_classes;

static double texel_mean(const gb_image *image, size_t k)
{
    const float *p = image->pixels + 3 * k;
    return (p[0] + p[1] + p[2]) / 3.0;
}

/* The floor's texels whose centre lies on a floor triangle: those 1.5
 * texels or more inside the block's footprint, those 0.5 to 2.5 texels
 * outside it (the rim), all of them. */
static floor_classes classify(const gb_scene *scene, const gb_atlas *atlas,
                              const gb_image *bake, const gb_image *gathered,
                              const gb_image *truth)
{
    floor_classes classes;
    memset(&classes, 0, sizeof classes);
    gb_texel_cover cover;
    gb_error error;
    if (gb_texel_cover_make(atlas, 0.0, &cover, &error) != GB_OK)
        return classes;
    double texel = 1.0 / atlas->header.texels_per_unit;
    for (uint32_t j = 0; j < cover.height; ++j)
        for (uint32_t i = 0; i < cover.width; ++i) {
            size_t k = (size_t)j * cover.width + i;
            uint32_t t = cover.triangle[k];
            if (t >= FLOOR_TRIANGLES)
                continue;
            double w[3], x = 0.0, z = 0.0;
            gb_texel_barycentric(atlas, t, i, j, w);
            for (int c = 0; c < 3; ++c) {
                const float *v = scene->positions + 3 * scene->indices[3 * t + c];
                x += w[c] * v[0];
                z += w[c] * v[2];
            }
            turn(-BLOCK_TURN, &x, &z);
            double outside = fmax(fabs(x), fabs(z)) - HALF_BLOCK;  /* Chebyshev, in units */
            texel_sums *in = outside <= -1.5 * texel ? &classes.footprint
                             : outside >= 0.5 * texel && outside <= 2.5 * texel ? &classes.rim
                                                                                 : NULL;
            double a = texel_mean(bake, k), g = texel_mean(gathered, k),
                   b = texel_mean(truth, k);
            texel_sums *wall = fabs(outside) <= 1.5 * texel ? &classes.wall : NULL;
            texel_sums *all[3] = {in, wall, &classes.floor};
            for (int m = 0; m < 3; ++m)
                if (all[m]) {
                    all[m]->bake += a;
                    all[m]->truth += b;
                    all[m]->squared_error += (a - b) * (a - b) / (b * b + 0.01 * 0.25);
                    all[m]->gathered_squared_error += (g - b) * (g - b) /
                                                       (b * b + 0.01 * 0.25);
                    ++all[m]->texels;
                }
        }
    gb_texel_cover_free(&cover);
    return classes;
}

static int bake(const gb_scene *scene, const gb_atlas *atlas, int rays, double accuracy,
                gb_image *image, uint64_t *traced)
{
    gb_lightmap_options options = {.threads = 0, .quality = rays, .paths = 1,
                                   .accuracy = accuracy, .seed = 7};
    gb_lightmap_stats stats;
    gb_error error;
    memset(image, 0, sizeof *image);
    if (gb_lightmap_bake(scene, atlas, NULL, &options, image, &stats, &error) != GB_OK) {
        printf("# gb_lightmap_bake: %s\n", error.message);
        return 0;
    }
    *traced = stats.rays;
    return 1;
}

static void test_block_on_floor(void)
{
    gb_scene scene;
    build_block_on_floor(&scene);
    gb_atlas atlas;
    gb_atlas_stats atlas_stats;
    gb_atlas_options atlas_options = {.size = 128, .padding = GB_ATLAS_DEFAULT_PADDING};
    gb_error error;
    if (!CHECK(gb_atlas_build(&scene, &atlas_options, &atlas, &atlas_stats, &error) == GB_OK,
               "block on a floor: the atlas")) {
        gb_scene_free(&scene);
        return;
    }
    enum { RAYS = 64 };
    gb_image interpolated, gathered, truth;
    uint64_t interpolated_rays = 0, gathered_rays = 0, truth_rays = 0;
    int baked = bake(&scene, &atlas, RAYS, 0.0, &interpolated, &interpolated_rays) &
                bake(&scene, &atlas, RAYS, -1.0, &gathered, &gathered_rays) &
                bake(&scene, &atlas, 16 * RAYS, -1.0, &truth, &truth_rays);
    if (CHECK(baked, "block on a floor: three bakes")) {
        floor_classes c = classify(&scene, &atlas, &interpolated, &gathered, &truth);
        double rim = c.rim.bake / c.rim.truth;
        printf("# floor: footprint %d texels, bake mean %.4g, truth %.4g; rim %d texels, "
               "bake %.4g, truth %.4g; floor relative MSE %.4g interpolated, %.4g every "
               "texel; rays %llu against %llu\n", c.footprint.texels,
               c.footprint.bake / c.footprint.texels, c.footprint.truth / c.footprint.texels,
               c.rim.texels, c.rim.bake / c.rim.texels, c.rim.truth / c.rim.texels,
               c.floor.squared_error / c.floor.texels,
               c.floor.gathered_squared_error / c.floor.texels,
               (unsigned long long)interpolated_rays, (unsigned long long)gathered_rays);
        printf("# wall: %d texels, relative MSE %.4g interpolated, %.4g every texel; bake mean "
               "%.4g, truth %.4g\n", c.wall.texels, c.wall.squared_error / c.wall.texels,
               c.wall.gathered_squared_error / c.wall.texels, c.wall.bake / c.wall.texels,
               c.wall.truth / c.wall.texels);
        CHECK(c.footprint.texels > 100 &&
                  c.footprint.bake <= 2.0 * c.footprint.truth +
                                          0.01 * c.rim.truth / c.rim.texels * c.footprint.texels,
              "the block's footprint: within 2x of the truth (which is dark), no light "
              "interpolated into it from the rim");
        CHECKF(c.rim.texels > 50 && fabs(rim - 1.0) < 0.05,
              "the rim 0.5 to 2.5 texels outside the block: within 5 %% of the truth (%.4f)",
              rim);
        CHECKF(c.wall.texels > 100 &&
                   c.wall.squared_error <= 1.1 * c.wall.gathered_squared_error,
               "the texels within 1.5 of the block's walls: no light carried across them "
               "(relative MSE %.4g, against %.4g gathered at every texel)",
               c.wall.squared_error / c.wall.texels,
               c.wall.gathered_squared_error / c.wall.texels);
        CHECK(c.floor.squared_error <= c.floor.gathered_squared_error,
              "the floor's relative MSE: interpolated no more than gathered at every texel");
        CHECK(3 * interpolated_rays < gathered_rays,
              "the interpolated bake traces under a third of the rays");
    }
    gb_image_free(&interpolated);
    gb_image_free(&gathered);
    gb_image_free(&truth);
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

int main(void)
{
    test_strides();
    test_corners();
    test_ward_error();
    test_block_on_floor();
    return tap_done();
}
