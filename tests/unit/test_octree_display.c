/* test_octree_display.c — the light octree's display (runtime/octree/octree.c,
 * vivianloc-2007 §4.2) against what can be worked out by hand:
 *
 *  1. A sun over a flat floor, its photons stored at every hit (photons
 *     --store all: on a lone floor every photon is a direct hit), clustered
 *     (cluster), displayed: the octree's term on the floor is the sun's
 *     reflected radiance Kd / π · E cos θ (octree.h: on a leaf's own plane a
 *     VDL gives Kd / π times its irradiance, whatever its direction).
 *  2. A hand-made octree over the same floor whose irradiance grows linearly
 *     across the leaves, with a missing leaf, a leaf without VDLs and an L of
 *     three such holes: every pixel finite, none outside the range of the
 *     leaves' values (no black seam), the jump between neighbouring
 *     pixels no larger than the spread of the leaves around them, and no
 *     black pixel right above the centre of a missing leaf.
 *  3. The VDL direction as the GPU gets it: packed octahedral 2 x 16 bits on
 *     the CPU (gb_photon_pack_direction, as cluster writes it), decoded by
 *     the shader's own GLSL (octree_vdl_direction.glsl) in a compute pass
 *     (test_octree_display_decode.comp.glsl); the angular error over 2^20
 *     directions, max and mean, beside the paper's 8 + 8 bit spherical
 *     (θ, φ) packing.
 *  4. Through the atlas (octree_atlas.h): the octree rendered into a
 *     hand-made atlas of the floor and shown through it gives the walk's
 *     image, within float rounding in one chart, within the gradient over a
 *     texel where two charts meet (a seam); a floor whose back is seen
 *     through the atlas's second layer.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/bake.h"
#include "../../runtime/context.h"
#include "../../runtime/headless.h"
#include "../../runtime/methods.h"
#include "../../runtime/octree/octree.h"
#include "../../tools/cluster/cluster.h"
#include "../../tools/photons/photons.h"
#include "atlas.h"
#include "light_octree.h"
#include "photon_map.h"
/* Of scene_builder.h this test needs only the quad, the light and the
 * camera. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "scene_builder.h"
#pragma GCC diagnostic pop
#include "tap.h"

#define PI 3.14159265358979323846

/* The floor: FLOOR_HALF on each side of the origin in x and z, y = 0,
 * albedo KD; seen from above at CAMERA_HEIGHT with a vertical field of view
 * of CAMERA_FOV degrees: x, z within 3 tan(15°) = 0.80 of the centre. */
#define FLOOR_HALF 2.0f
#define KD 0.5f
#define CAMERA_HEIGHT 3.0f
#define CAMERA_FOV 30.0f
#define IMAGE_SIZE 64

/* ---- scene and rendering ------------------------------------------------- */

static const float sun_irradiance = 2.0f;
static const float sun_direction[3] = {0.6f, -0.8f, 0.0f};    /* cos θ = 0.8 */

/* The floor wound to face toward (its front side), seen from above. */
static void build_floor_facing(gb_scene *scene, const float toward[3])
{
    memset(scene, 0, sizeof *scene);
    uint32_t grey = add_grey(scene, KD, 0.0f);
    const float h = FLOOR_HALF;
    const float corners[4][3] = {{-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}};
    add_quad_facing(scene, corners, toward, grey);
    const float irradiance[3] = {sun_irradiance, sun_irradiance, sun_irradiance};
    add_point_light(scene, GB_LIGHT_DIRECTIONAL, NULL, sun_direction, irradiance);
    const float eye[3] = {0, CAMERA_HEIGHT, 0}, target[3] = {0, 0, 0};
    set_camera(scene, eye, target, CAMERA_FOV, IMAGE_SIZE, IMAGE_SIZE);
    scene_done(scene);
}

static void build_sunlit_floor(gb_scene *scene)
{
    const float above[3] = {0, 1, 0};
    build_floor_facing(scene, above);
}

/* A fresh folder for NAME.lot. */
static int make_folder(char *folder, size_t size)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(folder, size, "%s/gibake-octree-display.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    return mkdtemp(folder) != NULL;
}

/* Writes octree as FOLDER/floor.lot and renders the octree's indirect term
 * of scene with it (gbview --method octree --terms indirect --bake FOLDER),
 * size x size pixels; through atlas (--atlas FILE) unless it is NULL. */
