/* nearest_node.c — geodesic nearest skeleton node of every voxel (see
 * nearest_node.h).
 *
 * The answer is the least (distance, node) over all paths of every cell: a
 * unique fixed point of "a cell is at most a neighbour plus the step", so
 * any order of work that reaches it gives the same bytes. First, raster
 * sweeps (forward over the cells with their 13 earlier neighbours, then
 * backward with the 13 later ones, as a chamfer distance transform) until a
 * pair of sweeps changes nothing: memory is read in order, and indoor
 * scenes settle in 3 or 4 pairs; the threads share each sweep, a plane
 * each in turn (see "raster sweeps" below). A volume that needs more (a maze) is done
 * again by Dijkstra's algorithm, on several threads: the lattice is cut into
 * slabs along z, each thread runs Dijkstra in its own slab and sends the
 * steps that leave it to the slab they enter; rounds go on until no step
 * improves anything. A thread writes and reads only cells of its slab. */
#include "nearest_node.h"

#include <sched.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "cell_list.h"
#include "huge_pages.h"
#include "thread_team.h"
#include "threads.h"

enum {
    BUCKETS = 2048,             /* > the longest step, a power of two */
    LONGEST_STEP = 1732,
    SEED_LENGTH = 866,          /* corner to voxel centre: sqrt(3)/2 voxel */
    MAX_SLABS = 64,
    SWEEP_THREADS_MAX = 8,      /* a sweep's planes go to at most this many */
};

/* A cell's state in 48 bits: distance (thousandths of a voxel) in the high
 * 24, node index in the low 24, so that comparing states compares (distance,
 * node) lexicographically. Non-empty cells hold BLOCKED, which nothing
 * improves; empty cells start at UNREACHED. A path that would be longer
 * than UNREACHED's distance (16 777 voxels) is never taken, and a voxel
 * that far from every node stays unreached. The lattice keeps a state in 6
 * bytes a cell (8 at 512^3 would be 1 GiB alone), read and written through
 * state_at and set_state. */
enum { STATE_BYTES = 6, NODE_BITS = 24 };
static const uint64_t BLOCKED = 0, UNREACHED = (1ull << 48) - 1;

/* Nodes are numbered below this (UNREACHED's node bits stay free). */
#define MAX_NODES ((1u << NODE_BITS) - 1)

static const uint32_t step_length[4] = {0, 1000, 1414, 1732};

static uint32_t distance_of(uint64_t state) { return (uint32_t)(state >> NODE_BITS); }
static int32_t node_of(uint64_t state) { return (int32_t)(state & MAX_NODES); }

static uint64_t state_of(uint32_t distance, uint32_t node)
{
    return (uint64_t)distance << NODE_BITS | node;
}

/* A cell reached with a state, from outside a slab or from a node. */
typedef struct arrival {
    uint64_t state;
    uint64_t cell;
} arrival;

typedef struct arrivals {
    arrival *items;
    size_t count, capacity;
} arrivals;

typedef struct geodesic {
    const gb_cubical_complex *complex;
    unsigned char *state;       /* per cell, STATE_BYTES each */
    ptrdiff_t offsets[26];
    uint64_t lengths[26];       /* step lengths, shifted to the distance bits */
} geodesic;

/* A state as its low 32 bits and its high 16, each moved whole (one word
 * assembled in memory from two smaller stores would stall the load). */
static uint64_t state_at(const geodesic *g, size_t cell)
{
    const unsigned char *at = g->state + STATE_BYTES * cell;
    uint32_t low;
    uint16_t high;
    memcpy(&low, at, sizeof low);
    memcpy(&high, at + 4, sizeof high);
    return (uint64_t)high << 32 | low;
}

static void set_state(geodesic *g, size_t cell, uint64_t state)
{
    unsigned char *at = g->state + STATE_BYTES * cell;
    uint32_t low = (uint32_t)state;
    uint16_t high = (uint16_t)(state >> 32);
    memcpy(at, &low, sizeof low);
    memcpy(at + 4, &high, sizeof high);
}

