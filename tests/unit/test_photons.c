/* The photon tracer (tools/photons) and the photon map file
 * (formats/photon_map.[ch]) against analytic answers: energy per bounce in a
 * closed box of albedo rho (also at coordinates of 1e6), the irradiance of
 * point, spot, directional and environment light on a plane, determinism
 * across thread counts, shards merged into the very map of a whole run, and
 * files that are corrupt, inconsistent or stale. Scenes are built in memory
 * and traced with a few thousand photons, so the file runs in seconds, also
 * under the sanitizers. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../../tools/photons/flux_probes.h"
#include "../../tools/photons/photons.h"
#include "container.h"
#include "photon_map.h"
#include "random.h"
#include "scene_builder.h"
#include "scratch.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* ---- helpers ----------------------------------------------------------- */

static gb_photons_options options_for(uint64_t count, unsigned bounces, gb_photon_store store)
{
    gb_photons_options o = {.count = count, .bounces = bounces, .store = store, .seed = 1,
                            .threads = 2};
    return o;
}

static gb_photon_map trace(const gb_scene *scene, const gb_photons_options *options,
                           gb_photons_stats *stats)
{
    gb_photon_map map;
    gb_error error;
    if (gb_photons_trace(scene, options, &map, stats, &error) != GB_OK) {
        fprintf(stderr, "trace: %s\n", error.message);
        exit(2);
    }
    return map;
}

typedef struct bounce_sums {
    double power[GB_PHOTON_MAX_BOUNCES + 1][3];
    uint64_t count[GB_PHOTON_MAX_BOUNCES + 1];
} bounce_sums;

static void sum_by_bounce(const gb_photon_map *map, bounce_sums *sums)
{
    memset(sums, 0, sizeof *sums);
    for (uint64_t i = 0; i < map->count; ++i) {
        unsigned b = gb_photon_bounce(map->normals[i]);
        ++sums->count[b];
        for (int k = 0; k < 3; ++k)
            sums->power[b][k] += map->powers[3 * i + k];
    }
}

static double total_power(const gb_photon_map *map, int channel)
{
    double sum = 0.0;
    for (uint64_t i = 0; i < map->count; ++i)
        sum += map->powers[3 * i + channel];
    return sum;
}

/* sqrt(N p (1 - p)): the standard deviation of a binomial count. */
static double binomial_sigma(double n, double p)
{
    return sqrt(n * p * (1.0 - p));
}

static int same_headers(const gb_photon_map_header *a, const gb_photon_map_header *b)
{
    return a->emitted_count == b->emitted_count && a->first_photon == b->first_photon &&
           a->end_photon == b->end_photon && a->scene_hash == b->scene_hash &&
           a->seed == b->seed && a->shard_index == b->shard_index &&
           a->shard_count == b->shard_count && a->bounces == b->bounces &&
           a->store == b->store && a->roulette_start == b->roulette_start &&
           memcmp(a->emitted_power, b->emitted_power, sizeof a->emitted_power) == 0 &&
           memcmp(a->bounds_min, b->bounds_min, sizeof a->bounds_min) == 0 &&
           memcmp(a->bounds_max, b->bounds_max, sizeof a->bounds_max) == 0;
}

static int same_maps(const gb_photon_map *a, const gb_photon_map *b)
{
    if (a->count != b->count || !same_headers(&a->header, &b->header))
        return 0;
    size_t n = (size_t)a->count;
    return n == 0 || (memcmp(a->positions, b->positions, 12 * n) == 0 &&
                      memcmp(a->powers, b->powers, 12 * n) == 0 &&
                      memcmp(a->directions, b->directions, 4 * n) == 0 &&
                      memcmp(a->normals, b->normals, 4 * n) == 0);
}

static int files_equal(const char *a, const char *b)
{
    size_t size_a = 0, size_b = 0;
    unsigned char *bytes_a = scratch_read(a, &size_a), *bytes_b = scratch_read(b, &size_b);
    int equal = bytes_a && bytes_b && size_a == size_b && memcmp(bytes_a, bytes_b, size_a) == 0;
    free(bytes_a);
    free(bytes_b);
    return equal;
}

/* ---- scenes ------------------------------------------------------------ */

/* The box lo..lo+size seen from inside, every face of albedo rho (colour
 * Kd), its ceiling (y = hi) also emitting Ke: power pi Ke size^2. */
static void build_closed_box(gb_scene *scene, float lo, float size, const float Kd[3],
                             const float Ke[3])
{
    memset(scene, 0, sizeof *scene);
    const float min[3] = {lo, lo, lo}, max[3] = {lo + size, lo + size, lo + size};
    uint32_t wall = add_material(scene, Kd, NULL, 0.0f, NULL);
    uint32_t ceiling = add_material(scene, Kd, NULL, 0.0f, Ke);
    add_box(scene, min, max, 1, wall);
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        int top = 1;
        for (int c = 0; c < 3; ++c)
            top &= scene->positions[3 * scene->indices[3 * t + c] + 1] == max[1];
        if (top)
            scene->triangle_material[t] = ceiling;
    }
    scene_done(scene);
}

