#include "view.h"

#include "camera.h"

#include <math.h>
#include <stdio.h>

static void set_basis(gb_view *view, gb_vec3 forward)
{
    view->forward = gb_vec3_normalize(forward);
    view->right = gb_vec3_normalize(gb_vec3_cross(view->forward, view->world_up));
    view->up = gb_vec3_cross(view->right, view->forward);
}

gb_result gb_view_from_camera(const gb_camera *camera, float scene_size, gb_view *view,
                              gb_error *error)
{
    gb_camera_frame frame;
    gb_result result = gb_camera_frame_make(camera, 1, 1, &frame, error);
    if (result != GB_OK)
        return result;
    view->position = frame.position;
    view->forward = frame.forward;
    view->right = frame.right;
    view->up = frame.up;
    view->world_up = gb_vec3_normalize(gb_vec3_load(camera->up));
    view->fov_y = camera->fov_y;
    view->near = scene_size > 0.0f && isfinite(scene_size) ? 1e-4f * scene_size : 1e-3f;
    return GB_OK;
}

gb_mat4 gb_view_matrix(const gb_view *view)
{
    return gb_mat4_view(view->position, view->forward, view->right, view->up);
}

gb_mat4 gb_view_inverse_matrix(const gb_view *view)
{
    return gb_mat4_view_inverse(view->position, view->forward, view->right, view->up);
}

gb_mat4 gb_view_projection(const gb_view *view, int width, int height)
{
    return gb_mat4_perspective_infinite(view->fov_y, (float)width / (float)height, view->near);
}

void gb_view_move(gb_view *view, float forward, float right, float up)
{
    view->position = gb_vec3_add(view->position, gb_vec3_scale(view->forward, forward));
    view->position = gb_vec3_add(view->position, gb_vec3_scale(view->right, right));
    view->position = gb_vec3_add(view->position, gb_vec3_scale(view->world_up, up));
}

/* Rodrigues: v turned by angle about the unit axis. */
static gb_vec3 rotate(gb_vec3 v, gb_vec3 axis, float angle)
{
    float c = cosf(angle), s = sinf(angle);
    gb_vec3 r = gb_vec3_scale(v, c);
    r = gb_vec3_add(r, gb_vec3_scale(gb_vec3_cross(axis, v), s));
    return gb_vec3_add(r, gb_vec3_scale(axis, gb_vec3_dot(axis, v) * (1.0f - c)));
}

void gb_view_turn(gb_view *view, float yaw, float pitch)
{
    gb_vec3 forward = rotate(view->forward, view->world_up, yaw);
    gb_vec3 pitched =
        rotate(forward, gb_vec3_normalize(gb_vec3_cross(forward, view->world_up)), pitch);
    if (fabsf(gb_vec3_dot(pitched, view->world_up)) < 0.99f)
        forward = pitched;
    set_basis(view, forward);
}

void gb_view_orbit(gb_view *view, gb_vec3 pivot, float yaw, float pitch)
{
    gb_vec3 offset = rotate(gb_vec3_sub(view->position, pivot), view->world_up, yaw);
    gb_vec3 forward = rotate(view->forward, view->world_up, yaw);
    gb_vec3 axis = gb_vec3_normalize(gb_vec3_cross(forward, view->world_up));
    gb_vec3 pitched = rotate(forward, axis, pitch);
    if (fabsf(gb_vec3_dot(pitched, view->world_up)) < 0.99f) {
        forward = pitched;
        offset = rotate(offset, axis, pitch);
    }
    view->position = gb_vec3_add(pivot, offset);
    set_basis(view, forward);
}

float gb_view_step_length(float speed, double seconds)
{
    if (!(seconds > 0.0))
        return 0.0f;
    return speed * (float)(seconds < GB_VIEW_LONGEST_STEP_SECONDS ? seconds
                                                                  : GB_VIEW_LONGEST_STEP_SECONDS);
}

void gb_view_camera_line(const gb_view *view, int width, int height, char *line, size_t size)
{
    gb_vec3 p = view->position, t = gb_vec3_add(view->position, view->forward),
            u = view->world_up;
    snprintf(line, size,
             "camera position %.7g %.7g %.7g target %.7g %.7g %.7g up %.7g %.7g %.7g "
             "fov %.7g resolution %d %d",
             p.x, p.y, p.z, t.x, t.y, t.z, u.x, u.y, u.z, view->fov_y, width, height);
}

gb_result gb_scene_view(const gb_scene *scene, uint32_t camera, gb_view *view,
                        gb_error *error)
{
    if (camera >= scene->camera_count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "camera %u: the scene has %u camera%s", camera,
                       scene->camera_count, scene->camera_count == 1 ? "" : "s");
    float diagonal = 0.0f;
    for (int c = 0; c < 3; ++c) {
        float d = scene->bounds_max[c] - scene->bounds_min[c];
        diagonal += d * d;
    }
    return gb_view_from_camera(&scene->cameras[camera], sqrtf(diagonal), view, error);
}
