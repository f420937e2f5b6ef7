/* collapse.c — ParDirCollapse with border lists and persistent isthmuses
 * (see collapse.h). */
#include "collapse.h"

#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"

/* For the few small functions of the inner loops. */
#define HOT static inline __attribute__((always_inline))

/* What a cell is listed for: the kind of its g, 3 - the pair's dimension. */
enum { KIND_CUBE, KIND_SQUARE, KIND_EDGE };

static const uint8_t kind_faces[GB_COLLAPSE_KINDS] = {GB_FACE_CUBE, GB_FACE_SQUARES,
                                                      GB_FACE_EDGES};

/* The direction-orientation of an axis and orientation (collapse.h). */
static int direction_of(int axis, int orientation)
{
    return 2 * axis + (orientation > 0);
}

/* The next cell along axis in the orientation: the cube beyond the square
 * a cube's pair of that direction frees. */
static size_t cell_beyond(const gb_cubical_complex *complex, size_t cell, int axis,
                          int orientation)
{
    return orientation < 0 ? cell - complex->step[axis] : cell + complex->step[axis];
}

/* ---- the cubes found in the running substep ---- */

/* A cube substep removes every pair it found; a cube beside one it removes
 * that was found too goes in the same substep, so the removal lists it
 * nowhere (it would only be examined again, gone). */
HOT int cube_is_found(const gb_collapse *collapse, size_t cell)
{
    return (collapse->cube_found[cell >> 3] >> (cell & 7)) & 1;
}

HOT void set_cube_found(gb_collapse *collapse, size_t cell, int found)
{
    uint8_t bit = (uint8_t)(1u << (cell & 7));
    collapse->cube_found[cell >> 3] = found ? collapse->cube_found[cell >> 3] | bit
                                            : collapse->cube_found[cell >> 3] & (uint8_t)~bit;
}

/* ---- the lists ---- */

/* The cell may hold the g (of that kind) of a pair the substep of that
 * kind and direction removes: examined there, in this iteration if that
 * substep is still to come, else in the next. */
HOT gb_result list_candidate(gb_collapse *collapse, size_t cell, int kind, int direction,
                             gb_error *error)
{
    int substep = GB_COLLAPSE_KINDS * direction + kind;
    gb_cell_list *list = substep > collapse->substep ? &collapse->border[substep]
                                                     : &collapse->pending[substep];
    return gb_cell_list_push(list, cell, error);
}

gb_result gb_collapse_reconsider(gb_collapse *collapse, size_t cell, gb_error *error)
{
    const size_t *step = collapse->complex->step;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                size_t neighbour = (size_t)((ptrdiff_t)cell + dx + dy * (ptrdiff_t)step[1] +
                                            dz * (ptrdiff_t)step[2]);
                for (int kind = 0; kind < GB_COLLAPSE_KINDS; ++kind) {
                    if (!(collapse->complex->faces[neighbour] & kind_faces[kind]))
                        continue;
                    for (int direction = 0; direction < GB_COLLAPSE_DIRECTIONS; ++direction)
                        if (list_candidate(collapse, neighbour, kind, direction, error))
                            return GB_ERROR_OUT_OF_MEMORY;
                }
            }
    return GB_OK;
}

gb_result gb_collapse_init(gb_collapse *collapse, gb_cubical_complex *complex,
                           gb_persistence *persistence, gb_error *error)
{
    memset(collapse, 0, sizeof *collapse);
    collapse->complex = complex;
    collapse->persistence = persistence;
    collapse->substep = GB_COLLAPSE_SUBSTEPS;
    collapse->cube_found = calloc(complex->cell_count / 8 + 1, 1);
    if (!collapse->cube_found)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "collapse: out of memory for %zu cells",
                       complex->cell_count);
    /* Every face is in a cube: the only free pairs are (square, cube) where
     * the cube's neighbour across the square is not empty. */
    for (size_t cell = 0; cell < complex->cell_count; ++cell) {
        if (!(complex->faces[cell] & GB_FACE_CUBE))
            continue;
        ++collapse->cubes;
        for (int axis = 0; axis < 3; ++axis)
            for (int orientation = -1; orientation <= 1; orientation += 2) {
                size_t beyond = cell_beyond(complex, cell, axis, orientation);
                if (!(complex->faces[beyond] & GB_FACE_CUBE) &&
                    list_candidate(collapse, cell, KIND_CUBE, direction_of(axis, orientation),
                                   error)) {
                    gb_collapse_free(collapse);
                    return GB_ERROR_OUT_OF_MEMORY;
                }
            }
    }
    return GB_OK;
}

