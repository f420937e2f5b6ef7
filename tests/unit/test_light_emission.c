/* Light leaving the lights (common/light_emission.h) against the analytic
 * distributions: an area light's directions follow cos(theta) / pi and its
 * rays carry pi Ke A; a directional light's rays are parallel to it, start
 * uniformly on a disc behind the scene, and bring E times the scene's
 * projected area into it; a point light's directions are uniform on the
 * sphere; a spot's power is the integral of its falloff; the lights are
 * picked by power. Then the photons tool and the topological method's VPLs
 * start from the very same rays: same seed, same first hit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/topo/topo.h"
#include "../../tools/photons/photons.h"
#include "light_emission.h"
#include "scene_builder.h"
#include "surface.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;
enum { N = 200000, BINS = 10 };
static const double CHI2_9_DOF = 27.9;    /* 0.1 % critical value */

/* ---- helpers ----------------------------------------------------------- */

typedef struct emitted {
    gb_scene scene;
    gb_surface_table surfaces;
    gb_light_emission emission;
} emitted;

static int emission_of(emitted *e, gb_sky_emission sky)
{
    gb_error error;
    scene_done(&e->scene);
    return CHECK(gb_surface_table_build(&e->scene, &e->surfaces, &error) == GB_OK &&
                     gb_light_emission_build(&e->scene, &e->surfaces, sky, &e->emission,
                                             &error) == GB_OK,
                 "emission built");
}

static void emitted_free(emitted *e)
{
    gb_light_emission_free(&e->emission);
    gb_surface_table_free(&e->surfaces);
    gb_scene_free(&e->scene);
}

/* Ray i of a run of N. */
static gb_emitted_ray ray_of(const emitted *e, uint64_t i)
{
    gb_random rng = gb_random_make(3, i);
    gb_emitted_ray ray;
    gb_light_emission_sample(&e->emission, N, &rng, &ray);
    return ray;
}

/* Chi-square of counts in BINS bins against equal expectation. */
static double chi_square(const long bins[BINS], long total)
{
    double expected = (double)total / BINS, chi2 = 0.0;
    for (int b = 0; b < BINS; ++b)
        chi2 += (bins[b] - expected) * (bins[b] - expected) / expected;
    return chi2;
}

static const float UNIT_LO[3] = {0, 0, 0}, UNIT_HI[3] = {1, 1, 1};

/* ---- area light -------------------------------------------------------- */

/* A 2 x 2 square at y = 0 facing +y, Ke 2: pi Ke A = 8 pi. cos(theta) / pi
 * has mean cos 2/3 and cos^2 uniform in [0, 1]. */
static void test_area(void)
{
    emitted e = {0};
    const float square[4][3] = {{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}};
    add_quad(&e.scene, square, add_grey(&e.scene, 0.5f, 2.0f));
    if (!emission_of(&e, GB_SKY_EMITTED))
        return;
    double power = 0.0, cos_sum = 0.0;
    long bins[BINS] = {0};
    int on_square = 1, unit = 1;
    for (uint64_t i = 0; i < N; ++i) {
        gb_emitted_ray r = ray_of(&e, i);
        power += r.power.x;
        cos_sum += r.direction.y;
        bins[(int)fminf(r.direction.y * r.direction.y * BINS, BINS - 1)]++;
        on_square &= r.origin.x >= 0.0f && r.origin.x <= 2.0f && r.origin.z >= 0.0f &&
                     r.origin.z <= 2.0f && fabsf(r.origin.y) < 1e-3f && r.direction.y >= 0.0f;
        unit &= fabsf(gb_vec3_length(r.direction) - 1.0f) < 1e-6f;
    }
    CHECK(on_square, "area: rays leave the square, on its front side");
    CHECK(unit, "area: unit directions");
    CHECK_NEAR(power, 8.0 * PI, 1e-4 * 8.0 * PI, "area: rays carry pi Ke A");
    CHECK_NEAR(cos_sum / N, 2.0 / 3.0, 0.003, "area: mean cos(theta) 2/3 (cos / pi)");
    CHECK(chi_square(bins, N) < CHI2_9_DOF, "area: cos^2(theta) uniform (chi-square, 10 bins)");
    emitted_free(&e);
}

