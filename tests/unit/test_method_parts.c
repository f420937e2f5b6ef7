/* test_method_parts.c — the GI methods' images drawn in parts
 * (runtime/indirect_method.h) on the Cornell box (found through $GB_ROOT,
 * default "."), 64x64, its indirect light alone: implicit, flc and flc-iv
 * drawn in 1 part, in 3, and flc in more parts than it has regular VPL
 * triangles, by method_frames.h, give gb_render_headless's bytes, image
 * after image (the renderer draws one part).
 * implicit in the window (a budget) solves its first image only and keeps
 * it: the same bytes as the loop without a budget, and a moved view is
 * drawn again. flc says its image is final once GB_FLC_CONVERGED_SAMPLES
 * samples are in, not before. */

#include <stdio.h>
#include <string.h>

#include "../../runtime/flc/flc.h"
#include "../../runtime/flc_iv/flc_iv.h"
#include "../../runtime/implicit/implicit.h"
#include "headless_render.h"
#include "method_frames.h"
#include "tap.h"

enum { SIZE = 64, IMAGES = 2, PARTS = 3, CAP_SIZE = 8 };
#define BUDGET_MS 16.0          /* any budget: the window's frames */
/* flc's N_avg for these tests: big enough VPLs for the Cornell box to have
 * regular triangles as well as divergent ones, so that parts cut both. */
#define FLC_N_AVG 4.0f

/* Every method's parameters here: 6 x 8 x 8 bins (quicker links than the
 * default), flc's N_avg above. */
static const gb_method_parameters test_parameters = {.implicit = {.bins = 8},
                                                     .flc = {.n_avg = FLC_N_AVG}};

typedef struct method_case {
    const char *name;
    gb_method method;
    const gb_indirect_method *indirect;
} method_case;

/* The regular (and divergent) VPL triangles flc makes of scene. */
static uint32_t flc_regular(const gb_scene *scene, const gb_flc_parameters *parameters,
                            uint32_t *divergent)
{
    gb_flc_levels levels;
    gb_flc_scene_levels(scene, parameters, &levels);
    gb_flc_triangles triangles;
    gb_error error;
    *divergent = 0;
    if (!succeeded(gb_flc_triangles_build_whole(scene, &levels, 1, &triangles, &error), &error))
        return 0;
    uint32_t regular = triangles.regular_count;
    *divergent = triangles.divergent_count;
    gb_flc_triangles_free(&triangles);
    return regular;
}

/* IMAGES images of c's method through the renderer (before any view is
 * open: it makes its own context current). */
static int render_method(const gb_scene *scene, const method_case *c, gb_image *image)
{
    gb_headless_options options = {
        .renderer = {.width = SIZE, .height = SIZE, .method = c->method,
                     .terms = GB_TERMS_INDIRECT, .parameters = test_parameters},
        .frames = IMAGES,
    };
    char what[160];
    snprintf(what, sizeof what, "%s: %d images through the renderer", c->name, IMAGES);
    return CHECK(render_headless(scene, &options, image), what);
}

/* IMAGES images through method_frames.h in one part, in PARTS and in
 * more_parts (when not 0): the renderer's bytes each. */
static void test_parts(method_view *v, const method_case *c, const gb_image *renderer,
                       int more_parts)
{
    gb_indirect_setup setup = method_view_setup(v, &test_parameters);
    int counts[3] = {1, PARTS, more_parts};
    char what[160];
    for (int i = 0; i < 3 && counts[i]; ++i) {
        gb_image image;
        snprintf(what, sizeof what, "%s: %d images of %d parts", c->name, IMAGES, counts[i]);
        if (!CHECK(method_render(v, c->indirect, &setup, IMAGES, counts[i], 0.0, &image), what))
            continue;
        snprintf(what, sizeof what, "%s: %d parts, the renderer's bytes", c->name, counts[i]);
        CHECK(same_image(renderer, &image), what);
        gb_image_free(&image);
    }
}

/* Three images of implicit with budget_ms, in parts (the last into image),
 * then one from a moved view (into moved); its step counts after the three. */