/* The black plane y = 0, |x|, |z| <= half. */
static void build_black_plane(gb_scene *scene, float half)
{
    memset(scene, 0, sizeof *scene);
    uint32_t black = add_grey(scene, 0.0f, 0.0f);
    const float p[4][3] = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
    const float above[3] = {0, 1, 0};
    add_quad_facing(scene, p, above, black);
}

/* ---- packing ----------------------------------------------------------- */

/* atan2(|a x b|, a . b): exact near 0, where acos of the dot product is not. */
static double angle_degrees(const float a[3], const float b[3])
{
    double cx = (double)a[1] * b[2] - (double)a[2] * b[1];
    double cy = (double)a[2] * b[0] - (double)a[0] * b[2];
    double cz = (double)a[0] * b[1] - (double)a[1] * b[0];
    double dot = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
    return atan2(sqrt(cx * cx + cy * cy + cz * cz), dot) * 180.0 / PI;
}

static void test_packing(void)
{
    gb_random rng = gb_random_make(5, 0);
    double worst_direction = 0.0, worst_normal = 0.0;
    int bounces_kept = 1;
    for (int i = 0; i < 200000; ++i) {
        float z = 2.0f * gb_random_float(&rng) - 1.0f, phi = 6.2831853f * gb_random_float(&rng);
        float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        float v[3] = {r * cosf(phi), r * sinf(phi), z}, d[3], n[3];
        unsigned bounce = (unsigned)i % 256u;
        gb_photon_unpack_direction(gb_photon_pack_direction(v), d);
        uint32_t packed = gb_photon_pack_normal(v, bounce);
        gb_photon_unpack_normal(packed, n);
        bounces_kept &= gb_photon_bounce(packed) == bounce;
        worst_direction = fmax(worst_direction, angle_degrees(v, d));
        worst_normal = fmax(worst_normal, angle_degrees(v, n));
    }
    printf("# octahedral error: direction (2x16 bits) %.5f deg, normal (2x12) %.4f deg\n",
           worst_direction, worst_normal);
    CHECK(worst_direction <= 0.003, "directions (2 x 16 bits) come back within 0.003 degrees");
    CHECK(worst_normal <= 0.05, "normals (2 x 12 bits) come back within 0.05 degrees");
    CHECK(bounces_kept, "the bounce count 0..255 survives beside the normal");
    int exact = 1;
    for (int axis = 0; axis < 6; ++axis) {
        float v[3] = {0, 0, 0}, d[3], n[3];
        v[axis / 2] = axis % 2 ? -1.0f : 1.0f;
        gb_photon_unpack_direction(gb_photon_pack_direction(v), d);
        gb_photon_unpack_normal(gb_photon_pack_normal(v, 3), n);
        exact &= memcmp(v, d, sizeof v) == 0 && memcmp(v, n, sizeof v) == 0;
    }
    CHECK(exact, "the six axis directions are packed exactly");
}

static void test_shard_ranges(void)
{
    int ok = 1;
    const uint64_t counts[] = {1, 7, 1000, 1000003};
    for (int c = 0; c < 4; ++c)
        for (uint32_t n = 1; n <= 9; ++n) {
            uint64_t expected_first = 0;
            for (uint32_t i = 0; i < n; ++i) {
                uint64_t first, end;
                gb_photon_shard_range(counts[c], i, n, &first, &end);
                ok &= first == expected_first && end >= first &&
                      end - first <= counts[c] / n + 1 && end - first >= counts[c] / n;
                expected_first = end;
            }
            ok &= expected_first == counts[c];
        }
    CHECK(ok, "shards are contiguous, disjoint, cover the run, sizes within one");
}

/* ---- energy ------------------------------------------------------------ */

/* Power after bounce k: Phi rho^k. Reflections 1 and 2 have no roulette and
 * a cosine-sampled grey diffuse weight of exactly rho, so their sums are
 * exact; later bounces survive with probability rho each (binomial). */
