/* test_refine — the window's way of drawing (renderer.h, gb_renderer_refine)
 * against whole frames (gb_renderer_draw, what --headless writes): a still
 * view drawn in parts, and a moving view drawn small then refined, end on
 * the same bytes; a change of terms starts again; M (method_cycle.h) skips
 * what cannot run without a bake and says why once. */
#include <stdio.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/method_cycle.h"
#include "../../runtime/renderer.h"
#include "headless_render.h"
#include "tap.h"

enum { WIDTH = 64, HEIGHT = 48, MOST_FRAMES = 4000 };
/* A budget no frame fits (a nanosecond): every image is cut into the most
 * parts and every moving image drawn at the largest divisor, whatever the
 * machine's speed or load. */
#define TINY_BUDGET_MS 1e-6

typedef struct seen {
    int most_parts, most_divisor, frames;
} seen;

static int same_pixels(const gb_image *a, const gb_image *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->pixels, b->pixels, sizeof(float) * 3 * (size_t)a->width * a->height) == 0;
}

static gb_renderer_options options_of(gb_method method, gb_terms terms, double budget_ms)
{
    return (gb_renderer_options){.width = WIDTH, .height = HEIGHT, .method = method,
                                 .terms = terms, .budget_ms = budget_ms};
}

/* The whole frame of view, as --headless draws it. */
static int whole_frame(const gb_scene *scene, gb_context *context, gb_method method,
                       gb_terms terms, const gb_view *view, gb_image *image)
{
    gb_renderer_options options = options_of(method, terms, 0.0);
    gb_renderer renderer;
    gb_error error;
    gb_result result = gb_renderer_create(scene, &options, &context->errors, &renderer, &error);
    if (result == GB_OK) {
        gb_renderer_draw(&renderer, view);
        result = gb_renderer_finish_frame(&renderer, &error);
    }
    if (result == GB_OK)
        result = gb_renderer_read(&renderer, image, &error);
    gb_renderer_destroy(&renderer);
    return succeeded(result, &error);
}

/* One check: the renderer's image is the whole frame of view with terms. */
static void check_whole_frame(const gb_scene *scene, gb_context *context, gb_renderer *renderer,
                              gb_terms terms, const gb_view *view, const char *what)
{
    gb_image refined = {0}, whole = {0};
    gb_error error;
    int read = succeeded(gb_renderer_read(renderer, &refined, &error), &error) &&
               whole_frame(scene, context, renderer->options.method, terms, view, &whole);
    CHECK(read && same_pixels(&refined, &whole), what);
    gb_image_free(&refined);
    gb_image_free(&whole);
}

/* Refines view until the image is final; what the status showed on the way. */
static int refine_until_final(gb_renderer *renderer, const gb_view *view, seen *s)
{
    gb_error error;
    gb_result result = GB_OK;
    for (int i = 0; i < MOST_FRAMES && result == GB_OK && !renderer->status.converged; ++i) {
        int changed;
        result = gb_renderer_refine(renderer, view, &changed, &error);
        s->most_parts = renderer->parts > s->most_parts ? renderer->parts : s->most_parts;
        s->most_divisor =
            renderer->divisor > s->most_divisor ? renderer->divisor : s->most_divisor;
        ++s->frames;
    }
    return succeeded(result, &error) && renderer->status.converged;
}

