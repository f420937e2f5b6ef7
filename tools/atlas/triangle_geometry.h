/* triangle_geometry.h — the double-precision triangle measures the atlas
 * steps share: a scene triangle's corners, its normal and area, and the
 * angles at its corners, in 3-D and in UV. Inline, no allocation; every
 * function is finite for degenerate input (a zero-length edge or a needle
 * gives angles 0 or 180 degrees, a zero normal, never a NaN).
 */
#ifndef GB_ATLAS_TRIANGLE_GEOMETRY_H
#define GB_ATLAS_TRIANGLE_GEOMETRY_H

#include <math.h>
#include <stdint.h>

#include "scene.h"

/* Corner c (0..2) of scene triangle t as doubles. */
static inline void gb_triangle_corner(const gb_scene *scene, uint32_t t, int c, double p[3])
{
    const float *q = scene->positions + 3 * (size_t)scene->indices[3 * (size_t)t + c];
    p[0] = q[0];
    p[1] = q[1];
    p[2] = q[2];
}

/* cross(p1 - p0, p2 - p0): twice the area, along the normal. */
static inline void gb_triangle_cross(const double p0[3], const double p1[3],
                                     const double p2[3], double n[3])
{
    double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double gb_length3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The unit normal of scene triangle t in n; returns twice its area (0: no
 * normal, n zero). */
static inline double gb_triangle_normal(const gb_scene *scene, uint32_t t, double n[3])
{
    double p[3][3];
    for (int c = 0; c < 3; ++c)
        gb_triangle_corner(scene, t, c, p[c]);
    gb_triangle_cross(p[0], p[1], p[2], n);
    double length = gb_length3(n);
    for (int k = 0; k < 3; ++k)
        n[k] = length > 0.0 ? n[k] / length : 0.0;
    return length;
}

/* The angle (radians, 0..pi) between vectors a and b of dimension 2 or 3:
 * atan2(|a x b|, a . b), exact near 0 and pi where acos is not. */
static inline double gb_angle_between(const double *a, const double *b, int dimension)
{
    double dot = 0.0, cross;
    for (int k = 0; k < dimension; ++k)
        dot += a[k] * b[k];
    if (dimension == 2) {
        cross = fabs(a[0] * b[1] - a[1] * b[0]);
    } else {
        double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        cross = gb_length3(n);
    }
    return atan2(cross, dot);
}

/* The angle at corner c of the triangle of corners p (dimension 2 or 3,
 * p[0..2] each of that many doubles, packed). */
static inline double gb_corner_angle(const double *p, int c, int dimension)
{
    const double *o = p + dimension * c, *a = p + dimension * ((c + 1) % 3),
                 *b = p + dimension * ((c + 2) % 3);
    double u[3], v[3];
    for (int k = 0; k < dimension; ++k) {
        u[k] = a[k] - o[k];
        v[k] = b[k] - o[k];
    }
    return gb_angle_between(u, v, dimension);
}

/* Twice the signed area of a UV triangle (u0 v0 u1 v1 u2 v2). */
static inline double gb_uv_twice_area(const double *uv)
{
    return (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[3] - uv[1]) * (uv[4] - uv[0]);
}

/* The angle distortion (degrees) of the corners of scene triangle t at
 * the UVs uv (6 doubles, any uniform scale): each corner's |UV angle -
 * 3-D angle| added to *sum; returns the largest. */
static inline double gb_triangle_angle_distortion(const gb_scene *scene, uint32_t t,
                                                  const double uv[6], double *sum)
{
    double p[9], largest = 0.0;
    for (int c = 0; c < 3; ++c)
        gb_triangle_corner(scene, t, c, p + 3 * c);
    for (int c = 0; c < 3; ++c) {
        double d = fabs(gb_corner_angle(uv, c, 2) - gb_corner_angle(p, c, 3)) * 180.0 / M_PI;
        *sum += d;
        largest = fmax(largest, d);
    }
    return largest;
}

#endif
