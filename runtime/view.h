/* view.h — the eye the runtime renders from: the pinhole camera of
 * common/camera.h, whose frame it starts from (right = cross(forward, up),
 * fov_y spans the image height whatever its width, pixel (0, 0) at the top
 * left of the written image), as GL matrices, plus the fly-camera moves of
 * the window.
 */
#ifndef GB_VIEW_H
#define GB_VIEW_H

#include <stddef.h>

#include "mat4.h"
#include "result.h"
#include "scene.h"

typedef struct gb_view {
    gb_vec3 position;
    gb_vec3 forward, right, up; /* unit, orthogonal */
    gb_vec3 world_up;           /* the camera's up: yaw turns about it */
    float fov_y;                /* degrees */
    float near;                 /* near plane, world units */
} gb_view;

/* The view of camera; scene_size (the diagonal of the scene's bounds) sets
 * the near plane. GB_ERROR_INVALID for a camera that defines no view. */
gb_result gb_view_from_camera(const gb_camera *camera, float scene_size, gb_view *view,
                              gb_error *error);

gb_mat4 gb_view_matrix(const gb_view *view);           /* world to view */
gb_mat4 gb_view_inverse_matrix(const gb_view *view);   /* view to world */
/* Reversed depth, infinite far plane (mat4.h). */
gb_mat4 gb_view_projection(const gb_view *view, int width, int height);

/* The view of camera index of scene (GB_ERROR_ARGUMENT for a bad index). */
gb_result gb_scene_view(const gb_scene *scene, uint32_t camera, gb_view *view,
                        gb_error *error);

/* Fly camera: moves along forward, right and world up (in world units). */
void gb_view_move(gb_view *view, float forward, float right, float up);
/* Turns by yaw about world up and pitch about right (radians), keeping the
 * view away from the poles. */
void gb_view_turn(gb_view *view, float yaw, float pitch);
/* Turns as gb_view_turn and moves the eye with the turn about pivot, which
 * stays where it is in the image. */
void gb_view_orbit(gb_view *view, gb_vec3 pivot, float yaw, float pitch);

/* The longest time one fly step covers, seconds: a step after a slow frame
 * is speed x this at most, not a jump across the scene. */
#define GB_VIEW_LONGEST_STEP_SECONDS 0.1
/* The length of a fly step at speed (units a second) after seconds. */
float gb_view_step_length(float speed, double seconds);

/* The view as a .scene camera line (formats/scene_file.h), target one unit
 * ahead, with its resolution: "camera position ... resolution W H". */
void gb_view_camera_line(const gb_view *view, int width, int height, char *line, size_t size);

#endif
