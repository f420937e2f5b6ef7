/* glb_camera.h — the scene's first camera in the glTF export
 * (glb_export.h), so that a viewer opens on the view gibake renders: a
 * perspective camera (yfov the camera's fov_y in radians, aspectRatio its
 * width / height, znear 10^-4 of the scene's diagonal, no zfar: an
 * infinite projection) and the node that places it. A glTF camera looks
 * down its node's -Z with +Y up, so the node's rotation takes X, Y, Z to
 * the frame's right, up and -forward (common/camera.h, the frame the
 * reference and the runtime render with).
 *
 * Appends ",{node}" to nodes (after the mesh's node 0) and "[camera]" as
 * the cameras array to cameras; returns 0 and appends nothing for a scene
 * whose camera defines no view. The caller owns the buffers and the scene.
 */
#ifndef GB_GLB_CAMERA_H
#define GB_GLB_CAMERA_H

#include "byte_buffer.h"
#include "scene.h"

int gb_glb_print_camera(const gb_scene *scene, gb_byte_buffer *nodes, gb_byte_buffer *cameras);

#endif
