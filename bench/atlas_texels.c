/* atlas_texels.c — where an atlas's texels go (bench/atlas.sh), as shares
 * of width x height:
 *
 *   atlas_texels NAME.atlas
 *
 * triangles  the triangles' UV area in texels (the fill ratio);
 * masks      the texels the triangles overlap (formats/atlas_mask.h, no
 *            padding) less the triangles' area: the raster's slack;
 * gutters    the texels of the padded masks less those of the masks;
 * unused     the texels in no padded mask.
 * The four add up to 1. Prints "NAME VALUE" lines.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "atlas.h"
#include "atlas_mask.h"

/* Marks triangle t's mask (padding P) in covered, one byte a texel. */
static int mark(const gb_atlas *atlas, uint32_t t, uint32_t padding, gb_atlas_mask *mask,
                unsigned char *covered)
{
    const gb_atlas_header *h = &atlas->header;
    double corners[6];
    gb_atlas_texel_corners(atlas->uvs + 6 * (size_t)t, h->width, h->height, corners);
    if (!gb_atlas_mask_of(mask, corners, 0.0, padding))
        return 0;
    for (uint32_t k = 0; k < mask->count; ++k) {
        int64_t row = mask->first + k;
        for (int64_t i = mask->columns[2 * k]; i <= mask->columns[2 * k + 1]; ++i)
            if (row >= 0 && row < h->height && i >= 0 && i < h->width)
                covered[(size_t)row * h->width + (size_t)i] = 1;
    }
    return 1;
}

/* The texels in the masks of padding P, or -1 when out of memory. */
static double masks_texels(const gb_atlas *atlas, uint32_t padding)
{
    const gb_atlas_header *h = &atlas->header;
    unsigned char *covered = calloc((size_t)h->width * h->height, 1);
    gb_atlas_mask mask = {0};
    double count = covered ? 0.0 : -1.0;
    for (uint32_t t = 0; covered && t < h->triangle_count; ++t)
        if (!mark(atlas, t, padding, &mask, covered))
            count = -1.0;
    for (size_t k = 0; count >= 0.0 && k < (size_t)h->width * h->height; ++k)
        count += covered[k];
    gb_atlas_mask_free(&mask);
    free(covered);
    return count;
}

static double triangle_texels(const gb_atlas *atlas)
{
    const gb_atlas_header *h = &atlas->header;
    double sum = 0.0;
    for (uint32_t t = 0; t < h->triangle_count; ++t) {
        double p[6];
        gb_atlas_texel_corners(atlas->uvs + 6 * (size_t)t, h->width, h->height, p);
        sum += 0.5 * fabs((p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]));
    }
    return sum;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: atlas_texels NAME.atlas\n");
        return 2;
    }
    gb_atlas atlas;
    gb_error error;
    if (gb_atlas_read(argv[1], &atlas, &error) != GB_OK) {
        fprintf(stderr, "atlas_texels: %s\n", error.message);
        return 1;
    }
    double all = (double)atlas.header.width * atlas.header.height;
    double triangles = triangle_texels(&atlas);
    double masks = masks_texels(&atlas, 0), padded = masks_texels(&atlas, atlas.header.padding);
    gb_atlas_free(&atlas);
    if (masks < 0.0 || padded < 0.0) {
        fprintf(stderr, "atlas_texels: out of memory\n");
        return 1;
    }
    printf("triangles %.3f\nmasks %.3f\ngutters %.3f\nunused %.3f\n", triangles / all,
           (masks - triangles) / all, (padded - masks) / all, (all - padded) / all);
    return 0;
}
