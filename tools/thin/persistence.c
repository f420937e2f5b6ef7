/* persistence.c — the chessboard distance and opening maps of the empty
 * space, and the lifespan test of an isthmus edge (see persistence.h). */
#include "persistence.h"

#include <stdlib.h>
#include <string.h>

#include "cell_list.h"

enum { FAR = UINT16_MAX };

/* The two maps share one array: distance in the low 16 bits of a cell's
 * word, opening in the high 16 bits. */
static uint16_t distance_at(const uint32_t *maps, size_t cell)
{
    return (uint16_t)(maps[cell] & 0xffff);
}

static void set_distance(uint32_t *maps, size_t cell, uint16_t distance)
{
    maps[cell] = (maps[cell] & 0xffff0000u) | distance;
}

static uint16_t opening_at(const uint32_t *maps, size_t cell)
{
    return (uint16_t)(maps[cell] >> 16);
}

static void set_opening(uint32_t *maps, size_t cell, uint16_t opening)
{
    maps[cell] = (maps[cell] & 0xffffu) | (uint32_t)opening << 16;
}

/* Index offsets of the 26 neighbours of a cell; the first 13 come before it
 * in index order, the last 13 after, in mirror order. */
static void neighbour_offsets(const gb_cubical_complex *complex, ptrdiff_t offsets[26])
{
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (dx || dy || dz)
                    offsets[n++] = dx + dy * (ptrdiff_t)complex->step[1] +
                                   dz * (ptrdiff_t)complex->step[2];
}

static uint16_t min_plus_one(const uint32_t *maps, size_t cell, const ptrdiff_t *offsets,
                             uint16_t value)
{
    for (int n = 0; n < 13; ++n) {
        uint16_t neighbour = distance_at(maps, (size_t)((ptrdiff_t)cell + offsets[n]));
        if (neighbour < value - 1)
            value = (uint16_t)(neighbour + 1);
    }
    return value;
}

/* Two raster passes of the 3x3x3 unit mask: exact for the chessboard metric.
 * Openings start at 0. */
static void chessboard_distance(const gb_cubical_complex *complex, uint32_t *maps)
{
    ptrdiff_t offsets[26];
    neighbour_offsets(complex, offsets);
    for (size_t cell = 0; cell < complex->cell_count; ++cell)
        maps[cell] = (complex->faces[cell] & GB_FACE_CUBE) ? FAR : 0;
    size_t first = complex->step[0] + complex->step[1] + complex->step[2];
    size_t last = complex->cell_count - first;
    for (size_t cell = first; cell < last; ++cell)
        if (maps[cell])
            set_distance(maps, cell, min_plus_one(maps, cell, offsets, distance_at(maps, cell)));
    for (size_t cell = last; cell-- > first;)
        if (maps[cell])
            set_distance(maps, cell,
                         min_plus_one(maps, cell, offsets + 13, distance_at(maps, cell)));
}

/* A cell next to one of distance + 1 lies in that cell's larger ball: only
 * the others (the ridge of the distance map) can start a ball of their own. */
static int on_ridge(const uint32_t *maps, size_t cell, const ptrdiff_t offsets[26])
{
    uint16_t above = (uint16_t)(distance_at(maps, cell) + 1);
    for (int n = 0; n < 26; ++n)
        if (distance_at(maps, (size_t)((ptrdiff_t)cell + offsets[n])) == above)
            return 0;
    return 1;
}

/* The ridge cells, by decreasing distance (counting sort). */
static gb_result ridge_by_distance(const gb_cubical_complex *complex, const uint32_t *maps,
                                   uint16_t largest, gb_cell_list *sorted, gb_error *error)
{
    ptrdiff_t offsets[26];
    neighbour_offsets(complex, offsets);
    gb_cell_list ridge = {0};
    gb_result result = GB_OK;
    for (size_t cell = 0; cell < complex->cell_count && !result; ++cell)
        if (distance_at(maps, cell) && on_ridge(maps, cell, offsets))
            result = gb_cell_list_push(&ridge, cell, error);
    size_t *start = calloc((size_t)largest + 2, sizeof *start);
    if (!result && !start)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "opening: out of memory");
    while (!result && sorted->capacity < ridge.count)
        result = gb_cell_list_grow(sorted, error);
    if (!result) {
        for (size_t n = 0; n < ridge.count; ++n)
            ++start[largest - distance_at(maps, ridge.items[n]) + 1];
        for (size_t level = 1; level <= (size_t)largest + 1; ++level)
            start[level] += start[level - 1];
        for (size_t n = 0; n < ridge.count; ++n)
            sorted->items[start[largest - distance_at(maps, ridge.items[n])]++] = ridge.items[n];
        sorted->count = ridge.count;
    }
    free(start);
    gb_cell_list_free(&ridge);
    return result;
}

