/* mesh_openmesh.h — the OpenMesh adapter (formats/mesh_openmesh.cpp, the
 * only C++ that touches OpenMesh): reads PLY, OFF and STL meshes, ASCII or
 * binary, into indexed triangles. Polygons are fan-triangulated. STL
 * triangles share a vertex where OpenMesh finds equal positions.
 *
 * OpenMesh builds a half-edge mesh: a face that would make an edge
 * non-manifold is kept on its own copies of its vertices (so vertex_count
 * may exceed the file's), and a face that repeats a vertex is refused; those,
 * and faces of fewer than 3 corners (lines, points), are degenerate and
 * counted in *skipped_faces. Before OpenMesh reads the
 * file, gb_mesh_check_file (mesh_check.h) walks its bytes as OpenMesh will
 * and refuses what OpenMesh would misread, crash or loop on, or allocate
 * for beyond what the file holds: a NaN, Inf or malformed number is named
 * with its line and vertex ("file:line: vertex 3: y 'nan' is not finite"),
 * as are counts the file cannot hold and vertex indices out of range. PLY
 * and OFF headers say how many faces follow: fewer read is still an error,
 * as are fewer vertices read. OpenMesh's messages (std::cerr) are captured
 * while reading, which is why reads must not run in parallel.
 *
 * On success the caller owns *positions (vertex_count * 3 floats) and
 * *indices (triangle_count * 3), both malloc'ed: release them with free().
 */
#ifndef GB_MESH_OPENMESH_H
#define GB_MESH_OPENMESH_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "result.h"

gb_result gb_openmesh_read(const char *path, float **positions, uint32_t *vertex_count,
                           uint32_t **indices, uint32_t *triangle_count,
                           uint32_t *skipped_faces, gb_error *error);

#ifdef __cplusplus
}
#endif

#endif
