/* texel_surface.c — one side of a triangle at a texel (texel_surface.h). */
#include "texel_surface.h"

#include "scene_triangles.h"

gb_texel_surface gb_texel_surface_at(const gb_scene *scene, uint32_t t, const double w[3],
                                     float side)
{
    gb_vec3 face = gb_vec3_scale(gb_triangle_normal(scene, t), side);
    gb_vec3 normal = {0.0f, 0.0f, 0.0f};
    double point[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
        gb_vec3 corner = gb_triangle_corner(scene, t, c);
        point[0] += w[c] * corner.x;
        point[1] += w[c] * corner.y;
        point[2] += w[c] * corner.z;
        normal = gb_vec3_madd(normal, gb_corner_normal(scene, t, c, face), (float)w[c]);
    }
    normal = gb_vec3_length(normal) > 0.0f ? gb_vec3_normalize(normal) : face;
    if (gb_vec3_dot(normal, face) < 0.0f)
        normal = gb_vec3_negate(normal);
    gb_texel_surface s = {{(float)point[0], (float)point[1], (float)point[2]}, normal, face};
    return s;
}
