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

#include "../../runtime/context.h"
#include "../../runtime/octree/octree.h"
#include "../../tools/cluster/cluster.h"
#include "../../tools/photons/photons.h"
#include "floor_octree.h"
#include "photon_map.h"
#include "tap.h"

#define PI 3.14159265358979323846

/* The floor (floor_octree.h), seen from above with a vertical field of
 * view of FLOOR_CAMERA_FOV degrees: x, z within 3 tan(15°) = 0.80 of the
 * centre. */

/* ---- scene and rendering ------------------------------------------------- */

static const float sun_irradiance = 2.0f;
static const float sun_direction[3] = {0.6f, -0.8f, 0.0f};    /* cos θ = 0.8 */

/* The floor wound to face toward (its front side), seen from above, lit
 * by the sun. */
static void build_floor_facing(gb_scene *scene, const float toward[3])
{
    floor_scene_begin(scene, toward);
    const float irradiance[3] = {sun_irradiance, sun_irradiance, sun_irradiance};
    add_point_light(scene, GB_LIGHT_DIRECTIONAL, NULL, sun_direction, irradiance);
    scene_done(scene);
}

static void build_sunlit_floor(gb_scene *scene)
{
    const float above[3] = {0, 1, 0};
    build_floor_facing(scene, above);
}

static int render_octree_at(const gb_scene *scene, const gb_light_octree *octree, int size,
                            gb_image *image)
{
    return floor_octree_render(scene, octree, NULL, size, image);
}

