/* atlas_mask.h — the texels a triangle of an atlas holds, padded: the one
 * conservative raster that both the writer (tools/atlas/packing.c, which
 * places the charts) and the reader (atlas.c, which checks that no two
 * charts' padded masks share a texel) use, so that what the packer kept
 * apart the reader finds apart (formats/FORMATS.md, "Atlas").
 *
 * Corners are in texel coordinates (x = u * width, y = v * height; texel
 * (i, j) is the square [i, i + 1) x [j, j + 1)). With a margin m >= 0, a
 * triangle touches texel (i, j) when the open square (i - m, i + 1 + m) x
 * (j - m, j + 1 + m) meets it: every texel square the triangle overlaps,
 * not those it only touches along an edge or a corner (m = 0, the file's
 * rule). Its padded mask with padding P: the texels within P of one it
 * touches along x and along y (a square of 2P + 1 texels about each).
 * A chart's (padded) mask is the union of its triangles'.
 *
 * Why disjoint padded masks keep charts apart: a point of a triangle lies
 * in the closed square of a texel the triangle touches. If the padded
 * masks of charts A and B share no texel, every texel A touches is more
 * than 2P columns or more than 2P rows from every texel B touches, so two
 * points of A and B are at least 2P texels apart along x or along y.
 *
 * The margin lets the packer raster a chart before its UVs are rounded to
 * fixed point (tools/atlas/atlas_build.h): a corner moved by at most m
 * along x and y moves every point of the triangle by at most m, so the
 * triangle with rounded corners touches (m = 0) only texels the one before
 * rounding touches with the margin m.
 *
 * Pure functions of their arguments, exact up to the rounding of one
 * division per edge (1e-12 texels at the largest atlas).
 */
#ifndef GB_ATLAS_MASK_H
#define GB_ATLAS_MASK_H

#include <stddef.h>
#include <stdint.h>

/* Triangle t's corners in texel coordinates from its six UVs (exact: a
 * float times an integer of at most 15 bits fits a double). */
void gb_atlas_texel_corners(const float uv[6], uint32_t width, uint32_t height,
                            double corners[6]);

/* One triangle's padded mask, row by row: rows first .. first + count - 1,
 * row first + k holding columns[2k] .. columns[2k + 1] (inclusive). The
 * rows of the triangle within P of a row are consecutive and their columns
 * overlap or touch (the triangle is convex), so each row is one run. The
 * rows and columns may lie outside the atlas. Zero it before the first
 * gb_atlas_mask_of; it keeps its arrays from one triangle to the next;
 * the caller frees them with gb_atlas_mask_free. */
typedef struct gb_atlas_mask {
    int64_t first;
    uint32_t count;
    int64_t *columns;
    size_t capacity;            /* rows the arrays hold */
    uint32_t *queue;            /* scratch of the sliding window */
} gb_atlas_mask;

/* The padded mask of the triangle of these corners (texel coordinates),
 * margin m >= 0, padding P. Returns 1, or 0 when out of memory (the mask
 * then holds no row). */
int gb_atlas_mask_of(gb_atlas_mask *mask, const double corners[6], double margin,
                     uint32_t padding);
void gb_atlas_mask_free(gb_atlas_mask *mask);

#endif
