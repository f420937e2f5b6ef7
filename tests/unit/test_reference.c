/* The reference renderer against analytic answers: the furnace, point, spot
 * and directional lights and a VPL over a plane, the decomposition of full
 * light transport into direct + indirect1 + further bounces, the 1/sqrt(spp)
 * convergence, and determinism across thread counts. Scenes are built in
 * memory and rendered at a few pixels so that the whole file runs in
 * seconds, also under the sanitizers. */
#include <math.h>
#include <string.h>

#include "camera.h"
#include "../../tools/reference/integrator.h"
#include "light_sampling.h"
#include "../../tools/reference/reference.h"
#include "scene_builder.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* ---- helpers ----------------------------------------------------------- */

typedef struct tracer {
    gb_path_tables tables;
    gb_integrator integrator;
} tracer;

static void tracer_make(tracer *t, const gb_scene *scene, gb_reference_mode mode,
                        const gb_vpl_set *vpls)
{
    gb_error error;
    memset(t, 0, sizeof *t);
    if (gb_path_tables_build(scene, 1, &t->tables, &error) != GB_OK) {
        fprintf(stderr, "tracer: %s\n", error.message);
        exit(2);
    }
    t->integrator = (gb_integrator){.paths = gb_path_tracer_over(scene, &t->tables),
                                    .vpls = vpls, .mode = mode, .max_bounces = 1};
}

static void tracer_free(tracer *t)
{
    gb_path_tables_free(&t->tables);
}

/* Radiance reflected straight up by the plane y = 0 at (x, z). */
static gb_vec3 radiance_from_above(const tracer *t, float x, float z)
{
    gb_path_state state = {.rng = gb_random_make(7, 0)};
    return gb_integrator_radiance(&t->integrator, gb_vec3_make(x, 1.0f, z),
                                  gb_vec3_make(0.0f, -1.0f, 0.0f), &state);
}

static gb_image render(const gb_scene *scene, gb_reference_options options)
{
    gb_image image;
    gb_error error;
    if (gb_reference_render(scene, &options, &image, NULL, &error) != GB_OK) {
        fprintf(stderr, "render: %s\n", error.message);
        exit(2);
    }
    return image;
}

static double image_mean(const gb_image *image)
{
    double sum = 0.0;
    size_t count = (size_t)image->width * image->height * image->channels;
    for (size_t i = 0; i < count; ++i)
        sum += image->pixels[i];
    return sum / (double)count;
}

static double rms_error_to(const gb_image *image, double expected)
{
    double sum = 0.0;
    size_t count = (size_t)image->width * image->height * image->channels;
    for (size_t i = 0; i < count; ++i)
        sum += (image->pixels[i] - expected) * (image->pixels[i] - expected);
    return sqrt(sum / (double)count);
}

/* A large plane y = 0 facing up. */
static void add_floor(gb_scene *scene, uint32_t material)
{
    const float p[4][3] = {{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}};
    const float above[3] = {0, 1, 0};
    add_quad_facing(scene, p, above, material);
}

/* Normalised Phong BRDF at a plane seen from straight above: the mirror
 * direction of wo is the normal, so cos a = cos(theta_i). */
static double brdf_from_above(double kd, double ks, double ns, double cos_i)
{
    return kd / PI + ks * (ns + 2.0) / (2.0 * PI) * pow(cos_i, ns);
}

/* ---- furnace ----------------------------------------------------------- */

/* A closed box of albedo rho whose inside emits Le everywhere. */
static void build_furnace(gb_scene *scene, float rho, float Le, int size)
{
    memset(scene, 0, sizeof *scene);
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    add_box(scene, lo, hi, 1, add_grey(scene, rho, Le));
    const float eye[3] = {0.1f, 0.2f, -0.3f}, target[3] = {0.3f, 0.1f, 1.0f};
    set_camera(scene, eye, target, 90.0f, size, size);
    scene_done(scene);
}

