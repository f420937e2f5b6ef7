/* surface_coverage.h — how much of a leaf's gathering disc its surfaces
 * really cover, seen from a VDL's direction: the area its gathered flux
 * fell on, over the disc's.
 *
 * vivianloc-2007 §3.1.1 divides a leaf's gathered flux by the disc's π r²,
 * the area the flux fell on where one flat surface crosses the whole disc.
 * At a chart's edge half the disc is off the surface; in a corner the leaf
 * holds two surfaces, each receiving from its own side; over a gap (a light
 * just under a ceiling) the ellipsoid holds both, but the light hides the
 * ceiling from below. There Φ / (π r²) is wrong (McGuire's box read through
 * the octree: its chart edges 29 % dark). With A(ω) the area of the
 * surface inside the gathering ellipsoid (gathering.h) seen from ω (toward
 * the light), projected on the plane across ω, a nearer surface hiding a
 * farther one, and A_plane(ω) = π r² |n_leaf · ω| the same for the leaf's
 * own plane through the centre, the coverage is
 *     κ(ω) = A(ω) / A_plane(ω),
 * and a VDL's irradiance on the leaf's plane is Φ / (κ π r²): the paper's
 * for one flat surface (κ = 1), and Φ / A(ω) across ω, whatever the
 * surfaces, once the shading (light_octree_shading.h) turns it by
 * n · ω / |n_leaf · ω|.
 *
 * Measured with Embree, both areas by the same GB_SURFACE_COVERAGE_RAYS
 * parallel rays along -ω over the disc of radius r across ω (Vogel's
 * spiral), each from 2 r away: A counts a ray whose first surface lies
 * inside the ellipsoid (a triangle's back met before it is the outside of a
 * wall the ray started behind: passed), A_plane one whose crossing of the
 * leaf's plane does. So κ is exactly 1 for one flat surface, and the
 * rays' discreteness cancels. Below |n_leaf · ω| = MIN_COS (the shading's
 * bound), where few rays meet the plane, κ(n_leaf) stands for κ(ω); 1 when
 * no ray met a surface.
 *
 * Thread-safe; the caller owns every argument.
 */
#ifndef GB_CLUSTER_SURFACE_COVERAGE_H
#define GB_CLUSTER_SURFACE_COVERAGE_H

#include "embree_scene.h"
#include "gathering.h"
#include "scene.h"

enum { GB_SURFACE_COVERAGE_RAYS = 64 };

/* κ(ω) over the region (a leaf's, its normal the leaf's), ω unit toward
 * the light; rays holds scene's triangles. */
float gb_surface_coverage(const gb_embree_scene *rays, const gb_scene *scene,
                          const gb_gathering_region *region, const float direction[3]);

#endif
