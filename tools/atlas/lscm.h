/* lscm.h — least-squares conformal maps (Lévy et al. 2002) of one chart,
 * through CGAL's Surface_mesh_parameterization::LSCM_parameterizer_3
 * (tools/atlas/lscm_cgal.cpp, the only C++ that touches CGAL).
 *
 * The chart comes as an indexed triangle mesh of its own: vertex_count
 * positions (x, y, z doubles) and triangle_count triangles of three vertex
 * indices, consistently oriented, every vertex manifold (discs.h builds it
 * so). It must be a topological disc; two far vertices of its border are
 * pinned (CGAL's Two_vertices_parameterizer_3) and the rest solved in the
 * least-squares sense.
 *
 * On GB_OK, uvs (vertex_count * 2 doubles, the caller's) holds each
 * vertex's (u, v), finite, at an arbitrary scale, rotation and possibly
 * mirrored: the caller normalises. On any failure (a CGAL error code, an
 * exception, a non-finite result) it returns GB_ERROR_UNSUPPORTED with
 * CGAL's reason in error, and uvs is unspecified. Reentrant: nothing is
 * shared between calls.
 */
#ifndef GB_LSCM_H
#define GB_LSCM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "result.h"

gb_result gb_lscm_parameterize(uint32_t vertex_count, const double *positions,
                               uint32_t triangle_count, const uint32_t *triangles,
                               double *uvs, gb_error *error);

#ifdef __cplusplus
}
#endif

#endif
