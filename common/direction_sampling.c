/* direction_sampling.c — directions and disc points by inversion
 * (direction_sampling.h). */
#include "direction_sampling.h"

#include <math.h>

#include "brdf.h"

/* (x, y, z) in the frame of the unit n, made unit again against rounding. */
static gb_vec3 around(gb_vec3 n, float x, float y, float z)
{
    gb_vec3 t, b;
    gb_vec3_frame(n, &t, &b);
    return gb_vec3_normalize(gb_vec3_from_frame(t, b, n, x, y, z));
}

/* A point of the unit disc at radius sqrt(u1), angle 2 pi u2, lifted to
 * z = sqrt(1 - r^2): cos(theta) / pi. */
gb_vec3 gb_cosine_direction(gb_vec3 n, float u1, float u2)
{
    float r = sqrtf(u1), phi = 2.0f * GB_PI * u2;
    return around(n, r * cosf(phi), r * sinf(phi), sqrtf(fmaxf(0.0f, 1.0f - u1)));
}

/* cos(theta) uniform in [cos_max, 1]: uniform in solid angle. */
gb_vec3 gb_cone_direction(gb_vec3 axis, float cos_max, float u1, float u2)
{
    float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    float sin_theta = sqrtf(fmaxf(0.0f, 1.0f - cos_theta * cos_theta));
    float phi = 2.0f * GB_PI * u2;
    return around(axis, sin_theta * cosf(phi), sin_theta * sinf(phi), cos_theta);
}

/* Radius r sqrt(u1): uniform in area. */
gb_vec3 gb_disc_point(gb_vec3 c, gb_vec3 n, float r, float u1, float u2)
{
    float rho = r * sqrtf(u1), phi = 2.0f * GB_PI * u2;
    gb_vec3 t, b;
    gb_vec3_frame(n, &t, &b);
    return gb_vec3_add(c, gb_vec3_from_frame(t, b, n, rho * cosf(phi), rho * sinf(phi), 0.0f));
}
