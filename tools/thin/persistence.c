/* persistence.c — the maps (filled by chessboard_maps.c), the births of
 * the isthmus edges and their lifespan test (see persistence.h). */
#include "persistence.h"

#include <stdlib.h>
#include <string.h>

#include "chessboard_maps.h"
#include "huge_pages.h"

gb_result gb_persistence_init(gb_persistence *persistence, const gb_cubical_complex *complex,
                              double scale, double min_lifespan, int thread_count,
                              gb_progress_callback progress, void *progress_user,
                              gb_error *error)
{
    memset(persistence, 0, sizeof *persistence);
    persistence->persistence = scale;
    persistence->min_lifespan = min_lifespan;
    size_t cells = complex->cell_count;
    /* A chessboard distance or opening above GB_CHESSBOARD_FAR - 1 needs a
     * cube of that radius inside the lattice: refused, not saturated. */
    int smallest = complex->size[0];
    for (int axis = 1; axis < 3; ++axis)
        smallest = complex->size[axis] < smallest ? complex->size[axis] : smallest;
    if (smallest > 2 * (GB_CHESSBOARD_FAR - 1))
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "persistence: every side above %d voxels (the maps hold 12 bits)",
                       2 * (GB_CHESSBOARD_FAR - 1));
    persistence->maps = malloc(GB_CHESSBOARD_MAP_BYTES * cells);
    gb_advise_huge_pages(persistence->maps, GB_CHESSBOARD_MAP_BYTES * cells);
    gb_result result = GB_OK;
    if (!persistence->maps)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                         "persistence: out of memory for %zu cells", cells);
    if (!result)
        result = gb_chessboard_maps(complex, persistence->maps, thread_count, progress,
                                    progress_user, error);
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
