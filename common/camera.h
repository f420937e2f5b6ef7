/* camera.h — the one pinhole camera of the toolchain: the frame of a
 * gb_camera and its primary rays. Pixel (x, y) counts from the top-left
 * corner, the image's right is cross(forward, up), and fov_y spans the image
 * height whatever its width. The reference renderer traces these rays; the
 * runtime's view (runtime/view.h) takes its basis from the same frame, so
 * both project a point to the same pixel (tests/unit/test_runtime.c).
 */
#ifndef GB_CAMERA_H
#define GB_CAMERA_H

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
