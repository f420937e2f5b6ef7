/* texel_interpolation.c — the texel lattice and Ward's error
 * (texel_interpolation.h). */
#include "texel_interpolation.h"

#include <math.h>

int gb_texel_stride(uint32_t i, uint32_t j, int top_stride)
{
    int stride = 1;
    while (stride < top_stride && i % (2u * stride) == 0 && j % (2u * stride) == 0)
        stride *= 2;
    return stride;
}

int gb_texel_corners(uint32_t i, uint32_t j, int stride, uint32_t width, uint32_t height,
                     gb_texel_corner corners[4])
{
    uint32_t cell = 2u * (uint32_t)stride;
    uint32_t i0 = i - i % cell, j0 = j - j % cell;
    double fx = (double)(i - i0) / cell, fy = (double)(j - j0) / cell;
    int count = 0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            double weight = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
            if (weight <= 0.0)
                continue;
            uint32_t ci = i0 + (uint32_t)dx * cell, cj = j0 + (uint32_t)dy * cell;
            if (ci >= width || cj >= height)
                return 0;
            corners[count++] = (gb_texel_corner){ci, cj, weight};
        }
    return count;
}

double gb_ward_error(gb_vec3 x, gb_vec3 n, gb_vec3 x_k, gb_vec3 n_k, float R_k)
{
    double distance = gb_vec3_length(gb_vec3_sub(x, x_k));
    double turn = 1.0 - (double)gb_vec3_dot(n, n_k);
    return distance / (double)R_k + sqrt(turn > 0.0 ? turn : 0.0);
}
