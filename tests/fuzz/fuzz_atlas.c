/* fuzz_atlas.c — libFuzzer target for the `.atlas` reader (formats/atlas.c):
 * any input gives either an atlas that passes gb_atlas_check, or an error
 * "fuzz: ...", never a crash or a read out of bounds (run under ASan/UBSan
 * by `make fuzz`). The input is copied into a 16-byte aligned buffer, as a
 * mapped file is; every UV of a parsed atlas is turned into the texel the
 * runtime would fetch and checked to lie in its chart's rect, grown by the
 * padding and by the rounding the reader allows (GB_ATLAS_RECT_TOLERANCE:
 * with no padding, a UV a thousandth of a texel outside its rect passes),
 * and every two triangles of different charts are checked, apart from the
 * reader's raster (tests/unit/uv_distance.h), to be at least twice the
 * padding apart along x or y, as disjoint padded masks promise.
 *
 * Every payload is CRC-checked by the container, so each input is parsed as
 * it is, then again with its checksums recomputed (fix_checksums.h), which
 * lets the mutations reach the atlas's own checks.
 */
#include "atlas.h"

#include <stddef.h>
#include <stdint.h>

#include "fuzz_reader.h"
#include "unit/uv_distance.h"

/* Traps when a corner's texel leaves its chart's padded rect. */
static float fetch_every_corner(const gb_atlas *atlas)
{
    const gb_atlas_header *h = &atlas->header;
    double margin = h->padding + GB_ATLAS_RECT_TOLERANCE;
    float sum = 0.0f;
    for (uint32_t t = 0; t < h->triangle_count; ++t) {
        const gb_atlas_chart *chart = &atlas->chart_records[atlas->charts[t]];
        for (int c = 0; c < 3; ++c) {
            double x = atlas->uvs[6 * (size_t)t + 2 * c] * (double)h->width;
            double y = atlas->uvs[6 * (size_t)t + 2 * c + 1] * (double)h->height;
            if (x < (double)chart->rect[0] - margin ||
                x > (double)chart->rect[0] + chart->rect[2] + margin ||
                y < (double)chart->rect[1] - margin ||
                y > (double)chart->rect[1] + chart->rect[3] + margin)
                __builtin_trap();
            sum += (float)(x + y);
        }
    }
    return sum;
}

/* Traps when two triangles of different charts are nearer than twice the
 * padding along x and y (beyond the rounding of double arithmetic). */
static void check_charts_apart(const gb_atlas *atlas)
{
    const gb_atlas_header *h = &atlas->header;
    double a[6], b[6];
    for (uint32_t s = 0; s < h->triangle_count; ++s)
        for (uint32_t t = s + 1; t < h->triangle_count; ++t) {
            if (atlas->charts[s] == atlas->charts[t])
                continue;
            for (int k = 0; k < 6; ++k) {
                double side = k % 2 ? h->height : h->width;
                a[k] = atlas->uvs[6 * (size_t)s + k] * side;
                b[k] = atlas->uvs[6 * (size_t)t + k] * side;
            }
            if (uv_distance(a, b) < 2.0 * h->padding - 1e-9)
                __builtin_trap();
        }
}

static float fetch_and_measure(const gb_atlas *atlas)
{
    check_charts_apart(atlas);
    return fetch_every_corner(atlas);
}

static int is_empty(const gb_atlas *atlas)
{
    return !atlas->uvs && !atlas->charts && !atlas->chart_records &&
           !atlas->header.triangle_count;
}

GB_FUZZ_READER(parse, gb_atlas, gb_atlas_parse, gb_atlas_check, gb_atlas_free,
               fetch_and_measure, is_empty)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_fuzz_parse_twice(data, size, parse);
    return 0;
}
