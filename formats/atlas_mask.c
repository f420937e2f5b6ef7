/* atlas_mask.c — the conservative raster of an atlas's triangles, padded
 * (atlas_mask.h). */
#include "atlas_mask.h"

#include <math.h>
#include <stdlib.h>

void gb_atlas_texel_corners(const float uv[6], uint32_t width, uint32_t height,
                            double corners[6])
{
    for (int c = 0; c < 3; ++c) {
        corners[2 * c] = (double)uv[2 * c] * width;
        corners[2 * c + 1] = (double)uv[2 * c + 1] * height;
    }
}

/* The cells (rows or columns) whose open interval (k - m, k + 1 + m) meets
 * [lo, hi]: k with k - m < hi and k + 1 + m > lo; at least one. */
static void cells(double lo, double hi, double margin, int64_t *first, int64_t *last)
{
    *first = (int64_t)floor(lo - margin);
    *last = (int64_t)ceil(hi + margin) - 1;
    if (*last < *first)
        *last = *first;
}

/* The rows the triangle itself touches (no padding). */
static void raster_rows(const double p[6], double margin, int64_t *first, int64_t *last)
{
    double lo = fmin(p[1], fmin(p[3], p[5])), hi = fmax(p[1], fmax(p[3], p[5]));
    cells(lo, hi, margin, first, last);
}

/* x into [*lo, *hi]. */
static void include(double x, double *lo, double *hi)
{
    *lo = fmin(*lo, x);
    *hi = fmax(*hi, x);
}

/* The columns the triangle itself touches in raster row j: the x extent of
 * its part in the closed slab j - m <= y <= j + 1 + m (its corners there
 * and where its edges cross the slab's two lines). */
static void raster_columns(const double p[6], double margin, int64_t j, int64_t *first,
                           int64_t *last)
{
    double bottom = (double)j - margin, top = (double)j + 1.0 + margin;
    double lo = INFINITY, hi = -INFINITY;
    for (int c = 0; c < 3; ++c) {
        const double *a = p + 2 * c, *b = p + 2 * ((c + 1) % 3);
        if (a[1] >= bottom && a[1] <= top)
            include(a[0], &lo, &hi);
        const double lines[2] = {bottom, top};
        for (int k = 0; k < 2; ++k)
            if (fmin(a[1], b[1]) < lines[k] && lines[k] < fmax(a[1], b[1]))
                include(a[0] + (lines[k] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]), &lo, &hi);
    }
    if (lo > hi) {  /* not a row of the triangle: its whole extent, to stay conservative */
        lo = fmin(p[0], fmin(p[2], p[4]));
        hi = fmax(p[0], fmax(p[2], p[4]));
    }
    cells(lo, hi, margin, first, last);
}

/* Room for rows rows. */
static int reserve(gb_atlas_mask *mask, size_t rows)
{
    if (rows <= mask->capacity)
        return 1;
    int64_t *columns = realloc(mask->columns, 2 * rows * sizeof *columns);
    if (columns)
        mask->columns = columns;
    uint32_t *queue = realloc(mask->queue, rows * sizeof *queue);
    if (queue)
        mask->queue = queue;
    if (!columns || !queue)
        return 0;
    mask->capacity = rows;
    return 1;
}

/* Row j of the padded mask from the raster rows r0 .. r1 (their columns
 * in raster, 2 per row): the least first column and the greatest last one
 * of the raster rows j - P .. j + P, each a sliding window over the raster
 * rows whose extreme is kept in a queue of row indices (monotone: each
 * row enters and leaves once), then grown by P. */
static void dilate(gb_atlas_mask *mask, const int64_t *raster, int64_t r0, int64_t r1,
                   uint32_t padding)
{
    int64_t p = padding;
    for (int side = 0; side < 2; ++side) {
        uint32_t head = 0, tail = 0;
        int64_t next = r0;  /* the next raster row to enter */
        for (int64_t j = r0 - p; j <= r1 + p; ++j) {
            for (; next <= r1 && next <= j + p; ++next) {
                int64_t v = raster[2 * (next - r0) + side];
                while (tail > head &&
                       (side ? raster[2 * mask->queue[tail - 1] + side] <= v
                             : raster[2 * mask->queue[tail - 1] + side] >= v))
                    --tail;
                mask->queue[tail++] = (uint32_t)(next - r0);
            }
            while (mask->queue[head] + r0 < j - p)
                ++head;
            int64_t extreme = raster[2 * mask->queue[head] + side];
            mask->columns[2 * (j - (r0 - p)) + side] = side ? extreme + p : extreme - p;
        }
    }
}

int gb_atlas_mask_of(gb_atlas_mask *mask, const double corners[6], double margin,
                     uint32_t padding)
{
    int64_t r0, r1;
    raster_rows(corners, margin, &r0, &r1);
    size_t rows = (size_t)(r1 - r0 + 1), padded = rows + 2 * (size_t)padding;
    mask->count = 0;
    if (!reserve(mask, 2 * padded))  /* the raster after the padded rows */
        return 0;
    int64_t *raster = mask->columns + 2 * padded;
    for (int64_t r = r0; r <= r1; ++r)
        raster_columns(corners, margin, r, &raster[2 * (r - r0)], &raster[2 * (r - r0) + 1]);
    dilate(mask, raster, r0, r1, padding);
    mask->first = r0 - padding;
    mask->count = (uint32_t)padded;
    return 1;
}

void gb_atlas_mask_free(gb_atlas_mask *mask)
{
    free(mask->columns);
    free(mask->queue);
    *mask = (gb_atlas_mask){0};
}
