/* embree_scene.h — the scene's triangles in an Embree 3 BVH, and the two
 * ray queries the reference renderer makes of it.
 *
 *   gb_embree_scene *rays;
 *   gb_embree_scene_create(scene, threads, &rays, &error);   // build, commit
 *   gb_embree_intersect(rays, origin, dir, tnear, tfar, &hit, &counter);
 *   gb_embree_scene_destroy(rays);
 *
 * One geometry, primitive id = triangle index. The BVH is built with high
 * quality and Embree's robust mode (no rays slip between triangles sharing
 * an edge). Embree errors are caught by one device callback and turned into
 * a gb_result by create. The queries are thread-safe; each thread counts
 * its rays in a counter of its own.
 */
#ifndef GB_EMBREE_SCENE_H
#define GB_EMBREE_SCENE_H

#include <embree3/rtcore.h>
#include <stdint.h>

#include "scene.h"
#include "vec3.h"

typedef struct gb_embree_scene gb_embree_scene;

typedef struct gb_hit {
    float t;                    /* distance along the (unit) direction */
    float u, v;                 /* barycentrics of corners 1 and 2 */
    uint32_t triangle;
} gb_hit;

/* threads: how many threads Embree may use to build (0: all). The scene must
 * outlive the gb_embree_scene (its positions are copied, but nothing else). */
gb_result gb_embree_scene_create(const gb_scene *scene, int threads, gb_embree_scene **out,
                                 gb_error *error);
void gb_embree_scene_destroy(gb_embree_scene *rays);

/* The Embree scene itself, for benchmarks that time raw rtcIntersect1. */
RTCScene gb_embree_scene_handle(const gb_embree_scene *rays);

/* Closest hit in (tnear, tfar); returns 0 on a miss. *rays is incremented. */
int gb_embree_intersect(const gb_embree_scene *rays, gb_vec3 origin, gb_vec3 dir, float tnear,
                        float tfar, gb_hit *hit, uint64_t *ray_count);

/* 1 when something lies in (tnear, tfar) along the ray. */
int gb_embree_occluded(const gb_embree_scene *rays, gb_vec3 origin, gb_vec3 dir, float tnear,
                       float tfar, uint64_t *ray_count);

#endif
