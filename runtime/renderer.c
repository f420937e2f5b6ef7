#include "renderer.h"

#include <string.h>

#include "progress.h"

static gb_result create_passes(gb_renderer *r, gb_error *error)
{
    int width = r->options.width, height = r->options.height;
    gb_result result = gb_gpu_scene_create(r->scene, &r->gpu_scene, error);
    if (result == GB_OK)
        result = gb_gbuffer_create(width, height, &r->gbuffer, error);
    if (result == GB_OK)
        result = gb_shadow_maps_create(r->scene, &r->options.shadow, &r->shadows, error);
    if (result == GB_OK)
        result = gb_direct_light_create(&r->direct, &r->scene->environment_texture, error);
    if (result == GB_OK)
        result = gb_output_create(width, height, &r->output, error);
    return result;
}

/* Creates the GI method's state the first time the method is used. */
static gb_result prepare_method(gb_renderer *r, gb_method method, gb_error *error)
{
    const gb_indirect_method *indirect = gb_method_indirect(method);
    if (!indirect || r->method_state[method])
        return GB_OK;
    gb_indirect_setup setup = {
        .scene = r->scene,
        .gpu_scene = &r->gpu_scene,
        .shadows = &r->shadows,
        .bake = r->options.bake,
        .parameters = &r->options.parameters,
        .width = r->options.width,
        .height = r->options.height,
        .progress = r->options.progress,
        .progress_user = r->options.progress_user,
    };
    gb_result result = indirect->create(&setup, &r->method_state[method], error);
    if (result == GB_OK)
        result = gb_gl_check(r->errors, gb_method_name(method), error);
    return result;
}

gb_result gb_renderer_create(const gb_scene *scene, const gb_renderer_options *options,
                             gb_gl_errors *errors, gb_renderer *renderer, gb_error *error)
{
    memset(renderer, 0, sizeof *renderer);
    if (options->width <= 0 || options->height <= 0 || options->width > 16384 ||
        options->height > 16384)
        return gb_fail(error, GB_ERROR_ARGUMENT, "resolution %dx%d is not in 1..16384",
                       options->width, options->height);
    gb_result result = gb_method_check(options->method, error);
    if (result != GB_OK)
        return result;
    renderer->scene = scene;
    renderer->options = *options;
    renderer->errors = errors;
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);   /* reversed depth (mat4.h) */
    result = create_passes(renderer, error);
    if (result == GB_OK)
        result = prepare_method(renderer, options->method, error);
    if (result == GB_OK)
        result = gb_gl_check(errors, "renderer setup", error);
    if (result != GB_OK) {
        gb_renderer_destroy(renderer);
        return result;
    }
    gb_timings_create(&renderer->timings);
    renderer->timings.finish_passes = options->finish_passes;
    return GB_OK;
}

gb_result gb_renderer_resize(gb_renderer *renderer, int width, int height, gb_error *error)
{
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return gb_fail(error, GB_ERROR_ARGUMENT, "resolution %dx%d is not in 1..16384", width,
                       height);
    gb_result result = gb_gbuffer_resize(&renderer->gbuffer, width, height, error);
    if (result == GB_OK)
        result = gb_output_resize(&renderer->output, width, height, error);
    if (result == GB_OK) {
        renderer->options.width = width;
        renderer->options.height = height;
    }
    return result;
}

gb_result gb_renderer_set_method(gb_renderer *renderer, gb_method method, gb_error *error)
{
    gb_result result = gb_method_check(method, error);
    if (result == GB_OK)
        result = prepare_method(renderer, method, error);
    if (result == GB_OK)
        renderer->options.method = method;
    return result;
}

void gb_renderer_set_terms(gb_renderer *renderer, gb_terms terms)
{
    renderer->options.terms = terms;
}

static void draw_shadow_maps(gb_renderer *r)
{
    if (r->shadows.drawn || r->options.no_shadows)
        return;
    gb_timings_begin(&r->timings, GB_PASS_SHADOW_MAPS);
    gb_shadow_maps_draw(&r->shadows, &r->gpu_scene);
    gb_timings_end(&r->timings, GB_PASS_SHADOW_MAPS);
}