typedef struct opening_front {
    uint32_t *maps;
    uint16_t *reach;            /* 1 + largest ball reach that went through the cell */
    ptrdiff_t offsets[26];
    gb_cell_list now, next;
} opening_front;

/* Breadth-first spread of the balls of radius level from the cells in
 * front->now: a cell is passed on while its remaining reach beats the best
 * reach that went through it before (from a larger or equal ball). */
static gb_result spread_balls(opening_front *front, uint16_t level, gb_error *error)
{
    while (front->now.count) {
        front->next.count = 0;
        for (size_t n = 0; n < front->now.count; ++n) {
            size_t cell = front->now.items[n];
            uint16_t reach = (uint16_t)(front->reach[cell] - 1);
            if (!reach)
                continue;
            for (int k = 0; k < 26; ++k) {
                size_t neighbour = (size_t)((ptrdiff_t)cell + front->offsets[k]);
                if (front->reach[neighbour] >= reach || !distance_at(front->maps, neighbour))
                    continue;
                front->reach[neighbour] = reach;
                if (!opening_at(front->maps, neighbour))
                    set_opening(front->maps, neighbour, level);
                if (gb_cell_list_push(&front->next, neighbour, error))
                    return GB_ERROR_OUT_OF_MEMORY;
            }
        }
        gb_cell_list swap = front->now;
        front->now = front->next;
        front->next = swap;
    }
    return GB_OK;
}

/* opening(x) = max { distance(y) : chessboard |x - y| < distance(y) }: balls
 * are spread from their centres by decreasing radius, so the first ball to
 * reach a cell is its largest; a ball is spread only where it reaches
 * farther than the larger ones before it. */
static gb_result chessboard_opening(const gb_cubical_complex *complex, uint32_t *maps,
                                    uint16_t largest, gb_progress_callback progress,
                                    void *progress_user, gb_error *error)
{
    gb_cell_list sorted = {0};
    gb_result result = ridge_by_distance(complex, maps, largest, &sorted, error);
    opening_front front = {.maps = maps};
    neighbour_offsets(complex, front.offsets);
    front.reach = result ? NULL : calloc(complex->cell_count, sizeof *front.reach);
    if (!result && !front.reach)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "opening: out of memory");
    size_t n = 0;
    while (n < sorted.count && !result) {
        uint16_t level = distance_at(maps, sorted.items[n]);
        front.now.count = 0;
        for (; n < sorted.count && distance_at(maps, sorted.items[n]) == level && !result; ++n) {
            uint32_t cell = sorted.items[n];
            if (front.reach[cell] >= level)
                continue;
            front.reach[cell] = level;
            if (!opening_at(maps, cell))
                set_opening(maps, cell, level);
            result = gb_cell_list_push(&front.now, cell, error);
        }
        if (!result)
            result = spread_balls(&front, level, error);
        if (!result && progress &&
            progress(progress_user, 0.5 + 0.5 * (double)n / (double)sorted.count))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    }
    gb_cell_list_free(&front.now);
    gb_cell_list_free(&front.next);
    gb_cell_list_free(&sorted);
    free(front.reach);
    return result;
}

static uint16_t largest_distance(const uint32_t *maps, size_t count)
{
    uint16_t largest = 0;
    for (size_t n = 0; n < count; ++n)
        if (distance_at(maps, n) > largest)
            largest = distance_at(maps, n);
    return largest;
}

gb_result gb_persistence_init(gb_persistence *persistence, const gb_cubical_complex *complex,
                              double scale, double min_lifespan,
                              gb_progress_callback progress, void *progress_user,
                              gb_error *error)
{
    memset(persistence, 0, sizeof *persistence);
    persistence->persistence = scale;
    persistence->min_lifespan = min_lifespan;
    size_t cells = complex->cell_count;
    persistence->maps = malloc(cells * sizeof *persistence->maps);
    gb_result result = GB_OK;
    if (!persistence->maps)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                         "persistence: out of memory for %zu cells", cells);
    if (!result) {
        chessboard_distance(complex, persistence->maps);
        persistence->largest_distance = largest_distance(persistence->maps, cells);
        if (progress && progress(progress_user, 0.5))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    }
    if (!result)
        result = chessboard_opening(complex, persistence->maps, persistence->largest_distance,
                                    progress, progress_user, error);
    if (result)
        gb_persistence_free(persistence);
    return result;
}

