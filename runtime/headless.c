#include "headless.h"

#include <string.h>

#include "context.h"

static gb_result render_frames(gb_renderer *renderer, const gb_view *view, int frames,
                               gb_error *error)
{
    gb_result result = GB_OK;
    for (int i = 0; i < frames && result == GB_OK; ++i) {
        gb_renderer_draw(renderer, view);
        result = gb_renderer_finish_frame(renderer, error);
    }
    return result;
}

/* As the window draws a still view: refine until frames full-resolution
 * images are shown or the image is final. */
static gb_result refine_frames(gb_renderer *renderer, const gb_view *view, int frames,
                               gb_error *error)
{
    gb_result result = GB_OK;
    while (result == GB_OK && renderer->status.images < (uint32_t)frames &&
           !renderer->status.converged) {
        int changed;
        result = gb_renderer_refine(renderer, view, &changed, error);
        if (result == GB_OK)
            result = gb_renderer_finish_frame(renderer, error);
    }
    return result;
}

/* Each pixel of image, the mean of its s x s block of samples. */
static gb_result box_filter(const gb_image *samples, int s, gb_image *image, gb_error *error)
{
    gb_result result = gb_image_allocate(image, samples->width / s, samples->height / s, 3,
                                         error);
    if (result != GB_OK)
        return result;
    float weight = 1.0f / (float)(s * s);
    for (int y = 0; y < samples->height; ++y)
        for (int x = 0; x < samples->width; ++x)
            for (int c = 0; c < 3; ++c)
                image->pixels[3 * ((size_t)(y / s) * image->width + x / s) + c] +=
                    weight * samples->pixels[3 * ((size_t)y * samples->width + x) + c];
    return GB_OK;
}

static gb_result read_frame(gb_renderer *renderer, int s, gb_image *image, gb_error *error)
{
    if (s <= 1)
        return gb_renderer_read(renderer, image, error);
    gb_image samples;
    gb_result result = gb_renderer_read(renderer, &samples, error);
    if (result == GB_OK)
        result = box_filter(&samples, s, image, error);
    gb_image_free(&samples);
    return result;
}

static void copy_timings(const gb_timings *from, gb_timings *to)
{
    if (!to)
        return;
    *to = *from;
    memset(to->queries, 0, sizeof to->queries);
}

gb_result gb_render_headless(const gb_scene *scene, const gb_headless_options *options,
                             gb_image *image, gb_timings *timings, gb_error *error)
{
    memset(image, 0, sizeof *image);
    gb_view view;
    gb_result result = gb_scene_view(scene, options->camera, &view, error);
    if (result != GB_OK)
        return result;
    gb_renderer_options renderer_options = options->renderer;
    const gb_camera *camera = &scene->cameras[options->camera];
    if (renderer_options.width <= 0 || renderer_options.height <= 0) {
        renderer_options.width = camera->width;
        renderer_options.height = camera->height;
    }
    int s = options->supersample > 1 ? options->supersample : 1;
    if (s > 16 || (long)renderer_options.width * s > 16384 ||
        (long)renderer_options.height * s > 16384)
        return gb_fail(error, GB_ERROR_ARGUMENT, "supersampling %d: too much for %dx%d", s,
                       renderer_options.width, renderer_options.height);
    renderer_options.width *= s;
    renderer_options.height *= s;
    gb_context context;
    result = gb_context_create_headless(&context, error);
    if (result != GB_OK)
        return result;
    gb_renderer renderer;
    result = gb_renderer_create(scene, &renderer_options, &context.errors, &renderer, error);
    int frames = options->frames > 0 ? options->frames : 1;
    if (result == GB_OK)
        result = renderer_options.budget_ms > 0.0
                     ? refine_frames(&renderer, &view, frames, error)
                     : render_frames(&renderer, &view, frames, error);
    if (result == GB_OK)
        result = read_frame(&renderer, s, image, error);
    copy_timings(&renderer.timings, timings);
    gb_renderer_destroy(&renderer);
    gb_context_destroy(&context);
    return result;
}
