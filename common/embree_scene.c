#include "embree_scene.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct gb_embree_scene {
    RTCDevice device;
    RTCScene scene;
    enum RTCError first_error;       /* set by the device callback */
    char message[512];
};

static void record_error(void *user, enum RTCError code, const char *message)
{
    gb_embree_scene *rays = user;
    if (rays->first_error != RTC_ERROR_NONE)
        return;
    rays->first_error = code;
    snprintf(rays->message, sizeof rays->message, "%s", message ? message : "unknown error");
}

static gb_result embree_failure(const gb_embree_scene *rays, gb_error *error)
{
    gb_result result = rays->first_error == RTC_ERROR_OUT_OF_MEMORY ? GB_ERROR_OUT_OF_MEMORY
                                                                     : GB_ERROR_UNSUPPORTED;
    return gb_fail(error, result, "embree: %s (error %d)", rays->message,
                   (int)rays->first_error);
}

static gb_result create_device(gb_embree_scene *rays, int threads, gb_error *error)
{
    char config[64];
    snprintf(config, sizeof config, "threads=%d,verbose=0", threads > 0 ? threads : 0);
    rays->device = rtcNewDevice(config);
    if (!rays->device) {
        enum RTCError code = rtcGetDeviceError(NULL);
        return gb_fail(error, code == RTC_ERROR_OUT_OF_MEMORY ? GB_ERROR_OUT_OF_MEMORY
                                                              : GB_ERROR_UNSUPPORTED,
                       "embree: cannot create a device (error %d)", (int)code);
    }
    rtcSetDeviceErrorFunction(rays->device, record_error, rays);
    return GB_OK;
}

/* The triangles as one Embree geometry: positions and indices copied into
 * buffers Embree allocates (and pads for its vector loads). */
static void attach_triangles(gb_embree_scene *rays, const gb_scene *scene)
{
    RTCGeometry geometry = rtcNewGeometry(rays->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *positions = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                               scene->vertex_count);
    uint32_t *indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                scene->triangle_count);
    if (positions && indices) {
        memcpy(positions, scene->positions, 3 * sizeof(float) * (size_t)scene->vertex_count);
        memcpy(indices, scene->indices, 3 * sizeof(uint32_t) * (size_t)scene->triangle_count);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(rays->scene, geometry, 0);
    rtcReleaseGeometry(geometry);
}

gb_result gb_embree_scene_create(const gb_scene *scene, int threads, gb_embree_scene **out,
                                 gb_error *error)
{
    *out = NULL;
    gb_embree_scene *rays = calloc(1, sizeof *rays);
    if (!rays)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "embree: out of memory");
    gb_result result = create_device(rays, threads, error);
    if (result != GB_OK) {
        free(rays);
        return result;
    }
    rays->scene = rtcNewScene(rays->device);
    if (rays->scene) {
        rtcSetSceneFlags(rays->scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(rays->scene, RTC_BUILD_QUALITY_HIGH);
        if (scene->triangle_count > 0)
            attach_triangles(rays, scene);
        rtcCommitScene(rays->scene);
    }
    if (rays->first_error != RTC_ERROR_NONE || !rays->scene) {
        result = embree_failure(rays, error);
        gb_embree_scene_destroy(rays);
        return result;
    }
    *out = rays;
    return GB_OK;
}

void gb_embree_scene_destroy(gb_embree_scene *rays)
{
    if (!rays)
        return;
    if (rays->scene)
        rtcReleaseScene(rays->scene);
    if (rays->device)
        rtcReleaseDevice(rays->device);
    free(rays);
}

RTCScene gb_embree_scene_handle(const gb_embree_scene *rays)
{
    return rays->scene;
}

static void fill_ray(struct RTCRay *ray, gb_vec3 origin, gb_vec3 dir, float tnear, float tfar)
{
    ray->org_x = origin.x;
    ray->org_y = origin.y;
    ray->org_z = origin.z;
    ray->dir_x = dir.x;
    ray->dir_y = dir.y;
    ray->dir_z = dir.z;
    ray->tnear = tnear;
    ray->tfar = tfar;
    ray->time = 0.0f;
    ray->mask = UINT32_MAX;
    ray->id = 0;
    ray->flags = 0;
}

int gb_embree_intersect(const gb_embree_scene *rays, gb_vec3 origin, gb_vec3 dir, float tnear,
                        float tfar, gb_hit *hit, uint64_t *ray_count)
{
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRayHit query;
    fill_ray(&query.ray, origin, dir, tnear, tfar);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rays->scene, &context, &query);
    ++*ray_count;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    hit->t = query.ray.tfar;
    hit->u = query.hit.u;
    hit->v = query.hit.v;
    hit->triangle = query.hit.primID;
    return 1;
}

int gb_embree_occluded(const gb_embree_scene *rays, gb_vec3 origin, gb_vec3 dir, float tnear,
                       float tfar, uint64_t *ray_count)
{
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRay ray;
    fill_ray(&ray, origin, dir, tnear, tfar);
    rtcOccluded1(rays->scene, &context, &ray);
    ++*ray_count;
    return ray.tfar < 0.0f;
}
