/* raw_path_rate.h — the like-for-like yardstick of the reference renderer:
 * Embree's raw rate on rays of the kinds, the order and the coherence that
 * the reference's full mode traces, with nothing else done. Bench code,
 * included by bench/reference_rate.c, which times it beside the reference
 * in the same run.
 *
 * The paths (tools/reference/integrator.c, trace_path, without the shading):
 *   - camera rays through the reference's pixels, samples and order: 16x16
 *     tiles handed out to the threads by the same work queue, pixels in row
 *     order in a tile, spp samples a pixel jittered from the pixel's PCG32
 *     stream, directions from gb_camera_direction (common/camera.h);
 *   - at each hit, the reference's shadow rays (rtcOccluded1): one toward a
 *     point of an area light picked by gb_light_table_sample, and one toward
 *     each point, spot and directional light that gb_delta_light_arriving
 *     says arrives there (common/light_sampling.h), each only when the light
 *     is on the side of the surface the ray came from;
 *   - then one bounce ray (rtcIntersect1), cosine-distributed about the
 *     geometric normal turned toward the incoming ray, until a ray misses or
 *     GB_PATH_ROULETTE_START (3) bounces, or the reference's bounce
 *     count if smaller, are done.
 * Those first bounces are the part of the reference's paths that does not
 * depend on the materials. Past them the reference plays Russian roulette
 * on its throughput, which needs the materials, so here the paths stop.
 * On the default scenes (320x240, 4 spp) that leaves the rays per sample
 * within 10% of the reference's (here / there: 3.8 / 4.1 Cornell, 1.7 /
 * 1.6 bunny, 7.5 / 7.9 Sponza); what is left out are the reference's
 * deepest, least coherent rays. reference_rate prints both programs' rays per sample.
 * Without roulette at all (64 bounces) the mix is far from the reference's:
 * 9.1 rays a sample on the Cornell box, 2.5 on the bunny, 87 on Sponza. No
 * surface records, materials, textures, BRDFs or weights: the hit point is
 * origin + t dir, the normal is Embree's Ng and the ray offset
 * gb_ray_offset of the point. The timed loop does make each ray (a few
 * random numbers, a camera direction, a light point, a cosine direction),
 * as any renderer of these paths must; rays are not drawn in advance as
 * raw_rate's are, since each depends on the hit before it.
 *
 * Timed like raw_rate (bench/raw_ray_rate.h): wall and process CPU time
 * around the work queue, without the BVH build (the Embree scene is built
 * exactly as the reference builds it).
 */
#ifndef GB_RAW_PATH_RATE_H
#define GB_RAW_PATH_RATE_H

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>

#include "raw_ray_rate.h"
#include "camera.h"
#include "../tools/reference/reference.h"
#include "embree_scene.h"
#include "light_sampling.h"
#include "path_tracing.h"
#include "random.h"
#include "surface.h"
#include "work_queue.h"

enum { PATH_TILE_SIZE = 16 };   /* tools/reference/render.c, TILE_SIZE */

typedef struct path_job {
    RTCScene rays;
    const gb_scene *scene;
    const gb_surface_table *surfaces;
    const gb_light_table *lights;
    gb_camera_frame frame;
    int spp, bounces, tiles_x;
    uint64_t seed;
    atomic_uint_fast64_t ray_count;
} path_job;

/* A hit reduced to what the next rays need. */
typedef struct path_vertex {
    gb_vec3 position;
    gb_vec3 ng;                 /* unit geometric normal, toward the incoming ray */
    float offset;               /* how far new origins move along ng */
} path_vertex;

static struct RTCRay path_ray(gb_vec3 origin, gb_vec3 dir, float tfar)
{
    return (struct RTCRay){.org_x = origin.x, .org_y = origin.y, .org_z = origin.z,
                           .dir_x = dir.x, .dir_y = dir.y, .dir_z = dir.z,
                           .tnear = 0, .tfar = tfar, .mask = UINT32_MAX};
}

/* Raw rtcIntersect1; returns 1 on a hit, the hit in *query. */
static int path_intersect(RTCScene rays, gb_vec3 origin, gb_vec3 dir, struct RTCRayHit *query,
                          uint64_t *count)
{
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    query->ray = path_ray(origin, dir, INFINITY);
    query->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query->hit.primID = RTC_INVALID_GEOMETRY_ID;
    query->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rays, &context, query);
    ++*count;
    return query->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