static int render_octree(const gb_scene *scene, const gb_light_octree *octree, gb_image *image)
{
    return render_octree_at(scene, octree, FLOOR_IMAGE_SIZE, image);
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
        double expected = FLOOR_KD / PI * sun_irradiance * cos_theta;
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

/* The hand-made octree (floor_octree.h): every leaf has one VDL straight
 * up, irradiance E0 (1 + GRADIENT_X i + GRADIENT_Z k), except the holes. */
#define E0 1.0f
#define GRADIENT_X 0.05f
#define GRADIENT_Z 0.03f

static float cell_irradiance(uint32_t i, uint32_t k)
{
    return E0 * (1.0f + GRADIENT_X * (float)i + GRADIENT_Z * (float)k);
}

static const float up[3] = {0, 1, 0};

static uint32_t fill_vdl(uint32_t i, uint32_t k, gb_light_octree_vdl *vdl)
{
    float e = cell_irradiance(i, k);
    vdl->irradiance[0] = vdl->irradiance[1] = vdl->irradiance[2] = e;
    vdl->direction = gb_photon_pack_direction(up);
    return 1;
}

static void make_octree(floor_octree *h, const gb_scene *scene, gb_light_octree *octree)
{
    floor_octree_make(h, up, 1, fill_vdl, scene, octree);
}

/* The floor facing toward, the hand-made octree without holes over it, and
 * the walk's image of it (checked as `what`): 1 when there is an image. */
typedef struct walked_floor {
    gb_scene scene;
    floor_octree *h;
    gb_light_octree octree;
    gb_image walk;
} walked_floor;

static int walk_floor(walked_floor *w, const float toward[3], const char *what)
{
    build_floor_facing(&w->scene, toward);
    if (!(w->h = calloc(1, sizeof *w->h)))
        return 0;
    make_octree(w->h, &w->scene, &w->octree);
    return CHECK(render_octree(&w->scene, &w->octree, &w->walk), what);
}

static void walked_floor_free(walked_floor *w, int walked)
{
    if (walked)
        gb_image_free(&w->walk);
    free(w->h);
    gb_scene_free(&w->scene);
}

/* What the display may show on the floor: Kd/pi times the leaves'
 * irradiances, interpolated (a convex combination of them). */
static void leaf_range(const floor_octree *h, double *low, double *high)
{
    *low = INFINITY;
    *high = 0.0;
    for (uint32_t i = 0; i < FLOOR_GRID; ++i)
        for (uint32_t k = 0; k < FLOOR_GRID; ++k)
            if (h->cells[i][k] == CELL_LIT) {
                *low = fmin(*low, FLOOR_KD / PI * cell_irradiance(i, k));
                *high = fmax(*high, FLOOR_KD / PI * cell_irradiance(i, k));
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

/* Straight above the centre of a missing leaf, on an odd image, the middle
 * pixel's ray goes through that centre, where every weight of the 2 x 2
 * windows around but the missing leaf's own vanishes (the trilinear
 * weights there are 1 for it, 0 for the others). */
static void test_hole_centres(const floor_octree *h, gb_scene *scene,
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
    walked_floor w;
    int rendered = walk_floor(&w, up, "whole hand-made octree displayed");
    floor_octree *h = w.h;
    gb_image holed;
    if (!h)
        return;
    floor_octree_punch_holes(h);
    make_octree(h, &w.scene, &w.octree);
    CHECK_EQ_INT(h->leaf_count, FLOOR_GRID * FLOOR_GRID - 2, "holes: two leaves missing");
    CHECK_EQ_INT(h->vdl_count, FLOOR_GRID * FLOOR_GRID - 5, "holes: three leaves without VDLs");
    if (CHECK(render_octree(&w.scene, &w.octree, &holed), "octree with holes displayed") &&
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
        double smooth = largest_jump(&w.walk), jump = largest_jump(&holed);
        int differ = 0;
        for (size_t i = 0; i < (size_t)FLOOR_IMAGE_SIZE * FLOOR_IMAGE_SIZE; ++i)
            differ += holed.pixels[3 * i] != w.walk.pixels[3 * i];
        printf("# leaves Kd/pi E in [%.5g, %.5g]; with holes the floor shows [%.5g, %.5g]; "
               "largest relative jump between neighbours %.4f (no holes %.4f, bound %.2f); "
               "%d of %d pixels changed\n",
               low, high, darkest, brightest, jump, smooth, bound, differ,
               FLOOR_IMAGE_SIZE * FLOOR_IMAGE_SIZE);
        CHECK(all_finite(&holed), "holes: every pixel finite (no NaN, no infinity)");
        CHECK(darkest >= low * (1.0 - 1e-5) && brightest <= high * (1.0 + 1e-5),
              "holes: every pixel within the leaves' range (no black seam)");
        CHECK(jump <= bound, "holes: neighbouring pixels differ by at most 0.16 (relative)");
        CHECK(differ > 0 && differ < FLOOR_IMAGE_SIZE * FLOOR_IMAGE_SIZE / 2,
              "holes: only the pixels near a hole change");
        /* Without holes the field is linear and trilinear interpolation
         * reproduces it: a pixel's jump is the gradient over one pixel. */
        CHECK(smooth < 0.02, "no holes: neighbouring pixels differ by under 2 %");
    }
    test_hole_centres(h, &w.scene, &w.octree);
    gb_image_free(&holed);
    walked_floor_free(&w, rendered);
}

/* ---- 4. through the atlas ------------------------------------------------ */

/* The floor laid flat in an atlas by hand (floor_octree.h's floor_atlas):
 * a square of ATLAS_SQUARE texels per chart, 2 texels of padding, one
 * chart or two (the quad's diagonal a seam between them). The octree
 * rendered into it and shown through it (octree_atlas.h) must give the
 * walk's image, the seam included. */
#define ATLAS_SQUARE 252
#define ATLAS_PADDING 2

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
    floor_atlas_make(scene, ATLAS_SQUARE, ATLAS_PADDING, (uint32_t)chart_count, &a);
    gb_image image;
    double worst = -1.0;
    if (floor_octree_render(scene, octree, &a.atlas, FLOOR_IMAGE_SIZE, &image)) {
        worst = all_finite(&image) ? largest_difference(&image, walk) : INFINITY;
        gb_image_free(&image);
    }
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
    walked_floor w;
    int walked = walk_floor(&w, up, "atlas: the walk displayed");
    if (walked) {
        double one = atlas_against_walk(&w.scene, &w.octree, 1, &w.walk);
        double two = atlas_against_walk(&w.scene, &w.octree, 2, &w.walk);
        printf("# through the atlas against the walk, largest relative pixel difference: "
               "one chart %.3g, two charts (a seam on the diagonal) %.3g\n", one, two);
        CHECK(one >= 0.0 && one <= ATLAS_TOLERANCE,
              "atlas of one chart: the walk's image within 10^-5");
        CHECK(two >= 0.0 && two <= SEAM_TOLERANCE,
              "atlas of two charts: the walk's image within 0.15 %, the seam included");
    }
    walked_floor_free(&w, walked);
}

/* The floor wound to face down, seen from above: the camera sees its back,
 * which the walk lights (it turns the normals toward the viewer) and the
 * atlas holds in its second layer. */
static void test_atlas_back_side(void)
{
    const float below[3] = {0, -1, 0};
    walked_floor w;
    int walked = walk_floor(&w, below, "atlas, back side: the walk displayed");
    if (walked) {
        double low, high;
        leaf_range(w.h, &low, &high);
        double difference = atlas_against_walk(&w.scene, &w.octree, 1, &w.walk);
        double centre = pixel(&w.walk, FLOOR_IMAGE_SIZE / 2, FLOOR_IMAGE_SIZE / 2);
        printf("# the floor's back seen: the walk shows %.4g at the centre (leaves from "
               "%.4g); through the atlas, largest relative pixel difference %.3g\n",
               centre, low, difference);
        CHECK(centre >= low * (1.0 - 1e-5), "atlas, back side: the walk lights the side seen");
        CHECK(difference >= 0.0 && difference <= ATLAS_TOLERANCE,
              "atlas, back side: the atlas's back layer gives the walk's image within 10^-5");
    }
    walked_floor_free(&w, walked);
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