/* ---- directional light --------------------------------------------------- */

/* Entry parameter of the ray into the unit cube (slab test), or -1. */
static float cube_entry(gb_vec3 o, gb_vec3 d)
{
    float enter = -INFINITY, leave = INFINITY;
    const float oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; ++k) {
        float t0 = (0.0f - oo[k]) / dd[k], t1 = (1.0f - oo[k]) / dd[k];
        enter = fmaxf(enter, fminf(t0, t1));
        leave = fminf(leave, fmaxf(t0, t1));
    }
    return enter <= leave ? enter : -1.0f;
}

/* The unit cube lit by E = 3 along unit d: every ray along d, from a disc of
 * radius R (the bounding sphere's) 2R behind the centre, uniform on it
 * (mean rho^2 = R^2 / 2), power E pi R^2; the rays that enter the cube
 * bring E (|dx| + |dy| + |dz|), the cube's projected area along d: the disc
 * covers the whole projection. */
static void test_directional(void)
{
    emitted e = {0};
    add_box(&e.scene, UNIT_LO, UNIT_HI, 0, add_grey(&e.scene, 0.5f, 0.0f));
    const float d[3] = {1.0f, -2.0f, 0.5f}, E[3] = {3, 3, 3};
    gb_vec3 axis = gb_vec3_normalize(gb_vec3_load(d));
    float unit_d[3];
    gb_vec3_store(axis, unit_d);
    add_point_light(&e.scene, GB_LIGHT_DIRECTIONAL, NULL, unit_d, E);
    if (!emission_of(&e, GB_SKY_EMITTED))
        return;
    const double R = sqrt(3.0) / 2.0;
    gb_vec3 c = gb_vec3_make(0.5f, 0.5f, 0.5f);
    double power = 0.0, entering = 0.0, rho2 = 0.0;
    int parallel = 1, behind = 1, on_disc = 1, outside = 1;
    for (uint64_t i = 0; i < N; ++i) {
        gb_emitted_ray r = ray_of(&e, i);
        gb_vec3 offset = gb_vec3_sub(r.origin, c);
        float along = gb_vec3_dot(offset, axis);
        float across2 = gb_vec3_dot(offset, offset) - along * along;
        parallel &= gb_vec3_dot(r.direction, axis) > 1.0f - 1e-6f;
        behind &= fabs(along + 2.0 * R) < 1e-5;
        on_disc &= across2 <= R * R * (1.0 + 1e-5);
        rho2 += across2 / (R * R);
        power += r.power.x;
        float t = cube_entry(r.origin, r.direction);
        if (t != -1.0f) {
            outside &= t > 0.0f;
            entering += r.power.x;
        }
    }
    CHECK(parallel, "directional: every ray along the light");
    CHECK(behind, "directional: from the plane 2R behind the centre");
    CHECK(on_disc, "directional: within R of the axis through the centre");
    CHECK_NEAR(rho2 / N, 0.5, 0.005, "directional: uniform on the disc (mean rho^2 = R^2 / 2)");
    CHECK(outside, "directional: every ray starts outside the scene");
    CHECK_NEAR(power, 3.0 * PI * R * R, 1e-4 * power, "directional: power E pi R^2");
    double projected = fabs(axis.x) + fabs(axis.y) + fabs(axis.z);
    CHECK_NEAR(entering / (3.0 * projected), 1.0, 0.01,
               "directional: the cube receives E times its projected area (the disc covers it)");
    emitted_free(&e);
}

/* ---- point and spot lights ----------------------------------------------- */

/* A point light of intensity 2 in the cube: power 4 pi I, directions
 * uniform on the sphere (mean 0, z uniform in [-1, 1]). */
