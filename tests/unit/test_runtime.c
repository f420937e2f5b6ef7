/* test_runtime.c — the runtime's pieces and its headless face on llvmpipe:
 * area-light sampling (deterministic, power kept), the matrices, method
 * names, baked-file checks, and renders of the Cornell box: direct light
 * against the reference renderer (and a render without shadows must miss
 * the same threshold), identical frames twice, resolution and cameras.
 * The Cornell box is found through $GB_ROOT (default "."). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/area_lights.h"
#include "../../runtime/bake.h"
#include "../../runtime/context.h"
#include "../../runtime/headless.h"
#include "../../runtime/mat4.h"
#include "../../runtime/methods.h"
#include "../../runtime/view.h"
#include "camera.h"
#include "headless_render.h"
#include "scene.h"
#include "scratch.h"
#include "tap.h"

/* The relative MSE (tools/imgdiff) of the direct light at 128x128, 16 area
 * samples, 4x4 supersampling, against `reference --mode direct --spp 64`:
 * about 0.0016 (half of it the reference's noise, most of the rest the
 * light's edges); without shadows about 0.026. The threshold sits between. */
#define DIRECT_RELATIVE_MSE_MAX 0.004
enum { SIZE = 128 };

static void test_radical_inverse(void)
{
    CHECK_NEAR(gb_radical_inverse2(0), 0.0, 0, "radical inverse of 0 is 0");
    CHECK_NEAR(gb_radical_inverse2(1), 0.5, 0, "radical inverse of 1 is 1/2");
    CHECK_NEAR(gb_radical_inverse2(6), 0.375, 0, "radical inverse of 6 (110b) is 0.011b");
}

static double emitted_power(const gb_scene *scene, int channel)
{
    double power = 0.0;
    for (uint32_t i = 0; i < scene->emissive_count; ++i) {
        uint32_t t = scene->emissive_triangles[i];
        power += M_PI * scene->materials[scene->triangle_material[t]].Ke[channel] *
                 gb_triangle_area(scene, t);
    }
    return power;
}

static void test_area_light_samples(const gb_scene *scene)
{
    gb_point_emitter *a = NULL, *b = NULL;
    uint32_t na = 0, nb = 0;
    gb_error error;
    CHECK(gb_area_light_sample(scene, 16, &a, &na, &error) == GB_OK, "area lights sampled");
    CHECK(gb_area_light_sample(scene, 16, &b, &nb, &error) == GB_OK, "sampled again");
    CHECK_EQ_INT(na, 16, "16 point emitters");
    CHECK(na == nb && memcmp(a, b, na * sizeof *a) == 0, "deterministic: the same points");
    for (int c = 0; c < 3; ++c) {
        double power = 0.0;
        for (uint32_t i = 0; i < na; ++i)
            power += M_PI * a[i].intensity[c];  /* a Lambertian emitter: pi I0 */
        CHECK_NEAR(power / emitted_power(scene, c), 1.0, 1e-5,
                   "the emitters' power is the area lights' power");
    }
    int inside = 1;
    for (uint32_t i = 0; i < na; ++i)
        for (int c = 0; c < 3; ++c)
            inside &= a[i].position[c] >= scene->bounds_min[c] &&
                      a[i].position[c] <= scene->bounds_max[c];
    CHECK(inside, "the emitters lie in the scene");
    CHECK(a[0].normal[1] < -0.99f, "the Cornell light emits downward");
    free(a);
    free(b);
    CHECK(gb_area_light_sample(scene, 0, &a, &na, &error) == GB_OK && na == 0 && !a,
          "0 samples: no emitter");
}