static void test_furnace(void)
{
    gb_scene scene;
    const float rho = 0.5f, Le = 1.0f;
    build_furnace(&scene, rho, Le, 16);
    gb_image image = render(&scene, (gb_reference_options){.spp = 64, .bounces = 1000});
    double expected = Le / (1.0 - rho);
    CHECK_NEAR(image_mean(&image), expected, 0.01 * expected,
               "furnace: rho 0.5, Le 1 converges to Le / (1 - rho) = 2 within 1% "
               "(16x16 pixels, 64 spp, 1000 bounces with roulette)");
    gb_image_free(&image);
    image = render(&scene, (gb_reference_options){.spp = 64, .bounces = 2});
    CHECK_NEAR(image_mean(&image), Le * (1 + rho + rho * rho), 0.01 * 1.75,
               "furnace: 2 bounces give Le (1 + rho + rho^2) within 1%");
    gb_image_free(&image);
    gb_scene_free(&scene);
}

/* RMS error against the exact furnace answer at 1, 4, 16, 64 spp: the slope
 * of log error over log spp is -1/2. */
static void test_convergence_rate(void)
{
    gb_scene scene;
    build_furnace(&scene, 0.5f, 1.0f, 16);
    const int spp[4] = {1, 4, 16, 64};
    double x[4], y[4], mx = 0, my = 0;
    for (int i = 0; i < 4; ++i) {
        gb_image image = render(&scene, (gb_reference_options){.spp = spp[i], .bounces = 1000,
                                                                .seed = 11});
        x[i] = log((double)spp[i]);
        y[i] = log(rms_error_to(&image, 2.0));
        mx += x[i] / 4;
        my += y[i] / 4;
        gb_image_free(&image);
    }
    double sxy = 0, sxx = 0;
    for (int i = 0; i < 4; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    CHECK_NEAR(sxy / sxx, -0.5, 0.1, "furnace: RMS error falls like spp^-1/2 (fitted slope "
               "over 1, 4, 16, 64 spp)");
    gb_scene_free(&scene);
}

/* ---- analytic lights over a plane ------------------------------------------ */

static void build_plane(gb_scene *scene, float kd, float ks, float ns)
{
    memset(scene, 0, sizeof *scene);
    const float Kd[3] = {kd, kd, kd}, Ks[3] = {ks, ks, ks};
    add_floor(scene, add_material(scene, Kd, Ks, ns, NULL));
    const float eye[3] = {0, 6, -6}, target[3] = {0, 0, 0};
    set_camera(scene, eye, target, 20.0f, 32, 32);
}

/* The same plane under a point light, finished. */
static void build_point_lit_plane(gb_scene *scene, float kd, float ks, float ns,
                                  const float position[3], const float intensity[3])
{
    build_plane(scene, kd, ks, ns);
    add_point_light(scene, GB_LIGHT_POINT, position, NULL, intensity);
    scene_done(scene);
}

static const float sample_points[4][2] = {{0, 0}, {1, 0.5f}, {-2, 1}, {3, -3}};

static void test_point_light(void)
{
    gb_scene scene;
    const float position[3] = {0, 2, 0}, intensity[3] = {10, 5, 2};
    build_point_lit_plane(&scene, 0.5f, 0.3f, 10.0f, position, intensity);
    tracer t;
    tracer_make(&t, &scene, GB_REFERENCE_DIRECT, NULL);
    double worst = 0;
    for (int i = 0; i < 4; ++i) {
        double x = sample_points[i][0], z = sample_points[i][1];
        double r2 = x * x + z * z + 4, cos_i = 2 / sqrt(r2);
        double expected = brdf_from_above(0.5, 0.3, 10, cos_i) * 5 * cos_i / r2;
        gb_vec3 L = radiance_from_above(&t, (float)x, (float)z);
        worst = fmax(worst, fabs(L.y - expected) / expected);
        worst = fmax(worst, fabs(L.x / L.y - 2.0) + fabs(L.z / L.y - 0.4));
    }
    CHECK(worst < 1e-4, "point light over a plane: f I cos(theta) / r^2 at 4 points "
          "(diffuse + Phong, coloured intensity), relative error < 1e-4");
    tracer_free(&t);
    gb_scene_free(&scene);
}

/* Exact radiance of the plane under the point light of
 * test_point_light_image, where the ray through image point (x, y) meets it. */
static double plane_under_light(const gb_camera_frame *frame, double x, double y)
{
    gb_vec3 d = gb_camera_direction(frame, (float)x, (float)y);
    gb_vec3 p = gb_vec3_madd(frame->position, d, -frame->position.y / d.y);
    double dx = 0.5 - p.x, dz = 0.5 - p.z, r2 = dx * dx + 9 + dz * dz;
    return 0.6 / PI * 20 * (3 / sqrt(r2)) / r2;
}

/* The same through the camera: each pixel against the exact value averaged
 * over the pixel's square (box filter; 8x8 midpoints). */
static void test_point_light_image(void)
{
    gb_scene scene;
    const float position[3] = {0.5f, 3, 0.5f}, intensity[3] = {20, 20, 20};
    build_point_lit_plane(&scene, 0.6f, 0.0f, 0.0f, position, intensity);
    gb_image image = render(&scene, (gb_reference_options){.mode = GB_REFERENCE_DIRECT,
                                                            .spp = 256});
    gb_camera_frame frame;
    gb_error error;
    gb_camera_frame_make(&scene.cameras[0], 32, 32, &frame, &error);
    double worst = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            double expected = 0;
            for (int i = 0; i < 64; ++i)
                expected += plane_under_light(&frame, x + (i % 8 + 0.5) / 8,
                                              y + (i / 8 + 0.5) / 8) / 64;
            worst = fmax(worst, fabs(image.pixels[3 * (32 * y + x)] - expected) / expected);
        }
    CHECK(worst < 0.01, "point light seen by the camera: every pixel within 1% of "
          "Kd/pi I cos(theta)/r^2 averaged over the pixel (256 spp)");
    gb_image_free(&image);
    gb_scene_free(&scene);
}

