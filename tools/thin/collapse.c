/* collapse.c — ParDirCollapse with border lists and persistent isthmuses
 * (see collapse.h). */
#include "collapse.h"

#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "thread_team.h"

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
 * nowhere (it would only be examined again, gone). A byte holds 8 cells of
 * one chunk, so only the chunk's thread changes it. */
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

/* A chunk is at least this many planes: a removal reaches less than 3
 * planes from its cell, so chunks two apart never meet. */
enum { CHUNK_PLANES = 8 };

/* The list a cell goes to: its chunk's parity, then its chunk's thread
 * (chunks taken two by two). */
HOT size_t bucket_of(const gb_collapse *collapse, size_t cell)
{
    size_t chunk = cell >> collapse->chunk_shift;
    return (chunk & 1) * (size_t)collapse->thread_count +
           ((chunk >> 1) & (size_t)(collapse->thread_count - 1));
}

/* A worker's list of a substep and bucket: 2 * thread_count buckets a
 * substep. */
HOT size_t list_index(const gb_collapse *collapse, int substep, size_t bucket)
{
    return (size_t)substep * 2 * (size_t)collapse->thread_count + bucket;
}

/* The cell may hold the g (of that kind) of a pair the substep of that
 * kind and direction removes: examined there, in this iteration if that
 * substep is still to come, else in the next. */
HOT gb_result list_candidate(gb_collapse_worker *worker, size_t cell, int kind, int direction)
{
    const gb_collapse *collapse = worker->collapse;
    int substep = GB_COLLAPSE_KINDS * direction + kind;
    size_t list = list_index(collapse, substep, bucket_of(collapse, cell));
    return gb_cell_list_push(substep > worker->substep ? &worker->border[list]
                                                       : &worker->pending[list],
                             cell, &worker->error);
}

gb_result gb_collapse_reconsider(gb_collapse *collapse, size_t cell, gb_error *error)
{
    const size_t *step = collapse->complex->step;
    gb_collapse_worker *worker = &collapse->workers[0];
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                size_t neighbour = (size_t)((ptrdiff_t)cell + dx + dy * (ptrdiff_t)step[1] +
                                            dz * (ptrdiff_t)step[2]);
                for (int kind = 0; kind < GB_COLLAPSE_KINDS; ++kind) {
                    if (!(collapse->complex->faces[neighbour] & kind_faces[kind]))
                        continue;
                    for (int direction = 0; direction < GB_COLLAPSE_DIRECTIONS; ++direction)
                        if (list_candidate(worker, neighbour, kind, direction)) {
                            *error = worker->error;
                            return GB_ERROR_OUT_OF_MEMORY;
                        }
                }
            }
    return GB_OK;
}

static size_t list_count(const gb_collapse *collapse)
{
    return list_index(collapse, GB_COLLAPSE_SUBSTEPS, 0);
}

static void free_worker(const gb_collapse *collapse, gb_collapse_worker *worker)
{
    for (size_t list = 0; worker->border && list < list_count(collapse); ++list) {
        gb_cell_list_free(&worker->border[list]);
        gb_cell_list_free(&worker->pending[list]);
    }
    free(worker->border);
    free(worker->pending);
    for (int axis = 0; axis < 3; ++axis)
        gb_cell_list_free(&worker->born[axis]);
    for (int parity = 0; parity < 2; ++parity)
        free(worker->pairs[parity].items);
}

void gb_collapse_free(gb_collapse *collapse)
{
    if (!collapse)
        return;
    for (int t = 0; collapse->workers && t < collapse->thread_count; ++t)
        free_worker(collapse, &collapse->workers[t]);
    free(collapse->workers);
    free(collapse->cube_found);
    memset(collapse, 0, sizeof *collapse);
}

