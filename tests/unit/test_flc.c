/* test_flc.c — Forward Light Cuts (runtime/flc/flc.h, flc_decimation.h): the
 * parameters (S0 of Eq. 1, S_k of Eq. 17, S̄_k, D_k of Eq. 18), the
 * partition of unity f^k (Eqs. 11, 16), Alg. 1's levels against Eq. 3, the
 * random values of Alg. 2, the subdivision of divergent triangles, hard
 * scenes (areas from 1e-12 to 1e6, every triangle divergent, receivers
 * touching VPLs, an empty scene), and renders of the Cornell box's indirect
 * light on llvmpipe against `reference --mode indirect1-unshadowed`: the
 * error falls as progressive frames grow, and a fixed frame count gives the
 * same image twice. The Cornell box is found through $GB_ROOT (default "."). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/flc/flc.h"
#include "../../runtime/headless.h"
#include "headless_render.h"
#include "scene_builder.h"
#include "tap.h"

/* The relative MSE (tools/imgdiff) of 16 progressive frames at 64x64
 * against the reference at 1024 spp: about 0.00045 (1 frame: 0.0017, 4:
 * 0.00083); the threshold leaves room. With 4 tiles (--tiling 1) and 4
 * frames about 0.0013: the blur of the untiling costs some at edges. */
#define FLC_RELATIVE_MSE_MAX 0.001
#define FLC_TILED_RELATIVE_MSE_MAX 0.003
enum { SIZE = 64, REFERENCE_SPP = 1024 };

static void test_parameters(void)
{
    CHECK_NEAR(gb_flc_S0(10.0, 64.0), 4.0 * M_PI * 100.0 / 64.0, 1e-9,
               "S0 = 4 pi D_near^2 / N_avg");
    gb_flc_levels l;
    gb_flc_levels_make(10.0, 64.0, 2.0, 5, &l);
    CHECK_EQ_INT(l.N, 5, "N = 5");
    int ok = 1;
    double inverse_sum = 0.0;
    for (int k = 0; k <= l.N; ++k) {
        inverse_sum += 1.0 / l.S[k];
        ok &= fabs(l.S[k] - l.S0 * pow(2.0, k)) <= 1e-4 * l.S[k];
        ok &= fabs(l.S_bar[k] - 1.0 / inverse_sum) <= 1e-5 * l.S_bar[k];
        ok &= fabs(l.D[k] - sqrt(l.S0 * pow(2.0, k))) <= 1e-5 * l.D[k];
        ok &= k == 0 || (l.S_bar[k] < l.S_bar[k - 1] && l.D[k] > l.D[k - 1]);
    }
    CHECK(ok, "S_k = S0 mu^k, S̄_k = 1 / sum 1/S_j decreasing, D_k = sqrt(S0 mu^k) increasing");
    CHECK_NEAR(l.S_bar[0], l.S0, 1e-6, "S̄_0 = S0");
    CHECK_NEAR(l.D[6], l.D[5], 0, "D_{N+1} = D_N");
    gb_flc_levels_make(10.0, 64.0, 2.0, 99, &l);
    CHECK_EQ_INT(l.N, GB_FLC_MAX_LEVELS - 1, "N is clamped to the levels there is room for");
}

