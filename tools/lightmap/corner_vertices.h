/* corner_vertices.h — the corners of a mesh primitive made into vertices
 * for the glTF export (glb_export.h): corners whose every attribute is the
 * same (bit for bit) share a vertex, corners that differ in any (a crease's
 * normals, a seam of the atlas or of the texture) get a vertex each.
 * Vertices are numbered in the order of their first corner, so the result
 * depends only on the corners.
 *
 * corners: corner_count * GB_VERTEX_FLOATS floats (position, normal,
 * texcoord 0, texcoord 1). The caller owns what it passes and the
 * gb_corner_vertices it gets (gb_corner_vertices_free, also on a zeroed
 * one).
 */
#ifndef GB_CORNER_VERTICES_H
#define GB_CORNER_VERTICES_H

#include <stdint.h>

#include "result.h"

enum { GB_VERTEX_FLOATS = 10 };

typedef struct gb_corner_vertices {
    float *vertices;            /* count * GB_VERTEX_FLOATS */
    uint32_t count;
    uint32_t *indices;          /* per corner: its vertex */
} gb_corner_vertices;

gb_result gb_corner_vertices_make(const float *corners, uint32_t corner_count,
                                  gb_corner_vertices *out, gb_error *error);
void gb_corner_vertices_free(gb_corner_vertices *vertices);

#endif