static int render_octree_through(const gb_scene *scene, const gb_light_octree *octree,
                                 const char *atlas, int size, gb_image *image)
{
    char folder[1024], path[1100], scene_path[1100];
    gb_error error;
    if (!make_folder(folder, sizeof folder))
        return 0;
    snprintf(path, sizeof path, "%s/floor.lot", folder);
    snprintf(scene_path, sizeof scene_path, "%s/floor.scene", folder);
    int ok = 0;
    gb_bake *bake = NULL;
    if (gb_light_octree_write(path, octree, &error) != GB_OK ||
        gb_bake_open(scene, scene_path, folder, &bake, &error) != GB_OK) {
        printf("# %s\n", error.message);
    } else if (gb_bake_problem(bake, GB_BAKE_LIGHT_OCTREE)) {
        printf("# %s\n", gb_bake_problem(bake, GB_BAKE_LIGHT_OCTREE));
    } else {
        gb_headless_options options = {
            .renderer = {.method = GB_METHOD_OCTREE, .terms = GB_TERMS_INDIRECT,
                         .width = size, .height = size, .bake = bake,
                         .parameters = {.atlas = atlas}},
        };
        ok = gb_render_headless(scene, &options, image, NULL, &error) == GB_OK;
        if (!ok)
            printf("# %s\n", error.message);
    }
    gb_bake_release(bake);
    unlink(path);
    rmdir(folder);
    return ok;
}

static int render_octree_at(const gb_scene *scene, const gb_light_octree *octree, int size,
                            gb_image *image)
{
    return render_octree_through(scene, octree, NULL, size, image);
}

static int render_octree(const gb_scene *scene, const gb_light_octree *octree, gb_image *image)
{
    return render_octree_at(scene, octree, IMAGE_SIZE, image);
}

static float pixel(const gb_image *image, int x, int y)
{
    return image->pixels[((size_t)y * image->width + x) * image->channels];
}

static int all_finite(const gb_image *image)
{
    size_t n = (size_t)image->width * image->height * image->channels;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(image->pixels[i]))
            return 0;
    return 1;
}

/* ---- 1. a sun over a floor ----------------------------------------------- */

/* Photons: PHOTONS emitted through the sun's disc (radius: the bounding
 * sphere, 2.83), half of them on the floor: 3 x 10^4 per m². cluster at
 * depth 5 (leaf edge 0.125) gathers K = 1000 of them, a disc of radius
 * ~0.1, well inside the floor for every leaf the camera's 0.8 sees; the
 * density estimate's relative deviation is ~1/sqrt(K) = 3.2 % per leaf. */
#define PHOTONS 400000
#define KNN 1000

/* Tolerances. The view covers ~13 x 13 leaves of independent estimates
 * (the two layers the floor's plane separates gather at the same point, so
 * they agree): the mean over the view has a deviation of ~3.2 % / 13 =
 * 0.25 %, bounded by 1 % (4 sigma, plus the estimator's K/(K-1) = +0.1 %
 * bias); a pixel interpolates 4 leaves, bounded by 12 % (3.75 sigma of a
 * single leaf). Measured: mean -0.32 %, largest pixel 6.9 %; with K = 4000
 * and 4 times the photons, 3.7 %: noise, halving as 1/sqrt(K). The other
 * convention (octree.h: E taken as facing the VDL's direction) would give
 * cos θ = 0.8 of the value, 20 % low. */
#define SUN_MEAN_TOLERANCE 0.01
#define SUN_PIXEL_TOLERANCE 0.12

static void test_sun_over_floor(void)
{
    gb_scene scene;
    build_sunlit_floor(&scene);
    gb_photons_options photon_options = {.count = PHOTONS, .store = GB_PHOTON_STORE_ALL};
    gb_cluster_options cluster_options = {.depth = 5, .knn = KNN};
    gb_photon_map map;
    gb_light_octree octree;
    gb_error error;
    if (!CHECK(gb_photons_trace(&scene, &photon_options, &map, NULL, &error) == GB_OK,
               "sun over a floor: photons --store all traced")) {
        printf("# %s\n", error.message);
        gb_scene_free(&scene);
        return;
    }
    gb_result built = gb_cluster_build(&scene, &map, &cluster_options, &octree, NULL, &error);
    gb_photon_map_free(&map);
    if (!CHECK(built == GB_OK, "sun over a floor: clustered into a light octree")) {
        printf("# %s\n", error.message);
        gb_scene_free(&scene);
        return;
    }
    gb_image image;
    if (CHECK(render_octree(&scene, &octree, &image), "sun over a floor: octree displayed")) {
        double cos_theta = -sun_direction[1];
        double expected = KD / PI * sun_irradiance * cos_theta;
        double sum = 0.0, worst = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                double v = pixel(&image, x, y);
                sum += v;
                worst = fmax(worst, fabs(v / expected - 1.0));
            }
        double mean = sum / ((double)image.width * image.height);
        printf("# Kd/pi E cos(theta) = %.6g; mean of the floor %.6g (%+.3f %%), "
               "largest pixel deviation %.3f %%\n",
               expected, mean, 100.0 * (mean / expected - 1.0), 100.0 * worst);
        CHECK(all_finite(&image), "sun over a floor: every pixel finite");
        CHECK(fabs(mean / expected - 1.0) < SUN_MEAN_TOLERANCE,
              "sun over a floor: mean radiance is Kd/pi E cos(theta) within 1 %");
        CHECK(worst < SUN_PIXEL_TOLERANCE,
              "sun over a floor: every pixel within 12 % of Kd/pi E cos(theta)");
        gb_image_free(&image);
    }
    gb_light_octree_free(&octree);
    gb_scene_free(&scene);
}

