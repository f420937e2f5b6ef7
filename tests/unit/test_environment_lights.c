/* test_environment_lights — the environment as directional lights by
 * median cut (common/environment_lights.h), against the integrals of a
 * constant sky worked out by hand and a map of one bright texel. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "environment_lights.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* Irradiance the lights give a surface of unit normal n: sum E max(0, n.wi). */
static double irradiance(const gb_light *lights, uint32_t count, const double n[3], int c)
{
    double E = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        double cosine = -(n[0] * lights[i].direction[0] + n[1] * lights[i].direction[1] +
                          n[2] * lights[i].direction[2]);
        E += lights[i].intensity[c] * (cosine > 0.0 ? cosine : 0.0);
    }
    return E;
}

/* A constant sky L: the lights' irradiances sum to 4 pi L (the whole
 * sphere), and a surface of any normal receives pi L (its hemisphere). */
static void test_constant_sky(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    float L[3] = {0.5f, 1.0f, 2.0f};
    memcpy(scene.environment, L, sizeof L);
    gb_light lights[GB_MOST_ENVIRONMENT_LIGHTS];
    uint32_t made = 0;
    gb_error error;
    CHECK(gb_environment_lights(&scene, GB_MOST_ENVIRONMENT_LIGHTS, lights, &made, &error) ==
              GB_OK, "constant sky: lights");
    CHECK_EQ_INT(made, GB_MOST_ENVIRONMENT_LIGHTS, "constant sky: as many lights as asked");
    for (int c = 0; c < 3; ++c) {
        double total = 0.0;
        for (uint32_t i = 0; i < made; ++i)
            total += lights[i].intensity[c];
        CHECK_NEAR(total, 4.0 * PI * L[c], 1e-4 * 4.0 * PI * L[c], "constant sky: 4 pi L in all");
    }
    const double normals[][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1},
                                 {0.57735, 0.57735, 0.57735}, {0.6, -0.8, 0}};
    double worst = 0.0;
    for (size_t k = 0; k < sizeof normals / sizeof normals[0]; ++k) {
        double E = irradiance(lights, made, normals[k], 1);
        worst = fmax(worst, fabs(E / (PI * L[1]) - 1.0));
    }
    CHECK_NEAR(worst, 0.0, 0.03, "constant sky: pi L on a surface of any normal, within 3 %");
}

/* A map black but for one texel: one light, toward that texel's centre,
 * carrying its L dOmega. */
static void test_one_bright_texel(void)
{
    enum { W = 16, H = 8 };
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    float *rgb = calloc(W * H * 3, sizeof *rgb);
    int row = 2, column = 11;
    for (int c = 0; c < 3; ++c)
        rgb[3 * (row * W + column) + c] = 100.0f;
    scene.environment_texture = (gb_texture){W, H, rgb};
    gb_light lights[8];
    uint32_t made = 0;
    gb_error error;
    gb_environment_lights(&scene, 8, lights, &made, &error);
    CHECK_EQ_INT(made, 1, "one bright texel: one light");
    /* the texel's centre: azimuth (u - 1/2) 2 pi, polar angle v pi */
    double phi = ((column + 0.5) / W - 0.5) * 2.0 * PI, theta = (row + 0.5) / H * PI;
    double toward[3] = {sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi)};
    double solid_angle = 2.0 * PI / W * (cos(PI * row / H) - cos(PI * (row + 1) / H));
    double cosine = -(toward[0] * lights[0].direction[0] + toward[1] * lights[0].direction[1] +
                      toward[2] * lights[0].direction[2]);
    CHECK_NEAR(cosine, 1.0, 1e-5, "one bright texel: the light comes from it");
    CHECK_NEAR(lights[0].intensity[0], 100.0 * solid_angle, 1e-4 * 100.0 * solid_angle,
               "one bright texel: its L dOmega");
    CHECK(lights[0].type == GB_LIGHT_DIRECTIONAL, "one bright texel: a directional light");
    free(rgb);
}

/* A black sky adds nothing; a lit one is appended after the scene's own
 * lights, which stay, and counted as the environment's. */
static void test_appended(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    gb_error error;
    CHECK(gb_scene_add_environment_lights(&scene, 16, &error) == GB_OK &&
              scene.light_count == 0 && scene.environment_light_count == 0,
          "black sky: no light");
    scene.environment[0] = scene.environment[1] = scene.environment[2] = 1.0f;
    gb_light own = {.type = GB_LIGHT_POINT, .intensity = {7, 7, 7}};
    free(scene.lights);
    scene.lights = malloc(sizeof own);
    scene.lights[0] = own;
    scene.light_count = 1;
    CHECK(gb_scene_add_environment_lights(&scene, 16, &error) == GB_OK, "white sky: appended");
    CHECK_EQ_INT(scene.light_count, 17, "white sky: the scene's light and 16");
    CHECK_EQ_INT(scene.environment_light_count, 16, "white sky: 16 counted as the sky's");
    CHECK(scene.lights[0].type == GB_LIGHT_POINT && scene.lights[0].intensity[0] == 7.0f,
          "white sky: the scene's own light first, unchanged");
    free(scene.lights);
}

/* The sky's share of the power, by hand: a sky of luminance 1 around a
 * scene of bounding radius R = 1 sends 4 pi^2; a directional light of
 * luminance 4 sends 4 pi: a share of pi / (pi + 1). */
static void test_share(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    float half = 1.0f / sqrtf(3.0f);    /* a cube whose diagonal is 2 */
    for (int k = 0; k < 3; ++k)
        scene.bounds_min[k] = -half, scene.bounds_max[k] = half;
    CHECK_NEAR(gb_environment_share(&scene), 0.0, 0.0, "share: a black sky has none");
    scene.environment[0] = scene.environment[1] = scene.environment[2] = 1.0f;
    CHECK_NEAR(gb_environment_share(&scene), 1.0, 1e-9, "share: a sky alone has all");
    CHECK_EQ_INT(gb_environment_light_count(&scene, 64), 64, "count: a sky alone gets the most");
    gb_light sun = {.type = GB_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}, .intensity = {4, 4, 4}};
    scene.lights = &sun;
    scene.light_count = 1;
    CHECK_NEAR(gb_environment_share(&scene), PI / (PI + 1.0), 1e-6, "share: sky against a sun");
    CHECK_EQ_INT(gb_environment_light_count(&scene, 64), (int)ceil(64 * PI / (PI + 1.0)),
                 "count: 64 times the share, rounded up");
}

int main(void)
{
    test_share();
    test_constant_sky();
    test_one_bright_texel();
    test_appended();
    return tap_done();
}
