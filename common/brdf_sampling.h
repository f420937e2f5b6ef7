/* brdf_sampling.h — importance sampling of the gibake BRDF (common/brdf.h)
 * for the reference path tracer: a cosine-weighted diffuse lobe and the
 * Phong lobe around the mirror direction, chosen in proportion to the
 * luminance of Kd and Ks.
 *
 * n is the unit shading normal turned to the side of wo; every direction is
 * unit and points away from the surface.
 */
#ifndef GB_BRDF_SAMPLING_H
#define GB_BRDF_SAMPLING_H

#include "brdf.h"
#include "vec3.h"

typedef struct gb_brdf_sample {
    gb_vec3 wi;
    gb_vec3 weight;             /* f(wo, wi) dot(n, wi) / pdf */
    float pdf;                  /* solid-angle density of wi */
} gb_brdf_sample;

/* f(wo, wi) (common/brdf.h) for vectors. */
gb_vec3 gb_brdf_eval_vectors(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, gb_vec3 wi);

/* Density with which gb_brdf_sample_direction picks wi. */
float gb_brdf_pdf(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, gb_vec3 wi);

/* Picks wi from three uniform numbers in [0, 1). Returns 0, and no sample,
 * when the surface reflects nothing or wi falls below the surface. */
int gb_brdf_sample_direction(const gb_brdf *brdf, gb_vec3 n, gb_vec3 wo, float u_lobe,
                             float u1, float u2, gb_brdf_sample *sample);

#endif