/* ---- 2. holes: a hand-made octree ---------------------------------------- */

/* Depth 4 over the cube (-2, -2.1, -2) + 4: leaf edge 0.25, the floor
 * (y = 0) in layer 8, 0.1 above its bottom face. Every cell (i, 8, k) is a
 * leaf with one VDL straight up, irradiance E0 (1 + GRADIENT_X i +
 * GRADIENT_Z k), except the holes. */
#define HAND_DEPTH 4u
#define HAND_GRID (1u << HAND_DEPTH)
#define HAND_LAYER 8u
#define E0 1.0f
#define GRADIENT_X 0.05f
#define GRADIENT_Z 0.03f

typedef enum { CELL_LIT, CELL_EMPTY, CELL_MISSING } cell_kind;

typedef struct hand_octree {
    cell_kind cells[HAND_GRID][HAND_GRID];  /* [i][k] of layer HAND_LAYER */
    gb_light_octree_node nodes[HAND_GRID * HAND_GRID * HAND_DEPTH];
    gb_light_octree_leaf leaves[HAND_GRID * HAND_GRID];
    gb_light_octree_vdl vdls[HAND_GRID * HAND_GRID];
    uint32_t node_count, leaf_count, vdl_count;
} hand_octree;

static float cell_irradiance(uint32_t i, uint32_t k)
{
    return E0 * (1.0f + GRADIENT_X * (float)i + GRADIENT_Z * (float)k);
}

/* Is there a leaf in the cube of level `level` at cell (x, y, z)? */
static int has_leaf(const hand_octree *h, uint32_t level, uint32_t x, uint32_t y, uint32_t z)
{
    uint32_t span = 1u << (HAND_DEPTH - level);
    if (HAND_LAYER < y * span || HAND_LAYER >= (y + 1) * span)
        return 0;
    for (uint32_t i = x * span; i < (x + 1) * span; ++i)
        for (uint32_t k = z * span; k < (z + 1) * span; ++k)
            if (h->cells[i][k] != CELL_MISSING)
                return 1;
    return 0;
}

static uint32_t add_leaf(hand_octree *h, uint32_t i, uint32_t k)
{
    gb_light_octree_leaf *leaf = &h->leaves[h->leaf_count];
    const float up[3] = {0, 1, 0};
    memset(leaf, 0, sizeof *leaf);
    memcpy(leaf->normal, up, sizeof leaf->normal);
    leaf->cell[0] = i;
    leaf->cell[1] = HAND_LAYER;
    leaf->cell[2] = k;
    leaf->first_vdl = h->vdl_count;
    if (h->cells[i][k] == CELL_LIT) {
        gb_light_octree_vdl *vdl = &h->vdls[h->vdl_count++];
        float e = cell_irradiance(i, k);
        vdl->irradiance[0] = vdl->irradiance[1] = vdl->irradiance[2] = e;
        vdl->direction = gb_photon_pack_direction(up);
        leaf->vdl_count = 1;
    }
    return h->leaf_count++;
}

/* The node pool in preorder, leaves in Morton order (children in order
 * c = x | y << 1 | z << 2, as the format says). */
static uint32_t build_node(hand_octree *h, uint32_t level, uint32_t x, uint32_t y, uint32_t z)
{
    if (!has_leaf(h, level, x, y, z))
        return GB_LIGHT_OCTREE_NONE;
    if (level == HAND_DEPTH)
        return add_leaf(h, x, z);
    uint32_t node = h->node_count++;
    for (uint32_t c = 0; c < 8; ++c)
        h->nodes[node].child[c] =
            build_node(h, level + 1, 2 * x + (c & 1), 2 * y + (c >> 1 & 1), 2 * z + (c >> 2));
    return node;
}

