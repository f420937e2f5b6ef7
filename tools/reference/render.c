/* render.c — gb_reference_render: the image in 16x16 tiles handed out to
 * threads, each pixel drawing from its own PCG32 stream (stream = pixel
 * index), so the image is the same whatever the number of threads. */
#include <math.h>
#include <stdatomic.h>
#include <string.h>
#include <time.h>

#include "camera.h"
#include "integrator.h"
#include "reference.h"
#include "surface.h"
#include "work_queue.h"

enum { TILE_SIZE = GB_REFERENCE_TILE_SIZE, MAX_RESOLUTION = 32768 };

typedef struct render_job {
    const gb_integrator *integrator;
    const gb_camera_frame *frame;
    gb_image *image;
    int spp;
    uint64_t seed;
    int tiles_x, tile_count;
    uint32_t split, split_count;        /* --tile I/N: I, N */
    atomic_uint_fast64_t rays;
    atomic_uint_fast64_t nonfinite;
} render_job;

static const char *const MODE_NAMES[] = {
    [GB_REFERENCE_FULL] = "full",
    [GB_REFERENCE_DIRECT] = "direct",
    [GB_REFERENCE_INDIRECT1] = "indirect1",
    [GB_REFERENCE_INDIRECT1_UNSHADOWED] = "indirect1-unshadowed",
    [GB_REFERENCE_VPL] = "vpl",
};
enum { MODE_COUNT = sizeof MODE_NAMES / sizeof MODE_NAMES[0] };

gb_result gb_reference_mode_parse(const char *name, gb_reference_mode *mode, gb_error *error)
{
    for (unsigned i = 0; i < MODE_COUNT; ++i)
        if (strcmp(name, MODE_NAMES[i]) == 0) {
            *mode = (gb_reference_mode)i;
            return GB_OK;
        }
    return gb_fail(error, GB_ERROR_ARGUMENT, "unknown mode \"%s\" (full, direct, indirect1, "
                   "indirect1-unshadowed, vpl)", name);
}

static void render_pixel(render_job *job, int x, int y, gb_path_state *state,
                         uint64_t *nonfinite)
{
    const gb_camera_frame *frame = job->frame;
    state->rng = gb_random_make(job->seed, (uint64_t)y * (uint64_t)frame->width + (uint64_t)x);
    gb_vec3 sum = {0.0f, 0.0f, 0.0f};
    double total[3] = {0.0, 0.0, 0.0};
    int kept = 0;
    for (int s = 0; s < job->spp; ++s) {
        float jx = gb_random_float(&state->rng), jy = gb_random_float(&state->rng);
        gb_vec3 dir = gb_camera_direction(frame, (float)x + jx, (float)y + jy);
        sum = gb_integrator_radiance(job->integrator, frame->position, dir, state);
        if (!isfinite(sum.x + sum.y + sum.z)) {
            ++*nonfinite;
            continue;
        }
        total[0] += sum.x;
        total[1] += sum.y;
        total[2] += sum.z;
        ++kept;
    }
    float *pixel = &job->image->pixels[3 * ((size_t)y * (size_t)frame->width + (size_t)x)];
    for (int c = 0; c < 3; ++c)
        pixel[c] = kept ? (float)(total[c] / kept) : 0.0f;
}

/* A work-queue item: one tile. */
static int render_tile(void *context, uint64_t item)
{
    render_job *job = context;
    int tile = (int)item;
    if (job->split_count > 1 && (uint32_t)tile % job->split_count != job->split)
        return 0;   /* another --tile's */
    int x0 = (tile % job->tiles_x) * TILE_SIZE, y0 = (tile / job->tiles_x) * TILE_SIZE;
    int x1 = x0 + TILE_SIZE < job->frame->width ? x0 + TILE_SIZE : job->frame->width;
    int y1 = y0 + TILE_SIZE < job->frame->height ? y0 + TILE_SIZE : job->frame->height;
    gb_path_state state = {.rays = 0};
    uint64_t nonfinite = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            render_pixel(job, x, y, &state, &nonfinite);
    atomic_fetch_add(&job->rays, state.rays);
    atomic_fetch_add(&job->nonfinite, nonfinite);
    return 0;
}

static gb_result run_threads(render_job *job, const gb_reference_options *options,
                             gb_error *error)
{
    gb_work_queue queue = {.item_count = (uint64_t)job->tile_count, .threads = options->threads,
                           .progress = options->progress,
                           .progress_user = options->progress_user};
    if (gb_work_queue_run(&queue, render_tile, job, NULL) != GB_OK)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "reference: interrupted");
    return GB_OK;
}

/* ---- options -------------------------------------------------------------- */

typedef struct settings {
    int spp, width, height, bounces;
} settings;

