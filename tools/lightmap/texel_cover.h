/* texel_cover.h — which scene triangle's field each atlas texel holds
 * (lightmap.h): every triangle rasterised at its atlas UVs, in texel units
 * (u · width, v · height), the centre of texel (i, j) at (i + 0.5, j + 0.5),
 * with a reach (texels): a texel goes to the triangle nearest its centre,
 * within the reach, ties to the smaller index. With gb_atlas_reach of the
 * atlas's padding (√2 texels at the default), what the runtime's render
 * into the atlas (octree_atlas_render.*.glsl) draws; with 0, the texels
 * whose centre a triangle covers. Texels beyond every triangle's reach get
 * GB_TEXEL_NONE (the gutter's further rounds fill them).
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

gb_result gb_texel_cover_make(const gb_atlas *atlas, double reach, gb_texel_cover *cover,
                              gb_error *error);
void gb_texel_cover_free(gb_texel_cover *cover);

/* The barycentric weights of triangle t's corners 0, 1, 2 at the centre of
 * texel (i, j) (summing to 1; in [0, 1] inside t, some negative past its
 * edges: its plane extended). */
void gb_texel_barycentric(const gb_atlas *atlas, uint32_t t, uint32_t i, uint32_t j,
                          double weights[3]);

#endif
