/* mesh_check.h — the bytes of a PLY, OFF or STL file checked before the
 * OpenMesh adapter (formats/mesh_openmesh.cpp) hands the file to OpenMesh.
 *
 * OpenMesh 9 trusts its input: header counts and a face's corner count
 * size its allocations before anything is read (a 150-byte PLY made it
 * allocate 2 GB), a PLY header without end_header or with a malformed
 * count loops forever, a property before the first element dereferences an
 * empty vector, and a NaN or a malformed number in an ASCII file makes
 * every later read fail silently (seen as "faces unread"). This check
 * walks the file the way OpenMesh will read it and refuses:
 *
 *  - a non-finite (NaN, Inf, beyond the float range) or malformed number
 *    among the coordinates, naming it, its line and its vertex (ASCII:
 *    "file:line: vertex 3: y 'nan' is not finite"; binary: "file: vertex 3:
 *    y is not finite (nan)"; STL: "facet 2: vertex 1: ...");
 *  - counts the file cannot hold: an element or header count needing more
 *    bytes than follow the header (each ASCII value takes at least 2 bytes,
 *    each binary value its size), a face with more corners than the rest of
 *    the file holds, a vertex index out of range, a truncated body;
 *  - PLY headers OpenMesh mishandles: no end_header, a malformed count or
 *    version, a property before any element, unknown types, list
 *    properties other than the faces' vertex_indices (OpenMesh reads them
 *    as one value), face properties before vertex_indices, a binary body
 *    that OpenMesh would start at the wrong byte (a comment or blanks just
 *    before or after end_header);
 *  - OFF: comments, 4OFF/nOFF, big-endian binary (OpenMesh reads
 *    little-endian only).
 *
 * The walk follows OpenMesh 9.0's readers (PLYReader, OFFReader, STLReader):
 * ASCII values are whitespace-separated tokens; OFF vertices end with the
 * rest of their line (colours, texture coordinates); an STL file is binary
 * when its size is 84 + 50 times the count at byte 80, and in ASCII the
 * three lines after a line containing "outer" are its vertices. Vertices,
 * faces and facets are numbered from 0, as face lists number vertices.
 *
 * Messages read "path:line: what is wrong" (ASCII) or "path: what is
 * wrong". On success *counts holds what the header declares (-1 where the
 * format says nothing: STL), to compare with what OpenMesh read.
 */
#ifndef GB_MESH_CHECK_H
#define GB_MESH_CHECK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "result.h"

typedef struct gb_mesh_counts {
    long long vertices, faces;  /* -1: not declared */
    long long short_faces;      /* faces of fewer than 3 corners (lines, points),
                                   which OpenMesh drops without a word */
} gb_mesh_counts;

/* bytes of a file named path (.ply, .off or .stl, ignoring case). */
gb_result gb_mesh_check(const void *bytes, size_t size, const char *path,
                        gb_mesh_counts *counts, gb_error *error);
/* The same on the file at path (mapped, not copied). */
gb_result gb_mesh_check_file(const char *path, gb_mesh_counts *counts, gb_error *error);

#ifdef __cplusplus
}
#endif

#endif