static void make_octree(hand_octree *h, const gb_scene *scene, gb_light_octree *octree)
{
    h->node_count = h->leaf_count = h->vdl_count = 0;
    build_node(h, 0, 0, 0, 0);
    memset(octree, 0, sizeof *octree);
    gb_light_octree_header *header = &octree->header;
    header->depth = HAND_DEPTH;
    header->node_count = h->node_count;
    header->leaf_count = h->leaf_count;
    header->vdl_count = h->vdl_count;
    header->origin[0] = -2.0f;
    header->origin[1] = -2.1f;
    header->origin[2] = -2.0f;
    header->size = 4.0f;
    header->scene_hash = scene->hash;
    header->photon_count = 1;
    header->emitted_count = 1;
    header->knn = 1;
    header->radius = 1.0f;
    header->vdls_max = 1;
    header->max_spread = 15.0f;
    header->flattening = 0.5f;
    octree->nodes = h->nodes;
    octree->leaves = h->leaves;
    octree->vdls = h->vdls;
}

/* What the display may show on the floor: Kd/pi times the leaves'
 * irradiances, interpolated (a convex combination of them). */
static void leaf_range(const hand_octree *h, double *low, double *high)
{
    *low = INFINITY;
    *high = 0.0;
    for (uint32_t i = 0; i < HAND_GRID; ++i)
        for (uint32_t k = 0; k < HAND_GRID; ++k)
            if (h->cells[i][k] == CELL_LIT) {
                *low = fmin(*low, KD / PI * cell_irradiance(i, k));
                *high = fmax(*high, KD / PI * cell_irradiance(i, k));
            }
}

/* The largest relative difference between a pixel and its right or lower
 * neighbour: |a - b| / min(a, b). */
static double largest_jump(const gb_image *image)
{
    double worst = 0.0;
    for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x) {
            double a = pixel(image, x, y);
            if (x + 1 < image->width) {
                double b = pixel(image, x + 1, y);
                worst = fmax(worst, fabs(a - b) / fmax(fmin(a, b), 1e-30));
            }
            if (y + 1 < image->height) {
                double b = pixel(image, x, y + 1);
                worst = fmax(worst, fabs(a - b) / fmax(fmin(a, b), 1e-30));
            }
        }
    return worst;
}

/* The holes, all inside the view (cells 4..11 in x and z): a missing leaf,
 * a leaf without VDLs beside a lit one, and an L of three (a missing leaf
 * between two empty ones) whose corner window keeps a single lit leaf. */
static void punch_holes(hand_octree *h)
{
    h->cells[6][6] = CELL_MISSING;
    h->cells[9][6] = CELL_EMPTY;
    h->cells[9][9] = CELL_MISSING;
    h->cells[10][9] = CELL_EMPTY;
    h->cells[9][10] = CELL_EMPTY;
}

/* Straight above the centre of a missing leaf, on an odd image, the middle
 * pixel's ray goes through that centre, where every weight of the 2 x 2
 * windows around but the missing leaf's own vanishes (the trilinear
 * weights there are 1 for it, 0 for the others). */
static void test_hole_centres(const hand_octree *h, gb_scene *scene,
                              const gb_light_octree *octree)
{
    static const uint32_t holes[2][2] = {{6, 6}, {9, 9}};
    double low, high;
    leaf_range(h, &low, &high);
    for (int i = 0; i < 2; ++i) {
        gb_camera *camera = &scene->cameras[0];
        float x = -2.0f + 0.25f * ((float)holes[i][0] + 0.5f);
        float z = -2.0f + 0.25f * ((float)holes[i][1] + 0.5f);
        camera->position[0] = camera->target[0] = x;
        camera->position[2] = camera->target[2] = z;
        camera->width = camera->height = 65;
        gb_image image;
        char what[160];
        snprintf(what, sizeof what, "hole centre (%u, %u): rendered", holes[i][0], holes[i][1]);
        if (!CHECK(render_octree_at(scene, octree, 65, &image), what))
            continue;
        double middle = pixel(&image, 32, 32);
        printf("# above the centre of missing leaf (%u, %u): middle pixel %.6g\n", holes[i][0],
               holes[i][1], middle);
        snprintf(what, sizeof what,
                 "hole centre (%u, %u): finite, no darker than the darkest leaf", holes[i][0],
                 holes[i][1]);
        CHECK(all_finite(&image) && middle >= low * (1.0 - 1e-5), what);
        gb_image_free(&image);
    }
}