typedef struct slab {
    geodesic *g;
    size_t begin, end;          /* its cells: indices begin .. end-1 (whole z layers) */
    gb_cell_list buckets[BUCKETS];
    size_t queued;
    arrivals inbox;             /* sorted arrivals to start from */
    arrivals outbox;            /* steps into other slabs */
    size_t empty_count, settled;
    gb_progress_callback progress;  /* slab 0 of the first round only */
    void *progress_user;
    gb_result result;
    gb_error error;
} slab;

static gb_result push_arrival(arrivals *list, size_t cell, uint64_t state, gb_error *error)
{
    if (!gb_array_reserve(&list->items, &list->capacity, list->count + 1, sizeof *list->items))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "nearest node: out of memory");
    list->items[list->count++] = (arrival){state, cell};
    return GB_OK;
}

static int compare_arrivals(const void *a, const void *b)
{
    const arrival *x = a, *y = b;
    if (x->state != y->state)
        return x->state < y->state ? -1 : 1;
    return x->cell < y->cell ? -1 : x->cell > y->cell;
}

static void neighbour_steps(geodesic *g)
{
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if (!dx && !dy && !dz)
                    continue;
                g->offsets[n] = dx + dy * (ptrdiff_t)g->complex->step[1] +
                                dz * (ptrdiff_t)g->complex->step[2];
                g->lengths[n] = (uint64_t)step_length[(dx != 0) + (dy != 0) + (dz != 0)]
                                << NODE_BITS;
                ++n;
            }
}

/* Returns the number of empty voxels. */
static size_t mark_empty_cells(geodesic *g, const gb_voxel_grid *grid,
                               const gb_empty_voxels *empty_voxels)
{
    size_t empty = 0;
    memset(g->state, 0, STATE_BYTES * g->complex->cell_count); /* BLOCKED */
    for (int32_t k = 0; k < grid->size[2]; ++k)
        for (int32_t j = 0; j < grid->size[1]; ++j) {
            size_t voxel = gb_voxel_index(grid, 0, j, k);
            size_t row = gb_voxel_cell(g->complex, 0, j, k);
            for (int32_t i = 0; i < grid->size[0]; ++i)
                if (gb_voxel_is_empty(empty_voxels, voxel + (size_t)i)) {
                    set_state(g, row + (size_t)i, UNREACHED);
                    ++empty;
                }
        }
    return empty;
}

/* ---- raster sweeps ---- */

/* Sweeps look at a row of cells (fixed y and z) only when a row it reads
 * from changed since it was last swept in that direction: changed[row] and
 * swept[direction][row] hold ticks, a row's place in the order of all the
 * rows of all the sweeps (first_tick of its sweep + its place in it).
 *
 * The threads of a team share a sweep: thread t takes the planes (fixed z)
 * t, t + T, ... of the sweep's order, and before each row waits for the
 * plane before it to have swept the rows this one reads (the layer before:
 * the row beside it and the next in the sweep's order). Each cell then
 * reads what it would read in one thread's sweep, so every sweep writes the
 * same states as on one thread, and the ticks are the same. */
typedef struct sweeper {
    geodesic *g;
    uint64_t *changed;          /* per row, shared */
    uint64_t *swept[2];         /* per row, forward and backward, shared */
    uint64_t *plane_done;       /* per plane of a sweep's order: (sweep number
                                   + 1) << 32 | its rows swept, shared */
    /* the thread's work space for a row, size[0] states each: the least of
     * its two face neighbours beside the row (the layer before, the row
     * before), of its two diagonal ones (the layer before, rows before and
     * after), and what those 12 offer each cell */
    uint64_t *face, *diagonal, *offered, *read;
} sweeper;

/* Does row (y, z) read from a row changed since it was last swept? It reads
 * itself, the row before it (after it, backward) and the three rows of the
 * layer before (after). */
static int row_is_stale(const sweeper *w, int32_t y, int32_t z, int backward)
{
    const gb_cubical_complex *c = w->g->complex;
    int32_t dz = backward ? 1 : -1, ny = c->size[1];
    size_t row = (size_t)y + (size_t)ny * (size_t)z;
    uint64_t since = w->swept[backward][row];
    if (w->changed[row] > since || w->changed[(size_t)(y + dz) + (size_t)ny * (size_t)z] > since)
        return 1;
    for (int32_t b = y - 1; b <= y + 1; ++b)
        if (w->changed[(size_t)b + (size_t)ny * (size_t)(z + dz)] > since)
            return 1;
    return 0;
}

