/* gutter.c — the lightmap's gutter, round by round (gutter.h). */
#include "gutter.h"

#include <stdlib.h>
#include <string.h>

/* Texel (x, y) of an unfilled texel from its filled neighbours in before
 * (flags was); 1 if it got a value. */
static int fill_texel(gb_image *image, const float *before, const uint8_t *was, int x, int y)
{
    int w = image->width, h = image->height, c = image->channels;
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float count = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h || !was[(size_t)qy * w + qx])
                continue;
            for (int k = 0; k < c && k < 4; ++k)
                sum[k] += before[((size_t)qy * w + qx) * c + k];
            count += 1.0f;
        }
    if (count == 0.0f)
        return 0;
    for (int k = 0; k < c && k < 4; ++k)
        image->pixels[((size_t)y * w + x) * c + k] = sum[k] / count;
    return 1;
}

int64_t gb_gutter_fill(gb_image *image, uint8_t *filled, uint32_t rounds)
{
    size_t texels = (size_t)image->width * image->height;
    float *before = malloc(texels * image->channels * sizeof *before);
    uint8_t *was = malloc(texels);
    if (!before || !was) {
        free(before);
        free(was);
        return -1;
    }
    int64_t count = 0;
    for (uint32_t round = 0; round < rounds; ++round) {
        memcpy(before, image->pixels, texels * image->channels * sizeof *before);
        memcpy(was, filled, texels);
        for (int y = 0; y < image->height; ++y)
            for (int x = 0; x < image->width; ++x) {
                size_t k = (size_t)y * image->width + x;
                if (!was[k] && fill_texel(image, before, was, x, y)) {
                    filled[k] = 1;
                    ++count;
                }
            }
    }
    free(before);
    free(was);
    return count;
}
