/* camera.h — primary rays of a pinhole gb_camera: pixel (x, y) counts from
 * the top-left corner, the image's right is cross(forward, up), and fov_y
 * spans the image height whatever its width.
 */
#ifndef GB_REFERENCE_CAMERA_H
#define GB_REFERENCE_CAMERA_H

#include "scene.h"
#include "vec3.h"

typedef struct gb_camera_frame {
    gb_vec3 position;
    gb_vec3 forward, right, up;  /* unit, orthogonal */
    float tan_half_fov_y;
    int width, height;
} gb_camera_frame;

/* GB_ERROR_INVALID for a camera that does not define a view (target on the
 * position, up along the view, field of view outside (0, 180)). */
gb_result gb_camera_frame_make(const gb_camera *camera, int width, int height,
                               gb_camera_frame *frame, gb_error *error);

/* Unit direction through the image point (x, y), in pixels: (0.5, 0.5) is
 * the centre of the top-left pixel. */
gb_vec3 gb_camera_direction(const gb_camera_frame *frame, float x, float y);

#endif