static void draw_direct_light(gb_renderer *r, const gb_view *view)
{
    gb_direct_inputs inputs = {
        .gbuffer = &r->gbuffer,
        .shadows = &r->shadows,
        .view = view,
        .shadows_enabled = !r->options.no_shadows,
    };
    memcpy(inputs.environment, r->scene->environment, sizeof inputs.environment);
    gb_timings_begin(&r->timings, GB_PASS_DIRECT_LIGHT);
    gb_direct_light_draw(&r->direct, &inputs);
    gb_timings_end(&r->timings, GB_PASS_DIRECT_LIGHT);
}

/* The GI method's indirect light, added onto the output. */
static void draw_indirect_light(gb_renderer *r, const gb_view *view, const gb_mat4 *view_matrix,
                                const gb_mat4 *projection)
{
    gb_method method = r->options.method;
    const gb_indirect_method *indirect = gb_method_indirect(method);
    if (!indirect || !r->method_state[method])
        return;
    gb_indirect_frame frame = {
        .gbuffer = &r->gbuffer,
        .shadows = &r->shadows,
        .view = view,
        .view_matrix = view_matrix,
        .projection = projection,
        .width = r->options.width,
        .height = r->options.height,
        .frame_index = r->method_frames[method]++,
        .part = 0,
        .parts = 1,
        .band = {0, r->options.height},
        .timings = &r->timings,
    };
    gb_output_bind(&r->output);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    gb_timings_begin(&r->timings, GB_PASS_INDIRECT_LIGHT);
    indirect->draw(r->method_state[method], &frame);
    gb_timings_end(&r->timings, GB_PASS_INDIRECT_LIGHT);
    gb_output_bind(&r->output);
    glDisable(GL_BLEND);
}

void gb_renderer_draw(gb_renderer *r, const gb_view *view)
{
    r->frame_start = gb_seconds();
    draw_shadow_maps(r);
    gb_mat4 view_matrix = gb_view_matrix(view);
    gb_mat4 projection = gb_view_projection(view, r->options.width, r->options.height);
    gb_timings_begin(&r->timings, GB_PASS_GBUFFER);
    gb_gbuffer_draw(&r->gbuffer, &r->gpu_scene, &view_matrix, &projection);
    gb_timings_end(&r->timings, GB_PASS_GBUFFER);
    gb_output_bind(&r->output);
    if (r->options.terms == GB_TERMS_INDIRECT)
        gb_output_clear(&r->output);
    else
        draw_direct_light(r, view);
    if (r->options.terms != GB_TERMS_DIRECT)
        draw_indirect_light(r, view, &view_matrix, &projection);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void gb_renderer_present(gb_renderer *renderer, int width, int height)
{
    gb_timings_begin(&renderer->timings, GB_PASS_PRESENT);
    gb_output_present(&renderer->output, width, height);
    gb_timings_end(&renderer->timings, GB_PASS_PRESENT);
}

gb_result gb_renderer_finish_frame(gb_renderer *renderer, gb_error *error)
{
    glFinish();
    gb_timings_end_frame(&renderer->timings, 1e3 * (gb_seconds() - renderer->frame_start));
    return gb_gl_check(renderer->errors, "frame", error);
}

gb_result gb_renderer_read(gb_renderer *renderer, gb_image *image, gb_error *error)
{
    gb_result result = gb_output_read(&renderer->output, image, error);
    if (result == GB_OK)
        result = gb_gl_check(renderer->errors, "reading the frame back", error);
    if (result != GB_OK)
        gb_image_free(image);
    return result;
}

void gb_renderer_destroy(gb_renderer *renderer)
{
    for (int m = 0; m < GB_METHOD_COUNT; ++m) {
        const gb_indirect_method *indirect = gb_method_indirect((gb_method)m);
        if (indirect && renderer->method_state[m])
            indirect->destroy(renderer->method_state[m]);
    }
    gb_timings_destroy(&renderer->timings);
    gb_output_destroy(&renderer->output);
    gb_direct_light_destroy(&renderer->direct);
    gb_shadow_maps_destroy(&renderer->shadows);
    gb_gbuffer_destroy(&renderer->gbuffer);
    gb_gpu_scene_destroy(&renderer->gpu_scene);
    memset(renderer, 0, sizeof *renderer);
}