/* A state nothing is reached from: BLOCKED and UNREACHED read as this, so
 * that a plain minimum of the offers never takes them (it stays above
 * UNREACHED with the longest step added, and does not overflow). */
static const uint64_t NO_SOURCE = UINT64_MAX >> 2;

static uint64_t source_at(const geodesic *g, size_t cell)
{
    uint64_t state = state_at(g, cell);
    return state == BLOCKED || state == UNREACHED ? NO_SOURCE : state;
}

static uint64_t least(uint64_t a, uint64_t b) { return a < b ? a : b; }

/* The least over the cells first .. first + count - 1 of two rows (cell
 * offsets a and b) as sources, into least_of. */
static void least_of_rows(const geodesic *g, size_t first, size_t count, ptrdiff_t a,
                          ptrdiff_t b, uint64_t *read, uint64_t *least_of)
{
    for (size_t n = 0; n < count; ++n)
        read[n] = source_at(g, (size_t)((ptrdiff_t)(first + n) + a));
    for (size_t n = 0; n < count; ++n)
        least_of[n] = least(read[n], source_at(g, (size_t)((ptrdiff_t)(first + n) + b)));
}

/* Each empty cell of the row takes the best of itself and its 13 neighbours
 * on the side already swept plus the step. The 12 beside the row are taken
 * for the whole row first: a face neighbour offers its state plus a step of
 * 1 straight across, sqrt 2 one cell along the row; a diagonal one sqrt 2
 * and sqrt 3. Then the cells in order, each with the one before it in the
 * row. Returns whether anything changed. */
static int sweep_row(const sweeper *w, size_t first, size_t count, int backward)
{
    geodesic *g = w->g;
    const size_t *step = g->complex->step;
    ptrdiff_t layer = backward ? (ptrdiff_t)step[2] : -(ptrdiff_t)step[2];
    ptrdiff_t row = backward ? (ptrdiff_t)step[1] : -(ptrdiff_t)step[1];
    const uint64_t one = (uint64_t)step_length[1] << NODE_BITS,
                   two = (uint64_t)step_length[2] << NODE_BITS,
                   three = (uint64_t)step_length[3] << NODE_BITS;
    /* the work rows hold the cells first - 1 .. first + count: cell first
     * + n and its neighbours along the row at n, n + 1, n + 2 */
    least_of_rows(g, first - 1, count + 2, layer, row, w->read, w->face);
    least_of_rows(g, first - 1, count + 2, layer - (ptrdiff_t)step[1],
                  layer + (ptrdiff_t)step[1], w->read, w->diagonal);
    const uint64_t *face = w->face, *diagonal = w->diagonal;
    for (size_t n = 0; n < count; ++n) {
        uint64_t across = least(least(face[n], face[n + 2]), diagonal[n + 1]);
        w->offered[n] = least(least(face[n + 1] + one, across + two),
                              least(diagonal[n], diagonal[n + 2]) + three);
    }
    int changed = 0;
    size_t before_first = backward ? first + count : first - 1;
    uint64_t before = source_at(g, before_first);
    for (size_t m = 0; m < count; ++m) {
        size_t n = backward ? count - 1 - m : m;
        uint64_t held = state_at(g, first + n);
        if (held == BLOCKED) {
            before = NO_SOURCE;
            continue;
        }
        uint64_t best = least(held, least(w->offered[n], before + one));
        if (best != held) {
            set_state(g, first + n, best);
            changed = 1;
        }
        before = best == UNREACHED ? NO_SOURCE : best;
    }
    return changed;
}

/* Waits until the plane's word says rows of sweep number have been swept
 * (the other thread runs a few microseconds a row: yield, do not sleep). */
static void wait_for_rows(const uint64_t *done, uint64_t number, uint32_t rows)
{
    uint64_t wanted = (number + 1) << 32 | rows;
    while (__atomic_load_n(done, __ATOMIC_ACQUIRE) < wanted)
        sched_yield();
}

/* Sweep number (forward when even) over the thread's planes of the rows
 * holding voxels (y, z in 1 .. size-2). Returns whether it changed
 * anything. */
