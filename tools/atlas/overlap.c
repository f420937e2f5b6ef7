/* overlap.c — the exact triangle overlap test over a uniform grid
 * (overlap.h). */
#include "overlap.h"

#include <math.h>
#include <stdlib.h>

static int64_t orientation(const int64_t *o, const int64_t *a, const int64_t *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Whether an edge of counterclockwise triangle a has all of b on or beyond
 * its line (outside a). */
static int edge_separates(const int64_t *a, const int64_t *b)
{
    for (int e = 0; e < 3; ++e) {
        const int64_t *p = a + 2 * e, *q = a + 2 * ((e + 1) % 3);
        if (orientation(p, q, b) <= 0 && orientation(p, q, b + 2) <= 0 &&
            orientation(p, q, b + 4) <= 0)
            return 1;
    }
    return 0;
}

int gb_triangles_overlap(const int64_t *a, const int64_t *b)
{
    return !edge_separates(a, b) && !edge_separates(b, a);
}

/* ---- the grid ---- */

typedef struct grid {
    uint32_t side;              /* cells along each axis */
    int64_t cell;               /* fixed-point units per cell */
    int64_t *boxes;             /* 4 per triangle: x, y minimum, x, y maximum */
    uint32_t *starts;           /* side * side + 1: CSR offsets into members */
    uint32_t *members;          /* triangle indices, cell by cell */
} grid;

static void box_of(const int64_t *p, int64_t box[4])
{
    for (int d = 0; d < 2; ++d) {
        box[d] = box[2 + d] = p[d];
        for (int c = 1; c < 3; ++c) {
            box[d] = p[2 * c + d] < box[d] ? p[2 * c + d] : box[d];
            box[2 + d] = p[2 * c + d] > box[2 + d] ? p[2 * c + d] : box[2 + d];
        }
    }
}

static uint32_t cell_of(const grid *g, int64_t x)
{
    int64_t c = x / g->cell;
    return (uint32_t)(c < g->side ? c : g->side - 1);
}

/* Two passes over the triangles: count per cell, then fill. */
static int grid_build(grid *g, const int64_t *corners, uint32_t count)
{
    size_t cells = (size_t)g->side * g->side;
    g->starts = calloc(cells + 1, sizeof *g->starts);
    g->boxes = malloc(4 * (size_t)(count ? count : 1) * sizeof *g->boxes);
    if (!g->starts || !g->boxes)
        return 0;
    for (uint32_t t = 0; t < count; ++t)
        box_of(corners + 6 * (size_t)t, g->boxes + 4 * (size_t)t);
    uint64_t total = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (uint32_t t = 0; t < count; ++t) {
            const int64_t *box = g->boxes + 4 * (size_t)t;
            uint32_t x0 = cell_of(g, box[0]), y0 = cell_of(g, box[1]);
            uint32_t x1 = cell_of(g, box[2]), y1 = cell_of(g, box[3]);
            for (uint32_t y = y0; y <= y1; ++y)
                for (uint32_t x = x0; x <= x1; ++x) {
                    size_t c = (size_t)y * g->side + x;
                    if (pass == 0)
                        ++total, ++g->starts[c + 1];
                    else
                        g->members[g->starts[c]++] = t;
                }
        }
        if (pass == 0) {
            if (total > UINT32_MAX)
                return 0;
            for (size_t c = 0; c < cells; ++c)
                g->starts[c + 1] += g->starts[c];
            g->members = malloc((total ? total : 1) * sizeof *g->members);
            if (!g->members)
                return 0;
        }
    }
    for (size_t c = cells; c > 0; --c)  /* starts were advanced to the ends */
        g->starts[c] = g->starts[c - 1];
    g->starts[0] = 0;
    return 1;
}

/* Whether the boxes of triangles i and j overlap (more than touch) and cell
 * (x, y) holds the low corner of their overlap: each pair is tested in one
 * cell only, and only when it can overlap. */
static int candidates(const grid *g, uint32_t i, uint32_t j, uint32_t x, uint32_t y)
{
    const int64_t *a = g->boxes + 4 * (size_t)i, *b = g->boxes + 4 * (size_t)j;
    if (!(a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]))
        return 0;
    return cell_of(g, a[0] > b[0] ? a[0] : b[0]) == x && cell_of(g, a[1] > b[1] ? a[1] : b[1]) == y;
}

static void grid_free(grid *g)
{
    free(g->boxes);
    free(g->starts);
    free(g->members);
}

gb_result gb_find_overlaps(const int64_t *corners, uint32_t count, uint32_t *pairs,
                           uint32_t pairs_capacity, uint64_t *pair_count, gb_error *error)
{
    double side = ceil(sqrt((double)count));
    grid g = {(uint32_t)(side < 1.0 ? 1.0 : side > 4096.0 ? 4096.0 : side), 0, NULL, NULL, NULL};
    g.cell = (GB_OVERLAP_ONE + g.side) / g.side;
    *pair_count = 0;
    if (!grid_build(&g, corners, count)) {
        grid_free(&g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (overlap grid)");
    }
    for (uint32_t y = 0; y < g.side; ++y)
        for (uint32_t x = 0; x < g.side; ++x) {
            size_t c = (size_t)y * g.side + x;
            for (uint32_t i = g.starts[c]; i < g.starts[c + 1]; ++i)
                for (uint32_t j = i + 1; j < g.starts[c + 1]; ++j) {
                    uint32_t s = g.members[i], t = g.members[j];
                    if (!candidates(&g, s, t, x, y) ||
                        !gb_triangles_overlap(corners + 6 * (size_t)s, corners + 6 * (size_t)t))
                        continue;
                    if (*pair_count < pairs_capacity) {
                        pairs[2 * *pair_count] = s;
                        pairs[2 * *pair_count + 1] = t;
                    }
                    ++*pair_count;
                }
        }
    grid_free(&g);
    return GB_OK;
}

/* ---- one chart ---- */

void gb_uvs_to_fixed(const double *uvs, uint32_t count, int64_t *fixed)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t k = 0; k < 3 * (size_t)count; ++k)
        for (int d = 0; d < 2; ++d) {
            lo[d] = fmin(lo[d], uvs[2 * k + d]);
            hi[d] = fmax(hi[d], uvs[2 * k + d]);
        }
    double side = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double scale = side > 0.0 ? (double)GB_OVERLAP_ONE / side : 0.0;
    for (size_t k = 0; k < 3 * (size_t)count; ++k)
        for (int d = 0; d < 2; ++d) {
            double x = round((uvs[2 * k + d] - lo[d]) * scale);
            fixed[2 * k + d] = x < 0.0 ? 0 : x > (double)GB_OVERLAP_ONE ? GB_OVERLAP_ONE
                                                                       : (int64_t)x;
        }
}

gb_result gb_chart_uvs_check(const double *uvs, uint32_t count, uint8_t *folded, uint32_t *folds,
                             uint64_t *overlaps, gb_error *error)
{
    int64_t *fixed = malloc(6 * (size_t)count * sizeof *fixed);
    if (!fixed)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (overlap)");
    gb_uvs_to_fixed(uvs, count, fixed);
    *folds = 0;
    *overlaps = 0;
    for (uint32_t i = 0; i < count; ++i) {
        folded[i] = !(gb_fixed_twice_area(fixed + 6 * (size_t)i) > 0);
        *folds += folded[i];
    }
    gb_result result = GB_OK;
    if (*folds == 0)
        result = gb_find_overlaps(fixed, count, NULL, 0, overlaps, error);
    free(fixed);
    return result;
}