void gb_collapse_free(gb_collapse *collapse)
{
    if (!collapse)
        return;
    for (int substep = 0; substep < GB_COLLAPSE_SUBSTEPS; ++substep) {
        gb_cell_list_free(&collapse->border[substep]);
        gb_cell_list_free(&collapse->pending[substep]);
    }
    for (int axis = 0; axis < 3; ++axis)
        gb_cell_list_free(&collapse->born[axis]);
    free(collapse->pairs);
    free(collapse->cube_found);
    memset(collapse, 0, sizeof *collapse);
}

/* The border of a new iteration: the cells pending from the last one (the
 * old border's allocation takes the next iteration's pending cells). */
static void start_iteration(gb_collapse *collapse)
{
    for (int substep = 0; substep < GB_COLLAPSE_SUBSTEPS; ++substep) {
        gb_cell_list *border = &collapse->border[substep];
        gb_cell_list candidates = collapse->pending[substep];
        border->count = 0;
        collapse->pending[substep] = *border;
        *border = candidates;
    }
}

static int any_pending(const gb_collapse *collapse)
{
    for (int substep = 0; substep < GB_COLLAPSE_SUBSTEPS; ++substep)
        if (collapse->pending[substep].count)
            return 1;
    return 0;
}

/* Facets born this iteration and still there get their birth recorded; the
 * others were collapsed at once and never needed one. */
static gb_result end_iteration(gb_collapse *collapse, gb_error *error)
{
    const uint8_t *faces = collapse->complex->faces;
    gb_result result = GB_OK;
    for (int axis = 0; axis < 3; ++axis) {
        gb_cell_list *born = &collapse->born[axis];
        for (size_t n = 0; n < born->count && !result; ++n)
            if (faces[born->items[n]] & gb_edge_bit(axis))
                result = gb_persistence_record_birth(collapse->persistence, born->items[n],
                                                     axis, collapse->iteration, error);
        born->count = 0;
    }
    return result;
}

/* ---- finding the free pairs of a substep ---- */

static gb_result add_pair(gb_collapse *collapse, size_t cell, uint8_t g, gb_error *error)
{
    if (!gb_array_reserve(&collapse->pairs, &collapse->pair_capacity, collapse->pair_count + 1,
                          sizeof *collapse->pairs))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "collapse: out of memory");
    collapse->pairs[collapse->pair_count++] = (uint64_t)cell << 8 | g;
    return GB_OK;
}

typedef struct substep {
    int axis;                   /* direction */
    int orientation;            /* -1 or +1 */
    int dimension;              /* of g: 3, 2 or 1 */
} substep;

/* The cell of f: g's cell for the negative orientation, the next cell along
 * the direction for the positive one. */
static size_t free_face_cell(const gb_cubical_complex *complex, size_t cell, substep s)
{
    return s.orientation < 0 ? cell : cell + complex->step[s.axis];
}

/* An isthmus edge is protected once old enough; one born this iteration has
 * no recorded birth yet, so its lifespan is 0 and it never is. */
static int is_protected(const gb_collapse *collapse, size_t cell, int axis)
{
    return gb_persistence_is_protected(collapse->persistence, collapse->complex, cell, axis,
                                       collapse->iteration);
}

/* The free pairs of the substep whose g is in cell, appended to the pairs. A
 * face of a cube is in the cube, so in a cell holding a cube only the cube
 * can be a g. */