void gb_persistence_free(gb_persistence *persistence)
{
    if (!persistence)
        return;
    free(persistence->maps);
    free(persistence->birth_keys);
    free(persistence->births);
    memset(persistence, 0, sizeof *persistence);
}

/* persistence * (opening - distance) + min_lifespan for the edge, with the
 * maxima of the two maps over the 4 cubes around it: cells cell - b - c for
 * b, c in {0, 1} steps along the two other axes. */
static double lifespan_threshold(const gb_persistence *persistence,
                                 const gb_cubical_complex *complex, size_t cell, int axis)
{
    size_t b = complex->step[(axis + 1) % 3], c = complex->step[(axis + 2) % 3];
    size_t around[4] = {cell, cell - b, cell - c, cell - b - c};
    uint16_t distance = 0, opening = 0;
    for (int n = 0; n < 4; ++n) {
        uint16_t d = gb_persistence_distance(persistence, around[n]);
        uint16_t o = gb_persistence_opening(persistence, around[n]);
        distance = d > distance ? d : distance;
        opening = o > opening ? o : opening;
    }
    return persistence->persistence * ((double)opening - (double)distance) +
           persistence->min_lifespan;
}

/* ---- the birth table ---- */

static size_t slot_of(uint64_t key, size_t capacity)
{
    return (size_t)((key * 0x9e3779b97f4a7c15ull) >> 17) & (capacity - 1);
}

/* The slot holding key, or the free slot where it would go. */
static size_t find_slot(const gb_persistence *p, uint64_t key)
{
    size_t slot = slot_of(key, p->birth_capacity);
    while (p->birth_keys[slot] && p->birth_keys[slot] != key)
        slot = (slot + 1) & (p->birth_capacity - 1);
    return slot;
}

static gb_result grow_births(gb_persistence *p, gb_error *error)
{
    size_t capacity = p->birth_capacity ? 2 * p->birth_capacity : 4096;
    uint64_t *keys = calloc(capacity, sizeof *keys);
    uint32_t *births = malloc(capacity * sizeof *births);
    if (!keys || !births) {
        free(keys);
        free(births);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "persistence: out of memory");
    }
    gb_persistence grown = *p;
    grown.birth_keys = keys;
    grown.births = births;
    grown.birth_capacity = capacity;
    for (size_t n = 0; n < p->birth_capacity; ++n)
        if (p->birth_keys[n]) {
            size_t slot = find_slot(&grown, p->birth_keys[n]);
            keys[slot] = p->birth_keys[n];
            births[slot] = p->births[n];
        }
    free(p->birth_keys);
    free(p->births);
    p->birth_keys = keys;
    p->births = births;
    p->birth_capacity = capacity;
    return GB_OK;
}

gb_result gb_persistence_record_birth(gb_persistence *persistence, size_t cell, int axis,
                                      uint32_t iteration, gb_error *error)
{
    if (2 * (persistence->birth_count + 1) > persistence->birth_capacity &&
        grow_births(persistence, error))
        return GB_ERROR_OUT_OF_MEMORY;
    uint64_t key = 1 + 3 * (uint64_t)cell + (uint64_t)axis;
    size_t slot = find_slot(persistence, key);
    if (!persistence->birth_keys[slot]) {
        persistence->birth_keys[slot] = key;
        persistence->births[slot] = iteration;
        ++persistence->birth_count;
    }
    return GB_OK;
}

int gb_persistence_is_protected(const gb_persistence *persistence,
                                const gb_cubical_complex *complex, size_t cell, int axis,
                                uint32_t iteration)
{
    if (!persistence->birth_capacity)
        return 0;
    size_t slot = find_slot(persistence, 1 + 3 * (uint64_t)cell + (uint64_t)axis);
    if (!persistence->birth_keys[slot] || persistence->births[slot] >= iteration)
        return 0;
    double lifespan = (double)iteration - (double)persistence->births[slot];
    return lifespan > lifespan_threshold(persistence, complex, cell, axis);
}
