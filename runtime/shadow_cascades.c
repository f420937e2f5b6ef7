#include "shadow_cascades.h"

#include <math.h>

#include "light_frame.h"
#include "scene_triangles.h"

float gb_cascade_view_far(const gb_view *view, const gb_scene *scene)
{
    float far = 2.0f * view->near;
    for (int k = 0; k < 8; ++k) {
        gb_vec3 to_corner = gb_vec3_sub(gb_scene_bounds_corner(scene, k), view->position);
        far = fmaxf(far, gb_vec3_dot(to_corner, view->forward));
    }
    return far;
}

void gb_cascade_splits(float near, float far, int count, float log_share, float *splits)
{
    for (int i = 0; i <= count; ++i) {
        float t = (float)i / (float)count;
        float logarithmic = near * powf(far / near, t);
        float uniform = near + (far - near) * t;
        splits[i] = log_share * logarithmic + (1.0f - log_share) * uniform;
    }
    splits[0] = near, splits[count] = far;
}

/* The eight corners of the view's slice [z0, z1]. */
static void slice_corners(const gb_view *view, float aspect, float z0, float z1,
                          gb_vec3 corners[8])
{
    float tan_half = tanf(0.5f * view->fov_y * 3.14159265358979f / 180.0f);
    for (int k = 0; k < 8; ++k) {
        float z = k & 4 ? z1 : z0;
        float y = (k & 2 ? 1.0f : -1.0f) * z * tan_half;
        float x = (k & 1 ? 1.0f : -1.0f) * z * tan_half * aspect;
        gb_vec3 p = gb_vec3_madd(view->position, view->forward, z);
        p = gb_vec3_madd(p, view->right, x);
        corners[k] = gb_vec3_madd(p, view->up, y);
    }
}

gb_cascade gb_cascade_fit(const gb_view *view, float aspect, float z0, float z1,
                          gb_vec3 direction, const gb_scene *scene, int size)
{
    gb_vec3 corners[8], centre = {0, 0, 0};
    slice_corners(view, aspect, z0, z1, corners);
    for (int k = 0; k < 8; ++k)
        centre = gb_vec3_add(centre, gb_vec3_scale(corners[k], 0.125f));
    float radius = 0.0f;
    for (int k = 0; k < 8; ++k)
        radius = fmaxf(radius, gb_vec3_length(gb_vec3_sub(corners[k], centre)));
    gb_light_frame f = gb_light_frame_make(gb_vec3_make(0, 0, 0), direction,
                                           gb_light_up_hint(gb_vec3_normalize(direction)));
    float texel = 2.0f * radius / (float)size;
    /* the centre in the light's frame, on whole texels */
    float x = texel * floorf(gb_vec3_dot(centre, f.right) / texel);
    float y = texel * floorf(gb_vec3_dot(centre, f.up) / texel);
    float nearest = INFINITY, farthest = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        float along = gb_vec3_dot(gb_scene_bounds_corner(scene, k), f.forward);
        nearest = fminf(nearest, along), farthest = fmaxf(farthest, along);
    }
    float margin = 1e-3f * (farthest - nearest) + 1e-20f;
    gb_mat4 light_view = gb_light_frame_view(&f);
    gb_mat4 projection = gb_mat4_orthographic(x - radius, x + radius, y - radius, y + radius,
                                              nearest - margin, farthest + margin);
    return (gb_cascade){gb_mat4_multiply(&projection, &light_view), z1, texel,
                        farthest - nearest + 2.0f * margin};
}