static int sweep_planes(const sweeper *w, uint64_t number, int thread, int thread_count)
{
    const gb_cubical_complex *c = w->g->complex;
    int backward = (int)(number & 1);
    int32_t ny = c->size[1], rows_y = ny - 3, rows_z = c->size[2] - 3;
    if (rows_y <= 0 || rows_z <= 0)
        return 0;
    size_t length = (size_t)c->size[0] - 3, rows = (size_t)rows_y * (size_t)rows_z;
    uint64_t first_tick = 2 + number * rows;    /* above the seeds' 1 */
    int changed = 0;
    for (int32_t p = thread; p < rows_z; p += thread_count)
        for (int32_t i = 0; i < rows_y; ++i) {
            if (p > 0)
                wait_for_rows(&w->plane_done[p - 1], number,
                              (uint32_t)(i + 2 < rows_y ? i + 2 : rows_y));
            size_t n = (size_t)p * (size_t)rows_y + (size_t)i;
            size_t m = backward ? rows - 1 - n : n;
            int32_t y = 1 + (int32_t)(m % (size_t)rows_y), z = 1 + (int32_t)(m / (size_t)rows_y);
            size_t row = (size_t)y + (size_t)ny * (size_t)z;
            if (row_is_stale(w, y, z, backward)) {
                w->swept[backward][row] = first_tick + n;
                if (sweep_row(w, gb_cell_index(c, 1, y, z), length, backward)) {
                    w->changed[row] = first_tick + n; /* stale for the rows reading it */
                    changed = 1;
                }
            }
            __atomic_store_n(&w->plane_done[p], (number + 1) << 32 | (uint64_t)(i + 1),
                             __ATOMIC_RELEASE);
        }
    return changed;
}

/* The sweeps of a team (sweep_on_team), and what thread 0 tells the others. */
typedef struct sweep_run {
    sweeper shared;             /* its work space is each thread's own */
    uint64_t *work;             /* 4 rows of states a thread */
    size_t width;
    int pairs;
    int changed[SWEEP_THREADS_MAX];
    int settled, stop;
    gb_progress_callback progress;
    void *progress_user;
} sweep_run;

/* Pairs of sweeps until a pair changes nothing (settled) or pairs are done. */
static void sweep_on_team(void *context, gb_thread_team *team, int thread, int thread_count)
{
    sweep_run *run = context;
    sweeper w = run->shared;
    w.face = run->work + 4 * run->width * (size_t)thread;
    w.diagonal = w.face + run->width;
    w.offered = w.diagonal + run->width;
    w.read = w.offered + run->width;
    for (int pair = 0; pair < run->pairs && !run->stop; ++pair) {
        int changed = sweep_planes(&w, 2 * (uint64_t)pair, thread, thread_count);
        gb_thread_team_wait(team);
        changed |= sweep_planes(&w, 2 * (uint64_t)pair + 1, thread, thread_count);
        run->changed[thread] = changed;
        gb_thread_team_wait(team);
        if (thread == 0) {
            int any = 0;
            for (int t = 0; t < thread_count; ++t)
                any |= run->changed[t];
            run->settled = !any;
            run->stop = run->settled ||
                        (run->progress && run->progress(run->progress_user,
                                                        (pair + 1.0) / (run->pairs + 1.0)));
        }
        gb_thread_team_wait(team);
    }
}

/* Sweeps until a forward and backward pair changes nothing (*settled = 1),
 * or gives up after pairs pairs (*settled = 0), on threads. */
static gb_result sweep_to_fixed_point(geodesic *g, int pairs, int threads, int *settled,
                                      gb_progress_callback progress, void *progress_user,
                                      gb_error *error)
{
    *settled = 0;
    const gb_cubical_complex *c = g->complex;
    size_t rows = (size_t)c->size[1] * (size_t)c->size[2];
    int32_t planes = c->size[2] > 3 ? c->size[2] - 3 : 0;
    threads = threads < 1 ? 1 : threads > SWEEP_THREADS_MAX ? SWEEP_THREADS_MAX : threads;
    threads = threads > planes ? (planes > 1 ? planes : 1) : threads;
    sweep_run run = {.shared.g = g, .width = (size_t)c->size[0], .pairs = pairs,
                     .progress = progress, .progress_user = progress_user};
    /* one allocation, zeroed: changed, swept forward and backward, the
     * planes' words, then the threads' work rows */
    run.shared.changed = calloc(3 * rows + (size_t)planes + 4 * run.width * (size_t)threads,
                                sizeof *run.shared.changed);
    if (!run.shared.changed)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "nearest node: out of memory");
    run.shared.swept[0] = run.shared.changed + rows;
    run.shared.swept[1] = run.shared.changed + 2 * rows;
    run.shared.plane_done = run.shared.changed + 3 * rows;
    run.work = run.shared.plane_done + planes;
    for (size_t row = 0; row < rows; ++row)
        run.shared.changed[row] = 1; /* the seeds */
    gb_thread_team_run(sweep_on_team, &run, threads);
    free(run.shared.changed);
    *settled = run.settled;
    if (run.stop && !run.settled)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    return GB_OK;
}

