/* method_frames.h — a GI method's images drawn as the renderer draws them
 * (indirect_method.h), in parts, for the tests of the parts contract and of
 * a method's prepare: the renderer's own passes (shadow maps, G-buffer)
 * come from a gb_renderer of the direct method with the indirect terms only
 * (its output cleared each image), then the method's draw is called for
 * each part with the output bound, additive blending, the depth test off
 * and the scissor test on the part's band of rows, as renderer.c does.
 *
 *   method_view v;
 *   if (!method_view_open(&scene, 64, 64, &v)) ...       // the reason printed
 *   gb_indirect_setup setup = method_view_setup(&v, &parameters);
 *   void *state;
 *   if (method->create(&setup, &state, &error) == GB_OK) {
 *       method_view_images(&v, method, state, 2, 3, 0.0, &image);  // image: the caller's
 *       method->destroy(state);
 *   }
 *   method_view_close(&v);
 *
 * Each returns 0 with "# reason" printed when it cannot.
 */
#ifndef GB_METHOD_FRAMES_H
#define GB_METHOD_FRAMES_H

#include <stdio.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/indirect_method.h"
#include "../../runtime/renderer.h"
#include "headless_render.h"

typedef struct method_view {
    gb_context context;
    gb_renderer renderer;
    gb_view view;               /* the scene's first camera */
} method_view;

static inline void method_view_close(method_view *v)
{
    gb_renderer_destroy(&v->renderer);
    gb_context_destroy(&v->context);
}

static inline int method_view_open(const gb_scene *scene, int width, int height, method_view *v)
{
    memset(v, 0, sizeof *v);
    gb_renderer_options options = {.width = width, .height = height,
                                   .method = GB_METHOD_DIRECT, .terms = GB_TERMS_INDIRECT};
    gb_error error;
    if (gb_scene_view(scene, 0, &v->view, &error) != GB_OK ||
        gb_context_create_headless(&v->context, &error) != GB_OK) {
        gb_context_destroy(&v->context);
        return succeeded(GB_ERROR_INVALID, &error);
    }
    /* A renderer that fails is destroyed by its create. */
    gb_result result =
        gb_renderer_create(scene, &options, &v->context.errors, &v->renderer, &error);
    if (result != GB_OK)
        gb_context_destroy(&v->context);
    return succeeded(result, &error);
}

/* The setup the renderer would give a method; parameters outlive it. */
static inline gb_indirect_setup method_view_setup(const method_view *v,
                                                  const gb_method_parameters *parameters)
{
    const gb_renderer *r = &v->renderer;
    gb_indirect_setup setup = {
        .scene = r->scene, .gpu_scene = &r->gpu_scene, .shadows = &r->shadows,
        .parameters = parameters, .width = r->options.width, .height = r->options.height,
    };
    return setup;
}

/* Image index of the view drawn in parts; *refine: what draw returned at
 * the last part. */
static inline int method_view_image(method_view *v, const gb_indirect_method *method,
                                    void *state, uint32_t index, int parts, double budget_ms,
                                    int *refine)
{
    gb_renderer *r = &v->renderer;
    int width = r->options.width, height = r->options.height;
    gb_renderer_draw(r, &v->view);
    gb_mat4 view_matrix = gb_view_matrix(&v->view);
    gb_mat4 projection = gb_view_projection(&v->view, width, height);
    gb_indirect_frame frame = {
        .gbuffer = &r->gbuffer, .shadows = &r->shadows, .view = &v->view,
        .view_matrix = &view_matrix, .projection = &projection,
        .width = width, .height = height, .frame_index = index, .parts = parts,
        .budget_ms = budget_ms, .timings = &r->timings,
    };
    gb_output_bind(&r->output);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_SCISSOR_TEST);
    for (int part = 0; part < parts; ++part) {
        int first = part * height / parts, end = (part + 1) * height / parts;
        frame.part = part;
        frame.band[0] = first;
        frame.band[1] = end - first;
        glScissor(0, first, width, end - first);
        *refine = method->draw(state, &frame);
    }
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    gb_error error;
    return succeeded(gb_renderer_finish_frame(r, &error), &error);
}

/* Images 0 .. images - 1 each in parts, the last one read into image. */
static inline int method_view_images(method_view *v, const gb_indirect_method *method,
                                     void *state, int images, int parts, double budget_ms,
                                     gb_image *image)
{
    int refine = 0;
    for (int i = 0; i < images; ++i)
        if (!method_view_image(v, method, state, (uint32_t)i, parts, budget_ms, &refine))
            return 0;
    gb_error error;
    return succeeded(gb_renderer_read(&v->renderer, image, &error), &error);
}

/* The method made from setup (its prepare's result in setup->prepared, or
 * NULL), images drawn in parts, destroyed: the last image into image. */
static inline int method_render(method_view *v, const gb_indirect_method *method,
                                const gb_indirect_setup *setup, int images, int parts,
                                double budget_ms, gb_image *image)
{
    void *state;
    gb_error error;
    if (!succeeded(method->create(setup, &state, &error), &error))
        return 0;
    int ok = method_view_images(v, method, state, images, parts, budget_ms, image);
    method->destroy(state);
    return ok;
}

/* Whether a and b are the same size and the same bytes. */
static inline int same_image(const gb_image *a, const gb_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           !memcmp(a->pixels, b->pixels,
                   (size_t)a->width * a->height * a->channels * sizeof *a->pixels);
}

#endif
