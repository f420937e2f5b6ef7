/* cubical_complex.h — the empty space of a voxel grid as a 3-D cubical
 * complex (Chaussard & Couprie, IWCIA 2009, section 2), the object thin
 * collapses.
 *
 * Every empty voxel becomes a closed unit cube: the 3-face itself and all its
 * faces (6 squares, 12 edges, 8 points). Two cubes that share only an edge or
 * a corner share that edge or point, so the components of the complex are the
 * 26-connected components of the empty voxels.
 *
 * Storage: one byte per lattice point ("cell") of a lattice padded by one
 * layer below and two above on every axis; the byte holds the faces whose
 * lowest corner is that point (bit names below). Voxel (i,j,k) of the grid is
 * the cube of cell (i+1,j+1,k+1); the point of cell (x,y,z) is the world
 * position world_origin + voxel_size * (x-1, y-1, z-1). Only cells 1..n+1 of
 * an axis of n voxels hold faces (n+1 only the upper boundary's points, edges
 * and squares), so a cell holding a face and its 26 neighbours are always
 * inside the array. Voxels outside the grid count as not empty.
 *
 * The caller owns the complex and frees it with gb_cubical_complex_free.
 */
#ifndef GB_CUBICAL_COMPLEX_H
#define GB_CUBICAL_COMPLEX_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"
#include "voxel_grid.h"

/* The faces a cell holds: the point, the three edges leaving it towards +x,
 * +y, +z, the three squares spanned from it, the cube. */
enum {
    GB_FACE_POINT = 1u << 0,
    GB_FACE_EDGE_X = 1u << 1,
    GB_FACE_EDGE_Y = 1u << 2,
    GB_FACE_EDGE_Z = 1u << 3,
    GB_FACE_SQUARE_YZ = 1u << 4, /* the square normal to x: spans y and z */
    GB_FACE_SQUARE_XZ = 1u << 5, /* normal to y */
    GB_FACE_SQUARE_XY = 1u << 6, /* normal to z */
    GB_FACE_CUBE = 1u << 7,
    GB_FACE_EDGES = GB_FACE_EDGE_X | GB_FACE_EDGE_Y | GB_FACE_EDGE_Z,
    GB_FACE_SQUARES = GB_FACE_SQUARE_YZ | GB_FACE_SQUARE_XZ | GB_FACE_SQUARE_XY,
};

/* The edge along axis a is GB_FACE_EDGE_X << a; the square normal to axis a
 * is GB_FACE_SQUARE_YZ << a. */
static inline uint8_t gb_edge_bit(int axis) { return (uint8_t)(GB_FACE_EDGE_X << axis); }
static inline uint8_t gb_square_bit(int normal_axis)
{
    return (uint8_t)(GB_FACE_SQUARE_YZ << normal_axis);
}

/* Number of faces in bits (a table lookup: no popcount instruction assumed). */
static inline int gb_face_count(uint8_t bits)
{
    static const uint8_t nibble[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    return nibble[bits & 15] + nibble[bits >> 4];
}

typedef struct gb_cubical_complex {
    int32_t size[3];    /* cells along x, y, z: the grid's voxels + 3 */
    size_t step[3];     /* index offset of one cell along x, y, z */
    size_t cell_count;
    uint8_t *faces;     /* cell_count bytes of GB_FACE_* bits */
} gb_cubical_complex;

/* The complex of the empty voxels (surface == 0) of grid. */
gb_result gb_cubical_complex_build(gb_cubical_complex *complex, const gb_voxel_grid *grid,
                                   gb_error *error);
void gb_cubical_complex_free(gb_cubical_complex *complex);

static inline size_t gb_cell_index(const gb_cubical_complex *complex, int32_t x, int32_t y,
                                   int32_t z)
{
    return (size_t)x + complex->step[1] * (size_t)y + complex->step[2] * (size_t)z;
}

/* The cell of voxel (i,j,k) of the grid. */
static inline size_t gb_voxel_cell(const gb_cubical_complex *complex, int32_t i, int32_t j,
                                   int32_t k)
{
    return gb_cell_index(complex, i + 1, j + 1, k + 1);
}

void gb_cell_coordinates(const gb_cubical_complex *complex, size_t cell, int32_t xyz[3]);

/* Number of faces of one dimension higher that contain the face: the edges
 * of a point (0..6), the squares of an edge along axis (0..4). */
static inline int gb_point_coface_count(const gb_cubical_complex *complex, size_t cell)
{
    const uint8_t *f = complex->faces;
    const size_t *s = complex->step;
    return gb_face_count(f[cell] & GB_FACE_EDGES) + ((f[cell - s[0]] & GB_FACE_EDGE_X) != 0) +
           ((f[cell - s[1]] & GB_FACE_EDGE_Y) != 0) + ((f[cell - s[2]] & GB_FACE_EDGE_Z) != 0);
}

/* The squares containing the edge along axis at cell: for each other axis b,
 * the square normal to b at the cell and at the cell one step back along the
 * third axis. */
static inline int gb_edge_coface_count(const gb_cubical_complex *complex, size_t cell, int axis)
{
    const uint8_t *f = complex->faces;
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    uint8_t square_b = gb_square_bit(b), square_c = gb_square_bit(c);
    return ((f[cell] & square_b) != 0) + ((f[cell] & square_c) != 0) +
           ((f[cell - complex->step[c]] & square_b) != 0) +
           ((f[cell - complex->step[b]] & square_c) != 0);
}

/* Counts of the faces of each dimension, and the Euler characteristic
 * points - edges + squares - cubes (whole-complex sweep; for tests and
 * statistics). */
typedef struct gb_face_counts {
    uint64_t points, edges, squares, cubes;
} gb_face_counts;

gb_face_counts gb_cubical_complex_count(const gb_cubical_complex *complex);
int64_t gb_euler_characteristic(gb_face_counts counts);

#endif
