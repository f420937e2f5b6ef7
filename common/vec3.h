/* vec3.h — the small 3-vector (and RGB colour) arithmetic of the reference
 * renderer. Plain values, no allocation.
 */
#ifndef GB_VEC3_H
#define GB_VEC3_H

#include <math.h>

typedef struct gb_vec3 {
    float x, y, z;
} gb_vec3;

static inline gb_vec3 gb_vec3_make(float x, float y, float z)
{
    gb_vec3 v = {x, y, z};
    return v;
}

/* The dot product of two float[3] (the runtime's and the formats' vectors). */
static inline float gb_dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline gb_vec3 gb_vec3_load(const float *p)
{
    return gb_vec3_make(p[0], p[1], p[2]);
}

static inline void gb_vec3_store(gb_vec3 v, float *p)
{
    p[0] = v.x;
    p[1] = v.y;
    p[2] = v.z;
}

static inline gb_vec3 gb_vec3_add(gb_vec3 a, gb_vec3 b)
{
    return gb_vec3_make(a.x + b.x, a.y + b.y, a.z + b.z);
}

static inline gb_vec3 gb_vec3_sub(gb_vec3 a, gb_vec3 b)
{
    return gb_vec3_make(a.x - b.x, a.y - b.y, a.z - b.z);
}

static inline gb_vec3 gb_vec3_scale(gb_vec3 a, float s)
{
    return gb_vec3_make(a.x * s, a.y * s, a.z * s);
}

/* Component-wise product (colours). */
static inline gb_vec3 gb_vec3_mul(gb_vec3 a, gb_vec3 b)
{
    return gb_vec3_make(a.x * b.x, a.y * b.y, a.z * b.z);
}

/* a + b * s */
static inline gb_vec3 gb_vec3_madd(gb_vec3 a, gb_vec3 b, float s)
{
    return gb_vec3_make(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}

static inline float gb_vec3_dot(gb_vec3 a, gb_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static inline gb_vec3 gb_vec3_cross(gb_vec3 a, gb_vec3 b)
{
    return gb_vec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static inline float gb_vec3_length(gb_vec3 a)
{
    return sqrtf(gb_vec3_dot(a, a));
}

/* a / |a|; the zero vector stays zero. */
static inline gb_vec3 gb_vec3_normalize(gb_vec3 a)
{
    float length = gb_vec3_length(a);
    return length > 0.0f ? gb_vec3_scale(a, 1.0f / length) : a;
}

static inline gb_vec3 gb_vec3_negate(gb_vec3 a)
{
    return gb_vec3_make(-a.x, -a.y, -a.z);
}

/* The largest |component|. */
static inline float gb_vec3_max_abs(gb_vec3 a)
{
    return fmaxf(fabsf(a.x), fmaxf(fabsf(a.y), fabsf(a.z)));
}

/* The largest component (colours: Russian roulette, sampling weights). */
static inline float gb_vec3_max(gb_vec3 a)
{
    return fmaxf(a.x, fmaxf(a.y, a.z));
}

/* Rec. 709 luminance of a linear RGB colour. */
static inline float gb_vec3_luminance(gb_vec3 c)
{
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

static inline int gb_vec3_is_zero(gb_vec3 a)
{
    return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f;
}

/* Two unit vectors t, b completing the unit n into an orthonormal frame
 * (Duff et al. 2017, "Building an orthonormal basis, revisited"). */
static inline void gb_vec3_frame(gb_vec3 n, gb_vec3 *t, gb_vec3 *b)
{
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = gb_vec3_make(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = gb_vec3_make(c, sign + n.y * n.y * a, -n.y);
}

/* x t + y b + z n */
static inline gb_vec3 gb_vec3_from_frame(gb_vec3 t, gb_vec3 b, gb_vec3 n, float x, float y,
                                         float z)
{
    return gb_vec3_make(x * t.x + y * b.x + z * n.x, x * t.y + y * b.y + z * n.y,
                        x * t.z + y * b.z + z * n.z);
}

#endif