static void test_spot_light(void)
{
    gb_scene scene;
    build_plane(&scene, 0.5f, 0.0f, 0.0f);
    const float position[3] = {0, 2, 0}, down[3] = {0, -1, 0}, intensity[3] = {8, 8, 8};
    add_point_light(&scene, GB_LIGHT_SPOT, position, down, intensity);
    scene.lights[0].cone_angle = 40;
    scene.lights[0].falloff_angle = 20;
    scene_done(&scene);
    tracer t;
    tracer_make(&t, &scene, GB_REFERENCE_DIRECT, NULL);
    const double angles[3] = {10, 30, 50};
    double cos_cone = cos(40 * PI / 180), cos_falloff = cos(20 * PI / 180);
    for (int i = 0; i < 3; ++i) {
        double x = 2 * tan(angles[i] * PI / 180), r2 = x * x + 4, cos_i = 2 / sqrt(r2);
        double s = (cos_i - cos_cone) / (cos_falloff - cos_cone);
        s = s <= 0 ? 0 : s >= 1 ? 1 : s * s * (3 - 2 * s);
        double expected = 0.5 / PI * 8 * s * cos_i / r2;
        gb_vec3 L = radiance_from_above(&t, (float)x, 0.0f);
        char what[160];
        snprintf(what, sizeof what, "spot light (cone 40, fall-off from 20 degrees) at %.0f "
                 "degrees: smoothstep fall-off times I cos/r^2", angles[i]);
        CHECK_NEAR(L.x, expected, 1e-4 * fmax(expected, 1e-3), what);
    }
    tracer_free(&t);
    gb_scene_free(&scene);
}