static void test_partition_of_unity(void)
{
    gb_flc_levels l;
    gb_flc_levels_make(3.0, 128.0, 1.7, 6, &l);
    int unity = 1, bounded = 1;
    for (int i = 0; i <= 4000; ++i) {
        float d = 2.0f * l.D[l.N] * (float)i / 4000.0f, sum = 0.0f;
        for (int k = 0; k <= l.N; ++k) {
            float f = gb_flc_support(&l, k, d);
            bounded &= f >= 0.0f && f <= 1.0f;
            sum += f;
        }
        unity &= fabsf(sum - 1.0f) < 1e-5f;
    }
    CHECK(unity, "sum_k f^k(d) = 1 for d from 0 to twice D_N (Eq. 11)");
    CHECK(bounded, "every f^k(d) is in [0, 1]");
    CHECK_NEAR(gb_flc_support(&l, 0, 0.5f * l.D[0]), 1.0, 0, "f^0 is 1 near the VPL");
    CHECK_NEAR(gb_flc_support(&l, 2, l.D[0]), 0.0, 0, "f^2 is 0 below D_1");
    CHECK_NEAR(gb_flc_support(&l, l.N, 1e9f), 1.0, 0, "the last level reaches every distance");
    CHECK_NEAR(gb_flc_support(&l, 1, 0.5f * (l.D[0] + l.D[1])), 0.5, 1e-6,
               "f^1 rises linearly between D_0 and D_1");
}

/* Alg. 1 over a regular grid of u: the share of each level and of discards. */
static void level_frequencies(const gb_flc_levels *l, float area, double *share, double *discard)
{
    enum { SAMPLES = 1 << 20 };
    long count[GB_FLC_MAX_LEVELS] = {0}, discarded = 0;
    for (int i = 0; i < SAMPLES; ++i) {
        int k = gb_flc_level(l, ((float)i + 0.5f) / SAMPLES, area);
        k < 0 ? ++discarded : ++count[k];
    }
    for (int k = 0; k <= l->N; ++k)
        share[k] = (double)count[k] / SAMPLES;
    *discard = (double)discarded / SAMPLES;
}

static void test_levels(void)
{
    gb_flc_levels l;
    gb_flc_levels_make(10.0, 256.0, 2.0, 5, &l);
    const float areas[] = {1e-3f * l.S0, 0.1f * l.S0, 0.4f * l.S0, l.S_bar[l.N]};
    for (int a = 0; a < 4; ++a) {
        double share[GB_FLC_MAX_LEVELS], discard, worst = 0.0;
        level_frequencies(&l, areas[a], share, &discard);
        for (int k = 0; k <= l.N; ++k)
            worst = fmax(worst, fabs(share[k] - areas[a] / l.S[k]));
        char what[128];
        snprintf(what, sizeof what, "area %.3g S0: P(level k) = area / S_k (Eq. 3)",
                 areas[a] / l.S0);
        CHECK_NEAR(worst, 0.0, 1e-5, what);
        CHECK_NEAR(discard, 1.0 - areas[a] / l.S_bar[l.N], 1e-5,
                   "and discarded with probability 1 - area / S̄_N");
    }
    double share[GB_FLC_MAX_LEVELS], discard;
    level_frequencies(&l, 2.0f * l.S_bar[l.N], share, &discard);
    CHECK_NEAR(discard, 0.0, 0, "a divergent triangle is never discarded");
    int consistent = 1;
    for (int i = 0; i < 1000; ++i) {
        float u = (float)i / 1000.0f, area = 0.3f * l.S0;
        int k = gb_flc_level(&l, u, area);
        for (int j = 0; j <= l.N; ++j)   /* exactly one level: the first with u < area / S̄_j */
            consistent &= (u < area / l.S_bar[j]) == (k >= 0 && j >= k);
    }
    CHECK(consistent, "each u gives one level: the first k with u < area / S̄_k, or none");
    l.keep_all = 1;
    int kept = 1;
    for (int i = 0; i < 1000; ++i)
        kept &= gb_flc_level(&l, (float)i / 1000.0f, 1e-3f * l.S0) == l.N;
    CHECK(kept, "no decimation (keep_all): every triangle kept, at level N");
    gb_flc_parameters parameters = {.levels = GB_FLC_NO_DECIMATION};
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    build_cornell_box(&scene, SIZE, SIZE);
    gb_flc_levels defaults, none;
    gb_flc_scene_levels(&scene, &(gb_flc_parameters){0}, &defaults);
    gb_flc_scene_levels(&scene, &parameters, &none);
    CHECK(none.keep_all && !defaults.keep_all && none.N == defaults.N &&
              none.S_bar[none.N] == defaults.S_bar[defaults.N],
          "GB_FLC_NO_DECIMATION: the default levels (so the same VPL triangles), keep_all set");
    gb_scene_free(&scene);
}