static void test_matrices(void)
{
    gb_mat4 p = gb_mat4_perspective_infinite(90.0f, 2.0f, 0.5f);
    gb_vec3 near = gb_mat4_transform_point(&p, gb_vec3_make(0, 0, -0.5f));
    gb_vec3 far = gb_mat4_transform_point(&p, gb_vec3_make(0, 0, -1e6f));
    CHECK_NEAR(near.z, 1.0, 1e-6, "reversed depth: 1 on the near plane");
    CHECK(far.z > 0.0f && far.z < 1e-6f, "reversed depth: toward 0 far away");
    gb_vec3 corner = gb_mat4_transform_point(&p, gb_vec3_make(2, 1, -1));
    CHECK_NEAR(corner.x, 1.0, 1e-6, "aspect 2: x at tan(45) x 2 is the right edge");
    CHECK_NEAR(corner.y, 1.0, 1e-6, "fov 90: y at tan(45) is the top edge");
    gb_mat4 o = gb_mat4_orthographic(-1, 1, -2, 2, 1, 3);
    CHECK_NEAR(gb_mat4_transform_point(&o, gb_vec3_make(0, 0, -1)).z, 1.0, 1e-6,
               "orthographic: depth 1 on the near plane");
    CHECK_NEAR(gb_mat4_transform_point(&o, gb_vec3_make(0, 0, -3)).z, 0.0, 1e-6,
               "orthographic: depth 0 on the far plane");
    gb_vec3 position = {1, 2, 3}, forward = {0, 0, -1}, right = {1, 0, 0}, up = {0, 1, 0};
    gb_mat4 view = gb_mat4_view(position, forward, right, up);
    gb_mat4 inverse = gb_mat4_view_inverse(position, forward, right, up);
    gb_mat4 product = gb_mat4_multiply(&inverse, &view);
    double most = 0.0;
    gb_mat4 identity = gb_mat4_identity();
    for (int i = 0; i < 16; ++i)
        most = fmax(most, fabs(product.m[i] - identity.m[i]));
    CHECK_NEAR(most, 0.0, 1e-6, "the view times its inverse is the identity");
}

/* The runtime's view and projection put the point a reference ray reaches
 * on the pixel that ray went through: both take common/camera.h's frame.
 * Cameras with a non-unit, tilted up vector, wide and tall images. */
static void test_camera_projection(void)
{
    const gb_camera cameras[] = {
        {{278, 273, -800}, {278, 273, 0}, {0, 1, 0}, 39.3f, 512, 512},
        {{-1.69f, 1.27f, 5.89f}, {-1.54f, 1.30f, 4.90f}, {-0.01f, 2.0f, 0.06f}, 36.0f, 640, 360},
        {{0.03f, 1.5f, 4.9f}, {0.02f, 1.6f, 3.9f}, {0.3f, 0.9f, 0.05f}, 70.0f, 90, 160},
    };
    double worst = 0.0;
    for (size_t c = 0; c < sizeof cameras / sizeof *cameras; ++c) {
        const gb_camera *camera = &cameras[c];
        gb_camera_frame frame;
        gb_view view;
        gb_error error;
        if (gb_camera_frame_make(camera, camera->width, camera->height, &frame, &error) ||
            gb_view_from_camera(camera, 10.0f, &view, &error)) {
            CHECK(0, error.message);
            return;
        }
        gb_mat4 world_to_view = gb_view_matrix(&view);
        gb_mat4 projection = gb_view_projection(&view, camera->width, camera->height);
        gb_mat4 world_to_clip = gb_mat4_multiply(&projection, &world_to_view);
        for (int j = 0; j <= 8; ++j)
            for (int i = 0; i <= 8; ++i) {
                float x = camera->width * (i + 0.5f) / 9.0f, y = camera->height * (j + 0.5f) / 9.0f;
                gb_vec3 d = gb_camera_direction(&frame, x, y);
                gb_vec3 p = gb_vec3_add(frame.position, gb_vec3_scale(d, 3.0f + (float)i));
                gb_vec3 ndc = gb_mat4_transform_point(&world_to_clip, p);
                double px = 0.5 * (ndc.x + 1.0) * camera->width;
                double py = 0.5 * (1.0 - ndc.y) * camera->height;
                worst = fmax(worst, fmax(fabs(px - x), fabs(py - y)));
            }
    }
    printf("# camera: largest distance from a reference ray's pixel to its projection: %g "
           "pixels\n", worst);
    CHECK(worst < 0.05, "the runtime projects each reference ray's point onto its pixel");
}

