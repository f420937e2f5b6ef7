/* headless_frames.h — what the per-pass benchmarks (flc_passes,
 * topo_passes) share: a renderer on a headless GL context, seen from the
 * scene's first camera, drawn a frame at a time so that the caller can read
 * its method's pass times after the first frame (the one that compiles the
 * shaders, left out of the means). Bench code, included by those programs.
 *
 *   headless_frames h;
 *   gb_result result = headless_frames_create(scene, &options, &h, error);
 *   if (result != GB_OK)
 *       return result;              // nothing to destroy
 *   for (int i = 0; i < frames && result == GB_OK; ++i)
 *       result = headless_frames_draw(&h, error);
 *   ...                             // h.renderer's timings and method_state
 *   headless_frames_destroy(&h);
 */
#ifndef GB_HEADLESS_FRAMES_H
#define GB_HEADLESS_FRAMES_H

#include "../runtime/context.h"
#include "../runtime/renderer.h"

typedef struct headless_frames {
    gb_view view;
    gb_context context;
    gb_renderer renderer;
} headless_frames;

/* The view, the context and the renderer of options; on failure nothing is
 * left to destroy. */
static gb_result headless_frames_create(const gb_scene *scene, const gb_renderer_options *options,
                                        headless_frames *h, gb_error *error)
{
    gb_result result = gb_scene_view(scene, 0, &h->view, error);
    if (result == GB_OK)
        result = gb_context_create_headless(&h->context, error);
    if (result != GB_OK)
        return result;
    result = gb_renderer_create(scene, options, &h->context.errors, &h->renderer, error);
    if (result != GB_OK)
        gb_context_destroy(&h->context);
    return result;
}

/* One frame: drawn, then its timings collected and GL errors checked. */
static gb_result headless_frames_draw(headless_frames *h, gb_error *error)
{
    gb_renderer_draw(&h->renderer, &h->view);
    return gb_renderer_finish_frame(&h->renderer, error);
}

static void headless_frames_destroy(headless_frames *h)
{
    gb_renderer_destroy(&h->renderer);
    gb_context_destroy(&h->context);
}

#endif