static void check_box_energy(const gb_scene *scene, double phi, const char *where)
{
    const double rho = 0.5;
    const uint64_t n = 20000;
    const unsigned bounces = 7;
    gb_photons_options o = options_for(n, bounces, GB_PHOTON_STORE_ALL);
    gb_photons_stats stats;
    gb_photon_map map = trace(scene, &o, &stats);
    gb_error error;
    char what[160];
    snprintf(what, sizeof what, "%s: every photon valid and inside the box", where);
    CHECK(gb_photon_map_check(&map, "box", &error) == GB_OK, what);
    snprintf(what, sizeof what, "%s: no path leaves the closed box", where);
    CHECK_EQ_INT(stats.escaped, 0, what);
    bounce_sums sums;
    sum_by_bounce(&map, &sums);
    double expected_total = 0.0, total = 0.0;
    int exact = 1, statistical = 1;
    for (unsigned k = 0; k <= bounces; ++k) {
        double expected = phi * pow(rho, k), got = sums.power[k][0];
        expected_total += expected;
        total += got;
        if (k <= GB_PHOTONS_ROULETTE_START) {
            exact &= fabs(got - expected) <= 1e-4 * expected;
            continue;
        }
        double p = pow(rho, k - GB_PHOTONS_ROULETTE_START);
        double sigma = phi * rho * rho / (double)n * binomial_sigma((double)n, p);
        statistical &= fabs(got - expected) <= 4.0 * sigma;
        if (fabs(got - expected) > 4.0 * sigma)
            printf("#   bounce %u: %.6g, expected %.6g +- %.3g\n", k, got, expected, sigma);
    }
    snprintf(what, sizeof what, "%s: power after bounces 0..2 is Phi rho^k (no roulette)",
             where);
    CHECK(exact, what);
    snprintf(what, sizeof what, "%s: power after bounces 3..7 is Phi rho^k within 4 sigma",
             where);
    CHECK(statistical, what);
    snprintf(what, sizeof what, "%s: --store all: total is Phi (1 - rho^8) / (1 - rho)", where);
    CHECK_NEAR(total / expected_total, 1.0, 0.01, what);
    /* in a convex box a reflected photon always lands on another face */
    int other_face = 1;
    for (uint64_t i = 1; i < map.count; ++i)
        if (gb_photon_bounce(map.normals[i]) == gb_photon_bounce(map.normals[i - 1]) + 1)
            other_face &= map.normals[i] << 8 != map.normals[i - 1] << 8;
    snprintf(what, sizeof what, "%s: no reflection hits its own face again", where);
    CHECK(other_face, what);
    gb_photon_map_free(&map);
}

static void test_closed_box(void)
{
    const float grey[3] = {0.5f, 0.5f, 0.5f}, white[3] = {1, 1, 1};
    gb_scene scene;
    build_closed_box(&scene, 0.0f, 1.0f, grey, white);
    check_box_energy(&scene, PI, "unit box");
    gb_scene_free(&scene);
    /* 1e4 wide at 1e6: one float ulp there is 0.06 */
    const float dim[3] = {1e-8f, 1e-8f, 1e-8f};
    build_closed_box(&scene, 1e6f, 1e4f, grey, dim);
    check_box_energy(&scene, PI, "box at 1e6");
    gb_scene_free(&scene);
}