static void test_directional_light_and_shadow(void)
{
    gb_scene scene;
    build_plane(&scene, 0.5f, 0.0f, 0.0f);
    const float direction[3] = {-0.6f, -0.8f, 0}, irradiance[3] = {3, 3, 3};
    add_point_light(&scene, GB_LIGHT_DIRECTIONAL, NULL, direction, irradiance);
    const float blocker[4][3] = {{3.5f, 2, -0.5f}, {3.5f, 2, 0.5f}, {4.5f, 2, 0.5f},
                                 {4.5f, 2, -0.5f}};
    add_quad(&scene, blocker, scene.triangle_material[0]);
    scene_done(&scene);
    tracer t;
    tracer_make(&t, &scene, GB_REFERENCE_DIRECT, NULL);
    gb_vec3 lit = radiance_from_above(&t, -3.0f, 0.0f);
    CHECK_NEAR(lit.x, 0.5 / PI * 3 * 0.8, 1e-5, "directional light: Kd/pi E cos(theta)");
    /* the point (2.5, 0, 0) sees the light through the blocker at height 2 */
    gb_vec3 shadowed = radiance_from_above(&t, 2.5f, 0.0f);
    CHECK(shadowed.x == 0.0f, "directional light: a quad in the way casts a shadow");
    tracer_free(&t);
    gb_scene_free(&scene);
}

static void test_vpl_light(void)
{
    gb_scene scene;
    build_plane(&scene, 0.5f, 0.3f, 10.0f);
    scene_done(&scene);
    gb_vpl vpls[2] = {{{0, 2, 0}, {0, -1, 0}, {6, 3, 1}}, {{1, 1, 1}, {0, 1, 0}, {100, 100, 100}}};
    gb_vpl_set set = {.scene_hash = scene.hash, .count = 2, .vpls = vpls};
    tracer t;
    tracer_make(&t, &scene, GB_REFERENCE_VPL, &set);
    double worst = 0;
    for (int i = 0; i < 4; ++i) {
        double x = sample_points[i][0], z = sample_points[i][1];
        double r2 = x * x + z * z + 4, cos_i = 2 / sqrt(r2);
        double expected = brdf_from_above(0.5, 0.3, 10, cos_i) * 6 * (cos_i / PI) * cos_i / r2;
        gb_vec3 L = radiance_from_above(&t, (float)x, (float)z);
        worst = fmax(worst, fabs(L.x - expected) / expected);
    }
    CHECK(worst < 1e-4, "VPL: f P cos(vpl)/pi cos(theta)/r^2; a VPL facing away adds nothing");
    tracer_free(&t);
    gb_scene_free(&scene);
}

/* ---- decomposition of the Cornell box ------------------------------------ */

/* z-score of the mean of (sum of parts - whole) over pixels: the pixels are
 * independent, so the standard error is the RMS difference / sqrt(pixels). */
static double difference_z(const gb_image *parts[3], const gb_image *whole, double *relative)
{
    size_t count = (size_t)whole->width * whole->height;
    double sum = 0, sum2 = 0, total = 0;
    for (size_t p = 0; p < count; ++p) {
        double d = 0;
        for (int c = 0; c < 3; ++c) {
            double part = 0;
            for (int i = 0; i < 3; ++i)
                part += parts[i]->pixels[3 * p + c];
            d += part - whole->pixels[3 * p + c];
            total += whole->pixels[3 * p + c];
        }
        sum += d;
        sum2 += d * d;
    }
    double mean = sum / count, rms = sqrt(sum2 / count);
    *relative = sum / total;
    return mean / (rms / sqrt((double)count));
}