/* The tessellation of a divergent triangle: c x c cells of an even level
 * m <= 64 whose sub-triangles, 2 / (3 c^2 m^2) of its area, are at most S̄_N
 * and as large as that allows (the least even m, the fewest cells). */
static void test_tessellation(void)
{
    gb_flc_levels l;
    gb_flc_levels_make(10.0, 256.0, 2.0, 5, &l);
    double limit = l.S_bar[l.N];
    int ok = 1, tight = 1;
    for (double ratio = 1.001; ratio < 256.0 * 256.0; ratio *= 1.01) {
        uint32_t c, m;
        gb_flc_tessellation(&l, ratio * limit, &c, &m);
        double sub = 2.0 / 3.0 * ratio * limit / ((double)c * c * m * m);
        ok &= m >= 2 && m % 2 == 0 && m <= GB_FLC_MAX_TESS_LEVEL && c <= 4 &&
              sub <= limit * (1 + 1e-9);
        /* the next even level down (none below 2) would leave sub-triangles over S̄_N */
        tight &= (m == 2 || 2.0 / 3.0 * ratio * limit / ((double)c * c * (m - 2) * (m - 2)) > limit) &&
                 (c == 1 || sqrt(2.0 / 3.0 * ratio) > 64.0 * (c - 1));
    }
    CHECK(ok, "areas of S̄_N to 65536 S̄_N: even levels <= 64, sub-triangles <= S̄_N");
    CHECK(tight, "the least even level, the fewest cells");
    uint32_t c, m;
    gb_flc_tessellation(&l, 1e6 * 65536.0 * limit, &c, &m);
    CHECK(c == 4 && m == 54, "past n = 256: capped at 4 cells of level 54 (t = 209)");
    gb_flc_tessellation(&l, 0.5 * limit, &c, &m);
    CHECK(c == 1 && m == 1, "a regular triangle: not tessellated");
    CHECK(gb_flc_subdivision(&l, l.S_bar[l.N]) == 1 &&
              gb_flc_subdivision(&l, 1.01 * l.S_bar[l.N]) == 2 &&
              gb_flc_subdivision(&l, 100.0 * l.S_bar[l.N]) == 10,
          "n = ceil(sqrt(area / S̄_N)), 1 for a regular triangle");
    CHECK(gb_flc_tess_coord_random(3, 5) == gb_flc_tess_coord_random(3, 5) &&
              gb_flc_tess_coord_random(3, 5) != gb_flc_tess_coord_random(5, 3),
          "v_rand_tess: a function of the sub-vertex's coordinates, not symmetric");
}

static void test_random(void)
{
    CHECK(gb_flc_hash(12345u) == gb_flc_hash(12345u) && gb_flc_hash(1u) != gb_flc_hash(2u),
          "the hash is a function, and mixes");
    uint32_t key = gb_flc_vertex_random(7, 0) ^ gb_flc_vertex_random(7, 1) ^
                   gb_flc_vertex_random(7, 2);
    double mean = 0.0;
    enum { FRAMES = 100000 };
    for (uint32_t frame = 0; frame < FRAMES; ++frame)
        mean += gb_flc_uniform(gb_flc_triangle_random(key, gb_flc_hash(frame)));
    CHECK_NEAR(mean / FRAMES, 0.5, 0.005, "a triangle's u_i over frames is uniform (mean 1/2)");
    CHECK(gb_flc_vertex_random(7, 3) == gb_flc_vertex_random(7, 3) &&
              gb_flc_vertex_random(7, 3) != gb_flc_vertex_random(8, 3),
          "v_rand depends on the seed and the vertex only");
}

static double scene_area(const gb_scene *scene)
{
    double area = 0.0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        area += gb_triangle_area(scene, t);
    return area;
}