static void seed_states(geodesic *g, const uint32_t *node_cells, uint32_t node_count)
{
    const size_t *step = g->complex->step;
    for (uint32_t n = 0; n < node_count; ++n)
        for (int d = 0; d < 8; ++d) {
            size_t cell = node_cells[n] - ((d & 1) ? step[0] : 0) -
                          ((d & 2) ? step[1] : 0) - ((d & 4) ? step[2] : 0);
            uint64_t seed = state_of(SEED_LENGTH, n), held = state_at(g, cell);
            if (held != BLOCKED && seed < held)
                set_state(g, cell, seed);
        }
}

/* ---- Dijkstra in a slab ---- */

static gb_result reach(slab *s, size_t cell, uint64_t state)
{
    if (state >= state_at(s->g, cell))
        return GB_OK;
    set_state(s->g, cell, state);
    ++s->queued;
    return gb_cell_list_push(&s->buckets[distance_of(state) % BUCKETS], cell, &s->error);
}

static gb_result settle(slab *s, size_t cell)
{
    const geodesic *g = s->g;
    uint64_t state = state_at(g, cell);
    for (int n = 0; n < 26; ++n) {
        size_t neighbour = (size_t)((ptrdiff_t)cell + g->offsets[n]);
        gb_result result = neighbour >= s->begin && neighbour < s->end
                               ? reach(s, neighbour, state + g->lengths[n])
                               : push_arrival(&s->outbox, neighbour, state + g->lengths[n],
                                              &s->error);
        if (result)
            return result;
    }
    return GB_OK;
}

static gb_result report(slab *s)
{
    if ((++s->settled & 0xffff) || !s->progress)
        return GB_OK;
    double fraction = (double)s->settled / (double)(s->empty_count + 1);
    if (s->progress(s->progress_user, fraction < 1.0 ? fraction : 1.0))
        return gb_fail(&s->error, GB_ERROR_INTERRUPTED, "interrupted");
    return GB_OK;
}

/* Dial's algorithm: buckets by distance, modulo BUCKETS. The inbox (sorted)
 * is fed in as the distance comes near, so that every queued distance lies
 * within BUCKETS of the current one. An entry whose cell has since been
 * reached by a shorter path is stale and skipped. */
static gb_result propagate(slab *s)
{
    const arrivals *inbox = &s->inbox;
    size_t next = 0;
    uint32_t distance = 0;
    for (;;) {
        if (!s->queued) {
            if (next == inbox->count)
                return GB_OK;
            distance = distance_of(inbox->items[next].state);
        }
        for (; next < inbox->count &&
               distance_of(inbox->items[next].state) < distance + (BUCKETS - LONGEST_STEP);
             ++next)
            if (reach(s, (size_t)inbox->items[next].cell, inbox->items[next].state))
                return GB_ERROR_OUT_OF_MEMORY;
        gb_cell_list *bucket = &s->buckets[distance % BUCKETS];
        for (size_t n = 0; n < bucket->count; ++n) {
            size_t cell = bucket->items[n];
            --s->queued;
            if (distance_of(state_at(s->g, cell)) != distance)
                continue;
            gb_result result = settle(s, cell);
            if (!result)
                result = report(s);
            if (result)
                return result;
        }
        bucket->count = 0;
        ++distance;
    }
}

/* Thread t runs slab t's Dijkstra (gb_run_threads). */
static void propagate_slab(void *slabs, int t, int thread_count)
{
    (void)thread_count;
    slab *s = &((slab *)slabs)[t];
    s->result = propagate(s);
}