gb_result gb_collapse_init(gb_collapse *collapse, gb_cubical_complex *complex,
                           gb_persistence *persistence, int thread_count, gb_error *error)
{
    memset(collapse, 0, sizeof *collapse);
    collapse->complex = complex;
    collapse->persistence = persistence;
    collapse->thread_count = 1;
    while (2 * collapse->thread_count <= thread_count &&
           2 * collapse->thread_count <= GB_COLLAPSE_MAX_THREADS)
        collapse->thread_count *= 2;
    collapse->parallel_cells = GB_COLLAPSE_PARALLEL_CELLS;
    while (((size_t)1 << collapse->chunk_shift) < CHUNK_PLANES * complex->step[2])
        ++collapse->chunk_shift;
    collapse->workers = calloc((size_t)collapse->thread_count, sizeof *collapse->workers);
    collapse->cube_found = calloc(complex->cell_count / 8 + 1, 1);
    int allocated = collapse->workers && collapse->cube_found;
    for (int t = 0; allocated && t < collapse->thread_count; ++t) {
        gb_collapse_worker *worker = &collapse->workers[t];
        worker->collapse = collapse;
        worker->substep = GB_COLLAPSE_SUBSTEPS;
        worker->border = calloc(list_count(collapse), sizeof *worker->border);
        worker->pending = calloc(list_count(collapse), sizeof *worker->pending);
        allocated = worker->border && worker->pending;
    }
    if (!allocated) {
        gb_collapse_free(collapse);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "collapse: out of memory for %zu cells",
                       complex->cell_count);
    }
    /* Every face is in a cube: the only free pairs are (square, cube) where
     * the cube's neighbour across the square is not empty. */
    gb_collapse_worker *worker = &collapse->workers[0];
    for (size_t cell = 0; cell < complex->cell_count; ++cell) {
        if (!(complex->faces[cell] & GB_FACE_CUBE))
            continue;
        ++collapse->cubes;
        for (int axis = 0; axis < 3; ++axis)
            for (int orientation = -1; orientation <= 1; orientation += 2) {
                size_t beyond = cell_beyond(complex, cell, axis, orientation);
                if (!(complex->faces[beyond] & GB_FACE_CUBE) &&
                    list_candidate(worker, cell, KIND_CUBE, direction_of(axis, orientation))) {
                    *error = worker->error;
                    gb_collapse_free(collapse);
                    return GB_ERROR_OUT_OF_MEMORY;
                }
            }
    }
    return GB_OK;
}

/* ---- iterations: their start and end, on thread 0 alone ---- */

/* Whether another iteration is needed, and its border: the cells pending
 * from the last one (the old border's allocation takes the next
 * iteration's pending cells). It is shared if every worker has its thread
 * (team_complete) and it looks large: as many cells listed, or examined by
 * the last iteration (most of an iteration's cells are listed during it),
 * as parallel_cells. */
static void begin_iteration(gb_collapse *collapse, int team_complete)
{
    uint64_t last_examined = collapse->cells_examined - collapse->cells_examined_before;
    collapse->cells_examined_before = collapse->cells_examined;
    size_t listed = 0;
    for (int t = 0; t < collapse->thread_count; ++t)
        for (size_t list = 0; list < list_count(collapse); ++list) {
            gb_collapse_worker *worker = &collapse->workers[t];
            gb_cell_list *border = &worker->border[list];
            gb_cell_list candidates = worker->pending[list];
            border->count = 0;
            worker->pending[list] = *border;
            *border = candidates;
            listed += candidates.count;
        }
    collapse->running = listed && !collapse->failed;
    collapse->parallel = collapse->running && collapse->thread_count > 1 && team_complete &&
                         (listed >= collapse->parallel_cells ||
                          last_examined >= collapse->parallel_cells);
    collapse->shared_iterations += (uint32_t)collapse->parallel;
}

static void fail(gb_collapse *collapse, gb_collapse_worker *worker, gb_result result)
{
    if (!worker->result)
        worker->result = result;
    __atomic_store_n(&collapse->failed, 1, __ATOMIC_RELAXED);
}

/* Facets born this iteration and still there get their birth recorded; the
 * others were collapsed at once and never needed one. The clock moves on
 * only if the iteration removed a pair. */