static void test_methods(void)
{
    gb_method method;
    gb_error error;
    CHECK(gb_method_parse("direct", &method, &error) == GB_OK && method == GB_METHOD_DIRECT,
          "method direct parses");
    CHECK(gb_method_parse("flc", &method, &error) == GB_OK && method == GB_METHOD_FLC,
          "method flc parses");
    CHECK(gb_method_parse("radiosity", &method, &error) == GB_ERROR_ARGUMENT &&
              strstr(error.message, "radiosity"), "an unknown method is refused by name");
    CHECK(gb_method_check(GB_METHOD_DIRECT, &error) == GB_OK, "direct is available");
    gb_method missing = GB_METHOD_COUNT;
    for (int m = GB_METHOD_COUNT - 1; m > GB_METHOD_DIRECT; --m)
        if (!gb_method_implemented((gb_method)m))
            missing = (gb_method)m;
    if (missing == GB_METHOD_COUNT)
        CHECK(gb_method_check(GB_METHOD_IMPLICIT, &error) == GB_OK, "every method is available");
    else
        CHECK(gb_method_check(missing, &error) == GB_ERROR_UNSUPPORTED &&
                  strstr(error.message, "available: direct"),
              "an unavailable method names those that are");
}

static void test_gl_errors(void)
{
    gb_context context;
    gb_error error;
    if (!CHECK(gb_context_create_headless(&context, &error) == GB_OK,
               "an OpenGL 4.5 core context, headless")) {
        printf("# %s\n", error.message);
        return;
    }
    CHECK(gb_gl_check(&context.errors, "setup", &error) == GB_OK, "no GL error at first");
    glEnable(0xdead);
    CHECK(gb_gl_check(&context.errors, "a bad call", &error) == GB_ERROR_INVALID &&
              strstr(error.message, "a bad call") && strstr(error.message, "INVALID_ENUM"),
          "a GL error is collected and reported where it was checked");
    CHECK(gb_gl_check(&context.errors, "after", &error) == GB_OK, "and then cleared");
    gb_context_destroy(&context);
}

static void test_bake_open(const gb_scene *scene)
{
    scratch_create("runtime");
    scratch_write_text(scratch_path("cornell.skel"), "not a skeleton at all");
    scratch_write_text(scratch_path("cornell.seg"), "");
    gb_bake *bake = NULL;
    gb_error error;
    CHECK(gb_bake_open(scene, "scenes/cornell/cornell.scene", scratch_folder, &bake,
                       &error) == GB_OK && bake,
          "opening a bake folder never fails on its files");
    if (bake) {
        const char *skel_problem = gb_bake_problem(bake, GB_BAKE_SKELETON);
        const char *voxels_problem = gb_bake_problem(bake, GB_BAKE_VOXELS);
        CHECK(skel_problem && strstr(skel_problem, "cornell.skel") && !gb_bake_skeleton(bake),
              "a corrupt .skel is reported by path and skipped");
        CHECK(gb_bake_problem(bake, GB_BAKE_SEGMENTS) && !gb_bake_segmentation(bake),
              "an empty .seg is reported and skipped");
        CHECK(voxels_problem && strstr(voxels_problem, "cornell.vdb") && !gb_bake_voxels(bake),
              "a missing .vdb is reported");
        const gb_voxel_grid *frame = (const gb_voxel_grid *)1;
        CHECK(!gb_bake_nearest_node(bake, &frame) && !frame && !gb_bake_light_octree(bake),
              "a missing .grid.vdb and .lot give no data");
        CHECK(strcmp(gb_bake_extension(GB_BAKE_NEAREST_NODE), ".grid.vdb") == 0 &&
                  strstr(gb_bake_path(bake, GB_BAKE_LIGHT_OCTREE), "/cornell.lot"),
              "each file is found by the scene's name and its kind's extension");
    }
    gb_bake_release(bake);
    gb_bake_release(NULL);
    scratch_remove();
}