static int finite_triangles(const gb_flc_triangles *list)
{
    for (uint32_t i = 0; i < list->count; ++i) {
        const gb_flc_triangle *t = &list->items[i];
        for (int c = 0; c < 3; ++c)
            if (!isfinite(t->p0[c]) || !isfinite(t->p1[c]) || !isfinite(t->p2[c]))
                return 0;
        if (!isfinite(t->area))
            return 0;
    }
    return 1;
}

/* The triangles of GL's equal-spacing tessellation of a triangle, every level
 * m: rings of m, m - 2, ... segments a side, 3 (2 r - 2) triangles between
 * rings r and r - 2, one at the centre for odd m. */
static uint64_t gl_triangles(uint32_t m)
{
    uint64_t count = m % 2;
    for (uint32_t r = m; r >= 2; r -= 2)
        count += 3 * (2 * r - 2);
    return count;
}

static void check_subdivision(const gb_scene *scene, const char *name)
{
    gb_flc_levels l;
    gb_flc_parameters parameters = {0};
    gb_flc_scene_levels(scene, &parameters, &l);
    gb_flc_triangles list;
    gb_error error;
    char what[160];
    snprintf(what, sizeof what, "%s: VPL triangles built", name);
    if (!CHECK(gb_flc_triangles_build(scene, &l, 1, &list, &error) == GB_OK, what)) {
        printf("# %s\n", error.message);
        return;
    }
    double area = 0.0, largest = 0.0;
    for (uint32_t i = 0; i < list.count; ++i) {
        area += list.items[i].area;
        largest = fmax(largest, list.items[i].area);
    }
    snprintf(what, sizeof what, "%s: the sub-triangles cover the scene's area", name);
    CHECK_NEAR(area / scene_area(scene), 1.0, 1e-3, what);
    snprintf(what, sizeof what, "%s: none is divergent after subdivision (<= S̄_N)", name);
    CHECK(list.capped_count == 0 && largest <= 1.0001 * l.S_bar[l.N], what);
    snprintf(what, sizeof what, "%s: every value finite", name);
    CHECK(finite_triangles(&list), what);
    CHECK_EQ_INT(list.regular_count + list.divergent_count, scene->triangle_count,
                 "every scene triangle is regular or divergent");
    int ordered = 1;
    uint32_t j = 0;     /* items[0, regular_count): the regular triangles, in scene order */
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        if (gb_triangle_area(scene, t) > l.S_bar[l.N])
            continue;
        const float *v = &scene->positions[3 * (size_t)scene->indices[3 * (size_t)t]];
        ordered &= j < list.regular_count && !memcmp(list.items[j].p0, v, sizeof(float[3]));
        ++j;
    }
    ordered &= j == list.regular_count;
    snprintf(what, sizeof what, "%s: the regular triangles first, the sub-triangles after", name);
    gb_flc_triangles whole;
    snprintf(what, sizeof what, "%s: the list for the tessellation built", name);
    if (CHECK(gb_flc_triangles_build_whole(scene, &l, 1, &whole, &error) == GB_OK, what)) {
        double whole_area = 0.0;
        uint64_t patches = 0, tessellated = 0;
        for (uint32_t i = 0; i < whole.count; ++i) {
            whole_area += whole.items[i].area;
            uint32_t c, m;
            gb_flc_tessellation(&l, whole.items[i].area, &c, &m);
            patches += i >= whole.regular_count ? (uint64_t)c * c : 0;
            tessellated += i >= whole.regular_count ? (uint64_t)c * c * gl_triangles(m) : 0;
        }
        snprintf(what, sizeof what, "%s: whole, the same regular triangles, then the divergent "
                 "ones whole, covering the scene's area", name);
        CHECK(whole.count == scene->triangle_count && whole.regular_count == list.regular_count &&
                  !memcmp(whole.items, list.items, list.regular_count * sizeof *list.items) &&
                  fabs(whole_area / scene_area(scene) - 1.0) < 1e-3,
              what);
        snprintf(what, sizeof what, "%s: room for every cell and sub-triangle", name);
        CHECK(whole.patch_bound >= patches && whole.tessellated_bound >= tessellated, what);
        gb_flc_triangles_free(&whole);
    }
    CHECK(ordered && list.count >= list.regular_count + 4 * list.divergent_count, what);
    gb_flc_triangles_free(&list);
}