static void end_iteration(gb_collapse *collapse)
{
    const uint8_t *faces = collapse->complex->faces;
    gb_collapse_worker *first = &collapse->workers[0];
    uint64_t pairs_removed = 0, cubes_removed = 0, cells_examined = 0;
    for (int t = 0; t < collapse->thread_count; ++t) {
        gb_collapse_worker *worker = &collapse->workers[t];
        for (int axis = 0; axis < 3; ++axis) {
            gb_cell_list *born = &worker->born[axis];
            for (size_t n = 0; n < born->count && !first->result; ++n)
                if (faces[born->items[n]] & gb_edge_bit(axis) &&
                    gb_persistence_record_birth(collapse->persistence, born->items[n], axis,
                                                collapse->iteration, &first->error))
                    fail(collapse, first, GB_ERROR_OUT_OF_MEMORY);
            born->count = 0;
        }
        pairs_removed += worker->pairs_removed;
        cubes_removed += worker->cubes_removed;
        cells_examined += worker->cells_examined;
    }
    if (pairs_removed > collapse->pairs_removed)
        ++collapse->iteration;
    collapse->pairs_removed = pairs_removed;
    collapse->cubes_removed = cubes_removed;
    collapse->cells_examined = cells_examined;
}

/* ---- finding the free pairs of a substep ---- */