HOT gb_result find_pairs_in_cell(gb_collapse *collapse, size_t cell, substep s, gb_error *error)
{
    const gb_cubical_complex *complex = collapse->complex;
    const uint8_t *faces = complex->faces;
    uint8_t here = faces[cell];
    size_t f = free_face_cell(complex, cell, s);
    if (s.dimension == 3) {
        size_t beyond = cell_beyond(complex, cell, s.axis, s.orientation);
        if (!(here & GB_FACE_CUBE) || (faces[beyond] & GB_FACE_CUBE))
            return GB_OK;
        set_cube_found(collapse, cell, 1);
        return add_pair(collapse, cell, GB_FACE_CUBE, error);
    }
    if (here & GB_FACE_CUBE)
        return GB_OK;
    if (s.dimension == 2) {
        for (int normal = 0; normal < 3; ++normal) {
            if (normal == s.axis || !(here & gb_square_bit(normal)))
                continue;
            int edge_axis = 3 - s.axis - normal;
            if (gb_edge_coface_count(complex, f, edge_axis) == 1 &&
                add_pair(collapse, cell, gb_square_bit(normal), error))
                return GB_ERROR_OUT_OF_MEMORY;
        }
        return GB_OK;
    }
    if ((here & gb_edge_bit(s.axis)) && gb_point_coface_count(complex, f) == 1 &&
        !is_protected(collapse, cell, s.axis))
        return add_pair(collapse, cell, gb_edge_bit(s.axis), error);
    return GB_OK;
}

/* ---- what a removal frees ---- */

/* A face h that lost a coface: if one coface k is left, (h, k) may be a new
 * free pair and k's cell is listed; if none, h is a facet (an edge's birth).
 * A facet itself needs no listing: it becomes a g when one of its faces
 * loses its other cofaces, which lists it then. */

HOT gb_result square_lost_coface(gb_collapse *collapse, size_t cell, int normal,
                                 gb_error *error)
{
    const uint8_t *faces = collapse->complex->faces;
    if (!(faces[cell] & gb_square_bit(normal)))
        return GB_OK;
    size_t behind = cell - collapse->complex->step[normal];
    int here = (faces[cell] & GB_FACE_CUBE) != 0, back = (faces[behind] & GB_FACE_CUBE) != 0;
    /* the cube left has the square on its low side (here) or high side */
    if (here + back != 1 || cube_is_found(collapse, here ? cell : behind))
        return GB_OK;
    return here ? list_candidate(collapse, cell, KIND_CUBE, direction_of(normal, -1), error)
                : list_candidate(collapse, behind, KIND_CUBE, direction_of(normal, +1), error);
}

HOT gb_result edge_became_facet(gb_collapse *collapse, size_t cell, int axis,
                                   gb_error *error)
{
    return gb_cell_list_push(&collapse->born[axis], cell, error);
}

HOT gb_result edge_lost_coface(gb_collapse *collapse, size_t cell, int axis, gb_error *error)
{
    const gb_cubical_complex *complex = collapse->complex;
    const uint8_t *faces = complex->faces;
    if (!(faces[cell] & gb_edge_bit(axis)))
        return GB_OK;
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    /* its squares: normal to b at cell and cell - c; normal to c at cell and
     * cell - b; the edge is on the square's low side along c, high along c,
     * low along b, high along b */
    size_t cells[4] = {cell, cell - complex->step[c], cell, cell - complex->step[b]};
    uint8_t bits[4] = {gb_square_bit(b), gb_square_bit(b), gb_square_bit(c), gb_square_bit(c)};
    int directions[4] = {direction_of(c, -1), direction_of(c, +1), direction_of(b, -1),
                         direction_of(b, +1)};
    int count = 0, last = 0;
    for (int n = 0; n < 4; ++n)
        if (faces[cells[n]] & bits[n]) {
            ++count;
            last = n;
        }
    if (count == 1)
        return list_candidate(collapse, cells[last], KIND_SQUARE, directions[last], error);
    if (count == 0)
        return edge_became_facet(collapse, cell, axis, error);
    return GB_OK;
}