/* Colour: channel c after bounce k is Phi_c Kd_c^k (bounces 1, 2: exact). */
static void test_colour(void)
{
    const float Kd[3] = {0.8f, 0.5f, 0.2f}, Ke[3] = {1.0f, 2.0f, 3.0f};
    gb_scene scene;
    build_closed_box(&scene, -0.5f, 1.0f, Kd, Ke);
    gb_photons_options o = options_for(5000, 2, GB_PHOTON_STORE_INDIRECT);
    gb_photon_map map = trace(&scene, &o, NULL);
    bounce_sums sums;
    sum_by_bounce(&map, &sums);
    int ok = sums.count[0] == 0;
    for (int c = 0; c < 3; ++c)
        for (int k = 1; k <= 2; ++k) {
            double expected = PI * Ke[c] * pow(Kd[c], k);
            ok &= fabs(sums.power[k][c] - expected) <= 1e-4 * expected;
        }
    CHECK(ok, "coloured box: channel c after bounce k is pi Ke_c Kd_c^k, no bounce 0 stored");
    for (int c = 0; c < 3; ++c)
        CHECK_NEAR(map.header.emitted_power[c], PI * Ke[c], 1e-5 * PI * Ke[c],
                   "header: emitted power is pi Ke A per channel");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* ---- lights over a plane ------------------------------------------------ */

/* Point light of intensity I at height h over the plane: the power landing in
 * the ring ra < r < rb is 2 pi I h (1/sqrt(ra^2 + h^2) - 1/sqrt(rb^2 + h^2)),
 * the integral of I cos(theta) / d^2 over the ring. */
static void test_point_light(void)
{
    gb_scene scene;
    build_black_plane(&scene, 100.0f);
    const float position[3] = {0, 1, 0}, intensity[3] = {2, 2, 2};
    add_point_light(&scene, GB_LIGHT_POINT, position, NULL, intensity);
    scene_done(&scene);
    const uint64_t n = 40000;
    gb_photons_options o = options_for(n, 1, GB_PHOTON_STORE_ALL);
    gb_photon_map map = trace(&scene, &o, NULL);
    const double rings[] = {0.0, 0.5, 1.0, 2.0, 4.0, 8.0}, h = 1.0, I = 2.0;
    double in_ring[5] = {0};
    for (uint64_t i = 0; i < map.count; ++i) {
        double r = hypot(map.positions[3 * i], map.positions[3 * i + 2]);
        for (int j = 0; j < 5; ++j)
            if (r >= rings[j] && r < rings[j + 1])
                in_ring[j] += map.powers[3 * i];
    }
    double photon_power = 4.0 * PI * I / (double)n;
    int ok = 1;
    for (int j = 0; j < 5; ++j) {
        double ra = rings[j], rb = rings[j + 1];
        double expected = 2.0 * PI * I * h * (1.0 / hypot(ra, h) - 1.0 / hypot(rb, h));
        double sigma = photon_power * binomial_sigma((double)n, expected / (4.0 * PI * I));
        double area = PI * (rb * rb - ra * ra);
        printf("#   ring %.1f..%.1f: irradiance %.5f, analytic %.5f +- %.5f\n", ra, rb,
               in_ring[j] / area, expected / area, sigma / area);
        ok &= fabs(in_ring[j] - expected) <= 4.0 * sigma;
    }
    CHECK(ok, "point light: irradiance in rings is I cos(theta) / r^2 within 4 sigma");
    CHECK_NEAR(map.header.emitted_power[0], 4.0 * PI * I, 1e-6 * 4.0 * PI * I,
               "point light power is 4 pi I");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* Spot pointing down at the plane: all its power 2 pi I ((1 - cos f) +
 * (cos f - cos c) / 2) lands inside the cone's disk. */
static void test_spot_light(void)
{
    gb_scene scene;
    build_black_plane(&scene, 100.0f);
    const float position[3] = {0, 1, 0}, down[3] = {0, -1, 0}, intensity[3] = {3, 3, 3};
    add_point_light(&scene, GB_LIGHT_SPOT, position, down, intensity);
    scene.lights[0].cone_angle = 30.0f;
    scene.lights[0].falloff_angle = 20.0f;
    scene_done(&scene);
    const uint64_t n = 20000;
    gb_photons_options o = options_for(n, 1, GB_PHOTON_STORE_ALL);
    gb_photon_map map = trace(&scene, &o, NULL);
    double cc = cos(30.0 * PI / 180.0), cf = cos(20.0 * PI / 180.0);
    double expected = 2.0 * PI * 3.0 * ((1.0 - cf) + 0.5 * (cf - cc));
    double sum = 0.0, sum2 = 0.0, widest = 0.0;
    for (uint64_t i = 0; i < map.count; ++i) {
        double p = map.powers[3 * i];
        sum += p;
        sum2 += p * p;
        widest = fmax(widest, hypot(map.positions[3 * i], map.positions[3 * i + 2]));
    }
    double sigma = sqrt(fmax(0.0, sum2 - sum * sum / (double)n));
    CHECK_NEAR(sum, expected, 4.0 * sigma, "spot light: the power landing is the spot's power");
    CHECK_NEAR(map.header.emitted_power[0], expected, 1e-5 * expected,
               "spot light power: 2 pi I ((1 - cos falloff) + (cos falloff - cos cone) / 2)");
    CHECK(widest <= tan(30.0 * PI / 180.0) + 1e-4, "spot light: no photon outside its cone");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* A tilted sun on the 2 x 2 plane: power E cos(theta) A lands on it. */
static void test_directional_light(void)
{
    gb_scene scene;
    build_black_plane(&scene, 1.0f);
    const float direction[3] = {0.6f, -0.8f, 0.0f}, irradiance[3] = {1, 1, 1};
    add_point_light(&scene, GB_LIGHT_DIRECTIONAL, NULL, direction, irradiance);
    scene_done(&scene);
    const uint64_t n = 20000;
    gb_photons_options o = options_for(n, 1, GB_PHOTON_STORE_ALL);
    gb_photon_map map = trace(&scene, &o, NULL);
    double disk_power = map.header.emitted_power[0], expected = 0.8 * 4.0;
    double sigma = disk_power / (double)n * binomial_sigma((double)n, expected / disk_power);
    CHECK_NEAR(disk_power, PI * 2.0, 1e-4, "sun: emitted through the disk of the bounding "
               "sphere, E pi R^2");
    CHECK_NEAR(total_power(&map, 0), expected, 4.0 * sigma,
               "sun: power landing on the plane is E cos(theta) A");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* Constant environment radiance L: each side of the plane receives pi L A. */
static void test_environment(void)
{
    gb_scene scene;
    build_black_plane(&scene, 1.0f);
    scene.environment[0] = scene.environment[1] = scene.environment[2] = 1.0f;
    scene_done(&scene);
    const uint64_t n = 20000;
    gb_photons_options o = options_for(n, 1, GB_PHOTON_STORE_ALL);
    gb_photon_map map = trace(&scene, &o, NULL);
    double emitted = map.header.emitted_power[0], expected = 2.0 * PI * 4.0;
    double sigma = emitted / (double)n * binomial_sigma((double)n, expected / emitted);
    CHECK_NEAR(total_power(&map, 0), expected, 4.0 * sigma,
               "environment: the plane receives pi L A on each side");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

static void test_no_light(void)
{
    const float grey[3] = {0.5f, 0.5f, 0.5f}, black[3] = {0, 0, 0};
    gb_scene scene;
    build_closed_box(&scene, 0.0f, 1.0f, grey, black);
    gb_photons_options o = options_for(100, 4, GB_PHOTON_STORE_ALL);
    gb_photon_map map;
    gb_error error;
    gb_photons_stats stats;
    CHECK_EQ_INT(gb_photons_trace(&scene, &o, &map, &stats, &error), GB_OK,
                 "a scene with no light is traced: its right answer is dark");
    CHECK(map.count == 0 && stats.rays == 0, "... no photon stored, no ray traced");
    CHECK(map.header.emitted_count == 100 && map.header.emitted_power[0] == 0.0 &&
          map.header.emitted_power[1] == 0.0 && map.header.emitted_power[2] == 0.0,
          "... 100 photons emitted, of power 0");
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* ---- determinism, shards, merge ---------------------------------------- */

static void test_determinism(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 8, 8);
    gb_photons_options o = options_for(10000, 8, GB_PHOTON_STORE_INDIRECT);
    o.threads = 1;
    gb_photon_map one = trace(&scene, &o, NULL);
    o.threads = 2;
    gb_photon_map two = trace(&scene, &o, NULL);
    o.threads = 5;
    gb_photon_map five = trace(&scene, &o, NULL);
    CHECK(one.count > 0 && same_maps(&one, &two) && same_maps(&one, &five),
          "the same photons on 1, 2 and 5 threads");
    o.seed = 2;
    gb_photon_map other = trace(&scene, &o, NULL);
    CHECK(!same_maps(&one, &other), "another seed, other photons");
    /* storing all hits changes nothing of the paths: indirect = all minus bounce 0 */
    o.seed = 1;
    o.store = GB_PHOTON_STORE_ALL;
    gb_photon_map all = trace(&scene, &o, NULL);
    uint64_t j = 0;
    int same = 1;
    for (uint64_t i = 0; i < all.count && same; ++i) {
        if (gb_photon_bounce(all.normals[i]) == 0)
            continue;
        same = j < one.count && all.directions[i] == one.directions[j] &&
               memcmp(&all.powers[3 * i], &one.powers[3 * j], 12) == 0;
        ++j;
    }
    CHECK(same && j == one.count, "--store indirect keeps exactly the reflected photons of all");
    gb_photon_map_free(&one);
    gb_photon_map_free(&two);
    gb_photon_map_free(&five);
    gb_photon_map_free(&other);
    gb_photon_map_free(&all);
    gb_scene_free(&scene);
}

static void test_shards_and_merge(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 8, 8);
    gb_error error;
    gb_photons_options o = options_for(9001, 8, GB_PHOTON_STORE_INDIRECT);
    gb_photon_map whole = trace(&scene, &o, NULL);
    gb_photon_map shards[3];
    o.shard_count = 3;
    for (uint32_t i = 0; i < 3; ++i) {
        o.shard_index = i;
        o.threads = 1 + (int)i;
        shards[2 - i] = trace(&scene, &o, NULL);   /* given out of order */
    }
    CHECK(shards[2].header.first_photon == 0 && shards[0].header.end_photon == 9001 &&
              shards[1].header.first_photon == shards[2].header.end_photon,
          "shard I of 3 traces the I-th range of photon indices");
    const char *names[3] = {"s2", "s1", "s0"};
    gb_photon_map merged;
    CHECK_EQ_INT(gb_photons_merge(shards, 3, names, &merged, &error), GB_OK, "merge 3 shards");
    CHECK(same_maps(&whole, &merged), "the merged shards are the whole run's map");
    gb_photon_map_write(scratch_path("whole.phot"), &whole, &error);
    gb_photon_map_write(scratch_path("merged.phot"), &merged, &error);
    CHECK(files_equal(scratch_path("whole.phot"), scratch_path("merged.phot")),
          "... byte for byte in the file");
    gb_photon_map_free(&merged);

    CHECK_EQ_INT(gb_photons_merge(shards, 2, names, &merged, &error), GB_ERROR_ARGUMENT,
                 "merging 2 of 3 shards is refused");
    gb_photon_map twice[3] = {shards[0], shards[0], shards[1]};
    CHECK_EQ_INT(gb_photons_merge(twice, 3, names, &merged, &error), GB_ERROR_ARGUMENT,
                 "a shard given twice is refused");
    CHECK(strstr(error.message, "also") != NULL, "... saying which");
    gb_photon_map odd[3] = {shards[0], shards[1], shards[2]};
    odd[1].header.seed = 99;
    CHECK_EQ_INT(gb_photons_merge(odd, 3, names, &merged, &error), GB_ERROR_ARGUMENT,
                 "a shard of another seed is refused");
    for (int i = 0; i < 3; ++i)
        gb_photon_map_free(&shards[i]);
    gb_photon_map_free(&whole);

    /* more shards than photons: the last shards are empty, and still merge */
    o = options_for(2, 8, GB_PHOTON_STORE_ALL);
    whole = trace(&scene, &o, NULL);
    gb_photon_map tiny[4];
    o.shard_count = 4;
    for (uint32_t i = 0; i < 4; ++i) {
        o.shard_index = i;
        tiny[i] = trace(&scene, &o, NULL);
    }
    const char *tiny_names[4] = {"t0", "t1", "t2", "t3"};
    int merged_ok = gb_photons_merge(tiny, 4, tiny_names, &merged, &error) == GB_OK;
    CHECK(tiny[3].count == 0 && tiny[3].header.first_photon == 2 && merged_ok &&
              same_maps(&whole, &merged),
          "2 photons in 4 shards: empty shards, and the merge is still the whole run");
    if (merged_ok)
        gb_photon_map_free(&merged);
    for (int i = 0; i < 4; ++i)
        gb_photon_map_free(&tiny[i]);
    gb_photon_map_free(&whole);
    gb_scene_free(&scene);
}

static int stop_at_once(void *user, double fraction)
{
    (void)user;
    (void)fraction;
    return 1;
}


/* Two photons in the first cell, one in the last, one on the upper bound
 * (clamped into the last cell): the sums and the change counted by hand. */
static void test_flux_probes(void)
{
    gb_photon_map map;
    gb_photon_arrays a;
    gb_error error;
    if (gb_photon_map_allocate(&map, 4, &a, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    for (int k = 0; k < 3; ++k) {
        map.header.bounds_min[k] = -1.0f;
        map.header.bounds_max[k] = 1.0f;
    }
    const float positions[4][3] = {{-0.99f, -0.99f, -0.99f}, {-0.95f, -0.9f, -0.99f},
                                   {0.99f, 0.99f, 0.99f}, {1.0f, 1.0f, 1.0f}};
    const float powers[4] = {1.0f, 2.0f, 3.0f, 4.0f};     /* R; G and B half of it */
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            a.positions[3 * i + k] = positions[i][k];
            a.powers[3 * i + k] = k == 0 ? powers[i] : 0.5f * powers[i];
        }
    gb_flux_probes p, q;
    int measured = gb_flux_probes_measure(&map, &p, &error) == GB_OK;
    enum { LAST = GB_FLUX_PROBES_CELLS * GB_FLUX_PROBES_CELLS * GB_FLUX_PROBES_CELLS - 1 };
    double total = 0.0;
    for (int c = 0; measured && c <= LAST; ++c)
        total += p.flux[c];
    CHECK(measured && p.flux[0] == 2.0 * 3.0 && p.flux[LAST] == 2.0 * 7.0 && total == 2.0 * 10.0,
          "flux probes: R + G + B of the photons in each cell, the bound in the last cell");
    a.powers[0] = 3.0f;        /* the first cell from 6 to 8 */
    measured &= gb_flux_probes_measure(&map, &q, &error) == GB_OK;
    CHECK(measured && fabs(gb_flux_probes_change(&p, &q) - 2.0 / sqrt(64.0 + 196.0)) < 1e-12,
          "... their change: |difference| / |later|");
    CHECK(measured && gb_flux_probes_change(&q, &q) == 0.0, "... none between equal probes");
    gb_flux_probes_free(&p);
    gb_flux_probes_free(&q);
    gb_photon_map_free(&map);
}

static void test_bad_options(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 8, 8);
    gb_photon_map map;
    gb_error error;
    gb_photons_options o = options_for(100, 4, GB_PHOTON_STORE_ALL);
    o.shard_index = 3;
    o.shard_count = 3;
    CHECK_EQ_INT(gb_photons_trace(&scene, &o, &map, NULL, &error), GB_ERROR_ARGUMENT,
                 "shard 3 of 3 is refused");
    o = options_for(100, 256, GB_PHOTON_STORE_ALL);
    CHECK_EQ_INT(gb_photons_trace(&scene, &o, &map, NULL, &error), GB_ERROR_ARGUMENT,
                 "256 bounces are refused");
    o = options_for(100000, 4, GB_PHOTON_STORE_ALL);
    o.progress = stop_at_once;
    CHECK_EQ_INT(gb_photons_trace(&scene, &o, &map, NULL, &error), GB_ERROR_INTERRUPTED,
                 "a progress callback can stop the run");
    CHECK(map.count == 0 && !map.storage, "... which gives no map");
    gb_scene_free(&scene);
}

/* ---- the file ------------------------------------------------------------ */

static gb_photon_map small_map(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 8, 8);
    gb_photons_options o = options_for(500, 4, GB_PHOTON_STORE_ALL);
    gb_photon_map map = trace(&scene, &o, NULL);
    gb_scene_free(&scene);
    return map;
}

static void test_round_trip(void)
{
    gb_photon_map map = small_map(), read;
    gb_error error;
    const char *path = scratch_path("round.phot");
    CHECK_EQ_INT(gb_photon_map_write(path, &map, &error), GB_OK, "write a photon map");
    CHECK_EQ_INT(gb_photon_map_read(path, &read, &error), GB_OK, "read it back");
    CHECK(same_maps(&map, &read), "every field and photon comes back");
    CHECK((uintptr_t)read.positions % 16 == 0 && (uintptr_t)read.normals % 16 == 0 &&
              !read.storage,
          "the arrays are 16-byte aligned views of the file, no copy");
    size_t size = 0;
    unsigned char *bytes = scratch_read(path, &size);
    size_t header_bytes = 32 + 5 * 48 + 128;
    CHECK(size <= header_bytes + 4 * 16 + GB_PHOTON_SIZE * map.count,
          "the file holds 32 bytes per photon and a fixed header");
    CHECK_EQ_INT(gb_photon_map_check_scene(&read, read.header.scene_hash + 1, path, &error),
                 GB_ERROR_STALE, "a map of another scene is stale");
    gb_photon_map parsed;
    CHECK_EQ_INT(gb_photon_map_parse(bytes + 1, size - 1, "odd", &parsed, &error),
                 GB_ERROR_ARGUMENT, "an unaligned buffer is refused");
    free(bytes);
    gb_photon_map_free(&read);
    gb_photon_map_free(&map);
}

/* Writes map's sections as they are (no checks) with a changed header. */
static gb_result write_raw(const char *path, const gb_photon_map *map, uint32_t version,
                           const unsigned char *header, gb_error *error)
{
    gb_container_writer *w = gb_container_writer_create("PHOT", version);
    uint64_t n = map->count;
    gb_container_add(w, "header", header, 128, error);
    gb_container_add(w, "positions", map->positions, 12 * n, error);
    gb_container_add(w, "powers", map->powers, 12 * n, error);
    gb_container_add(w, "directions", map->directions, 4 * n, error);
    gb_container_add(w, "normals", map->normals, 4 * n, error);
    gb_result result = gb_container_commit(w, path, error);
    gb_container_writer_destroy(w);
    return result;
}

/* The valid header bytes of map (read back from its file). */
static void header_bytes(const gb_photon_map *map, unsigned char header[128])
{
    gb_error error;
    const char *path = scratch_path("header.phot");
    gb_photon_map_write(path, map, &error);
    gb_container container;
    gb_container_read(path, "PHOT", &container, &error);
    memcpy(header, gb_container_find(&container, "header")->data, 128);
    gb_container_close(&container);
}

static void put32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

/* A map sharing map's arrays but with one photon field changed. */
typedef struct edited {
    gb_photon_map map;
    gb_photon_arrays arrays;
} edited;

static void edit_copy(const gb_photon_map *map, edited *e)
{
    gb_error error;
    gb_photon_map_allocate(&e->map, map->count, &e->arrays, &error);
    e->map.header = map->header;
    memcpy(e->arrays.positions, map->positions, 12 * map->count);
    memcpy(e->arrays.powers, map->powers, 12 * map->count);
    memcpy(e->arrays.directions, map->directions, 4 * map->count);
    memcpy(e->arrays.normals, map->normals, 4 * map->count);
}

static gb_result read_edit(const gb_photon_map *map, int field, const unsigned char *header,
                           gb_error *error)
{
    edited e;
    edit_copy(map, &e);
    uint64_t last = map->count - 1;
    if (field == 0)
        e.arrays.positions[3 * last + 1] = NAN;
    if (field == 1)
        e.arrays.positions[0] = map->header.bounds_max[0] + 10.0f;
    if (field == 2)
        e.arrays.powers[4] = -1.0f;
    if (field == 3)
        e.arrays.normals[2] = (e.arrays.normals[2] & 0xFFFFFFu) | (200u << 24);
    if (field == 4)
        e.arrays.directions[1] &= 0xFFFF0000u;
    if (field == 5) {  /* the direction turned to the other side of the normal */
        float d[3];
        gb_photon_unpack_normal(e.arrays.normals[3], d);
        for (int k = 0; k < 3; ++k)
            d[k] = -d[k];
        e.arrays.directions[3] = gb_photon_pack_direction(d);
    }
    const char *path = scratch_path("edited.phot");
    write_raw(path, &e.map, 1, header, error);
    gb_photon_map_free(&e.map);
    gb_photon_map read;
    gb_result result = gb_photon_map_read(path, &read, error);
    gb_photon_map_free(&read);
    return result;
}

static void test_corrupt_files(void)
{
    gb_photon_map map = small_map(), read;
    gb_error error;
    unsigned char header[128], bad[128];
    header_bytes(&map, header);
    const char *path = scratch_path("bad.phot");

    const char *photon_problems[] = {"a NaN position", "a photon outside the scene bounds",
                                     "a negative power", "a bounce count above bounces",
                                     "a zero packed field",
                                     "a photon arriving from behind its surface"};
    for (int field = 0; field < 6; ++field) {
        char what[128];
        snprintf(what, sizeof what, "%s is refused", photon_problems[field]);
        CHECK_EQ_INT(read_edit(&map, field, header, &error), GB_ERROR_INVALID, what);
    }

    struct {
        int at;
        uint32_t value;
        const char *what;
    } fields[] = {
        {24, 999999, "a stored count that the sections do not hold"},
        {48, 5, "shard 5 of 1"},
        {52, 2, "a range that is not the shard's"},
        {56, 0, "zero bounces"},
        {60, 7, "an unknown store mode"},
        {64, 100, "roulette start above bounces"},
        {68, 1, "a nonzero reserved field"},
        {0, 0, "no photon emitted"},
    };
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; ++i) {
        memcpy(bad, header, sizeof bad);
        put32(bad + fields[i].at, fields[i].value);
        if (fields[i].at == 0)
            put32(bad + 4, 0);  /* the whole u64 */
        write_raw(path, &map, 1, bad, &error);
        char what[128];
        snprintf(what, sizeof what, "%s is refused", fields[i].what);
        CHECK_EQ_INT(gb_photon_map_read(path, &read, &error), GB_ERROR_FORMAT, what);
    }
    memcpy(bad, header, sizeof bad);
    float nan = NAN;
    memcpy(bad + 96, &nan, 4);
    write_raw(path, &map, 1, bad, &error);
    CHECK_EQ_INT(gb_photon_map_read(path, &read, &error), GB_ERROR_FORMAT,
                 "NaN scene bounds are refused");
    write_raw(path, &map, 2, header, &error);
    CHECK_EQ_INT(gb_photon_map_read(path, &read, &error), GB_ERROR_UNSUPPORTED,
                 "a newer format version is refused");

    /* a flipped byte anywhere: the container's checksums */
    const char *good = scratch_path("good.phot");
    gb_photon_map_write(good, &map, &error);
    size_t size = 0;
    unsigned char *bytes = scratch_read(good, &size);
    bytes[size - 5] ^= 0x10;
    gb_photon_map parsed;
    CHECK_EQ_INT(gb_photon_map_parse(bytes, size, "flipped", &parsed, &error),
                 GB_ERROR_CHECKSUM, "a flipped byte in the photons is refused");
    CHECK(strncmp(error.message, "flipped: ", 9) == 0, "... naming the file");
    bytes[size - 5] ^= 0x10;
    CHECK_EQ_INT(gb_photon_map_parse(bytes, size - 1, "short", &parsed, &error), GB_ERROR_FORMAT,
                 "a truncated file is refused");
    CHECK_EQ_INT(gb_photon_map_parse(bytes, size, "restored", &parsed, &error), GB_OK,
                 "the restored bytes parse again");
    gb_photon_map_free(&parsed);
    free(bytes);
    CHECK_EQ_INT(gb_photon_map_read(scratch_path("missing.phot"), &read, &error), GB_ERROR_IO,
                 "a missing file is an I/O error");
    gb_photon_map_free(&map);
}

int main(void)
{
    scratch_create("photons");
    test_packing();
    test_shard_ranges();
    test_closed_box();
    test_colour();
    test_point_light();
    test_spot_light();
    test_directional_light();
    test_environment();
    test_no_light();
    test_determinism();
    test_shards_and_merge();
    test_flux_probes();
    test_bad_options();
    test_round_trip();
    test_corrupt_files();
    scratch_remove();
    return tap_done();
}