static void test_point(void)
{
    emitted e = {0};
    add_box(&e.scene, UNIT_LO, UNIT_HI, 1, add_grey(&e.scene, 0.5f, 0.0f));
    const float p[3] = {0.5f, 0.5f, 0.5f}, I[3] = {2, 2, 2};
    add_point_light(&e.scene, GB_LIGHT_POINT, p, NULL, I);
    if (!emission_of(&e, GB_SKY_EMITTED))
        return;
    double power = 0.0, mean[3] = {0, 0, 0};
    long bins[BINS] = {0};
    int from_light = 1;
    for (uint64_t i = 0; i < N; ++i) {
        gb_emitted_ray r = ray_of(&e, i);
        power += r.power.x;
        mean[0] += r.direction.x, mean[1] += r.direction.y, mean[2] += r.direction.z;
        bins[(int)fminf((r.direction.z + 1.0f) * 0.5f * BINS, BINS - 1)]++;
        from_light &= gb_vec3_length(gb_vec3_sub(r.origin, gb_vec3_load(p))) == 0.0f;
    }
    CHECK(from_light, "point: rays leave the light's position");
    CHECK_NEAR(power, 8.0 * PI, 1e-4 * 8.0 * PI, "point: power 4 pi I");
    CHECK(fabs(mean[0]) / N < 0.005 && fabs(mean[1]) / N < 0.005 && fabs(mean[2]) / N < 0.005,
          "point: mean direction 0");
    CHECK(chi_square(bins, N) < CHI2_9_DOF, "point: z uniform in [-1, 1] (chi-square, 10 bins)");
    emitted_free(&e);
}

/* A spot down -y, cone 40, falloff 25, I = 1: every direction in the cone,
 * power 2 pi I ((1 - cos 25) + (cos 25 - cos 40) / 2). */
static void test_spot(void)
{
    emitted e = {0};
    add_box(&e.scene, UNIT_LO, UNIT_HI, 1, add_grey(&e.scene, 0.5f, 0.0f));
    const float p[3] = {0.5f, 0.9f, 0.5f}, down[3] = {0, -1, 0}, I[3] = {1, 1, 1};
    add_point_light(&e.scene, GB_LIGHT_SPOT, p, down, I);
    e.scene.lights[0].cone_angle = 40.0f;
    e.scene.lights[0].falloff_angle = 25.0f;
    if (!emission_of(&e, GB_SKY_EMITTED))
        return;
    double power = 0.0, cos_cone = cos(40.0 * PI / 180.0), cos_falloff = cos(25.0 * PI / 180.0);
    int in_cone = 1;
    for (uint64_t i = 0; i < N; ++i) {
        gb_emitted_ray r = ray_of(&e, i);
        power += r.power.x;
        in_cone &= -r.direction.y >= cos_cone - 1e-6;
    }
    double expected = 2.0 * PI * ((1.0 - cos_falloff) + 0.5 * (cos_falloff - cos_cone));
    CHECK(in_cone, "spot: every direction in the cone");
    CHECK_NEAR(power / expected, 1.0, 0.005, "spot: rays carry the integral of the falloff");
    CHECK_NEAR(e.emission.power[0] / expected, 1.0, 1e-6,
               "spot: weighed (picked) by the integral of the falloff");
    emitted_free(&e);
}

/* ---- picking and the sky --------------------------------------------------- */

/* A point light (power 4 pi) and a sky of L = 0.1 (power 4 pi L pi R^2)
 * around the cube: each picked in proportion to its power; with the sky
 * as lights, only the point light emits. */