/* A 1000-unit room (faces of 1e6) holding triangles of 1e-12 to 1e2. */
static void build_extreme_scene(gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    const float lo[3] = {0, 0, 0}, hi[3] = {1000, 1000, 1000};
    uint32_t grey = add_grey(scene, 0.7f, 0.0f);
    add_box(scene, lo, hi, 1, grey);
    for (int e = -6; e <= 1; ++e) {
        float side = powf(10.0f, (float)e), x = 10.0f + 100.0f * (float)(e + 6);
        float p[4][3] = {{x, 1, 1}, {x + side, 1, 1}, {x + side, 1 + side, 1}, {x, 1 + side, 1}};
        add_quad(scene, p, grey);
    }
    const float light[3] = {500, 900, 500}, intensity[3] = {1e5f, 1e5f, 1e5f};
    add_point_light(scene, GB_LIGHT_POINT, light, NULL, intensity);
    const float eye[3] = {500, 500, 50}, target[3] = {500, 500, 1000};
    set_camera(scene, eye, target, 60.0f, SIZE, SIZE);
    scene_done(scene);
}

static void test_hard_scenes(void)
{
    gb_scene empty;
    memset(&empty, 0, sizeof empty);
    gb_flc_levels l;
    gb_flc_levels_make(1.0, 256.0, 2.0, 5, &l);
    gb_flc_triangles list;
    gb_error error;
    CHECK(gb_flc_triangles_build(&empty, &l, 1, &list, &error) == GB_OK && list.count == 0,
          "an empty scene: no VPL triangle, no failure");
    gb_flc_triangles_free(&list);
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    build_cornell_box(&scene, SIZE, SIZE);
    check_subdivision(&scene, "Cornell box (its walls divergent)");
    gb_scene_free(&scene);
    build_extreme_scene(&scene);
    check_subdivision(&scene, "areas from 1e-12 to 1e6");
    gb_flc_levels_make(1.0, 256.0, 2.0, 5, &l);
    if (CHECK(gb_flc_triangles_build(&scene, &l, 1, &list, &error) == GB_OK,
              "a tiny S0 against faces of 1e6: still built")) {
        CHECK(list.capped_count > 0 && finite_triangles(&list),
              "the faces past n = 256 are counted as capped, every value finite");
        gb_flc_triangles_free(&list);
    }
    gb_scene_free(&scene);
}

static int render_flc_levels(const gb_scene *scene, int frames, int tiling, int levels,
                             gb_image *image)
{
    gb_headless_options options = {
        .renderer = {.width = SIZE, .height = SIZE, .method = GB_METHOD_FLC,
                     .terms = GB_TERMS_INDIRECT,
                     .parameters = {.flc = {.tiling = tiling, .levels = levels}}},
        .frames = frames,
    };
    return render_headless(scene, &options, image);
}

static int render_flc(const gb_scene *scene, int frames, int tiling, gb_image *image)
{
    return render_flc_levels(scene, frames, tiling, 0, image);
}

static int all_finite(const gb_image *image)
{
    size_t count = (size_t)image->width * image->height * image->channels;
    for (size_t i = 0; i < count; ++i)
        if (!isfinite(image->pixels[i]) || image->pixels[i] < 0.0f)
            return 0;
    return 1;
}