static void test_holes(void)
{
    gb_scene scene;
    build_sunlit_floor(&scene);
    hand_octree *h = calloc(1, sizeof *h);
    gb_light_octree octree;
    gb_image whole, holed;
    if (!h)
        return;
    make_octree(h, &scene, &octree);
    int rendered = CHECK(render_octree(&scene, &octree, &whole), "whole hand-made octree displayed");
    punch_holes(h);
    make_octree(h, &scene, &octree);
    CHECK_EQ_INT(h->leaf_count, HAND_GRID * HAND_GRID - 2, "holes: two leaves missing");
    CHECK_EQ_INT(h->vdl_count, HAND_GRID * HAND_GRID - 5, "holes: three leaves without VDLs");
    if (CHECK(render_octree(&scene, &octree, &holed), "octree with holes displayed") &&
        rendered) {
        double low, high, darkest = INFINITY, brightest = 0.0;
        leaf_range(h, &low, &high);
        for (int y = 0; y < holed.height; ++y)
            for (int x = 0; x < holed.width; ++x) {
                darkest = fmin(darkest, pixel(&holed, x, y));
                brightest = fmax(brightest, pixel(&holed, x, y));
            }
        /* Two neighbouring pixels each show a convex combination of the
         * leaves of their 2 x 2 windows, together within 3 x 3 leaves:
         * they differ by at most 2 (GRADIENT_X + GRADIENT_Z) E0 Kd/pi, and
         * both are at least E0 Kd/pi: a relative jump of at most 0.16.
         * A black seam would jump by 100 %. */
        double bound = 2.0 * (GRADIENT_X + GRADIENT_Z);
        double smooth = largest_jump(&whole), jump = largest_jump(&holed);
        int differ = 0;
        for (size_t i = 0; i < (size_t)IMAGE_SIZE * IMAGE_SIZE; ++i)
            differ += holed.pixels[3 * i] != whole.pixels[3 * i];
        printf("# leaves Kd/pi E in [%.5g, %.5g]; with holes the floor shows [%.5g, %.5g]; "
               "largest relative jump between neighbours %.4f (no holes %.4f, bound %.2f); "
               "%d of %d pixels changed\n",
               low, high, darkest, brightest, jump, smooth, bound, differ,
               IMAGE_SIZE * IMAGE_SIZE);
        CHECK(all_finite(&holed), "holes: every pixel finite (no NaN, no infinity)");
        CHECK(darkest >= low * (1.0 - 1e-5) && brightest <= high * (1.0 + 1e-5),
              "holes: every pixel within the leaves' range (no black seam)");
        CHECK(jump <= bound, "holes: neighbouring pixels differ by at most 0.16 (relative)");
        CHECK(differ > 0 && differ < IMAGE_SIZE * IMAGE_SIZE / 2,
              "holes: only the pixels near a hole change");
        /* Without holes the field is linear and trilinear interpolation
         * reproduces it: a pixel's jump is the gradient over one pixel. */
        CHECK(smooth < 0.02, "no holes: neighbouring pixels differ by under 2 %");
    }
    test_hole_centres(h, &scene, &octree);
    if (rendered)
        gb_image_free(&whole);
    gb_image_free(&holed);
    free(h);
    gb_scene_free(&scene);
}

/* ---- 4. through the atlas ------------------------------------------------ */

/* The floor laid flat in an atlas by hand: texel (x, z) of a square of
 * ATLAS_SQUARE texels per chart, 2 texels of padding. With one chart both
 * triangles share the square; with two, each triangle has a square of its
 * own, side by side, so that the quad's diagonal is a seam between charts.
 * The octree rendered into it and shown through it (octree_atlas.h) must
 * give the walk's image, the seam included. */
#define ATLAS_SQUARE 252
#define ATLAS_PADDING 2

typedef struct floor_atlas {
    gb_atlas atlas;
    float uvs[2 * 6];
    uint32_t charts[2];
    gb_atlas_chart records[2];
} floor_atlas;

/* Whether (x, z) -> (u, v) keeps the floor's triangles counterclockwise;
 * otherwise (z, x) -> (u, v) does. */
static int keeps_winding(const gb_scene *scene)
{
    const float *p[3];
    for (int c = 0; c < 3; ++c)
        p[c] = scene->positions + 3 * scene->indices[c];
    return (p[1][0] - p[0][0]) * (p[2][2] - p[0][2]) - (p[1][2] - p[0][2]) * (p[2][0] - p[0][0]) >
           0.0f;
}

static void make_floor_atlas(const gb_scene *scene, int chart_count, floor_atlas *a)
{
    const uint32_t side = ATLAS_SQUARE + 2 * ATLAS_PADDING;
    int straight = keeps_winding(scene);
    memset(a, 0, sizeof *a);
    for (uint32_t t = 0; t < 2; ++t) {
        uint32_t chart = chart_count == 1 ? 0 : t;
        a->charts[t] = chart;
        for (int c = 0; c < 3; ++c) {
            const float *p = scene->positions + 3 * scene->indices[3 * t + c];
            float s = (p[straight ? 0 : 2] + FLOOR_HALF) / (2.0f * FLOOR_HALF);
            float r = (p[straight ? 2 : 0] + FLOOR_HALF) / (2.0f * FLOOR_HALF);
            a->uvs[6 * t + 2 * c] =
                (float)(chart * side + ATLAS_PADDING + s * ATLAS_SQUARE) / (chart_count * side);
            a->uvs[6 * t + 2 * c + 1] = (float)(ATLAS_PADDING + r * ATLAS_SQUARE) / side;
        }
    }
    for (int chart = 0; chart < chart_count; ++chart)
        a->records[chart] = (gb_atlas_chart){
            chart_count == 1 ? 2 : 1, 0.0f, 0.0f, 0.0f,
            {chart * side + ATLAS_PADDING, ATLAS_PADDING, ATLAS_SQUARE, ATLAS_SQUARE}};
    a->atlas.header = (gb_atlas_header){
        .scene_hash = scene->hash, .triangle_count = 2, .chart_count = (uint32_t)chart_count,
        .width = (uint32_t)chart_count * side, .height = side,
        .texels_per_unit = ATLAS_SQUARE / (2.0f * FLOOR_HALF), .padding = ATLAS_PADDING};
    a->atlas.uvs = a->uvs;
    a->atlas.charts = a->charts;
    a->atlas.chart_records = a->records;
}