/* ---- slabs and rounds ---- */

/* Cuts the lattice into count slabs of about the same number of empty
 * voxels, along z; returns how many slabs it made (at least 1). */
static int cut_slabs(geodesic *g, slab *slabs, int count)
{
    const gb_cubical_complex *c = g->complex;
    size_t layer = c->step[2], total = 0;
    size_t *empty = calloc((size_t)c->size[2], sizeof *empty);
    if (!empty)
        count = 1;
    for (int32_t z = 0; empty && z < c->size[2]; ++z) {
        for (size_t cell = (size_t)z * layer; cell < (size_t)(z + 1) * layer; ++cell)
            empty[z] += state_at(g, cell) != BLOCKED;
        total += empty[z];
    }
    int made = 0;
    size_t begin = 0, sum = 0;
    for (int32_t z = 0; z < c->size[2] && made < count - 1 && empty; ++z) {
        sum += empty[z];
        if (sum * (size_t)count >= total * (size_t)(made + 1) && sum > 0) {
            slabs[made].begin = begin;
            slabs[made].end = begin = (size_t)(z + 1) * layer;
            ++made;
        }
    }
    slabs[made].begin = begin;
    slabs[made].end = c->cell_count;
    free(empty);
    return made + 1;
}

static size_t owner_of(const slab *slabs, int count, size_t cell)
{
    int s = 0;
    while (s < count - 1 && cell >= slabs[s].end)
        ++s;
    return (size_t)s;
}

/* Every node starts in the empty voxels around its corner. */
static gb_result seed_nodes(slab *slabs, int count, const uint32_t *node_cells,
                            uint32_t node_count, gb_error *error)
{
    const size_t *step = slabs[0].g->complex->step;
    for (uint32_t n = 0; n < node_count; ++n)
        for (int d = 0; d < 8; ++d) {
            size_t cell = node_cells[n] - ((d & 1) ? step[0] : 0) -
                          ((d & 2) ? step[1] : 0) - ((d & 4) ? step[2] : 0);
            slab *s = &slabs[owner_of(slabs, count, cell)];
            if (push_arrival(&s->inbox, cell, state_of(SEED_LENGTH, n), error))
                return GB_ERROR_OUT_OF_MEMORY;
        }
    return GB_OK;
}

/* Runs every slab's Dijkstra, one thread a slab, the first on this one. */
static gb_result run_slabs(slab *slabs, int count, gb_error *error)
{
    gb_run_threads(propagate_slab, slabs, count);
    for (int s = 0; s < count; ++s)
        if (slabs[s].result) {
            *error = slabs[s].error;
            return slabs[s].result;
        }
    return GB_OK;
}

/* Moves every outbox into the inbox of the slab its cells belong to; *moved
 * tells whether anything moved. */
static gb_result exchange(slab *slabs, int count, int *moved, gb_error *error)
{
    *moved = 0;
    for (int s = 0; s < count; ++s)
        slabs[s].inbox.count = 0;
    for (int s = 0; s < count; ++s) {
        arrivals *out = &slabs[s].outbox;
        for (size_t n = 0; n < out->count; ++n) {
            slab *to = &slabs[owner_of(slabs, count, (size_t)out->items[n].cell)];
            if (push_arrival(&to->inbox, (size_t)out->items[n].cell, out->items[n].state, error))
                return GB_ERROR_OUT_OF_MEMORY;
            *moved = 1;
        }
        out->count = 0;
    }
    return GB_OK;
}

/* A non-empty voxel: the best (distance + step, node) of its empty neighbours. */
static int32_t node_from_neighbours(const geodesic *g, size_t cell)
{
    uint64_t best = UNREACHED;
    for (int n = 0; n < 26; ++n) {
        uint64_t state = state_at(g, (size_t)((ptrdiff_t)cell + g->offsets[n]));
        if (state != BLOCKED && state != UNREACHED && state + g->lengths[n] < best)
            best = state + g->lengths[n];
    }
    return best == UNREACHED ? -1 : node_of(best);
}