static void check_method(const gb_scene *scene, gb_context *context, gb_method method)
{
    const char *name = gb_method_name(method);
    char what[160];
    gb_view start, view;
    gb_error error;
    gb_scene_view(scene, 0, &start, &error);
    view = start;
    gb_renderer_options options = options_of(method, GB_TERMS_BOTH, TINY_BUDGET_MS);
    gb_renderer renderer;
    if (!succeeded(gb_renderer_create(scene, &options, &context->errors, &renderer, &error),
                   &error)) {
        CHECK(0, "a renderer");
        return;
    }
    /* Still from the first frame. */
    seen still = {0};
    int final = refine_until_final(&renderer, &view, &still);
    snprintf(what, sizeof what, "%s, still: the image becomes final", name);
    CHECK(final, what);
    snprintf(what, sizeof what, "%s, still: drawn in parts (%d)", name, still.most_parts);
    CHECK(still.most_parts > 1, what);
    snprintf(what, sizeof what, "%s, still: the bytes of the whole frame", name);
    check_whole_frame(scene, context, &renderer, GB_TERMS_BOTH, &view, what);

    /* Moving for a few frames, then still. */
    seen moving = {0};
    for (int i = 0; i < 4; ++i) {
        gb_view_turn(&view, 0.05f, 0.01f);
        int changed;
        gb_renderer_refine(&renderer, &view, &changed, &error);
        moving.most_divisor =
            renderer.divisor > moving.most_divisor ? renderer.divisor : moving.most_divisor;
    }
    snprintf(what, sizeof what, "%s, moving: smaller images (1/%d)", name, moving.most_divisor);
    CHECK(moving.most_divisor > 1, what);
    CHECK(!renderer.status.converged, "moving: not final");
    final = refine_until_final(&renderer, &view, &moving);
    snprintf(what, sizeof what, "%s, moved then still: final", name);
    CHECK(final, what);
    snprintf(what, sizeof what, "%s, moved then still: the bytes of the whole frame", name);
    check_whole_frame(scene, context, &renderer, GB_TERMS_BOTH, &view, what);

    /* Another light term: drawn again, to its own whole frame. */
    gb_renderer_set_terms(&renderer, GB_TERMS_DIRECT);
    seen terms = {0};
    final = refine_until_final(&renderer, &view, &terms);
    snprintf(what, sizeof what, "%s: T starts the image again (%d frames)", name, terms.frames);
    CHECK(terms.frames > 1, what);
    snprintf(what, sizeof what, "%s, direct terms: final", name);
    CHECK(final, what);
    snprintf(what, sizeof what, "%s, direct terms: the bytes of the whole frame", name);
    check_whole_frame(scene, context, &renderer, GB_TERMS_DIRECT, &view, what);
    gb_renderer_destroy(&renderer);
}

typedef struct reports {
    int count;
    char last[1200];
} reports;

static void keep_report(void *user, const char *message)
{
    reports *r = user;
    ++r->count;
    snprintf(r->last, sizeof r->last, "%s", message);
}

/* Without a bake: direct -> flc (topo and octree skipped, told once each)
 * -> implicit -> flc-iv -> direct -> flc (told nothing more). */
static void check_cycle(const gb_scene *scene, gb_context *context)
{
    gb_renderer_options options = options_of(GB_METHOD_DIRECT, GB_TERMS_BOTH, 50.0);
    gb_renderer renderer;
    gb_error error;
    if (!succeeded(gb_renderer_create(scene, &options, &context->errors, &renderer, &error),
                   &error)) {
        CHECK(0, "a renderer");
        return;
    }
    gb_method_cycle cycle = {0};
    reports told = {0};
    const gb_method expected[] = {GB_METHOD_FLC, GB_METHOD_IMPLICIT, GB_METHOD_FLC_IV,
                                  GB_METHOD_DIRECT, GB_METHOD_FLC};
    int all = 1;
    for (int i = 0; i < 5; ++i) {
        gb_method m = gb_method_cycle_next(&cycle, &renderer, keep_report, &told);
        all = all && m == expected[i] && renderer.options.method == m;
        if (i == 0) {
            CHECK_EQ_INT(told.count, 2, "M without a bake: topo and octree skipped, told why");
            CHECK(strstr(told.last, "octree skipped: ") == told.last, "... naming the method");
        }
    }
    CHECK(all, "M cycles direct, flc, implicit, flc-iv, direct, flc");
    CHECK_EQ_INT(told.count, 2, "... and tells why a method is skipped only once");
    gb_renderer_destroy(&renderer);
}

int main(void)
{
    gb_scene scene;
    gb_context context;
    gb_error error;
    if (!load_cornell(&scene))
        return CHECK(0, "the Cornell box"), tap_done();
    if (!succeeded(gb_context_create_headless(&context, &error), &error)) {
        gb_scene_free(&scene);
        return CHECK(0, "a headless context"), tap_done();
    }
    check_method(&scene, &context, GB_METHOD_DIRECT);
    check_method(&scene, &context, GB_METHOD_IMPLICIT);
    check_cycle(&scene, &context);
    gb_context_destroy(&context);
    gb_scene_free(&scene);
    return tap_done();
}