HOT gb_result add_pair(gb_collapse_worker *worker, gb_pair_list *pairs, size_t cell, uint8_t g)
{
    if (!gb_array_reserve(&pairs->items, &pairs->capacity, pairs->count + 1,
                          sizeof *pairs->items))
        return gb_fail(&worker->error, GB_ERROR_OUT_OF_MEMORY, "collapse: out of memory");
    pairs->items[pairs->count++] = (uint64_t)cell << 8 | g;
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

/* The free pairs of the substep whose g is in cell, appended to pairs (no
 * face changes while pairs are found). A face of a cube
 * is in the cube, so in a cell holding a cube only the cube can be a g. */
HOT gb_result find_pairs_in_cell(gb_collapse_worker *worker, size_t cell, substep s,
                                 gb_pair_list *pairs)
{
    gb_collapse *collapse = worker->collapse;
    const gb_cubical_complex *complex = collapse->complex;
    const uint8_t *faces = complex->faces;
    uint8_t here = faces[cell];
    size_t f = free_face_cell(complex, cell, s);
    if (s.dimension == 3) {
        size_t beyond = cell_beyond(complex, cell, s.axis, s.orientation);
        if (!(here & GB_FACE_CUBE) || (faces[beyond] & GB_FACE_CUBE))
            return GB_OK;
        set_cube_found(collapse, cell, 1);
        return add_pair(worker, pairs, cell, GB_FACE_CUBE);
    }
    if (here & GB_FACE_CUBE)
        return GB_OK;
    if (s.dimension == 2) {
        for (int normal = 0; normal < 3; ++normal) {
            if (normal == s.axis || !(here & gb_square_bit(normal)))
                continue;
            int edge_axis = 3 - s.axis - normal;
            if (gb_edge_coface_count(complex, f, edge_axis) == 1 &&
                add_pair(worker, pairs, cell, gb_square_bit(normal)))
                return GB_ERROR_OUT_OF_MEMORY;
        }
        return GB_OK;
    }
    if ((here & gb_edge_bit(s.axis)) && gb_point_coface_count(complex, f) == 1 &&
        !is_protected(collapse, cell, s.axis))
        return add_pair(worker, pairs, cell, gb_edge_bit(s.axis));
    return GB_OK;
}

/* ---- what a removal frees ---- */

/* A face h that lost a coface: if one coface k is left, (h, k) may be a new
 * free pair and k's cell is listed; if none, h is a facet (an edge's birth).
 * A facet itself needs no listing: it becomes a g when one of its faces
 * loses its other cofaces, which lists it then. */

HOT gb_result square_lost_coface(gb_collapse_worker *worker, size_t cell, int normal)
{
    const gb_collapse *collapse = worker->collapse;
    const uint8_t *faces = collapse->complex->faces;
    if (!(faces[cell] & gb_square_bit(normal)))
        return GB_OK;
    size_t behind = cell - collapse->complex->step[normal];
    int here = (faces[cell] & GB_FACE_CUBE) != 0;
    int back = (faces[behind] & GB_FACE_CUBE) != 0;
    /* the cube left has the square on its low side (here) or high side */
    if (here + back != 1 || cube_is_found(collapse, here ? cell : behind))
        return GB_OK;
    return here ? list_candidate(worker, cell, KIND_CUBE, direction_of(normal, -1))
                : list_candidate(worker, behind, KIND_CUBE, direction_of(normal, +1));
}

HOT gb_result edge_lost_coface(gb_collapse_worker *worker, size_t cell, int axis)
{
    const gb_cubical_complex *complex = worker->collapse->complex;
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
        return list_candidate(worker, cells[last], KIND_SQUARE, directions[last]);
    if (count == 0)
        return gb_cell_list_push(&worker->born[axis], cell, &worker->error);
    return GB_OK;
}

HOT gb_result point_lost_coface(gb_collapse_worker *worker, size_t cell)
{
    const gb_cubical_complex *complex = worker->collapse->complex;
    const uint8_t *faces = complex->faces;
    uint8_t here = faces[cell];
    if (!(here & GB_FACE_POINT))
        return GB_OK;
    /* its edges: along each axis, starting at the point (low end) or ending
     * at it (high end) */
    int count = 0, last_direction = 0;
    size_t last = cell;
    for (int axis = 0; axis < 3; ++axis) {
        if (here & gb_edge_bit(axis)) {
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
    return count == 1 ? list_candidate(worker, last, KIND_EDGE, last_direction) : GB_OK;
}

/* Removed: the cube of cell and its square normal to axis at square_cell.
 * Lost a coface: the cube's 5 other squares and the square's 4 edges. */
HOT gb_result after_cube(gb_collapse_worker *worker, size_t cell, int axis, size_t square_cell)
{
    const size_t *step = worker->collapse->complex->step;
    for (int normal = 0; normal < 3; ++normal) {
        if (square_lost_coface(worker, cell, normal) ||
            square_lost_coface(worker, cell + step[normal], normal))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    if (edge_lost_coface(worker, square_cell, b) ||
        edge_lost_coface(worker, square_cell + step[c], b) ||
        edge_lost_coface(worker, square_cell, c) ||
        edge_lost_coface(worker, square_cell + step[b], c))
        return GB_ERROR_OUT_OF_MEMORY;
    return GB_OK;
}

/* Removed: the square normal to normal at cell (spanning the direction axis
 * and edge_axis) and its edge along edge_axis at edge_cell. Lost a coface:
 * the square's 3 other edges and the edge's 2 points. */
HOT gb_result after_square(gb_collapse_worker *worker, size_t cell, int axis, int edge_axis,
                           size_t edge_cell)
{
    const size_t *step = worker->collapse->complex->step;
    size_t opposite = edge_cell == cell ? cell + step[axis] : cell;
    if (edge_lost_coface(worker, opposite, edge_axis) ||
        edge_lost_coface(worker, cell, axis) ||
        edge_lost_coface(worker, cell + step[edge_axis], axis) ||
        point_lost_coface(worker, edge_cell) ||
        point_lost_coface(worker, edge_cell + step[edge_axis]))
        return GB_ERROR_OUT_OF_MEMORY;
    return GB_OK;
}

/* Removed: the edge along axis at cell and its point at point_cell. Lost a
 * coface: the edge's other point. */
HOT gb_result after_edge(gb_collapse_worker *worker, size_t cell, int axis, size_t point_cell)
{
    size_t other = point_cell == cell ? cell + worker->collapse->complex->step[axis] : cell;
    return point_lost_coface(worker, other);
}

HOT int axis_of_square(uint8_t square)
{
    return square == GB_FACE_SQUARE_YZ ? 0 : square == GB_FACE_SQUARE_XZ ? 1 : 2;
}

/* Removes the pair unless it is gone (its cell was listed twice, so it was
 * found twice). */
HOT gb_result remove_pair(gb_collapse_worker *worker, uint64_t pair, substep s)
{
    gb_collapse *collapse = worker->collapse;
    uint8_t *faces = collapse->complex->faces;
    size_t cell = (size_t)(pair >> 8);
    uint8_t g = (uint8_t)(pair & 0xff);
    if (!(faces[cell] & g))
        return GB_OK;
    faces[cell] &= (uint8_t)~g;
    size_t f = free_face_cell(collapse->complex, cell, s);
    ++worker->pairs_removed;
    if (s.dimension == 3) {
        faces[f] &= (uint8_t)~gb_square_bit(s.axis);
        set_cube_found(collapse, cell, 0);
        ++worker->cubes_removed;
        return after_cube(worker, cell, s.axis, f);
    }
    if (s.dimension == 2) {
        int edge_axis = 3 - s.axis - axis_of_square(g);
        faces[f] &= (uint8_t)~gb_edge_bit(edge_axis);
        return after_square(worker, cell, s.axis, edge_axis, f);
    }
    faces[f] &= (uint8_t)~GB_FACE_POINT;
    return after_edge(worker, cell, s.axis, f);
}

/* ---- substeps ---- */

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

/* The free pairs in the chunks of threads first .. first + count - 1,
 * from every thread's lists, appended to the worker's pairs by the parity of
 * their chunk. */
HOT gb_result find_pairs(gb_collapse_worker *worker, substep s, int first, int count)
{
    const gb_collapse *collapse = worker->collapse;
    for (int parity = 0; parity < 2; ++parity) {
        worker->pairs[parity].count = 0;
        for (int owner = first; owner < first + count; ++owner) {
            size_t list = list_index(collapse, worker->substep,
                                     (size_t)(parity * collapse->thread_count + owner));
            for (int t = 0; t < collapse->thread_count; ++t) {
                const gb_cell_list *cells = &collapse->workers[t].border[list];
                worker->cells_examined += cells->count;
                for (size_t n = 0; n < cells->count; ++n) {
                    if (n + PREFETCH_AHEAD < cells->count)
                        prefetch_around(collapse->complex, cells->items[n + PREFETCH_AHEAD]);
                    if (find_pairs_in_cell(worker, cells->items[n], s, &worker->pairs[parity]))
                        return GB_ERROR_OUT_OF_MEMORY;
                }
            }
        }
    }
    return GB_OK;
}

HOT gb_result remove_pairs(gb_collapse_worker *worker, substep s, const gb_pair_list *pairs)
{
    const gb_cubical_complex *complex = worker->collapse->complex;
    for (size_t n = 0; n < pairs->count; ++n) {
        if (n + PREFETCH_AHEAD < pairs->count)
            prefetch_around(complex, (size_t)(pairs->items[n + PREFETCH_AHEAD] >> 8));
        if (remove_pair(worker, pairs->items[n], s))
            return GB_ERROR_OUT_OF_MEMORY;
    }
    return GB_OK;
}

/* Whether any thread listed a cell for the substep: every thread sees the
 * same lists here (the last barrier ended all changes to them), so all
 * skip an empty substep and its barriers alike. */
static int any_listed(const gb_collapse *collapse, int substep)
{
    for (int t = 0; t < collapse->thread_count; ++t)
        for (size_t bucket = 0; bucket < 2 * (size_t)collapse->thread_count; ++bucket)
            if (collapse->workers[t].border[list_index(collapse, substep, bucket)].count)
                return 1;
    return 0;
}

static int has_failed(gb_collapse *collapse)
{
    return __atomic_load_n(&collapse->failed, __ATOMIC_RELAXED);
}

/* All free pairs of one direction, orientation and dimension, found on the
 * complex as it is, then removed together: in the chunks of this thread
 * (team not NULL: the others do theirs, and the removals in even chunks end
 * before those in odd chunks start) or in every chunk (team NULL). */
HOT void collapse_substep(gb_collapse_worker *worker, gb_thread_team *team, substep s,
                          int thread)
{
    gb_collapse *collapse = worker->collapse;
    worker->substep = GB_COLLAPSE_KINDS * direction_of(s.axis, s.orientation) + 3 - s.dimension;
    if (!any_listed(collapse, worker->substep))
        return;
    int first = team ? thread : 0, count = team ? 1 : collapse->thread_count;
    if (!has_failed(collapse) && find_pairs(worker, s, first, count))
        fail(collapse, worker, GB_ERROR_OUT_OF_MEMORY);
    for (int parity = 0; parity < 2; ++parity) {
        if (team)
            gb_thread_team_wait(team);
        if (!has_failed(collapse) && remove_pairs(worker, s, &worker->pairs[parity]))
            fail(collapse, worker, GB_ERROR_OUT_OF_MEMORY);
    }
    if (team)
        gb_thread_team_wait(team);
}

/* One substep per direction, orientation and dimension, each compiled for
 * its constants (the scans are the inner loop of thin). */
#define SUBSTEPS_OF(axis, orientation)                                                      \
    do {                                                                                    \
        collapse_substep(worker, team, (substep){axis, orientation, 3}, thread);           \
        collapse_substep(worker, team, (substep){axis, orientation, 2}, thread);           \
        collapse_substep(worker, team, (substep){axis, orientation, 1}, thread);           \
    } while (0)

/* An iteration: team NULL, by thread alone (0) in every chunk. */
static void collapse_iteration(gb_collapse_worker *worker, gb_thread_team *team, int thread)
{
    SUBSTEPS_OF(0, -1);
    SUBSTEPS_OF(0, 1);
    SUBSTEPS_OF(1, -1);
    SUBSTEPS_OF(1, 1);
    SUBSTEPS_OF(2, -1);
    SUBSTEPS_OF(2, 1);
}

/* ---- the run ---- */

typedef struct run {
    gb_collapse *collapse;
    gb_progress_callback progress;
    void *progress_user;
} run;

/* Thread 0 starts and ends each iteration; in between, all threads share it
 * (a large one) or thread 0 does it alone while the others wait. */
static void run_on_team(void *context, gb_thread_team *team, int thread, int thread_count)
{
    const run *r = context;
    gb_collapse *collapse = r->collapse;
    gb_collapse_worker *worker = &collapse->workers[thread];
    for (;;) {
        if (thread == 0)
            begin_iteration(collapse, thread_count == collapse->thread_count);
        gb_thread_team_wait(team);
        if (!collapse->running)
            break;
        if (collapse->parallel) {
            collapse_iteration(worker, team, thread);
            gb_thread_team_wait(team);
        } else if (thread == 0) {
            collapse_iteration(worker, NULL, 0);
            gb_thread_team_wait(team);
        } else {
            gb_thread_team_wait_long(team);
        }
        if (thread != 0)
            continue;
        end_iteration(collapse);
        double done = collapse->cubes ? (double)collapse->cubes_removed / (double)collapse->cubes
                                      : 1.0;
        if (r->progress && r->progress(r->progress_user, done) && !collapse->failed) {
            gb_fail(&worker->error, GB_ERROR_INTERRUPTED, "interrupted");
            fail(collapse, worker, GB_ERROR_INTERRUPTED);
        }
    }
    worker->substep = GB_COLLAPSE_SUBSTEPS;
}

gb_result gb_collapse_run(gb_collapse *collapse, gb_progress_callback progress,
                          void *progress_user, gb_error *error)
{
    run r = {collapse, progress, progress_user};
    gb_thread_team_run(run_on_team, &r, collapse->thread_count);
    for (int t = 0; t < collapse->thread_count; ++t)
        if (collapse->workers[t].result) {
            *error = collapse->workers[t].error;
            return collapse->workers[t].result;
        }
    return GB_OK;
}
