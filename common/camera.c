#include "camera.h"

#include <math.h>

gb_result gb_camera_frame_make(const gb_camera *camera, int width, int height,
                               gb_camera_frame *frame, gb_error *error)
{
    gb_vec3 position = gb_vec3_load(camera->position);
    gb_vec3 forward = gb_vec3_normalize(gb_vec3_sub(gb_vec3_load(camera->target), position));
    gb_vec3 right = gb_vec3_normalize(gb_vec3_cross(forward, gb_vec3_load(camera->up)));
    if (gb_vec3_is_zero(forward) || gb_vec3_is_zero(right) || !isfinite(gb_vec3_max_abs(right)))
        return gb_fail(error, GB_ERROR_INVALID,
                       "camera: the target is on the position or up is along the view");
    if (!(camera->fov_y > 0.0f && camera->fov_y < 180.0f))
        return gb_fail(error, GB_ERROR_INVALID, "camera: field of view %g is not in (0, 180)",
                       (double)camera->fov_y);
    if (width <= 0 || height <= 0)
        return gb_fail(error, GB_ERROR_INVALID, "camera: resolution %dx%d is empty", width,
                       height);
    frame->position = position;
    frame->forward = forward;
    frame->right = right;
    frame->up = gb_vec3_cross(right, forward);
    frame->tan_half_fov_y = tanf(0.5f * camera->fov_y * 3.14159265358979f / 180.0f);
    frame->width = width;
    frame->height = height;
    return GB_OK;
}

gb_vec3 gb_camera_direction(const gb_camera_frame *frame, float x, float y)
{
    float sy = frame->tan_half_fov_y, sx = sy * (float)frame->width / (float)frame->height;
    float px = (2.0f * x / (float)frame->width - 1.0f) * sx;
    float py = (1.0f - 2.0f * y / (float)frame->height) * sy;
    gb_vec3 dir = gb_vec3_madd(frame->forward, frame->right, px);
    return gb_vec3_normalize(gb_vec3_madd(dir, frame->up, py));
}