/* Writes the node of every voxel, in grid order, over the state array
 * itself: voxel v's int32 goes to bytes 4v..4v+3 once its states are read,
 * while the states still to be read (of later voxels' cells and their
 * neighbours, cells above v) start at byte 6(v + 1) or later, so nothing
 * is overwritten before it is read. Returns the array shrunk to the
 * voxels. */
static int32_t *write_nodes_in_place(geodesic *g, const gb_voxel_grid *grid)
{
    int32_t *nearest = (int32_t *)(void *)g->state;
    size_t v = 0;
    for (int32_t k = 0; k < grid->size[2]; ++k)
        for (int32_t j = 0; j < grid->size[1]; ++j)
            for (int32_t i = 0; i < grid->size[0]; ++i, ++v) {
                size_t cell = gb_voxel_cell(g->complex, i, j, k);
                uint64_t state = state_at(g, cell);
                nearest[v] = state == BLOCKED ? node_from_neighbours(g, cell)
                             : state == UNREACHED ? -1 : node_of(state);
            }
    g->state = NULL;
    int32_t *shrunk = realloc(nearest, (v ? v : 1) * sizeof *nearest);
    return shrunk ? shrunk : nearest;
}

static void free_slab(slab *s)
{
    for (int b = 0; b < BUCKETS; ++b)
        gb_cell_list_free(&s->buckets[b]);
    free(s->inbox.items);
    free(s->outbox.items);
}

/* Dijkstra's algorithm on count slabs, from the nodes; cells must be fresh
 * (BLOCKED or UNREACHED). */
static gb_result dijkstra(geodesic *g, int threads, const uint32_t *node_cells,
                          uint32_t node_count, size_t empty_count,
                          gb_progress_callback progress, void *progress_user, gb_error *error)
{
    slab *slabs = calloc(MAX_SLABS, sizeof *slabs);
    if (!slabs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "nearest node: out of memory");
    int count = cut_slabs(g, slabs, threads < 1 ? 1 : threads > MAX_SLABS ? MAX_SLABS : threads);
    for (int s = 0; s < count; ++s)
        slabs[s].g = g;
    slabs[0].progress = progress;
    slabs[0].progress_user = progress_user;
    slabs[0].empty_count = empty_count / (size_t)count;
    gb_result result = seed_nodes(slabs, count, node_cells, node_count, error);
    for (int moved = 1; !result && moved;) {
        for (int s = 0; s < count; ++s)
            if (slabs[s].inbox.count > 1)
                qsort(slabs[s].inbox.items, slabs[s].inbox.count, sizeof(arrival),
                      compare_arrivals);
        result = run_slabs(slabs, count, error);
        slabs[0].progress = NULL; /* later rounds are short */
        if (!result)
            result = exchange(slabs, count, &moved, error);
    }
    for (int s = 0; s < count; ++s)
        free_slab(&slabs[s]);
    free(slabs);
    return result;
}

gb_result gb_nearest_node(const gb_voxel_grid *grid, const gb_empty_voxels *empty,
                          const gb_cubical_complex *complex,
                          const uint32_t *node_cells, uint32_t node_count,
                          const gb_nearest_options *options, int32_t **nearest,
                          gb_error *error)
{
    int threads = options->threads;
    gb_progress_callback progress = options->progress;
    void *progress_user = options->progress_user;
    *nearest = NULL;
    if (node_count >= MAX_NODES)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "nearest node: %u skeleton nodes, at most %u", node_count,
                       MAX_NODES - 1);
    geodesic g = {.complex = complex};
    g.state = malloc(STATE_BYTES * complex->cell_count);
    gb_advise_huge_pages(g.state, STATE_BYTES * complex->cell_count);
    if (!g.state)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "nearest node: out of memory for %zu cells", complex->cell_count);
    neighbour_steps(&g);
    mark_empty_cells(&g, grid, empty);
    seed_states(&g, node_cells, node_count);
    int settled = 0;
    gb_result result = sweep_to_fixed_point(&g, options->sweep_pairs, threads, &settled,
                                            progress, progress_user, error);
    if (!result && !settled) {
        size_t empty_count = mark_empty_cells(&g, grid, empty);
        result = dijkstra(&g, threads, node_cells, node_count, empty_count, progress,
                          progress_user, error);
    }
    if (!result)
        *nearest = write_nodes_in_place(&g, grid);
    free(g.state);
    return result;
}
