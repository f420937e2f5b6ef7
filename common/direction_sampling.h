/* direction_sampling.h — unit directions and disc points from uniform
 * numbers, the densities light leaves a light and a diffuse surface with:
 *
 *   gb_cosine_direction   pdf cos(theta) / pi over the hemisphere around n
 *                         (Malley's method: a uniform point of the unit disc
 *                         lifted onto the hemisphere);
 *   gb_cone_direction     uniform over the cone of directions within
 *                         acos(cos_max) of axis, pdf 1 / (2 pi (1 - cos_max));
 *                         cos_max = -1: uniform over the sphere, 1 / (4 pi);
 *   gb_disc_point         uniform over the disc of radius r centred at c,
 *                         facing n, pdf 1 / (pi r^2).
 * n and axis are unit; u1, u2 uniform in [0, 1). Nothing is kept.
 */
#ifndef GB_DIRECTION_SAMPLING_H
#define GB_DIRECTION_SAMPLING_H

#include "vec3.h"

gb_vec3 gb_cosine_direction(gb_vec3 n, float u1, float u2);
gb_vec3 gb_cone_direction(gb_vec3 axis, float cos_max, float u1, float u2);
gb_vec3 gb_disc_point(gb_vec3 c, gb_vec3 n, float r, float u1, float u2);

#endif
