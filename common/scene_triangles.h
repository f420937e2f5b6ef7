/* scene_triangles.h — a scene triangle's corners and normals, and the
 * corners of the scene's bounds, one definition for the reference
 * renderer, the runtime and the bakers (the front normal is the side that
 * emits: common/brdf.h, "Sides").
 *
 *   gb_vec3 face = gb_triangle_normal(scene, t);        // unit, cross(v1 - v0, v2 - v0)
 *   gb_vec3 n = gb_corner_normal(scene, t, k, face);    // the mesh's, or face
 */
#ifndef GB_SCENE_TRIANGLES_H
#define GB_SCENE_TRIANGLES_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "scene.h"
#include "vec3.h"

/* Corner k (0..7) of the scene's bounds: bit 0 of k picks x's max, bit 1
 * y's, bit 2 z's. */
static inline gb_vec3 gb_scene_bounds_corner(const gb_scene *scene, int k)
{
    return gb_vec3_make(k & 1 ? scene->bounds_max[0] : scene->bounds_min[0],
                        k & 2 ? scene->bounds_max[1] : scene->bounds_min[1],
                        k & 4 ? scene->bounds_max[2] : scene->bounds_min[2]);
}

/* Corner k (0, 1, 2) of triangle t. */
static inline gb_vec3 gb_triangle_corner(const gb_scene *scene, uint32_t t, int k)
{
    return gb_vec3_load(&scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + k]]);
}

/* The unit front normal of triangle t, cross(v1 - v0, v2 - v0) normalised
 * (the scene has no zero-area triangle: gb_scene_finish drops them). */
static inline gb_vec3 gb_triangle_normal(const gb_scene *scene, uint32_t t)
{
    gb_vec3 a = gb_triangle_corner(scene, t, 0);
    gb_vec3 b = gb_triangle_corner(scene, t, 1), c = gb_triangle_corner(scene, t, 2);
    return gb_vec3_normalize(gb_vec3_cross(gb_vec3_sub(b, a), gb_vec3_sub(c, a)));
}

/* The mesh's normal at corner k of triangle t, unit, when it has one that
 * is usable (finite, not zero); face otherwise. */
static inline gb_vec3 gb_corner_normal(const gb_scene *scene, uint32_t t, int k, gb_vec3 face)
{
    if (!scene->corner_normals)
        return face;
    gb_vec3 n = gb_vec3_normalize(gb_vec3_load(&scene->corner_normals[9 * (size_t)t + 3 * k]));
    return isfinite(n.x + n.y + n.z) && gb_vec3_length(n) > 0.5f ? n : face;
}

#endif
