/* occupancy.c — the occupied texels and the first place a mask fits
 * (occupancy.h). */
#include "occupancy.h"

#include <stdlib.h>
#include <string.h>

#include "bit_rows.h"

int gb_occupancy_init(gb_occupancy *o, uint32_t width, uint32_t height)
{
    memset(o, 0, sizeof *o);
    o->width = width;
    o->height = height;
    o->words = (width + 63) / 64;
    o->bits = calloc((size_t)o->words * height, sizeof *o->bits);
    o->longest_free = malloc((size_t)height * sizeof *o->longest_free);
    if (!o->bits || !o->longest_free) {
        gb_occupancy_free(o);
        return 0;
    }
    for (uint32_t y = 0; y < height; ++y)
        o->longest_free[y] = width;
    return 1;
}

void gb_occupancy_free(gb_occupancy *o)
{
    free(o->bits);
    free(o->longest_free);
    memset(o, 0, sizeof *o);
}

static const uint64_t *row_of(const gb_occupancy *o, uint32_t y)
{
    return o->bits + (size_t)y * o->words;
}

/* The first column at or after from where a free run of at least length
 * texels starts in row (the row's width when none). */
static uint64_t free_run_from(const gb_occupancy *o, const uint64_t *row, uint64_t from,
                              uint64_t length)
{
    for (uint64_t start = gb_bits_next(row, from, o->width, 0); start < o->width;) {
        uint64_t end = gb_bits_next(row, start, start + length < o->width ? start + length
                                                                           : o->width, 1);
        if (end - start >= length)
            return start;
        start = gb_bits_next(row, end, o->width, 0);
    }
    return o->width;
}

/* Where row r of the mask at column x meets an occupied texel: 1 with the
 * next column at which it may not (*next: the run that met one moved to
 * the next free run of the atlas's row long enough to hold it), else 0. */
static int row_blocks(const gb_occupancy *o, const gb_chart_mask *m, uint32_t r, uint64_t x,
                      uint32_t y, uint64_t *next)
{
    const uint64_t *row = row_of(o, y + r);
    for (uint32_t k = m->row_starts[r]; k < m->row_starts[r + 1]; ++k) {
        uint64_t first = x + m->runs[2 * k], last = x + m->runs[2 * k + 1];
        uint64_t p = gb_bits_next(row, first, last + 1, 1);
        if (p <= last) {
            *next = free_run_from(o, row, p, last - first + 1) - m->runs[2 * k];
            return 1;
        }
    }
    return 0;
}

/* Whether every row of the mask at row y has a free run as long as its
 * own longest one: else it fits nowhere in that row. */
static int rows_have_room(const gb_occupancy *o, const gb_chart_mask *m, uint32_t y)
{
    if (o->longest_free[y + m->widest_row] < m->longest_run)
        return 0;
    for (uint32_t r = 0; r < m->height; ++r)
        if (o->longest_free[y + r] < m->row_longest[r])
            return 0;
    return 1;
}

/* The leftmost column before end at which the mask fits in row y; 0 when
 * none. The row that blocked last is tried first. */
static int leftmost(const gb_occupancy *o, const gb_chart_mask *m, uint32_t y, uint64_t end,
                    uint64_t *x_at)
{
    uint64_t x = 0;
    uint32_t first_row = m->widest_row;
    while (x + m->width <= o->width && x < end) {
        uint64_t next;
        int blocked = row_blocks(o, m, first_row, x, y, &next);
        for (uint32_t r = 0; r < m->height && !blocked; ++r)
            if (r != first_row && row_blocks(o, m, r, x, y, &next))
                blocked = 1, first_row = r;
        if (!blocked) {
            *x_at = x;
            return 1;
        }
        x = next;
    }
    return 0;
}

int gb_occupancy_find(const gb_occupancy *o, const gb_chart_mask *const *masks, int count,
                      uint32_t first_row, int *which, uint32_t *x, uint32_t *y)
{
    for (uint64_t row = first_row; row < o->height; ++row) {
        int found = 0;
        uint64_t best = 0;
        for (int i = 0; i < count; ++i) {
            const gb_chart_mask *m = masks[i];
            uint64_t at;
            if (row + m->height > o->height || m->width > o->width ||
                !rows_have_room(o, m, (uint32_t)row) ||
                !leftmost(o, m, (uint32_t)row, found ? best : o->width, &at))
                continue;
            found = 1;
            best = at;
            *which = i;
        }
        if (found) {
            *x = (uint32_t)best;
            *y = (uint32_t)row;
            return 1;
        }
    }
    return 0;
}

/* The longest run of clear bits of row y. */
static uint32_t longest_free_run(const gb_occupancy *o, uint32_t y)
{
    const uint64_t *row = row_of(o, y);
    uint64_t longest = 0;
    for (uint64_t x = gb_bits_next(row, 0, o->width, 0); x < o->width;) {
        uint64_t end = gb_bits_next(row, x, o->width, 1);
        longest = end - x > longest ? end - x : longest;
        x = gb_bits_next(row, end, o->width, 0);
    }
    return (uint32_t)longest;
}

void gb_occupancy_mark(gb_occupancy *o, const gb_chart_mask *m, uint32_t x, uint32_t y)
{
    for (uint32_t r = 0; r < m->height; ++r) {
        uint64_t *row = o->bits + (size_t)(y + r) * o->words;
        for (uint32_t k = m->row_starts[r]; k < m->row_starts[r + 1]; ++k)
            gb_bits_set(row, (uint64_t)x + m->runs[2 * k], (uint64_t)x + m->runs[2 * k + 1]);
        o->longest_free[y + r] = longest_free_run(o, y + r);
    }
}
