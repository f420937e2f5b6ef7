/* chart_mask.c — a chart's padded mask as runs (chart_mask.h): its
 * triangles' padded masks set in a bitmap of its box, then read back row
 * by row. */
#include "chart_mask.h"

#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "bit_rows.h"

/* The triangles' padded masks into bits (words per row), shifted by the
 * padding into the box; 0 when out of memory. */
static int raster(uint64_t *bits, size_t words, const gb_chart_mask *mask, const double *corners,
                  uint32_t triangle_count, double margin, uint32_t padding,
                  gb_atlas_mask *scratch)
{
    for (uint32_t t = 0; t < triangle_count; ++t) {
        if (!gb_atlas_mask_of(scratch, corners + 6 * (size_t)t, margin, padding))
            return 0;
        for (uint32_t k = 0; k < scratch->count; ++k) {
            int64_t row = scratch->first + k + padding;
            int64_t first = scratch->columns[2 * k] + padding;
            int64_t last = scratch->columns[2 * k + 1] + padding;
            /* inside the box by the corners' margin (chart_mask.h); clipped
             * only against a caller's mistake */
            first = first < 0 ? 0 : first;
            last = last >= mask->width ? (int64_t)mask->width - 1 : last;
            if (row >= 0 && row < mask->height && first <= last)
                gb_bits_set(bits + (size_t)row * words, (uint64_t)first, (uint64_t)last);
        }
    }
    return 1;
}

/* The runs of the bitmap into mask; 0 when out of memory. */
static int read_runs(gb_chart_mask *mask, const uint64_t *bits, size_t words)
{
    size_t capacity = 0, count = 0;
    for (uint32_t r = 0; r < mask->height; ++r) {
        mask->row_starts[r] = (uint32_t)count;
        const uint64_t *row = bits + (size_t)r * words;
        for (uint64_t x = gb_bits_next(row, 0, mask->width, 1); x < mask->width;
             x = gb_bits_next(row, x, mask->width, 1)) {
            uint64_t end = gb_bits_next(row, x, mask->width, 0);
            if (!gb_array_reserve(&mask->runs, &capacity, 2 * (count + 1), sizeof *mask->runs))
                return 0;
            mask->runs[2 * count] = (uint32_t)x;
            mask->runs[2 * count + 1] = (uint32_t)(end - 1);
            ++count;
            mask->texels += end - x;
            if (end - x > mask->row_longest[r])
                mask->row_longest[r] = (uint32_t)(end - x);
            if (end - x > mask->longest_run) {
                mask->longest_run = (uint32_t)(end - x);
                mask->widest_row = r;
            }
            x = end;
        }
    }
    mask->row_starts[mask->height] = (uint32_t)count;
    return 1;
}

int gb_chart_mask_make(gb_chart_mask *mask, const double *corners, uint32_t triangle_count,
                       uint32_t rect_width, uint32_t rect_height, double margin,
                       uint32_t padding, gb_atlas_mask *scratch)
{
    memset(mask, 0, sizeof *mask);
    mask->width = rect_width + 2 * padding;
    mask->height = rect_height + 2 * padding;
    size_t words = (mask->width + 63) / 64;
    uint64_t *bits = calloc(words * mask->height, sizeof *bits);
    mask->row_starts = malloc(((size_t)mask->height + 1) * sizeof *mask->row_starts);
    mask->row_longest = calloc(mask->height, sizeof *mask->row_longest);
    int ok = bits && mask->row_starts && mask->row_longest &&
             raster(bits, words, mask, corners, triangle_count, margin, padding, scratch) &&
             read_runs(mask, bits, words);
    free(bits);
    if (!ok)
        gb_chart_mask_free(mask);
    return ok;
}

void gb_chart_mask_free(gb_chart_mask *mask)
{
    free(mask->row_starts);
    free(mask->row_longest);
    free(mask->runs);
    memset(mask, 0, sizeof *mask);
}
