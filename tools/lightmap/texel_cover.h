/* texel_cover.h — which scene triangle covers the centre of each atlas
 * texel (lightmap.h): every triangle rasterised at its atlas UVs, in texel
 * units (u · width, v · height), the centre of texel (i, j) at
 * (i + 0.5, j + 0.5). A centre on an edge shared by two triangles belongs
 * to one of them (a tie rule on the edge's direction, as a GPU's fill
 * rule), so each centre has at most one triangle; were two triangles to
 * overlap (the atlas's writer checks they do not), the later one in scene
 * order keeps the texel.
 *
 * The caller owns the gb_texel_cover and frees it with gb_texel_cover_free
 * (also on a zeroed one).
 */
#ifndef GB_TEXEL_COVER_H
#define GB_TEXEL_COVER_H

#include <stdint.h>

#include "atlas.h"
#include "result.h"

#define GB_TEXEL_NONE 0xFFFFFFFFu

typedef struct gb_texel_cover {
    uint32_t width, height;
    uint32_t *triangle;         /* width * height, row 0 first: a triangle or GB_TEXEL_NONE */
} gb_texel_cover;

gb_result gb_texel_cover_make(const gb_atlas *atlas, gb_texel_cover *cover, gb_error *error);
void gb_texel_cover_free(gb_texel_cover *cover);

/* The barycentric weights of triangle t's corners 0, 1, 2 at the centre of
 * texel (i, j) (summing to 1; in [0, 1] when t covers it). */
void gb_texel_barycentric(const gb_atlas *atlas, uint32_t t, uint32_t i, uint32_t j,
                          double weights[3]);

/* For texel (i, j), which no triangle covers: of the triangles covering its
 * 8 neighbours, the one whose point nearest the texel's centre (texel
 * units) is nearest, ties to the smaller index, with the barycentric
 * weights of the centre in it (extended past its edges: some negative);
 * GB_TEXEL_NONE when no neighbour is covered. The gutter's first ring (the
 * runtime's octree_atlas_border.frag.glsl). */
uint32_t gb_texel_border_triangle(const gb_atlas *atlas, const gb_texel_cover *cover,
                                  uint32_t i, uint32_t j, double weights[3]);

#endif