static void test_cornell_decomposition(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 32, 32);
    gb_reference_options options = {.spp = 64, .seed = 3};
    gb_image full = render(&scene, options);
    options.mode = GB_REFERENCE_DIRECT;
    gb_image direct = render(&scene, options);
    options.mode = GB_REFERENCE_INDIRECT1;
    gb_image indirect1 = render(&scene, options);
    options.mode = GB_REFERENCE_FULL;
    options.min_bounces = 3;
    gb_image further = render(&scene, options);
    options.mode = GB_REFERENCE_INDIRECT1_UNSHADOWED;
    options.min_bounces = 0;
    gb_image unshadowed = render(&scene, options);
    const gb_image *parts[3] = {&direct, &indirect1, &further};
    double relative, z = difference_z(parts, &full, &relative);
    printf("# cornell: direct %.4f indirect1 %.4f further %.4f full %.4f unshadowed %.4f "
           "(means); sum - full: %.3f%%, z = %.2f\n", image_mean(&direct),
           image_mean(&indirect1), image_mean(&further), image_mean(&full),
           image_mean(&unshadowed), 100 * relative, z);
    CHECK(fabs(z) < 4.0, "Cornell box: direct + indirect1 + bounces >= 3 = full within noise "
          "(|z| < 4 over 32x32 pixels, 64 spp)");
    CHECK(fabs(relative) < 0.02, "Cornell box: the parts add up to full within 2%");
    CHECK(image_mean(&indirect1) > 0.15 * image_mean(&direct) &&
              image_mean(&further) > 0.1 * image_mean(&indirect1),
          "Cornell box: indirect1 and further bounces carry light");
    CHECK(image_mean(&unshadowed) > 1.02 * image_mean(&indirect1),
          "Cornell box: ignoring indirect shadows over-estimates the first bounce");
    gb_image *images[5] = {&full, &direct, &indirect1, &further, &unshadowed};
    for (int i = 0; i < 5; ++i)
        gb_image_free(images[i]);
    gb_scene_free(&scene);
}

/* In a convex room, nothing can block a segment between two surfaces:
 * unshadowed and shadowed first bounces are the same estimate. */
static void test_unshadowed_in_convex_room(void)
{
    gb_scene scene = {0};
    const float lo[3] = {-2, -1, -3}, hi[3] = {2, 1.5f, 3};
    add_box(&scene, lo, hi, 1, add_grey(&scene, 0.6f, 0.0f));
    const float position[3] = {0.5f, 1.0f, 1.0f}, intensity[3] = {5, 5, 5};
    add_point_light(&scene, GB_LIGHT_POINT, position, NULL, intensity);
    const float eye[3] = {0, 0, -2.5f}, target[3] = {1, -0.5f, 3};
    set_camera(&scene, eye, target, 70.0f, 12, 12);
    scene_done(&scene);
    gb_reference_options options = {.mode = GB_REFERENCE_INDIRECT1, .spp = 8};
    gb_image shadowed = render(&scene, options);
    options.mode = GB_REFERENCE_INDIRECT1_UNSHADOWED;
    gb_image unshadowed = render(&scene, options);
    double worst = 0;
    for (size_t i = 0; i < 3 * 12 * 12; ++i)
        worst = fmax(worst, fabs(unshadowed.pixels[i] - shadowed.pixels[i]) /
                                fmax(shadowed.pixels[i], 1e-3));
    CHECK(worst < 1e-3, "convex room: indirect1-unshadowed equals indirect1, pixel by pixel");
    gb_image_free(&shadowed);
    gb_image_free(&unshadowed);
    gb_scene_free(&scene);
}

/* ---- determinism, options ----------------------------------------------- */

static void test_determinism(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 40, 24);
    gb_reference_options options = {.spp = 4, .seed = 5, .threads = 1};
    gb_image one = render(&scene, options);
    options.threads = 2;
    gb_image two = render(&scene, options);
    options.threads = 3;
    gb_image three = render(&scene, options);
    options.seed = 6;
    gb_image other = render(&scene, options);
    size_t bytes = sizeof(float) * 3 * 40 * 24;
    CHECK(memcmp(one.pixels, two.pixels, bytes) == 0 &&
              memcmp(one.pixels, three.pixels, bytes) == 0,
          "the same seed gives the same bytes on 1, 2 and 3 threads");
    CHECK(memcmp(one.pixels, other.pixels, bytes) != 0, "another seed gives another image");
    gb_image *images[4] = {&one, &two, &three, &other};
    for (int i = 0; i < 4; ++i)
        gb_image_free(images[i]);
    gb_scene_free(&scene);
}

static gb_result try_render(const gb_scene *scene, gb_reference_options options)
{
    gb_image image;
    gb_error error;
    gb_result result = gb_reference_render(scene, &options, &image, NULL, &error);
    gb_image_free(&image);
    return result;
}

