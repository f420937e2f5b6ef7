/* texel_interpolation.h — which texels a lightmap gathers and which it
 * interpolates (Ward, Rubinstein and Clear 1988, "A ray tracing solution
 * for diffuse interreflection": irradiance changes over the distance to the
 * surfaces a point sees, so a gather stands for its neighbours within a
 * fraction `a` of that distance), on the atlas's texel grid:
 *
 *   the texels on the lattice of stride GB_TEXEL_TOP_STRIDE gather; then,
 *   for s = GB_TEXEL_TOP_STRIDE / 2, ..., 1, each texel on the lattice of
 *   stride s but not 2 s is the bilinear mean of the corners of its cell
 *   of the 2 s lattice (2 or 4 texels, computed before it) when every
 *   corner k with a weight holds the same chart and side and
 *       ε_k = |x − x_k| / R_k + sqrt(1 − n · n_k)  <=  a
 *   (R_k the harmonic mean distance of k's gather rays, final_gather.h; an
 *   interpolated texel's R is its corners' least), else it gathers.
 *
 * With a = 0 every texel gathers. Pure functions of their arguments.
 */
#ifndef GB_TEXEL_INTERPOLATION_H
#define GB_TEXEL_INTERPOLATION_H

#include <stdint.h>

#include "vec3.h"

enum { GB_TEXEL_TOP_STRIDE = 8 };

/* The stride s of texel (i, j)'s pass: the largest power of two up to
 * top_stride that divides both i and j. */
int gb_texel_stride(uint32_t i, uint32_t j, int top_stride);

typedef struct gb_texel_corner {
    uint32_t i, j;
    double weight;              /* > 0; a texel's corners sum to 1 */
} gb_texel_corner;

/* The corners with a weight of the 2 s lattice's cell holding texel (i, j)
 * of stride s < top_stride, in an atlas width x height; returns how many
 * (2 or 4), or 0 when one lies outside the atlas. */
int gb_texel_corners(uint32_t i, uint32_t j, int stride, uint32_t width, uint32_t height,
                     gb_texel_corner corners[4]);

/* Ward's error ε of a point x with unit normal n against a gather at x_k,
 * normal n_k, harmonic mean distance R_k. */
double gb_ward_error(gb_vec3 x, gb_vec3 n, gb_vec3 x_k, gb_vec3 n_k, float R_k);

#endif