/* Raw rtcOccluded1; the answer is not needed, only the work. */
static void path_occluded(RTCScene rays, gb_vec3 origin, gb_vec3 dir, float tfar,
                          uint64_t *count)
{
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRay ray = path_ray(origin, dir, tfar);
    rtcOccluded1(rays, &context, &ray);
    ++*count;
}

static path_vertex vertex_at(const struct RTCRayHit *query)
{
    gb_vec3 dir = gb_vec3_make(query->ray.dir_x, query->ray.dir_y, query->ray.dir_z);
    gb_vec3 origin = gb_vec3_make(query->ray.org_x, query->ray.org_y, query->ray.org_z);
    gb_vec3 ng = gb_vec3_normalize(gb_vec3_make(query->hit.Ng_x, query->hit.Ng_y,
                                                query->hit.Ng_z));
    path_vertex v = {.position = gb_vec3_madd(origin, dir, query->ray.tfar),
                     .ng = gb_vec3_dot(ng, dir) > 0.0f ? gb_vec3_negate(ng) : ng};
    v.offset = gb_ray_offset(gb_vec3_max_abs(v.position));
    return v;
}

/* The origin of a ray leaving v toward dir (as gb_surface_ray_origin). */
static gb_vec3 leaving(const path_vertex *v, gb_vec3 dir)
{
    float side = gb_vec3_dot(dir, v->ng) >= 0.0f ? 1.0f : -1.0f;
    return gb_vec3_madd(v->position, v->ng, side * v->offset);
}

/* The reference's area-light shadow ray: toward a point picked by power,
 * ending at the light's surface moved off by its offset. */
static void area_shadow_ray(const path_job *job, const path_vertex *v, gb_random *rng,
                            uint64_t *count)
{
    gb_area_light_sample light;
    float u_pick = gb_random_float(rng), u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    if (!gb_light_table_sample(job->lights, job->surfaces, u_pick, u1, u2, &light))
        return;
    gb_vec3 to_light = gb_vec3_sub(light.position, v->position);
    float d2 = gb_vec3_dot(to_light, to_light);
    if (!(d2 > 0.0f))
        return;
    gb_vec3 wi = gb_vec3_scale(to_light, 1.0f / sqrtf(d2));
    if (-gb_vec3_dot(light.normal, wi) <= 0.0f || gb_vec3_dot(v->ng, wi) <= 0.0f)
        return;
    gb_vec3 origin = leaving(v, wi);
    gb_vec3 segment = gb_vec3_sub(gb_vec3_madd(light.position, light.normal, light.offset),
                                  origin);
    float distance = gb_vec3_length(segment);
    path_occluded(job->rays, origin, gb_vec3_scale(segment, 1.0f / distance), distance, count);
}

/* One shadow ray toward each delta light that reaches v. */
static void delta_shadow_rays(const path_job *job, const path_vertex *v, uint64_t *count)
{
    for (uint32_t i = 0; i < job->scene->light_count; ++i) {
        gb_delta_light_sample light;
        if (gb_delta_light_arriving(&job->scene->lights[i], v->position, &light) &&
            gb_vec3_dot(v->ng, light.wi) > 0.0f)
            path_occluded(job->rays, leaving(v, light.wi), light.wi, light.distance, count);
    }
}

/* Cosine-distributed about n. */
static gb_vec3 cosine_direction(gb_vec3 n, gb_random *rng)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    float r = sqrtf(u1), phi = 6.2831853f * u2;
    gb_vec3 t, b;
    gb_vec3_frame(n, &t, &b);
    return gb_vec3_normalize(gb_vec3_from_frame(t, b, n, r * cosf(phi), r * sinf(phi),
                                                sqrtf(fmaxf(0.0f, 1.0f - u1))));
}

/* The rays of one path from the camera ray (origin, dir). */
static void trace_raw_path(const path_job *job, gb_vec3 origin, gb_vec3 dir, gb_random *rng,
                           uint64_t *count)
{
    struct RTCRayHit query;
    if (!path_intersect(job->rays, origin, dir, &query, count))
        return;
    for (int bounce = 1; bounce <= job->bounces; ++bounce) {
        path_vertex v = vertex_at(&query);
        area_shadow_ray(job, &v, rng, count);
        delta_shadow_rays(job, &v, count);
        gb_vec3 wi = cosine_direction(v.ng, rng);
        if (!path_intersect(job->rays, leaving(&v, wi), wi, &query, count))
            return;
    }
}

