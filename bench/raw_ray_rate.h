/* raw_ray_rate.h — the incoherent yardstick of the ray-tracing benchmarks:
 * Embree's raw rtcIntersect1 rate on incoherent random rays (origins uniform
 * in the scene's bounds, directions uniform), RAYS_PER_THREAD rays a thread,
 * timed in wall and process CPU time. Bench code, included by the bench
 * programs that compare a tool's rate with it in the same run: like for
 * like for photons_rate (photons' rays are incoherent); for reference_rate
 * only context, its like-for-like yardstick is bench/raw_path_rate.h.
 */
#ifndef GB_RAW_RAY_RATE_H
#define GB_RAW_RAY_RATE_H

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

#include "embree_scene.h"
#include "progress.h"
#include "random.h"

enum { RAYS_PER_THREAD = 1 << 20, MAX_THREADS = 64 };

typedef struct rate {
    double wall, cpu;           /* Mrays/s; Mrays per CPU-second x threads */
} rate;

static double process_cpu_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

typedef struct raw_job {
    const gb_embree_scene *rays;
    struct RTCRayHit *queries;  /* RAYS_PER_THREAD */
    uint64_t hits;
} raw_job;

static void random_rays(const gb_scene *scene, uint64_t stream, struct RTCRayHit *queries)
{
    gb_random rng = gb_random_make(1234, stream);
    for (int i = 0; i < RAYS_PER_THREAD; ++i) {
        struct RTCRay *ray = &queries[i].ray;
        float o[3];
        for (int k = 0; k < 3; ++k)
            o[k] = scene->bounds_min[k] +
                   gb_random_float(&rng) * (scene->bounds_max[k] - scene->bounds_min[k]);
        float z = 2 * gb_random_float(&rng) - 1, phi = 6.2831853f * gb_random_float(&rng);
        float r = sqrtf(fmaxf(0, 1 - z * z));
        *ray = (struct RTCRay){.org_x = o[0], .org_y = o[1], .org_z = o[2],
                               .dir_x = r * cosf(phi), .dir_y = r * sinf(phi), .dir_z = z,
                               .tnear = 0, .tfar = INFINITY, .mask = UINT32_MAX};
    }
}

/* Raw rtcIntersect1, nothing else in the loop. */
static void *trace_raw(void *user)
{
    raw_job *job = user;
    RTCScene scene = gb_embree_scene_handle(job->rays);
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int i = 0; i < RAYS_PER_THREAD; ++i) {
        struct RTCRayHit *q = &job->queries[i];
        q->hit.geomID = RTC_INVALID_GEOMETRY_ID;
        q->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, q);
        job->hits += q->hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return NULL;
}

static rate raw_rate(const gb_scene *scene, int threads, gb_error *error)
{
    gb_embree_scene *rays;
    if (gb_embree_scene_create(scene, threads, &rays, error) != GB_OK)
        return (rate){-1, -1};
    raw_job jobs[MAX_THREADS];
    pthread_t ids[MAX_THREADS];
    for (int t = 0; t < threads; ++t) {
        jobs[t] = (raw_job){.rays = rays,
                            .queries = malloc(RAYS_PER_THREAD * sizeof(struct RTCRayHit))};
        random_rays(scene, (uint64_t)t, jobs[t].queries);
    }
    double start = gb_seconds(), cpu_start = process_cpu_seconds();
    for (int t = 0; t < threads; ++t)
        pthread_create(&ids[t], NULL, trace_raw, &jobs[t]);
    for (int t = 0; t < threads; ++t)
        pthread_join(ids[t], NULL);
    double seconds = gb_seconds() - start, cpu = process_cpu_seconds() - cpu_start;
    for (int t = 0; t < threads; ++t)
        free(jobs[t].queries);
    gb_embree_scene_destroy(rays);
    double mrays = 1e-6 * threads * (double)RAYS_PER_THREAD;
    return (rate){mrays / seconds, mrays / cpu * threads};
}

#endif