/* The slope of log(error) over log(frames), least squares. */
static double log_slope(const int *frames, const double *errors, int count)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < count; ++i) {
        double x = log(frames[i]), y = log(errors[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

static void test_progressive(const gb_scene *scene, const gb_image *reference)
{
    static const int frames[] = {1, 2, 4, 8, 16};
    double errors[5];
    for (int i = 0; i < 5; ++i) {
        gb_image image;
        if (!CHECK(render_flc(scene, frames[i], 0, &image), "flc renders the indirect light"))
            return;
        errors[i] = relative_mse(&image, reference);
        printf("# %2d frames: relative MSE %.6g\n", frames[i], errors[i]);
        gb_image_free(&image);
    }
    CHECK(log_slope(frames, errors, 5) < 0.0, "the error falls as frames grow (fitted slope < 0)");
    CHECK(errors[4] < errors[0], "16 frames beat 1");
    CHECK(errors[4] < FLC_RELATIVE_MSE_MAX, "16 frames: relative MSE below the threshold");
}

static void test_renders(const gb_scene *scene)
{
    gb_reference_options options = {
        .mode = GB_REFERENCE_INDIRECT1_UNSHADOWED, .spp = REFERENCE_SPP,
        .width = SIZE, .height = SIZE,
    };
    gb_image reference, a, b;
    if (!CHECK(render_reference(scene, &options, &reference),
               "reference --mode indirect1-unshadowed renders"))
        return;
    test_progressive(scene, &reference);
    if (CHECK(render_flc(scene, 3, 0, &a), "3 frames") &&
        CHECK(render_flc(scene, 3, 0, &b), "3 frames again")) {
        CHECK(a.width == b.width && memcmp(a.pixels, b.pixels, (size_t)SIZE * SIZE * 3 *
                                           sizeof(float)) == 0,
              "a fixed frame count gives the same image");
        CHECK(all_finite(&a), "every pixel finite and >= 0 (receivers touch VPLs at the corners)");
        gb_image_free(&a);
        gb_image_free(&b);
    }
    if (CHECK(render_flc(scene, 4, 1, &a), "4 tiles (--tiling 1)")) {
        double error_tiled = relative_mse(&a, &reference);
        printf("# tiling 1, 4 frames: relative MSE %.6g\n", error_tiled);
        CHECK(error_tiled < FLC_TILED_RELATIVE_MSE_MAX, "tiled: relative MSE below 0.003");
        gb_image_free(&a);
    }
    if (CHECK(render_flc_levels(scene, 1, 0, GB_FLC_NO_DECIMATION, &a),
              "no decimation (every VPL triangle)")) {
        double error_all = relative_mse(&a, &reference);
        printf("# no decimation, 1 frame: relative MSE %.6g\n", error_all);
        CHECK(error_all < FLC_RELATIVE_MSE_MAX,
              "no decimation, 1 frame: relative MSE below the 16-frame threshold");
        gb_image_free(&a);
    }
    gb_image_free(&reference);
}

/* 3 frames of 64x64 through a renderer, the last 2 measured (gb_flc_measure),
 * as bench/flc_passes.c; the last frame into image. */
static int measured_frames(const gb_scene *scene, int levels, gb_flc_pass_times *times,
                           gb_image *image)
{
    gb_view view;
    gb_context context;
    gb_error error;
    if (gb_scene_view(scene, 0, &view, &error) != GB_OK ||
        gb_context_create_headless(&context, &error) != GB_OK) {
        printf("# %s\n", error.message);
        return 0;
    }
    gb_renderer_options options = {.width = SIZE, .height = SIZE, .method = GB_METHOD_FLC,
                                   .terms = GB_TERMS_INDIRECT,
                                   .parameters = {.flc = {.levels = levels}}};
    gb_renderer renderer;
    gb_result result = gb_renderer_create(scene, &options, &context.errors, &renderer, &error);
    for (int i = 0; i < 3 && result == GB_OK; ++i) {
        gb_renderer_draw(&renderer, &view);
        result = gb_renderer_finish_frame(&renderer, &error);
        if (i == 0)
            gb_flc_measure(renderer.method_state[GB_METHOD_FLC], 1);
    }
    if (result == GB_OK)
        result = gb_renderer_read(&renderer, image, &error);
    if (result == GB_OK)
        gb_flc_times(renderer.method_state[GB_METHOD_FLC], times);
    else
        printf("# %s\n", error.message);
    gb_renderer_destroy(&renderer);
    gb_context_destroy(&context);
    return result == GB_OK;
}

/* The sub-triangles GL's tessellation makes of the scene's divergent triangles. */
static uint64_t tessellated_count(const gb_scene *scene, int levels)
{
    gb_flc_levels l;
    gb_flc_scene_levels(scene, &(gb_flc_parameters){.levels = levels}, &l);
    uint64_t count = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        uint32_t c, m;
        gb_flc_tessellation(&l, gb_triangle_area(scene, t), &c, &m);
        count += m > 1 ? (uint64_t)c * c * gl_triangles(m) : 0;
    }
    return count;
}

static void test_pass_times(const gb_scene *scene)
{
    gb_flc_pass_times t;
    gb_image measured, plain;
    if (CHECK(measured_frames(scene, 0, &t, &measured), "3 frames, the last 2 measured")) {
        CHECK(t.frames == 2 && t.regular_ms >= 0.0 && t.divergent_ms > 0.0 &&
                  t.resolve_ms > 0.0,
              "the pass times cover the 2 measured frames");
        CHECK(t.regular_triangles == 0 && t.divergent_triangles > 0,
              "the Cornell box: every triangle divergent");
        uint64_t all = tessellated_count(scene, 0);
        printf("# %llu VPLs of %llu sub-triangles over 2 frames\n",
               (unsigned long long)t.divergent_vpls, (unsigned long long)all);
        CHECK(t.divergent_vpls > 0 && t.divergent_vpls < 2 * all,
              "the tessellation's VPLs: some of its sub-triangles, decimated");
        if (CHECK(render_flc(scene, 3, 0, &plain), "3 frames unmeasured")) {
            CHECK(!memcmp(measured.pixels, plain.pixels, (size_t)SIZE * SIZE * 3 * sizeof(float)),
                  "measuring leaves the image as it was");
            gb_image_free(&plain);
        }
        gb_image_free(&measured);
    }
    if (CHECK(measured_frames(scene, GB_FLC_NO_DECIMATION, &t, &measured),
              "no decimation, measured")) {
        uint64_t all = tessellated_count(scene, GB_FLC_NO_DECIMATION);
        printf("# no decimation: %llu VPLs over 2 frames, %llu sub-triangles a frame\n",
               (unsigned long long)t.divergent_vpls, (unsigned long long)all);
        CHECK(t.divergent_vpls == 2 * all,
              "no decimation: a VPL for every sub-triangle of GL's tessellation pattern");
        gb_image_free(&measured);
    }
}

static void test_extreme_render(void)
{
    gb_scene scene;
    build_extreme_scene(&scene);
    gb_image image;
    gb_headless_options options = {
        .renderer = {.method = GB_METHOD_FLC, .terms = GB_TERMS_INDIRECT,
                     .parameters = {.flc = {.n_avg = 64}}},
        .frames = 2,
    };
    if (CHECK(render_headless(&scene, &options, &image),
              "the scene of areas 1e-12 to 1e6 renders")) {
        CHECK(all_finite(&image), "no NaN, no Inf");
        gb_image_free(&image);
    }
    gb_scene_free(&scene);
}

int main(void)
{
    test_parameters();
    test_partition_of_unity();
    test_levels();
    test_random();
    test_tessellation();
    test_hard_scenes();
    gb_scene scene;
    if (!load_cornell(&scene)) {
        printf("1..0 # SKIP the Cornell box does not load\n");
        return 0;
    }
    test_renders(&scene);
    test_pass_times(&scene);
    test_extreme_render();
    gb_scene_free(&scene);
    return tap_done();
}