HOT gb_result point_lost_coface(gb_collapse *collapse, size_t cell, gb_error *error)
{
    const gb_cubical_complex *complex = collapse->complex;
    const uint8_t *faces = complex->faces;
    if (!(faces[cell] & GB_FACE_POINT))
        return GB_OK;
    /* its edges: along each axis, starting at the point (low end) or ending
     * at it (high end) */
    int count = 0, last_direction = 0;
    size_t last = cell;
    for (int axis = 0; axis < 3; ++axis) {
        if (faces[cell] & gb_edge_bit(axis)) {
            ++count;
            last = cell;
            last_direction = direction_of(axis, -1);
        }
        size_t before = cell - complex->step[axis];
        if (faces[before] & gb_edge_bit(axis)) {
            ++count;
            last = before;
            last_direction = direction_of(axis, +1);
        }
    }
    return count == 1 ? list_candidate(collapse, last, KIND_EDGE, last_direction, error)
                      : GB_OK;
}

/* Removed: the cube of cell and its square normal to axis at square_cell.
 * Lost a coface: the cube's 5 other squares and the square's 4 edges. */
HOT gb_result after_cube(gb_collapse *collapse, size_t cell, int axis, size_t square_cell,
                            gb_error *error)
{
    const size_t *step = collapse->complex->step;
    for (int normal = 0; normal < 3; ++normal) {
        if (square_lost_coface(collapse, cell, normal, error) ||
            square_lost_coface(collapse, cell + step[normal], normal, error))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    if (edge_lost_coface(collapse, square_cell, b, error) ||
        edge_lost_coface(collapse, square_cell + step[c], b, error) ||
        edge_lost_coface(collapse, square_cell, c, error) ||
        edge_lost_coface(collapse, square_cell + step[b], c, error))
        return GB_ERROR_OUT_OF_MEMORY;
    return GB_OK;
}

/* Removed: the square normal to normal at cell (spanning the direction axis
 * and edge_axis) and its edge along edge_axis at edge_cell. Lost a coface:
 * the square's 3 other edges and the edge's 2 points. */
HOT gb_result after_square(gb_collapse *collapse, size_t cell, int axis, int edge_axis,
                              size_t edge_cell, gb_error *error)
{
    const size_t *step = collapse->complex->step;
    size_t opposite = edge_cell == cell ? cell + step[axis] : cell;
    if (edge_lost_coface(collapse, opposite, edge_axis, error) ||
        edge_lost_coface(collapse, cell, axis, error) ||
        edge_lost_coface(collapse, cell + step[edge_axis], axis, error) ||
        point_lost_coface(collapse, edge_cell, error) ||
        point_lost_coface(collapse, edge_cell + step[edge_axis], error))
        return GB_ERROR_OUT_OF_MEMORY;
    return GB_OK;
}

/* Removed: the edge along axis at cell and its point at point_cell. Lost a
 * coface: the edge's other point. */
HOT gb_result after_edge(gb_collapse *collapse, size_t cell, int axis, size_t point_cell,
                            gb_error *error)
{
    size_t other = point_cell == cell ? cell + collapse->complex->step[axis] : cell;
    return point_lost_coface(collapse, other, error);
}

HOT int axis_of_square(uint8_t square)
{
    return square == GB_FACE_SQUARE_YZ ? 0 : square == GB_FACE_SQUARE_XZ ? 1 : 2;
}

HOT gb_result remove_pair(gb_collapse *collapse, uint64_t pair, substep s, gb_error *error)
{
    uint8_t *faces = collapse->complex->faces;
    size_t cell = (size_t)(pair >> 8);
    uint8_t g = (uint8_t)(pair & 0xff);
    if (!(faces[cell] & g))
        return GB_OK;       /* found twice (its cell was listed twice): removed */
    size_t f = free_face_cell(collapse->complex, cell, s);
    faces[cell] &= (uint8_t)~g;
    ++collapse->pairs_removed;
    if (s.dimension == 3) {
        faces[f] &= (uint8_t)~gb_square_bit(s.axis);
        set_cube_found(collapse, cell, 0);
        ++collapse->cubes_removed;
        return after_cube(collapse, cell, s.axis, f, error);
    }
    if (s.dimension == 2) {
        int edge_axis = 3 - s.axis - axis_of_square(g);
        faces[f] &= (uint8_t)~gb_edge_bit(edge_axis);
        return after_square(collapse, cell, s.axis, edge_axis, f, error);
    }
    faces[f] &= (uint8_t)~GB_FACE_POINT;
    return after_edge(collapse, cell, s.axis, f, error);
}

/* ---- iterations ---- */

/* The cells a removal at cell reads are its neighbours across rows and
 * planes, far apart in memory: on a large complex each is a cache miss, and
 * asking for them a few cells ahead hides the wait. On the Cornell box at
 * 512 the loads of those neighbours were most of remove_pair, itself 40 %
 * of thin (perf); with the prefetch the collapse took 26.9 and 30.0 s
 * against 37.2 and 35.5 s without (thin --stats, runs alternated, the same
 * bytes). At 256 it makes no difference. */
enum { PREFETCH_AHEAD = 8 };

HOT void prefetch_around(const gb_cubical_complex *complex, size_t cell)
{
    const uint8_t *faces = complex->faces;
    size_t row = complex->step[1], plane = complex->step[2];
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            __builtin_prefetch(faces + cell + (ptrdiff_t)dz * (ptrdiff_t)plane +
                               (ptrdiff_t)dy * (ptrdiff_t)row, 1);
}

/* All free pairs of one direction, orientation and dimension, found on the
 * complex as it is, then removed together. */
HOT gb_result collapse_substep(gb_collapse *collapse, substep s, gb_error *error)
{
    collapse->pair_count = 0;
    collapse->substep =
        GB_COLLAPSE_KINDS * direction_of(s.axis, s.orientation) + 3 - s.dimension;
    const gb_cell_list *border = &collapse->border[collapse->substep];
    size_t count = border->count;
    collapse->cells_examined += count;
    for (size_t n = 0; n < count; ++n) {
        if (n + PREFETCH_AHEAD < count)
            prefetch_around(collapse->complex, border->items[n + PREFETCH_AHEAD]);
        if (find_pairs_in_cell(collapse, border->items[n], s, error))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    for (size_t n = 0; n < collapse->pair_count; ++n) {
        if (n + PREFETCH_AHEAD < collapse->pair_count)
            prefetch_around(collapse->complex,
                            (size_t)(collapse->pairs[n + PREFETCH_AHEAD] >> 8));
        if (remove_pair(collapse, collapse->pairs[n], s, error))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    return GB_OK;
}

/* One substep per direction, orientation and dimension, each compiled for
 * its constants (the scans are the inner loop of thin). */
#define SUBSTEPS_OF(axis, orientation)                                                      \
    (collapse_substep(collapse, (substep){axis, orientation, 3}, error) ||                  \
     collapse_substep(collapse, (substep){axis, orientation, 2}, error) ||                  \
     collapse_substep(collapse, (substep){axis, orientation, 1}, error))

static gb_result collapse_iteration(gb_collapse *collapse, gb_error *error)
{
    if (SUBSTEPS_OF(0, -1) || SUBSTEPS_OF(0, 1) || SUBSTEPS_OF(1, -1) || SUBSTEPS_OF(1, 1) ||
        SUBSTEPS_OF(2, -1) || SUBSTEPS_OF(2, 1))
        return GB_ERROR_OUT_OF_MEMORY;
    collapse->substep = GB_COLLAPSE_SUBSTEPS;
    return end_iteration(collapse, error);
}

gb_result gb_collapse_run(gb_collapse *collapse, gb_progress_callback progress,
                          void *progress_user, gb_error *error)
{
    while (any_pending(collapse)) {
        start_iteration(collapse);
        if (collapse_iteration(collapse, error))
            return GB_ERROR_OUT_OF_MEMORY;
        ++collapse->iteration;
        double done = collapse->cubes ? (double)collapse->cubes_removed / (double)collapse->cubes
                                      : 1.0;
        if (progress && progress(progress_user, done))
            return gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    }
    return GB_OK;
}