/* The largest relative difference between two images of the floor. */
static double largest_difference(const gb_image *a, const gb_image *b)
{
    double worst = 0.0;
    for (int y = 0; y < a->height; ++y)
        for (int x = 0; x < a->width; ++x) {
            double p = pixel(a, x, y), q = pixel(b, x, y);
            worst = fmax(worst, fabs(p - q) / fmax(fmin(p, q), 1e-30));
        }
    return worst;
}

/* The octree through the floor's atlas of chart_count charts against the
 * walk (the image `walk`): the largest relative pixel difference, or -1. */
static double atlas_against_walk(const gb_scene *scene, const gb_light_octree *octree,
                                 int chart_count, const gb_image *walk)
{
    floor_atlas a;
    make_floor_atlas(scene, chart_count, &a);
    char folder[1024], path[1100];
    gb_error error;
    gb_image image;
    double worst = -1.0;
    if (!make_folder(folder, sizeof folder))
        return worst;
    snprintf(path, sizeof path, "%s/floor.atlas", folder);
    if (gb_atlas_write(path, &a.atlas, &error) != GB_OK)
        printf("# %s\n", error.message);
    else if (render_octree_through(scene, octree, path, IMAGE_SIZE, &image)) {
        worst = all_finite(&image) ? largest_difference(&image, walk) : INFINITY;
        gb_image_free(&image);
    }
    unlink(path);
    rmdir(folder);
    return worst;
}

/* Tolerances. The hand-made octree without holes is linear across the
 * floor, and so are the walk's trilinear interpolation and the atlas's
 * bilinear one: the two agree to float rounding (measured: 3.5e-7). At a chart
 * border, the gutter's first ring holds the value at the chart's nearest
 * point, the field held constant across the border rather than extended
 * linearly: a bilinear read there weighs such a texel by at most 1/2 and
 * it is off by the gradient over at most 0.71 texel, 0.05 x E0 per leaf of
 * 0.25 over texels of 4 / 252: 0.11 % (measured: 0.041 %; with the ring the
 * mean of its neighbours instead, 0.22 %). */
#define ATLAS_TOLERANCE 1e-5
#define SEAM_TOLERANCE 0.0015

static void test_atlas(void)
{
    gb_scene scene;
    build_sunlit_floor(&scene);
    hand_octree *h = calloc(1, sizeof *h);
    gb_light_octree octree;
    gb_image walk;
    if (!h)
        return;
    make_octree(h, &scene, &octree);
    if (CHECK(render_octree(&scene, &octree, &walk), "atlas: the walk displayed")) {
        double one = atlas_against_walk(&scene, &octree, 1, &walk);
        double two = atlas_against_walk(&scene, &octree, 2, &walk);
        printf("# through the atlas against the walk, largest relative pixel difference: "
               "one chart %.3g, two charts (a seam on the diagonal) %.3g\n", one, two);
        CHECK(one >= 0.0 && one <= ATLAS_TOLERANCE,
              "atlas of one chart: the walk's image within 10^-5");
        CHECK(two >= 0.0 && two <= SEAM_TOLERANCE,
              "atlas of two charts: the walk's image within 0.15 %, the seam included");
        gb_image_free(&walk);
    }
    free(h);
    gb_scene_free(&scene);
}

/* The floor wound to face down, seen from above: the camera sees its back,
 * which the walk lights (it turns the normals toward the viewer) and the
 * atlas holds in its second layer. */
