/* brdf.h — the reflection and lighting conventions of gibake, written once
 * for the reference renderer (tools/reference) and the runtime. The runtime's
 * GLSL (runtime/brdf.glsl) mirrors these functions name for name; change both
 * together.
 *
 * Every quantity is linear RGB in the scene's radiometric units. Every
 * function takes cosines (dot products of unit vectors), never vectors, so
 * that C and GLSL agree without sharing a vector type.
 *
 * Directions point away from the surface point: wo toward the viewer (the
 * previous vertex of the path), wi toward the light.
 *
 * Sides. Surfaces reflect on both sides: at a hit, the geometric normal ng
 * is turned toward wo, and the shading normal n (the interpolated corner
 * normals, or ng) is turned to the same side as ng. Light arriving from the
 * other side of ng (dot(ng, wi) <= 0) is not reflected: nothing shines
 * through a surface. Emission is one-sided: a triangle whose material has
 * Ke > 0 emits only from its front face, the side of
 * cross(v1 - v0, v2 - v0) (counter-clockwise corners seen from the front);
 * its back face is an ordinary reflector.
 *
 * BRDF (diffuse + normalised Phong), for dot(n, wo) > 0 and dot(n, wi) > 0,
 * zero otherwise:
 *     f(wo, wi) = Kd / pi + Ks (Ns + 2) / (2 pi) max(0, cos a)^Ns
 *     cos a = dot(r, wi), r = 2 dot(n, wo) n - wo the mirror direction of wo,
 *           = 2 dot(n, wo) dot(n, wi) - dot(wo, wi).
 * Kd is the material's Kd times its diffuse texture (map_Kd, bilinear,
 * repeating, v = 0 at the bottom row) when it has one: the MTL convention
 * that the map multiplies Kd. The Phong lobe reflects exactly Ks at normal
 * incidence and less toward grazing angles; Kd + Ks <= 1 keeps a surface
 * passive (the scene's business, not checked here).
 *
 * Light sources. For a point x, the light reflected toward wo is
 * f(wo, wi) * E * dot(n, wi) where E is the irradiance the source gives a
 * surface facing it:
 *   area light    Ke of the emitting triangle is its radiance (W sr^-1 m^-2),
 *                 uniform over its front hemisphere; power pi |Ke| area.
 *   point light   intensity I (W/sr) at p: E = I / r^2, wi = (p - x) / r.
 *   spot light    a point light times gb_spot_falloff of the angle between
 *                 its direction and (x - p): 1 inside falloff_angle, 0
 *                 outside cone_angle, a smoothstep of the cosines between.
 *   directional   direction d (the way light travels), irradiance E on a
 *                 surface facing it, wi = -d, no fall-off with distance.
 *   environment   constant radiance from every direction no surface blocks.
 *   VPL           position p, unit normal m, power P (W): a one-sided
 *                 diffuse emitter of intensity P max(0, dot(m, w)) / pi
 *                 toward w, then as a point light: E = that / r^2.
 * Visibility of every source is exact in the reference (shadow rays); the
 * runtime methods approximate it, which is what the reference measures.
 */
#ifndef GB_BRDF_H
#define GB_BRDF_H

#include <math.h>

#define GB_PI 3.14159265358979323846f

typedef struct gb_brdf {
    float Kd[3];                /* diffuse reflectance, texture applied */
    float Ks[3];                /* Phong reflectance */
    float Ns;                   /* Phong exponent, >= 0 */
} gb_brdf;

/* (Ns + 2) / (2 pi): the Phong lobe's normalisation. */
static inline float gb_phong_normalization(float Ns)
{
    return (Ns + 2.0f) / (2.0f * GB_PI);
}

/* cos a, the cosine between wi and the mirror direction of wo about n. */
static inline float gb_phong_cos_mirror(float n_dot_wo, float n_dot_wi, float wo_dot_wi)
{
    return 2.0f * n_dot_wo * n_dot_wi - wo_dot_wi;
}

/* The Phong lobe's factor (Ns + 2) / (2 pi) max(0, cos a)^Ns, without Ks. */
static inline float gb_phong_lobe(float Ns, float cos_mirror)
{
    return cos_mirror > 0.0f ? gb_phong_normalization(Ns) * powf(cos_mirror, Ns) : 0.0f;
}

/* f(wo, wi) into f[3] (without the cosine of wi). */
static inline void gb_brdf_eval(const gb_brdf *brdf, float n_dot_wo, float n_dot_wi,
                                float wo_dot_wi, float f[3])
{
    if (n_dot_wo <= 0.0f || n_dot_wi <= 0.0f) {
        f[0] = f[1] = f[2] = 0.0f;
        return;
    }
    int glossy = brdf->Ks[0] > 0.0f || brdf->Ks[1] > 0.0f || brdf->Ks[2] > 0.0f;
    float lobe = glossy ? gb_phong_lobe(brdf->Ns, gb_phong_cos_mirror(n_dot_wo, n_dot_wi,
                                                                      wo_dot_wi))
                        : 0.0f;
    for (int c = 0; c < 3; ++c)
        f[c] = brdf->Kd[c] / GB_PI + brdf->Ks[c] * lobe;
}

/* Spot fall-off for cos_angle, the cosine of the angle between the spot's
 * direction and the direction from the spot to the point. */
static inline float gb_spot_falloff(float cos_angle, float cone_angle_degrees,
                                    float falloff_angle_degrees)
{
    float cos_cone = cosf(cone_angle_degrees * (GB_PI / 180.0f));
    float cos_falloff = cosf(falloff_angle_degrees * (GB_PI / 180.0f));
    if (cos_angle <= cos_cone)
        return 0.0f;
    if (cos_angle >= cos_falloff || cos_falloff <= cos_cone)
        return 1.0f;
    float t = (cos_angle - cos_cone) / (cos_falloff - cos_cone);
    return t * t * (3.0f - 2.0f * t);
}

/* Irradiance factor of a point source at distance squared r2: 1 / r^2. */
static inline float gb_inverse_square(float r2)
{
    return 1.0f / r2;
}

/* Intensity factor of a VPL toward a direction at cosine cos_vpl to its
 * normal: max(0, cos) / pi (times its power). */
static inline float gb_vpl_emission(float cos_vpl)
{
    return cos_vpl > 0.0f ? cos_vpl / GB_PI : 0.0f;
}

#endif
