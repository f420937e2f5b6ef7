/* mat4.h — the 4x4 matrices of the runtime, column-major as OpenGL takes
 * them (m[column * 4 + row]), so a gb_mat4 goes to glUniformMatrix4fv with
 * transpose GL_FALSE. Its 3-vectors are common/vec3.h's.
 *
 * Projections use reversed depth (near -> 1, far or infinity -> 0) with
 * glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): a float depth buffer then
 * keeps its precision over the whole range.
 */
#ifndef GB_MAT4_H
#define GB_MAT4_H

#include "vec3.h"

typedef struct gb_mat4 {
    float m[16];
} gb_mat4;

gb_mat4 gb_mat4_identity(void);
gb_mat4 gb_mat4_multiply(const gb_mat4 *a, const gb_mat4 *b);
/* World to view of an eye at position looking along forward (unit), with
 * right and up unit and orthogonal to it: the view looks down -z. */
gb_mat4 gb_mat4_view(gb_vec3 position, gb_vec3 forward, gb_vec3 right, gb_vec3 up);
/* Its inverse (view to world), the transpose of the rotation. */
gb_mat4 gb_mat4_view_inverse(gb_vec3 position, gb_vec3 forward, gb_vec3 right, gb_vec3 up);
/* Perspective, reversed depth, infinite far plane: depth = near / -z. */
gb_mat4 gb_mat4_perspective_infinite(float fov_y_degrees, float aspect, float near);
/* Perspective, reversed depth, between near and far. */
gb_mat4 gb_mat4_perspective(float fov_y_degrees, float aspect, float near, float far);
/* Orthographic over [left, right] x [bottom, top] x [-far, -near] in view
 * space, reversed depth. */
gb_mat4 gb_mat4_orthographic(float left, float right, float bottom, float top, float near,
                             float far);
/* m times the point (x, y, z, 1), divided by w. */
gb_vec3 gb_mat4_transform_point(const gb_mat4 *m, gb_vec3 p);

#endif