static void test_bad_options(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 8, 8);
    CHECK_EQ_INT(try_render(&scene, (gb_reference_options){.camera = 1}), GB_ERROR_ARGUMENT,
                 "a camera the scene lacks is refused");
    CHECK_EQ_INT(try_render(&scene, (gb_reference_options){.mode = GB_REFERENCE_VPL}),
                 GB_ERROR_ARGUMENT, "vpl mode without VPLs is refused");
    CHECK_EQ_INT(try_render(&scene, (gb_reference_options){.bounces = 2, .min_bounces = 3}),
                 GB_ERROR_ARGUMENT, "min bounces above bounces is refused");
    gb_vpl vpl = {{0, 1, 0}, {0, 1, 0}, {1, 1, 1}};
    gb_vpl_set stale = {.scene_hash = scene.hash + 1, .count = 1, .vpls = &vpl};
    CHECK_EQ_INT(try_render(&scene, (gb_reference_options){.mode = GB_REFERENCE_VPL,
                                                           .vpls = &stale}),
                 GB_ERROR_STALE, "VPLs made from another scene are refused as stale");
    gb_reference_mode mode;
    gb_error error;
    CHECK(gb_reference_mode_parse("indirect1-unshadowed", &mode, &error) == GB_OK &&
              mode == GB_REFERENCE_INDIRECT1_UNSHADOWED &&
              gb_reference_mode_parse("indirect2", &mode, &error) == GB_ERROR_ARGUMENT,
          "mode names parse, unknown ones are refused");
    gb_scene_free(&scene);
}

/* ---- light table ----------------------------------------------------------- */

static void test_light_table(void)
{
    gb_scene scene = {0};
    const float big[4][3] = {{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}};
    const float small[4][3] = {{5, 2, 0}, {6, 2, 0}, {6, 2, 1}, {5, 2, 1}};
    add_quad(&scene, big, add_grey(&scene, 0.5f, 1.0f));   /* power pi * 1 * 4 */
    add_quad(&scene, small, add_grey(&scene, 0.5f, 2.0f)); /* power pi * 2 * 1 */
    const float eye[3] = {0, 0, -5}, target[3] = {0, 0, 0};
    set_camera(&scene, eye, target, 40, 8, 8);
    scene_done(&scene);
    gb_light_table table;
    gb_surface_table surfaces;
    gb_error error;
    gb_light_table_build(&scene, &table, &error);
    gb_surface_table_build(&scene, &surfaces, &error);
    double total = 0;
    for (uint32_t t = 0; t < scene.triangle_count; ++t)
        total += gb_light_table_pdf_area(&table, t) * gb_triangle_area(&scene, t);
    CHECK_NEAR(total, 1.0, 1e-6, "light table: area densities integrate to 1");
    gb_random rng = gb_random_make(1, 1);
    int on_big = 0, inside = 1;
    for (int i = 0; i < 30000; ++i) {
        gb_area_light_sample s;
        float u0 = gb_random_float(&rng), u1 = gb_random_float(&rng), u2 = gb_random_float(&rng);
        gb_light_table_sample(&table, &surfaces, u0, u1, u2, &s);
        on_big += s.position.x <= 2.0f;
        inside &= s.position.y == 2.0f && s.position.z >= 0 && s.position.z <= 2;
    }
    CHECK_NEAR(on_big / 30000.0, 4.0 / 6.0, 0.01, "light table: lights picked by power");
    CHECK(inside, "light table: samples lie on the lights");
    gb_light_table_free(&table);
    gb_surface_table_free(&surfaces);
    gb_scene_free(&scene);
}

int main(void)
{
    test_point_light();
    test_point_light_image();
    test_spot_light();
    test_directional_light_and_shadow();
    test_vpl_light();
    test_light_table();
    test_furnace();
    test_convergence_rate();
    test_cornell_decomposition();
    test_unshadowed_in_convex_room();
    test_determinism();
    test_bad_options();
    return tap_done();
}