/* A work-queue item: one tile, pixels in the reference's order. */
static int trace_path_tile(void *context, uint64_t item)
{
    path_job *job = context;
    const gb_camera_frame *frame = &job->frame;
    int x0 = (int)(item % (uint64_t)job->tiles_x) * PATH_TILE_SIZE;
    int y0 = (int)(item / (uint64_t)job->tiles_x) * PATH_TILE_SIZE;
    int x1 = x0 + PATH_TILE_SIZE < frame->width ? x0 + PATH_TILE_SIZE : frame->width;
    int y1 = y0 + PATH_TILE_SIZE < frame->height ? y0 + PATH_TILE_SIZE : frame->height;
    uint64_t count = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            gb_random rng = gb_random_make(job->seed, (uint64_t)y * (uint64_t)frame->width +
                                                          (uint64_t)x);
            for (int s = 0; s < job->spp; ++s) {
                float jx = gb_random_float(&rng), jy = gb_random_float(&rng);
                gb_vec3 dir = gb_camera_direction(frame, (float)x + jx, (float)y + jy);
                trace_raw_path(job, frame->position, dir, &rng, &count);
            }
        }
    atomic_fetch_add(&job->ray_count, count);
    return 0;
}

/* The tables and the camera the paths need, resolved from options as the
 * reference resolves them (0: the camera's resolution, 64 spp, 64 bounces),
 * the bounces cut where the reference's roulette starts. */
static gb_result prepare_paths(const gb_scene *scene, const gb_reference_options *options,
                               path_job *job, gb_error *error)
{
    if (options->camera >= scene->camera_count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "raw paths: no camera %u",
                       (unsigned)options->camera);
    const gb_camera *camera = &scene->cameras[options->camera];
    int custom = options->width > 0 || options->height > 0;
    int width = custom ? options->width : camera->width;
    int height = custom ? options->height : camera->height;
    job->scene = scene;
    job->spp = options->spp ? options->spp : GB_REFERENCE_DEFAULT_SPP;
    int bounces = options->bounces ? options->bounces : GB_REFERENCE_DEFAULT_BOUNCES;
    job->bounces = bounces < GB_PATH_ROULETTE_START ? bounces : GB_PATH_ROULETTE_START;
    job->seed = options->seed;
    job->tiles_x = (width + PATH_TILE_SIZE - 1) / PATH_TILE_SIZE;
    return gb_camera_frame_make(camera, width, height, &job->frame, error);
}

/* Rays per second of the raw paths for options (full mode's camera,
 * resolution, spp, seed, bounces, threads); *rays_per_sample gets the mean
 * number of rays of a camera sample. {-1, -1} on failure. */
static rate raw_path_rate(const gb_scene *scene, const gb_reference_options *options,
                          double *rays_per_sample, gb_error *error)
{
    path_job job = {.ray_count = 0};
    gb_surface_table surfaces = {0};
    gb_light_table lights = {0};
    gb_embree_scene *rays = NULL;
    gb_result result = prepare_paths(scene, options, &job, error);
    if (result == GB_OK)
        result = gb_surface_table_build(scene, &surfaces, error);
    if (result == GB_OK)
        result = gb_light_table_build(scene, &lights, error);
    if (result == GB_OK)
        result = gb_embree_scene_create(scene, options->threads, &rays, error);
    rate measured = {-1, -1};
    if (result == GB_OK) {
        job.rays = gb_embree_scene_handle(rays);
        job.surfaces = &surfaces;
        job.lights = &lights;
        int tiles_y = (job.frame.height + PATH_TILE_SIZE - 1) / PATH_TILE_SIZE;
        gb_work_queue queue = {.item_count = (uint64_t)job.tiles_x * (uint64_t)tiles_y,
                               .threads = options->threads};
        double start = gb_seconds(), cpu_start = process_cpu_seconds();
        gb_work_queue_run(&queue, trace_path_tile, &job, NULL);
        double seconds = gb_seconds() - start, cpu = process_cpu_seconds() - cpu_start;
        double count = (double)atomic_load(&job.ray_count), mrays = 1e-6 * count;
        measured = (rate){mrays / seconds, mrays / cpu * options->threads};
        *rays_per_sample = count / ((double)job.frame.width * job.frame.height * job.spp);
    }
    gb_embree_scene_destroy(rays);
    gb_light_table_free(&lights);
    gb_surface_table_free(&surfaces);
    return measured;
}

#endif