static void test_atlas_back_side(void)
{
    gb_scene scene;
    const float below[3] = {0, -1, 0};
    build_floor_facing(&scene, below);
    hand_octree *h = calloc(1, sizeof *h);
    gb_light_octree octree;
    gb_image walk;
    if (!h)
        return;
    make_octree(h, &scene, &octree);
    if (CHECK(render_octree(&scene, &octree, &walk), "atlas, back side: the walk displayed")) {
        double low, high;
        leaf_range(h, &low, &high);
        double difference = atlas_against_walk(&scene, &octree, 1, &walk);
        printf("# the floor's back seen: the walk shows %.4g at the centre (leaves from "
               "%.4g); through the atlas, largest relative pixel difference %.3g\n",
               pixel(&walk, IMAGE_SIZE / 2, IMAGE_SIZE / 2), low, difference);
        CHECK(pixel(&walk, IMAGE_SIZE / 2, IMAGE_SIZE / 2) >= low * (1.0 - 1e-5),
              "atlas, back side: the walk lights the side seen");
        CHECK(difference >= 0.0 && difference <= ATLAS_TOLERANCE,
              "atlas, back side: the atlas's back layer gives the walk's image within 10^-5");
        gb_image_free(&walk);
    }
    free(h);
    gb_scene_free(&scene);
}

/* ---- 3. VDL direction packing -------------------------------------------- */

static const char decode_shader[] =
#include "tests/unit/test_octree_display_decode.comp.glsl.inc"
    ;

/* n directions: a Fibonacci sphere, then the 6 axes and the octahedron's
 * fold lines (z = 0, x = 0, y = 0 great circles), where the packing is
 * least regular. */
#define FOLD_SAMPLES 4096

static size_t test_directions(float *d, size_t n)
{
    size_t count = 0, sphere = n - 6 - 3 * FOLD_SAMPLES;
    double golden = PI * (3.0 - sqrt(5.0));
    for (size_t i = 0; i < sphere; ++i, ++count) {
        double z = 1.0 - (2.0 * (double)i + 1.0) / (double)sphere;
        double r = sqrt(fmax(0.0, 1.0 - z * z)), phi = golden * (double)i;
        d[3 * count] = (float)(r * cos(phi));
        d[3 * count + 1] = (float)(r * sin(phi));
        d[3 * count + 2] = (float)z;
    }
    for (int axis = 0; axis < 6; ++axis, ++count) {
        d[3 * count] = d[3 * count + 1] = d[3 * count + 2] = 0.0f;
        d[3 * count + axis % 3] = axis < 3 ? 1.0f : -1.0f;
    }
    for (int plane = 0; plane < 3; ++plane)
        for (int i = 0; i < FOLD_SAMPLES; ++i, ++count) {
            double a = 2.0 * PI * (i + 0.37) / FOLD_SAMPLES;
            d[3 * count + plane] = 0.0f;
            d[3 * count + (plane + 1) % 3] = (float)cos(a);
            d[3 * count + (plane + 2) % 3] = (float)sin(a);
        }
    return count;
}

static double angle_degrees(const float a[3], const float b[3])
{
    double ax = a[0], ay = a[1], az = a[2], bx = b[0], by = b[1], bz = b[2];
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    return atan2(sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz) * 180.0 / PI;
}

/* The paper's packing (§4.2.2, Figure 8), for comparison: θ in [0, π] and
 * φ in [0, 2π) on 8 bits each, each rounded to the nearest of 256 levels
 * (θ: 0..π both included; φ: steps of 2π / 256, wrapping). */
static void paper_round_trip(const float v[3], float out[3])
{
    double theta = acos(fmax(-1.0, fmin(1.0, (double)v[2])));
    double phi = atan2((double)v[1], (double)v[0]);
    if (phi < 0.0)
        phi += 2.0 * PI;
    double qt = floor(theta / PI * 255.0 + 0.5), qp = fmod(floor(phi / (2.0 * PI) * 256.0 + 0.5), 256.0);
    theta = qt * PI / 255.0;
    phi = qp * 2.0 * PI / 256.0;
    out[0] = (float)(sin(theta) * cos(phi));
    out[1] = (float)(sin(theta) * sin(phi));
    out[2] = (float)cos(theta);
}

static GLuint compute_program(gb_error *error)
{
    GLuint shader = glCreateShader(GL_COMPUTE_SHADER), program = 0;
    const char *source = decode_shader;
    GLint compiled = 0, linked = 0;
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (compiled) {
        program = glCreateProgram();
        glAttachShader(program, shader);
        glLinkProgram(program);
        glGetProgramiv(program, GL_LINK_STATUS, &linked);
    }
    if (!compiled || !linked) {
        char log[512] = "";
        if (compiled)
            glGetProgramInfoLog(program, sizeof log, NULL, log);
        else
            glGetShaderInfoLog(shader, sizeof log, NULL, log);
        gb_fail(error, GB_ERROR_INVALID, "decode shader: %s", log);
        if (program)
            glDeleteProgram(program);
        program = 0;
    }
    glDeleteShader(shader);
    return program;
}