static void test_picking_and_sky(void)
{
    emitted e = {0};
    add_box(&e.scene, UNIT_LO, UNIT_HI, 0, add_grey(&e.scene, 0.5f, 0.0f));
    const float p[3] = {0.5f, 2.0f, 0.5f}, I[3] = {1, 1, 1};
    add_point_light(&e.scene, GB_LIGHT_POINT, p, NULL, I);
    for (int k = 0; k < 3; ++k)
        e.scene.environment[k] = 0.1f;
    if (!emission_of(&e, GB_SKY_EMITTED))
        return;
    const double R = sqrt(3.0) / 2.0, sky = 4.0 * PI * 0.1 * PI * R * R;
    double share = 4.0 * PI / (4.0 * PI + sky), worst = 0.0;
    long from_point = 0;
    for (uint64_t i = 0; i < N; ++i) {
        gb_emitted_ray r = ray_of(&e, i);
        if (gb_vec3_length(gb_vec3_sub(r.origin, gb_vec3_load(p))) == 0.0f)
            ++from_point;
        else    /* a sky ray: its power over its pick probability and N */
            worst = fmax(worst, fabs(r.power.x * (1.0 - share) * N / sky - 1.0));
    }
    CHECK_NEAR((double)from_point / N, share, 3.0 * sqrt(share * (1.0 - share) / N),
               "pick: the point light by its share of the power");
    CHECK(worst < 1e-4, "sky: each ray 4 pi L pi R^2 over its probability and N");
    gb_light_emission_free(&e.emission);
    gb_error error;
    CHECK(gb_light_emission_build(&e.scene, &e.surfaces, GB_SKY_AS_LIGHTS, &e.emission,
                                  &error) == GB_OK &&
              e.emission.emitter_count == 1 && e.emission.emitters[0].type == GB_EMITTER_POINT,
          "sky as lights: not emitted itself");
    emitted_free(&e);
}

/* ---- the two users --------------------------------------------------------- */

/* The Cornell box with a point light, a spot and a sun besides its own
 * light: for each seed, photon 0's first hit (photons, one photon, every
 * hit stored) is the first VPL of the topological method (path 0). */
static void test_photons_and_vpls_agree(void)
{
    gb_scene scene = {0};
    build_cornell_box(&scene, 32, 32);
    const float p[3] = {278, 400, 279}, down[3] = {0, -1, 0}, I[3] = {2e5f, 2e5f, 2e5f};
    const float sun[3] = {0.0f, -0.6f, 0.8f}, E[3] = {3, 3, 3};
    add_point_light(&scene, GB_LIGHT_POINT, p, NULL, I);
    add_point_light(&scene, GB_LIGHT_SPOT, p, down, I);
    scene.lights[1].cone_angle = 50.0f;
    scene.lights[1].falloff_angle = 30.0f;
    add_point_light(&scene, GB_LIGHT_DIRECTIONAL, NULL, sun, E);
    scene_done(&scene);
    int compared = 0, same = 1;
    for (uint64_t seed = 1; seed <= 60; ++seed) {
        gb_photons_options options = {.count = 1, .bounces = 1, .store = GB_PHOTON_STORE_ALL,
                                      .seed = seed, .threads = 1};
        gb_photon_map map;
        gb_photons_stats stats;
        gb_vpl_set vpls;
        gb_error error;
        if (gb_photons_trace(&scene, &options, &map, &stats, &error) != GB_OK ||
            gb_topo_vpls_generate(&scene, 1, seed, &vpls, &error) != GB_OK) {
            CHECK(0, error.message);
            break;
        }
        if (map.count > 0 && gb_photon_bounce(map.normals[0]) == 0) {  /* photon 0 hit */
            ++compared;
            same &= memcmp(map.positions, vpls.vpls[0].position, 3 * sizeof(float)) == 0;
        }
        gb_photon_map_free(&map);
        gb_vpl_free(&vpls);
    }
    CHECK(compared >= 30, "photons and VPLs: most first photons hit the box");
    CHECK(same, "photons and VPLs: same seed, same first hit");
    gb_scene_free(&scene);
}

int main(void)
{
    test_area();
    test_directional();
    test_point();
    test_spot();
    test_picking_and_sky();
    test_photons_and_vpls_agree();
    return tap_done();
}
