#include "renderer.h"

#include <math.h>
#include <string.h>

#include "background_setup.h"
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

/* The next refine draws a new image, and the shown one is final no more. */
static void start_again(gb_renderer *r)
{
    r->restart = 1;
    r->status.converged = 0;
}

static gb_indirect_setup setup_of(const gb_renderer *r)
{
    return (gb_indirect_setup){
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
}

/* The method's create, given what its prepare made (or NULL). */
static gb_result create_method(gb_renderer *r, gb_method method, void *prepared,
                               gb_error *error)
{
    gb_indirect_setup setup = setup_of(r);
    setup.prepared = prepared;
    gb_result result =
        gb_method_indirect(method)->create(&setup, &r->method_state[method], error);
    if (result == GB_OK)
        result = gb_gl_check(r->errors, gb_method_name(method), error);
    return result;
}

/* Drops the setup running on its thread, if any. */
static void cancel_setup(gb_renderer *r)
{
    gb_background_setup_cancel(r->setup_job);
    r->setup_job = NULL;
    r->status.setup_fraction = -1.0;
}

/* Creates the GI method's state the first time the method is used: at once,
 * or with background_setup its prepare on a thread (the frames meanwhile
 * draw no indirect light, gb_renderer_refine creates it once prepared). */
static gb_result prepare_method(gb_renderer *r, gb_method method, gb_error *error)
{
    const gb_indirect_method *indirect = gb_method_indirect(method);
    if (r->setup_job && r->setup_method != method)
        cancel_setup(r);
    if (!indirect || r->method_state[method] || r->setup_job)
        return GB_OK;
    if (!r->options.background_setup || !indirect->prepare)
        return create_method(r, method, NULL, error);
    gb_indirect_setup setup = setup_of(r);
    gb_result result = gb_background_setup_start(indirect, &setup, &r->setup_job, error);
    r->setup_method = method;
    r->status.setup_fraction = 0.0;
    return result;
}

gb_result gb_renderer_poll_setup(gb_renderer *r, gb_error *error)
{
    int finished = 0;
    if (!r->setup_job)
        return GB_OK;
    r->status.setup_fraction = gb_background_setup_progress(r->setup_job, &finished);
    if (!finished)
        return GB_OK;
    void *prepared = NULL;
    gb_result result = gb_background_setup_finish(r->setup_job, &prepared, error);
    r->setup_job = NULL;
    r->status.setup_fraction = -1.0;
    if (result == GB_OK)
        result = create_method(r, r->setup_method, prepared, error);
    else
        gb_method_indirect(r->setup_method)->discard(prepared);
    start_again(r);
    return result;
}

gb_result gb_renderer_create(const gb_scene *scene, const gb_renderer_options *options,
                             gb_gl_errors *errors, gb_renderer *renderer, gb_error *error)
{
    memset(renderer, 0, sizeof *renderer);
    renderer->status.setup_fraction = -1.0;
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

/* The G-buffer and the output at the full size divided by divisor. */
static gb_result fit_size(gb_renderer *r, int divisor, gb_error *error)
{
    int width = r->options.width / divisor, height = r->options.height / divisor;
    width = width > 0 ? width : 1;
    height = height > 0 ? height : 1;
    r->divisor = divisor;
    gb_result result = gb_gbuffer_resize(&r->gbuffer, width, height, error);
    if (result == GB_OK && !r->output.framebuffer)
        result = gb_output_create(width, height, &r->output, error);
    else if (result == GB_OK)
        result = gb_output_resize(&r->output, width, height, error);
    return result;
}

gb_result gb_renderer_resize(gb_renderer *renderer, int width, int height, gb_error *error)
{
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return gb_fail(error, GB_ERROR_ARGUMENT, "resolution %dx%d is not in 1..16384", width,
                       height);
    if (width == renderer->options.width && height == renderer->options.height)
        return GB_OK;
    renderer->options.width = width;
    renderer->options.height = height;
    start_again(renderer);
    /* gb_renderer_refine sizes each image itself. */
    return renderer->options.budget_ms > 0.0 ? GB_OK : fit_size(renderer, 1, error);
}

gb_result gb_renderer_set_method(gb_renderer *renderer, gb_method method, gb_error *error)
{
    gb_result result = gb_method_check(method, error);
    if (result == GB_OK)
        result = prepare_method(renderer, method, error);
    if (result == GB_OK) {
        renderer->options.method = method;
        start_again(renderer);
    }
    return result;
}

void gb_renderer_set_terms(gb_renderer *renderer, gb_terms terms)
{
    renderer->options.terms = terms;
    start_again(renderer);
}

/* The maps once, and the cascades for view unless it moves. */
static void draw_shadow_maps(gb_renderer *r, const gb_view *view)
{
    if (r->options.no_shadows)
        return;
    gb_timings_begin(&r->timings, GB_PASS_SHADOW_MAPS);
    gb_shadow_maps_draw(&r->shadows, &r->gpu_scene);
    if (!r->moving)
        gb_shadow_maps_fit_view(&r->shadows, r->scene, &r->gpu_scene, view, r->gbuffer.width,
                                r->gbuffer.height);
    gb_timings_end(&r->timings, GB_PASS_SHADOW_MAPS);
}

static void draw_direct_light(gb_renderer *r, const gb_view *view)
{
    gb_direct_inputs inputs = {
        .gbuffer = &r->gbuffer,
        .shadows = &r->shadows,
        .view = view,
        .shadows_enabled = !r->options.no_shadows,
        .cascades = !r->moving,
    };
    memcpy(inputs.environment, r->scene->environment, sizeof inputs.environment);
    gb_timings_begin(&r->timings, GB_PASS_DIRECT_LIGHT);
    gb_direct_light_draw(&r->direct, &inputs);
    gb_timings_end(&r->timings, GB_PASS_DIRECT_LIGHT);
}

/* The GI method's indirect light, added onto the output within the
 * scissor box; the method's gb_image_state. */
static int draw_indirect_light(gb_renderer *r, const gb_view *view, const gb_mat4 *view_matrix,
                               const gb_mat4 *projection, int part, int parts,
                               const int band[2], double budget_ms)
{
    gb_method method = r->options.method;
    const gb_indirect_method *indirect = gb_method_indirect(method);
    if (!indirect || !r->method_state[method])
        return 0;
    gb_indirect_frame frame = {
        .gbuffer = &r->gbuffer,
        .shadows = &r->shadows,
        .view = view,
        .view_matrix = view_matrix,
        .projection = projection,
        .width = r->gbuffer.width,
        .height = r->gbuffer.height,
        .frame_index = r->method_frames[method],
        .part = part,
        .parts = parts,
        .band = {band[0], band[1]},
        .budget_ms = budget_ms,
        .timings = &r->timings,
    };
    gb_output_bind(&r->output);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    gb_timings_begin(&r->timings, GB_PASS_INDIRECT_LIGHT);
    int state = indirect->draw(r->method_state[method], &frame);
    gb_timings_end(&r->timings, GB_PASS_INDIRECT_LIGHT);
    gb_output_bind(&r->output);
    glDisable(GL_BLEND);
    if (part + 1 == parts)
        ++r->method_frames[method];
    return state;
}

/* The rows of part (of parts) of an image height rows high, from the top:
 * band[0] the first in GL's bottom-up rows, band[1] how many. */
static void band_of_part(int part, int parts, int height, int band[2])
{
    int top = (int)((long)height * part / parts), bottom = (int)((long)height * (part + 1) / parts);
    band[0] = height - bottom;
    band[1] = bottom - top;
}

/* One part of the image: at part 0 the shadow maps (once) and the G-buffer;
 * then the direct and the indirect light within the part's band. budget_ms:
 * the method's (indirect_method.h), 0 for whole images. The image's
 * gb_image_state. */
static int draw_part(gb_renderer *r, const gb_view *view, int part, int parts,
                     double budget_ms)
{
    int width = r->gbuffer.width, height = r->gbuffer.height;
    gb_mat4 view_matrix = gb_view_matrix(view);
    gb_mat4 projection = gb_view_projection(view, width, height);
    if (part == 0) {
        draw_shadow_maps(r, view);
        gb_timings_begin(&r->timings, GB_PASS_GBUFFER);
        gb_gbuffer_draw(&r->gbuffer, &r->gpu_scene, &view_matrix, &projection);
        gb_timings_end(&r->timings, GB_PASS_GBUFFER);
    }
    int band[2];
    band_of_part(part, parts, height, band);
    gb_output_bind(&r->output);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, band[0], width, band[1]);
    if (r->options.terms == GB_TERMS_INDIRECT)
        gb_output_clear(&r->output);
    else
        draw_direct_light(r, view);
    int state = GB_IMAGE_FINAL;
    if (r->options.terms != GB_TERMS_DIRECT)
        state = draw_indirect_light(r, view, &view_matrix, &projection, part, parts, band,
                                    budget_ms);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return state;
}

/* The status of a complete image at full / divisor: state, the method's
 * gb_image_state. */
static void count_image(gb_renderer *r, int divisor, int state)
{
    r->status.divisor = divisor;
    if (divisor > 1)
        r->status.images = 0;
    else if (state != GB_IMAGE_PROVISIONAL)
        ++r->status.images;
    r->status.provisional = state == GB_IMAGE_PROVISIONAL;
    r->status.converged = divisor == 1 && state == GB_IMAGE_FINAL;
}

void gb_renderer_draw(gb_renderer *r, const gb_view *view)
{
    r->frame_start = gb_seconds();
    r->moving = 0;
    int state = draw_part(r, view, 0, 1, 0.0);
    if (r->restart || memcmp(view, &r->view, sizeof *view) != 0)
        r->status.images = 0;
    r->view = *view;
    r->restart = 0;
    r->status.part = 0;
    r->status.parts = 1;
    count_image(r, 1, state);
}

/* The image drawn is complete: it becomes the shown one. */
static void show_image(gb_renderer *r, int state)
{
    gb_output drawn = r->output;
    r->output = r->shown;
    r->shown = drawn;
    r->part = 0;
    count_image(r, r->divisor, state);
}

/* The next parts of the image being drawn (planned at its part 0) while
 * they fit the budget; at least one. Nonzero when the image is complete. */
static int draw_parts(gb_renderer *r, const gb_view *view, int *state)
{
    double elapsed = 0.0, part_ms;
    do {
        double start = gb_seconds();
        *state = draw_part(r, view, r->part, r->parts, r->options.budget_ms);
        glFinish();
        part_ms = 1e3 * (gb_seconds() - start);
        elapsed += part_ms;
        ++r->part;
    } while (r->part < r->parts && elapsed + part_ms <= r->options.budget_ms);
    r->image_ms += elapsed;
    return r->part == r->parts;
}

/* Plans the next image of a still view: twice the resolution of the shown
 * one, up to the full; in as many parts as fit the budget. */
static gb_result plan_image(gb_renderer *r, int moving, gb_error *error)
{
    int divisor = moving ? gb_frame_budget_divisor(&r->budget, r->options.width,
                                                   r->options.height)
                         : (r->status.divisor > 1 ? r->status.divisor / 2 : 1);
    gb_result result = fit_size(r, divisor, error);
    r->moving = moving;
    r->part = 0;
    r->parts = moving ? 1
                      : gb_frame_budget_parts(&r->budget, r->gbuffer.width, r->gbuffer.height);
    r->image_ms = 0.0;
    return result;
}

gb_result gb_renderer_refine(gb_renderer *r, const gb_view *view, int *changed,
                             gb_error *error)
{
    *changed = 0;
    r->frame_start = gb_seconds();
    r->budget.budget_ms = r->options.budget_ms;
    if (memcmp(view, &r->view, sizeof *view) != 0) {
        r->view = *view;
        start_again(r);
    }
    int moving = r->restart;
    if (!moving && r->status.converged)
        return GB_OK;
    r->restart = 0;
    gb_result result = GB_OK;
    if (moving || r->part == 0)
        result = plan_image(r, moving, error);
    int state = GB_IMAGE_FINAL;
    if (result == GB_OK && draw_parts(r, view, &state)) {
        gb_frame_budget_measure(&r->budget, r->image_ms,
                                (double)r->gbuffer.width * (double)r->gbuffer.height);
        show_image(r, state);
        *changed = 1;
    }
    r->status.part = r->part;
    r->status.parts = r->part ? r->parts : 1;
    return result;
}

/* The image to present or read: refine's last complete one, else the output. */
static const gb_output *image_of(const gb_renderer *r)
{
    return r->shown.framebuffer ? &r->shown : &r->output;
}

void gb_renderer_present(gb_renderer *renderer, int width, int height)
{
    gb_timings_begin(&renderer->timings, GB_PASS_PRESENT);
    gb_output_present(image_of(renderer), width, height);
    gb_timings_end(&renderer->timings, GB_PASS_PRESENT);
}

gb_result gb_renderer_finish_frame(gb_renderer *renderer, gb_error *error)
{
    glFinish();
    gb_timings_end_frame(&renderer->timings, 1e3 * (gb_seconds() - renderer->frame_start));
    return gb_gl_check(renderer->errors, "frame", error);
}

int gb_renderer_point_at(gb_renderer *r, const gb_view *view, float x, float y,
                         gb_vec3 *point)
{
    int width = r->gbuffer.width, height = r->gbuffer.height;
    int column = (int)(x * (float)width), row = height - 1 - (int)(y * (float)height);
    if (column < 0 || column >= width || row < 0 || row >= height)
        return 0;
    float depth = 0.0f;
    glGetTextureSubImage(r->gbuffer.depth, 0, column, row, 0, 1, 1, 1, GL_DEPTH_COMPONENT,
                         GL_FLOAT, sizeof depth, &depth);
    if (!(depth > 0.0f))
        return 0;
    /* gbuffer_world_position.glsl: view z = -near / depth along the pixel's ray. */
    float distance = view->near / depth;
    float tan_y = tanf(0.5f * view->fov_y * (float)M_PI / 180.0f);
    float ndc_x = 2.0f * ((float)column + 0.5f) / (float)width - 1.0f;
    float ndc_y = 2.0f * ((float)row + 0.5f) / (float)height - 1.0f;
    gb_vec3 ray = gb_vec3_add(view->forward,
                              gb_vec3_scale(view->right, ndc_x * tan_y * width / height));
    ray = gb_vec3_add(ray, gb_vec3_scale(view->up, ndc_y * tan_y));
    *point = gb_vec3_add(view->position, gb_vec3_scale(ray, distance));
    return 1;
}

gb_result gb_renderer_read(gb_renderer *renderer, gb_image *image, gb_error *error)
{
    gb_result result = gb_output_read(image_of(renderer), image, error);
    if (result == GB_OK)
        result = gb_gl_check(renderer->errors, "reading the frame back", error);
    if (result != GB_OK)
        gb_image_free(image);
    return result;
}

void gb_renderer_destroy(gb_renderer *renderer)
{
    cancel_setup(renderer);
    for (int m = 0; m < GB_METHOD_COUNT; ++m) {
        const gb_indirect_method *indirect = gb_method_indirect((gb_method)m);
        if (indirect && renderer->method_state[m])
            indirect->destroy(renderer->method_state[m]);
    }
    gb_timings_destroy(&renderer->timings);
    gb_output_destroy(&renderer->output);
    gb_output_destroy(&renderer->shown);
    gb_direct_light_destroy(&renderer->direct);
    gb_shadow_maps_destroy(&renderer->shadows);
    gb_gbuffer_destroy(&renderer->gbuffer);
    gb_gpu_scene_destroy(&renderer->gpu_scene);
    memset(renderer, 0, sizeof *renderer);
}
