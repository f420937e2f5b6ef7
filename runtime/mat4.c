#include "mat4.h"

#include <math.h>
#include <string.h>

gb_mat4 gb_mat4_identity(void)
{
    gb_mat4 r = {{0}};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
    return r;
}

gb_mat4 gb_mat4_multiply(const gb_mat4 *a, const gb_mat4 *b)
{
    gb_mat4 r;
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) {
            float sum = 0.0f;
            for (int k = 0; k < 4; ++k)
                sum += a->m[k * 4 + row] * b->m[column * 4 + k];
            r.m[column * 4 + row] = sum;
        }
    return r;
}

static void set_row(gb_mat4 *m, int row, gb_vec3 v, float w)
{
    m->m[0 * 4 + row] = v.x;
    m->m[1 * 4 + row] = v.y;
    m->m[2 * 4 + row] = v.z;
    m->m[3 * 4 + row] = w;
}

gb_mat4 gb_mat4_view(gb_vec3 position, gb_vec3 forward, gb_vec3 right, gb_vec3 up)
{
    gb_mat4 r = gb_mat4_identity();
    set_row(&r, 0, right, -gb_vec3_dot(right, position));
    set_row(&r, 1, up, -gb_vec3_dot(up, position));
    gb_vec3 back = gb_vec3_scale(forward, -1.0f);
    set_row(&r, 2, back, -gb_vec3_dot(back, position));
    return r;
}

static void set_column(gb_mat4 *m, int column, gb_vec3 v)
{
    m->m[column * 4 + 0] = v.x;
    m->m[column * 4 + 1] = v.y;
    m->m[column * 4 + 2] = v.z;
}

gb_mat4 gb_mat4_view_inverse(gb_vec3 position, gb_vec3 forward, gb_vec3 right, gb_vec3 up)
{
    gb_mat4 r = gb_mat4_identity();
    set_column(&r, 0, right);
    set_column(&r, 1, up);
    set_column(&r, 2, gb_vec3_scale(forward, -1.0f));
    set_column(&r, 3, position);
    return r;
}

gb_mat4 gb_mat4_perspective_infinite(float fov_y_degrees, float aspect, float near)
{
    float f = 1.0f / tanf(0.5f * fov_y_degrees * 3.14159265358979f / 180.0f);
    gb_mat4 r = {{0}};
    r.m[0] = f / aspect;
    r.m[5] = f;
    r.m[11] = -1.0f;    /* w = -z */
    r.m[14] = near;     /* z = near, depth = near / -z */
    return r;
}

gb_mat4 gb_mat4_perspective(float fov_y_degrees, float aspect, float near, float far)
{
    float f = 1.0f / tanf(0.5f * fov_y_degrees * 3.14159265358979f / 180.0f);
    gb_mat4 r = {{0}};
    r.m[0] = f / aspect;
    r.m[5] = f;
    r.m[10] = near / (far - near);          /* depth 1 at -near, 0 at -far */
    r.m[11] = -1.0f;
    r.m[14] = far * near / (far - near);
    return r;
}

gb_mat4 gb_mat4_orthographic(float left, float right, float bottom, float top, float near,
                             float far)
{
    gb_mat4 r = gb_mat4_identity();
    r.m[0] = 2.0f / (right - left);
    r.m[5] = 2.0f / (top - bottom);
    r.m[10] = 1.0f / (far - near);          /* depth 1 at -near, 0 at -far */
    r.m[12] = -(right + left) / (right - left);
    r.m[13] = -(top + bottom) / (top - bottom);
    r.m[14] = far / (far - near);
    return r;
}

gb_vec3 gb_mat4_transform_point(const gb_mat4 *m, gb_vec3 p)
{
    float v[4];
    for (int row = 0; row < 4; ++row)
        v[row] = m->m[row] * p.x + m->m[4 + row] * p.y + m->m[8 + row] * p.z + m->m[12 + row];
    float inv_w = v[3] != 0.0f ? 1.0f / v[3] : 1.0f;
    return gb_vec3_make(v[0] * inv_w, v[1] * inv_w, v[2] * inv_w);
}