static int implicit_images(method_view *v, double budget_ms, gb_image *image, gb_image *moved,
                           gb_implicit_step_times *times)
{
    gb_indirect_setup setup = method_view_setup(v, &test_parameters);
    void *state;
    gb_error error;
    if (!succeeded(gb_implicit_method.create(&setup, &state, &error), &error))
        return 0;
    gb_view first = v->view;
    int ok = method_view_images(v, &gb_implicit_method, state, 3, PARTS, budget_ms, image);
    gb_implicit_times(state, times);
    gb_view_turn(&v->view, 0.3f, 0.1f);
    int refine;
    ok = ok && method_view_image(v, &gb_implicit_method, state, 3, PARTS, budget_ms, &refine) &&
         succeeded(gb_renderer_read(&v->renderer, moved, &error), &error);
    v->view = first;
    gb_implicit_method.destroy(state);
    if (!ok)
        gb_image_free(image);
    return ok;
}

/* Without a budget each image is solved; with one the first only, and the
 * bytes are the same, also from a view that moved after the first image
 * (its target drawn again from the kept solution). */
static void test_implicit_budget(method_view *v)
{
    gb_implicit_step_times loop, window;
    gb_image every, first, every_moved, first_moved;
    if (!CHECK(implicit_images(v, 0.0, &every, &every_moved, &loop),
               "implicit: 3 images without a budget, a 4th from a moved view"))
        return;
    CHECK_EQ_INT(loop.frames, 3, "implicit without a budget: each image solved");
    if (CHECK(implicit_images(v, BUDGET_MS, &first, &first_moved, &window),
              "implicit: the same with a budget")) {
        CHECK(window.frames == 1 && window.rebuilds == 0,
              "implicit with a budget: the first image solved, no links rebuilt");
        CHECK(same_image(&every, &first),
              "implicit with a budget: the bytes of the loop without one");
        CHECK(same_image(&every_moved, &first_moved),
              "implicit with a budget: the moved view drawn again, the loop's bytes");
        gb_image_free(&first);
        gb_image_free(&first_moved);
    }
    gb_image_free(&every);
    gb_image_free(&every_moved);
}

/* flc's draw: another image would refine it until the cap, not after. */
static void test_flc_cap(const gb_scene *scene)
{
    method_view v;
    if (!CHECK(method_view_open(scene, CAP_SIZE, CAP_SIZE, &v), "a small view for flc's cap"))
        return;
    gb_indirect_setup setup = method_view_setup(&v, &test_parameters);
    void *state;
    gb_error error;
    if (CHECK(succeeded(gb_flc_method.create(&setup, &state, &error), &error), "flc made")) {
        int ok = 1, refining = 1, refine = 0;
        for (uint32_t i = 0; ok && i < GB_FLC_CONVERGED_SAMPLES; ++i) {
            ok = method_view_image(&v, &gb_flc_method, state, i, 1, BUDGET_MS, &refine);
            if (i + 1 < GB_FLC_CONVERGED_SAMPLES)
                refining &= refine != 0;
        }
        CHECK(ok && refining, "flc: each image before the cap says another would refine it");
        CHECK(ok && !refine, "flc: the image of the cap's sample says it is final");
        gb_flc_method.destroy(state);
    }
    method_view_close(&v);
}

int main(void)
{
    gb_scene scene;
    if (!CHECK(load_cornell(&scene), "the Cornell box loads"))
        return tap_done();
    uint32_t divergent, regular = flc_regular(&scene, &test_parameters.flc, &divergent);
    printf("# flc, N_avg %g: %u regular VPL triangles, %u divergent\n", FLC_N_AVG, regular,
           divergent);
    CHECK(regular >= PARTS && divergent > 0,
          "flc: the Cornell box has regular VPL triangles for each part, and divergent ones");
    static const method_case cases[] = {
        {"implicit", GB_METHOD_IMPLICIT, &gb_implicit_method},
        {"flc", GB_METHOD_FLC, &gb_flc_method},
        {"flc-iv", GB_METHOD_FLC_IV, &gb_flc_iv_method},
    };
    gb_image renders[3];
    int rendered[3];
    for (int i = 0; i < 3; ++i)
        rendered[i] = render_method(&scene, &cases[i], &renders[i]);
    method_view v;
    if (CHECK(method_view_open(&scene, SIZE, SIZE, &v), "a headless view of the Cornell box")) {
        for (int i = 0; i < 3; ++i)
            if (rendered[i])
                test_parts(&v, &cases[i], &renders[i],
                           cases[i].method == GB_METHOD_FLC ? (int)regular + 2 : 0);
        test_implicit_budget(&v);
        method_view_close(&v);
    }
    for (int i = 0; i < 3; ++i)
        if (rendered[i])
            gb_image_free(&renders[i]);
    test_flc_cap(&scene);
    gb_scene_free(&scene);
    return tap_done();
}
