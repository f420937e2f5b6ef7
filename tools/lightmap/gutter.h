/* gutter.h — the texels around the charts of a lightmap filled from the
 * filled ones (lightmap.h), so that a bilinear read at a chart's border
 * never reaches black: `rounds` rounds (the atlas's padding less one: the
 * triangles' reach fills the first ring, texel_cover.h), each giving
 * every unfilled texel that has filled neighbours the mean of its filled 8
 * neighbours as they were before the round. It is the rule of the
 * runtime's render into the atlas (octree_atlas_gutter.frag.glsl), so the
 * two lightmaps agree in the gutter too. As the charts' padded masks share
 * no texel (atlas.h: the texels a chart's triangles overlap, grown by the
 * padding; the reach's texels and the rounds stay within them), a gutter
 * texel only takes values of its own chart.
 *
 * filled: width * height flags, 1 where a texel holds a value; updated.
 * Returns the number of texels filled, or -1 when out of memory.
 */
#ifndef GB_GUTTER_H
#define GB_GUTTER_H

#include <stdint.h>

#include "image.h"

int64_t gb_gutter_fill(gb_image *image, uint8_t *filled, uint32_t rounds);

#endif