/* Packs the directions, decodes them with the GLSL of the octree pass. */
static int decode_on_gpu(const uint32_t *packed, size_t n, float *decoded, gb_error *error)
{
    gb_context context;
    memset(&context, 0, sizeof context);
    if (gb_context_create_headless(&context, error) != GB_OK)
        return 0;
    GLuint program = compute_program(error);
    int ok = program != 0;
    if (ok) {
        GLuint buffers[2];
        glCreateBuffers(2, buffers);
        glNamedBufferStorage(buffers[0], (GLsizeiptr)(n * 4), packed, 0);
        glNamedBufferStorage(buffers[1], (GLsizeiptr)(n * 16), NULL, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
        glUseProgram(program);
        glUniform1ui(glGetUniformLocation(program, "count"), (GLuint)n);
        glDispatchCompute((GLuint)((n + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        float *vec4s = malloc(n * 16);
        ok = vec4s != NULL;
        if (ok) {
            glGetNamedBufferSubData(buffers[1], 0, (GLsizeiptr)(n * 16), vec4s);
            for (size_t i = 0; i < n; ++i)
                memcpy(&decoded[3 * i], &vec4s[4 * i], 3 * sizeof(float));
            free(vec4s);
        }
        glDeleteBuffers(2, buffers);
        glDeleteProgram(program);
        ok = ok && gb_gl_check(&context.errors, "decode", error) == GB_OK;
    }
    gb_context_destroy(&context);
    return ok;
}

#define DIRECTIONS (1u << 20)
/* 16 bits per octahedral coordinate: a cell of the square is 1 / 32767
 * wide, its half-diagonal 2.2e-5 of the square's units, ~0.0022° on the
 * sphere at the map's mean scale (√π radians per unit: 4π sr over the area
 * 4 of the square); the precise encoding picks the best of the cell's four
 * corners. Measured: max 0.00246°, mean 0.00121° (the paper's 8 + 8 bit
 * (θ, φ): max 0.78°, mean 0.35°). */
#define PACKING_MAX_DEGREES 0.003
#define PACKING_MEAN_DEGREES 0.0015

static void test_direction_packing(void)
{
    float *d = malloc(DIRECTIONS * 3 * sizeof *d), *gpu = malloc(DIRECTIONS * 3 * sizeof *gpu);
    uint32_t *packed = malloc(DIRECTIONS * sizeof *packed);
    if (!d || !gpu || !packed) {
        free(d), free(gpu), free(packed);
        CHECK(0, "packing: memory for the directions");
        return;
    }
    size_t n = test_directions(d, DIRECTIONS);
    for (size_t i = 0; i < n; ++i)
        packed[i] = gb_photon_pack_direction(&d[3 * i]);
    gb_error error;
    if (CHECK(decode_on_gpu(packed, n, gpu, &error), "packing: decoded by the shader's GLSL")) {
        double max_gpu = 0, sum_gpu = 0, max_cpu = 0, max_paper = 0, sum_paper = 0, cpu_gpu = 0;
        for (size_t i = 0; i < n; ++i) {
            float cpu[3], paper[3];
            gb_photon_unpack_direction(packed[i], cpu);
            paper_round_trip(&d[3 * i], paper);
            double e = angle_degrees(&d[3 * i], &gpu[3 * i]);
            max_gpu = fmax(max_gpu, e);
            sum_gpu += e;
            max_cpu = fmax(max_cpu, angle_degrees(&d[3 * i], cpu));
            cpu_gpu = fmax(cpu_gpu, angle_degrees(cpu, &gpu[3 * i]));
            double p = angle_degrees(&d[3 * i], paper);
            max_paper = fmax(max_paper, p);
            sum_paper += p;
        }
        printf("# %zu directions, octahedral 2 x 16 bits decoded on the GPU: max %.5f deg, "
               "mean %.5f deg (CPU decode max %.5f deg; CPU vs GPU %.5f deg); "
               "the paper's 8 + 8 bit (theta, phi): max %.3f deg, mean %.3f deg\n",
               n, max_gpu, sum_gpu / (double)n, max_cpu, cpu_gpu, max_paper,
               sum_paper / (double)n);
        CHECK(max_gpu < PACKING_MAX_DEGREES, "packing: largest angular error under 0.003 deg");
        CHECK(sum_gpu / (double)n < PACKING_MEAN_DEGREES,
              "packing: mean angular error under 0.0015 deg");
        CHECK(cpu_gpu < 0.001, "packing: the GLSL decode agrees with the CPU's");
        CHECK(max_paper > 100.0 * max_gpu,
              "packing: over 100 times finer than the paper's 8 + 8 bits");
    } else {
        printf("# %s\n", error.message);
    }
    free(d);
    free(gpu);
    free(packed);
}

int main(void)
{
    test_direction_packing();
    test_holes();
    test_atlas();
    test_atlas_back_side();
    test_sun_over_floor();
    return tap_done();
}