static int render(const gb_scene *scene, uint32_t camera, int width, int height,
                  int no_shadows, int supersample, gb_image *image)
{
    gb_headless_options options = {
        .renderer = {.width = width, .height = height, .no_shadows = no_shadows},
        .camera = camera,
        .supersample = supersample,
    };
    return render_headless(scene, &options, image);
}

static void test_against_reference(const gb_scene *scene)
{
    gb_reference_options options = {
        .mode = GB_REFERENCE_DIRECT, .spp = 64, .width = SIZE, .height = SIZE,
    };
    gb_image reference, frame, unshadowed;
    if (!CHECK(render_reference(scene, &options, &reference), "reference --mode direct renders"))
        return;
    if (!CHECK(render(scene, 0, SIZE, SIZE, 0, 4, &frame), "supersampled 4x4")) {
        gb_image_free(&reference);
        return;
    }
    double shadowed = relative_mse(&frame, &reference);
    gb_image_free(&frame);
    printf("# relative MSE to the reference: %.6g (threshold %g)\n", shadowed,
           DIRECT_RELATIVE_MSE_MAX);
    CHECK(shadowed < DIRECT_RELATIVE_MSE_MAX,
          "direct light is within the threshold of the reference");
    if (render(scene, 0, SIZE, SIZE, 1, 4, &unshadowed)) {
        double without = relative_mse(&unshadowed, &reference);
        printf("# without shadows: %.6g\n", without);
        CHECK(without > DIRECT_RELATIVE_MSE_MAX, "without shadows it misses the threshold");
        gb_image_free(&unshadowed);
    }
    gb_image_free(&reference);
}

static int same_pixels(const gb_image *a, const gb_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->pixels, b->pixels, (size_t)a->width * a->height * a->channels *
                  sizeof(float)) == 0;
}

/* A second camera: the first one moved. */
static int add_camera(gb_scene *scene)
{
    gb_camera *cameras = realloc(scene->cameras, (scene->camera_count + 1) * sizeof *cameras);
    if (!cameras)
        return 0;
    scene->cameras = cameras;
    cameras[scene->camera_count] = cameras[0];
    cameras[scene->camera_count].position[0] += 150.0f;
    scene->camera_count += 1;
    return 1;
}

static void test_renders(gb_scene *scene)
{
    gb_image first, second, small, other;
    if (!CHECK(render(scene, 0, SIZE, SIZE, 0, 1, &first), "headless render of the Cornell box"))
        return;
    CHECK(first.width == SIZE && first.height == SIZE && first.channels == 3,
          "the image has the asked size, RGB");
    test_against_reference(scene);
    if (CHECK(render(scene, 0, SIZE, SIZE, 0, 1, &second), "rendered again")) {
        CHECK(same_pixels(&first, &second), "rendering twice gives identical pixels");
        gb_image_free(&second);
    }
    if (CHECK(render(scene, 0, 96, 64, 0, 1, &small), "--resolution 96x64")) {
        CHECK(small.width == 96 && small.height == 64, "the frame has the new size");
        gb_image_free(&small);
    }
    gb_image none;
    gb_error error;
    gb_headless_options bad = {.camera = 7};
    CHECK(gb_render_headless(scene, &bad, &none, NULL, &error) == GB_ERROR_ARGUMENT &&
              strstr(error.message, "camera 7"), "a camera the scene lacks is refused");
    if (add_camera(scene) && CHECK(render(scene, 1, SIZE, SIZE, 0, 1, &other), "camera 1")) {
        CHECK(!same_pixels(&first, &other), "another camera, another image");
        gb_image_free(&other);
    }
    gb_image_free(&first);
}

int main(void)
{
    test_radical_inverse();
    test_matrices();
    test_camera_projection();
    test_methods();
    test_gl_errors();
    gb_scene scene;
    if (!load_cornell(&scene)) {
        CHECK(0, "the Cornell box loads (from $GB_ROOT/scenes/cornell)");
        return tap_done();
    }
    test_area_light_samples(&scene);
    test_bake_open(&scene);
    test_renders(&scene);
    gb_scene_free(&scene);
    return tap_done();
}
