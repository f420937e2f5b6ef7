/* texel_surface.h — the surface a lightmap texel stands for: one side of
 * its triangle at the texel centre's barycentric weights (lightmap.h,
 * "Decided here"). Nothing is allocated; the caller owns the scene.
 */
#ifndef GB_TEXEL_SURFACE_H
#define GB_TEXEL_SURFACE_H

#include <stdint.h>

#include "scene.h"
#include "vec3.h"

typedef struct gb_texel_surface {
    gb_vec3 x;                  /* on the triangle's plane (w may reach past its edges) */
    gb_vec3 n;                  /* unit shading normal, on ng's side */
    gb_vec3 ng;                 /* unit geometric normal of the side */
} gb_texel_surface;

/* Side `side` (1: the side the winding faces, cross(v1 - v0, v2 - v0); -1
 * the back) of triangle t at weights w: the corners' normals as the
 * runtime gives them (scene_triangles.h) interpolated, normalised, turned
 * to ng's side (the face normal where they cancel). */
gb_texel_surface gb_texel_surface_at(const gb_scene *scene, uint32_t t, const double w[3],
                                     float side);

#endif
