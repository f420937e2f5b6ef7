/* cavities.c — opening the 2-cycles left by collapse (see cavities.h).
 *
 * The regions of the complement are flooded one at a time from the outside
 * (cell 0, on the padding), a bit per cell, a row span at a time: a square
 * with one side flooded and the other not separates the flooded region
 * from a cavity; it is removed and the cavity flooded in turn, until no
 * square separates a flooded cell from an unflooded one. */
#include "cavities.h"

#include <stdlib.h>
#include <string.h>

#include "cell_list.h"

typedef struct flood {
    const gb_cubical_complex *complex;
    uint8_t *flooded;           /* a bit per cell */
    gb_cell_list seeds;         /* cells whose row span is still to fill */
} flood;

static int is_flooded(const flood *f, size_t cell)
{
    return (f->flooded[cell >> 3] >> (cell & 7)) & 1;
}

/* Can the flood enter cell from its neighbour one step along axis below it
 * (from_below) or above it: the square between them is not in the complex,
 * and cell is neither a cube nor flooded? The square between cell and cell
 * - step is the one at cell. */
static int can_enter(const flood *f, size_t cell, int axis, int from_below)
{
    const uint8_t *faces = f->complex->faces;
    size_t square_cell = from_below ? cell : cell + f->complex->step[axis];
    return !(faces[square_cell] & gb_square_bit(axis)) && !(faces[cell] & GB_FACE_CUBE) &&
           !is_flooded(f, cell);
}

/* Seeds the first cell of each run of cells the span [first, last] can
 * enter in the row one step along axis (direction -1 or +1). */
static gb_result seed_row(flood *f, size_t first, size_t last, int axis, int direction,
                          gb_error *error)
{
    size_t step = f->complex->step[axis], count = f->complex->cell_count;
    if (direction < 0 && first < step)
        first = step;       /* a span across rows may start in the first plane */
    if (direction > 0 && last + step >= count)
        last = count - 1 - step;
    int in_run = 0;
    for (size_t cell = first; cell <= last; ++cell) {
        size_t next = direction < 0 ? cell - step : cell + step;
        int enters = can_enter(f, next, axis, direction > 0);
        if (enters && !in_run && gb_cell_list_push(&f->seeds, next, error))
            return GB_ERROR_OUT_OF_MEMORY;
        in_run = enters;
    }
    return GB_OK;
}

/* Fills the span of seed's row it reaches along x, then seeds the rows
 * beside the span along y and z. */
static gb_result fill_span(flood *f, size_t seed, gb_error *error)
{
    if (is_flooded(f, seed))
        return GB_OK;       /* seeded twice: filled from the other seed */
    size_t first = seed, last = seed;
    while (first > 0 && can_enter(f, first - 1, 0, 0))
        --first;
    while (last + 1 < f->complex->cell_count && can_enter(f, last + 1, 0, 1))
        ++last;
    for (size_t cell = first; cell <= last; ++cell)
        f->flooded[cell >> 3] |= (uint8_t)(1u << (cell & 7));
    for (int axis = 1; axis < 3; ++axis)
        if (seed_row(f, first, last, axis, -1, error) ||
            seed_row(f, first, last, axis, +1, error))
            return GB_ERROR_OUT_OF_MEMORY;
    return GB_OK;
}

/* The region of start: cells joined through faces of the lattice whose
 * square is not in the complex, cubes excepted, filled a row span at a time
 * (memory read in order). A span running off either end of a row goes on
 * into the padding cells of the next or previous row, which are outside
 * anyway. */
static gb_result flood_region(flood *f, size_t start, gb_error *error)
{
    if (is_flooded(f, start) || (f->complex->faces[start] & GB_FACE_CUBE))
        return GB_OK;
    f->seeds.count = 0;
    gb_result result = gb_cell_list_push(&f->seeds, start, error);
    while (!result && f->seeds.count)
        result = fill_span(f, f->seeds.items[--f->seeds.count], error);
    return result;
}

static gb_result list_squares(const gb_cubical_complex *complex, gb_cell_list *cells,
                              uint64_t *squares, gb_error *error)
{
    *squares = 0;
    for (size_t cell = 0; cell < complex->cell_count; ++cell) {
        uint8_t f = complex->faces[cell] & GB_FACE_SQUARES;
        if (!f)
            continue;
        *squares += (uint64_t)gb_face_count(f);
        if (gb_cell_list_push(cells, cell, error))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    return GB_OK;
}

static gb_result record_birth_if_facet(gb_collapse *collapse, size_t cell, int axis,
                                       gb_error *error)
{
    if ((collapse->complex->faces[cell] & gb_edge_bit(axis)) &&
        gb_edge_coface_count(collapse->complex, cell, axis) == 0)
        return gb_persistence_record_birth(collapse->persistence, cell, axis,
                                           collapse->iteration, error);
    return GB_OK;
}

/* Removes the square; its edges may become facets (born now). */
static gb_result remove_square(gb_collapse *collapse, size_t cell, int normal, gb_error *error)
{
    const gb_cubical_complex *complex = collapse->complex;
    complex->faces[cell] &= (uint8_t)~gb_square_bit(normal);
    int b = (normal + 1) % 3, c = (normal + 2) % 3;
    if (record_birth_if_facet(collapse, cell, b, error) ||
        record_birth_if_facet(collapse, cell + complex->step[c], b, error) ||
        record_birth_if_facet(collapse, cell, c, error) ||
        record_birth_if_facet(collapse, cell + complex->step[b], c, error))
        return GB_ERROR_OUT_OF_MEMORY;
    return gb_collapse_reconsider(collapse, cell, error);
}

/* One pass over the squares left: each one between a flooded cell and an
 * unflooded one is removed and the cavity behind it flooded. */
static gb_result open_separating_squares(flood *f, gb_collapse *collapse,
                                         const gb_cell_list *cells, uint32_t *opened,
                                         gb_error *error)
{
    const gb_cubical_complex *complex = collapse->complex;
    gb_result result = GB_OK;
    for (size_t n = 0; n < cells->count && !result; ++n) {
        size_t cell = cells->items[n];
        for (int normal = 0; normal < 3 && !result; ++normal) {
            if (!(complex->faces[cell] & gb_square_bit(normal)))
                continue;
            size_t behind = cell - complex->step[normal];
            if (is_flooded(f, cell) == is_flooded(f, behind))
                continue;
            result = remove_square(collapse, cell, normal, error);
            if (!result)
                result = flood_region(f, is_flooded(f, cell) ? behind : cell, error);
            ++*opened;
        }
    }
    return result;
}

gb_result gb_open_cavities(gb_cubical_complex *complex, gb_collapse *collapse,
                           uint64_t *squares_left, uint32_t *opened, gb_error *error)
{
    *opened = 0;
    gb_cell_list cells = {0};
    gb_result result = list_squares(complex, &cells, squares_left, error);
    if (result || !*squares_left) {
        gb_cell_list_free(&cells);
        return result;
    }
    flood f = {.complex = complex};
    f.flooded = calloc(complex->cell_count / 8 + 1, 1);
    if (!f.flooded)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cavities: out of memory");
    if (!result)
        result = flood_region(&f, 0, error);
    for (uint32_t before = UINT32_MAX; !result && *opened != before;) {
        before = *opened;
        result = open_separating_squares(&f, collapse, &cells, opened, error);
    }
    free(f.flooded);
    gb_cell_list_free(&f.seeds);
    gb_cell_list_free(&cells);
    return result;
}
