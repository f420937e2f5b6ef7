/* shadow_cascades.h — where the cascades of a directional light's shadow
 * map go (shadow_maps.c draws them): the view's depth range cut into
 * GB_SHADOW_CASCADES slices (the practical split of Zhang et al. 2006,
 * uniform and logarithmic mixed), each slice covered by one orthographic
 * map along the light, so that texels near the eye are small where the
 * view needs them.
 *
 * A cascade is fitted to its slice's bounding sphere, whose size depends
 * only on the slice's depths, the field of view and the aspect; its
 * centre is snapped to whole texels in the light's frame, so that turning
 * or moving the eye neither resizes nor shifts texels across the scene
 * (no shimmering edges). Its depth range is the scene's bounds along the
 * light: every occluder between the light and the slice is in the map.
 *
 * Plain math on the CPU; nothing is allocated. */
#ifndef GB_SHADOW_CASCADES_H
#define GB_SHADOW_CASCADES_H

#include "mat4.h"
#include "scene.h"
#include "view.h"

enum { GB_SHADOW_CASCADES = 4 };

/* The share of the logarithmic split in the practical split scheme. */
#define GB_CASCADE_LOG_SHARE 0.6f

typedef struct gb_cascade {
    gb_mat4 world_to_clip;      /* reversed depth, x and y over [-1, 1] */
    float far;                  /* the slice's far depth along the view */
    float texel;                /* world size of a texel */
    float depth_range;          /* world length of its depth 0..1 */
} gb_cascade;

/* The view depth beyond which the scene's bounds hold nothing: the
 * farthest corner's depth along the view (at least twice its near). */
float gb_cascade_view_far(const gb_view *view, const gb_scene *scene);

/* splits[0..count]: near, the ends of each slice, far. */
void gb_cascade_splits(float near, float far, int count, float log_share, float *splits);

/* The cascade of the slice [z0, z1] of the view (aspect width / height)
 * for light travelling along direction, a size x size map. */
gb_cascade gb_cascade_fit(const gb_view *view, float aspect, float z0, float z1,
                          gb_vec3 direction, const gb_scene *scene, int size);

#endif