static gb_result check_vpls(const gb_scene *scene, const gb_reference_options *options,
                            gb_error *error)
{
    if (options->mode != GB_REFERENCE_VPL)
        return GB_OK;
    if (!options->vpls)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: vpl mode needs a VPL set");
    gb_result result = gb_vpl_check(options->vpls, "VPL set", error);
    if (result == GB_OK)
        result = gb_vpl_check_scene(options->vpls, scene->hash, "VPL set", error);
    return result;
}

static gb_result resolve_options(const gb_scene *scene, const gb_reference_options *options,
                                 settings *out, gb_error *error)
{
    if ((unsigned)options->mode >= MODE_COUNT)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: unknown mode %d", options->mode);
    if (options->tile_count > 1 && options->tile >= options->tile_count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: tile %u of %u", options->tile,
                       options->tile_count);
    if (options->camera >= scene->camera_count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: no camera %u (the scene has %u)",
                       (unsigned)options->camera, (unsigned)scene->camera_count);
    const gb_camera *camera = &scene->cameras[options->camera];
    int custom = options->width > 0 || options->height > 0;
    out->width = custom ? options->width : camera->width;
    out->height = custom ? options->height : camera->height;
    if (out->width <= 0 || out->height <= 0 || out->width > MAX_RESOLUTION ||
        out->height > MAX_RESOLUTION)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: resolution %dx%d is not in 1..%d",
                       out->width, out->height, MAX_RESOLUTION);
    int default_spp = options->mode == GB_REFERENCE_VPL ? GB_REFERENCE_DEFAULT_VPL_SPP
                                                         : GB_REFERENCE_DEFAULT_SPP;
    out->spp = options->spp ? options->spp : default_spp;
    out->bounces = options->bounces ? options->bounces : GB_REFERENCE_DEFAULT_BOUNCES;
    if (out->spp < 1 || out->bounces < 1 || options->min_bounces < 0 ||
        options->min_bounces > out->bounces)
        return gb_fail(error, GB_ERROR_ARGUMENT, "reference: need spp >= 1 and "
                       "0 <= min bounces <= bounces (got %d, %d, %d)", out->spp,
                       options->min_bounces, out->bounces);
    return check_vpls(scene, options, error);
}

/* ---- the render ------------------------------------------------------------ */

typedef struct renderer {
    gb_path_tables tables;
    gb_integrator integrator;
    gb_camera_frame frame;
} renderer;

static gb_result prepare(const gb_scene *scene, const gb_reference_options *options,
                         const settings *settings, renderer *r, gb_error *error)
{
    gb_result result = gb_camera_frame_make(&scene->cameras[options->camera], settings->width,
                                            settings->height, &r->frame, error);
    if (result == GB_OK)
        result = gb_path_tables_build(scene, options->threads, &r->tables, error);
    r->integrator = (gb_integrator){
        .paths = gb_path_tracer_over(scene, &r->tables),
        .vpls = options->vpls,
        .mode = options->mode,
        .min_bounces = options->min_bounces,
        .max_bounces = settings->bounces,
    };
    return result;
}

static void release(renderer *r)
{
    gb_path_tables_free(&r->tables);
}

static gb_result render_image(renderer *r, const gb_reference_options *options,
                              const settings *settings, gb_image *image,
                              gb_reference_stats *stats, gb_error *error)
{
    render_job job = {
        .integrator = &r->integrator,
        .frame = &r->frame,
        .image = image,
        .spp = settings->spp,
        .seed = options->seed,
        .tiles_x = (settings->width + TILE_SIZE - 1) / TILE_SIZE,
        .split = options->tile,
        .split_count = options->tile_count,
    };
    job.tile_count = job.tiles_x * ((settings->height + TILE_SIZE - 1) / TILE_SIZE);
    double start = gb_seconds(), cpu_start = gb_cpu_seconds();
    gb_result result = run_threads(&job, options, error);
    stats->seconds = gb_seconds() - start;
    stats->cpu_seconds = gb_cpu_seconds() - cpu_start;
    stats->rays = atomic_load(&job.rays);
    stats->nonfinite_samples = atomic_load(&job.nonfinite);
    stats->samples = (uint64_t)settings->width * (uint64_t)settings->height * settings->spp;
    return result;
}

gb_result gb_reference_render(const gb_scene *scene, const gb_reference_options *options,
                              gb_image *image, gb_reference_stats *stats, gb_error *error)
{
    gb_reference_stats unused;
    stats = stats ? stats : &unused;
    *stats = (gb_reference_stats){0};
    *image = (gb_image){0};
    settings settings = {0};
    gb_result result = resolve_options(scene, options, &settings, error);
    if (result != GB_OK)
        return result;
    renderer r = {0};
    double start = gb_seconds();
    result = prepare(scene, options, &settings, &r, error);
    stats->build_seconds = gb_seconds() - start;
    if (result == GB_OK)
        result = gb_image_allocate(image, settings.width, settings.height, 3, error);
    if (result == GB_OK)
        result = render_image(&r, options, &settings, image, stats, error);
    if (result != GB_OK)
        gb_image_free(image);
    release(&r);
    return result;
}
