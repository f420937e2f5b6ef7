/* persistence.c — the chessboard distance and opening maps of the empty
 * space, and the lifespan test of an isthmus edge (see persistence.h). */
#include "persistence.h"

#include <stdlib.h>
#include <string.h>


/* Writing the maps of a cell (persistence.h: 12 bits each in 3 bytes;
 * gb_map_distance and gb_map_opening read them). */
static void set_opening(unsigned char *maps, size_t cell, uint16_t opening)
{
    unsigned char *at = maps + GB_PERSISTENCE_MAP_BYTES * cell;
    at[1] = (unsigned char)((at[1] & 0x0f) | (opening & 0x0f) << 4);
    at[2] = (unsigned char)(opening >> 4);
}

/* The chessboard distance (persistence.h), by the two raster passes of the
 * 3x3x3 unit mask, exact for that metric: forward, a cube takes the least
 * of its 13 earlier neighbours plus one (the 9 of the plane before, the 3
 * of the row before, the cell before); backward, the same with the 13
 * later ones. Other cells are 0. The passes run a plane at a time in
 * 16-bit buffers: the 12 neighbours of the rows beside a row are taken for
 * the whole row at once (the least of 4 rows, then of 3 columns), only the
 * cell before it in the row in order. Cubes lie at least a cell inside the
 * lattice on every axis, so the edge rows and columns stay 0. */
typedef struct distance_planes {
    int32_t width, height;      /* of a plane: the lattice's x and y sizes */
    uint16_t *done;             /* the plane the pass left: before (forward) or after */
    uint16_t *plane;            /* the plane of the pass */
    uint16_t *least;            /* a row: the least of the 4 rows beside it */
} distance_planes;

/* The row's cells from the least of the 12 neighbours beside it and the
 * cell before it in the pass's order (direction +1 or -1 along x). */
static void distance_row(distance_planes *p, int32_t y, int direction)
{
    int32_t w = p->width;
    const uint16_t *done = p->done + (size_t)y * w, *beside = p->plane + (size_t)(y - direction) * w;
    uint16_t *row = p->plane + (size_t)y * w, *least = p->least;
    for (int32_t x = 0; x < w; ++x) {
        uint16_t a = done[x - w] < done[x] ? done[x - w] : done[x];
        uint16_t b = done[x + w] < beside[x] ? done[x + w] : beside[x];
        least[x] = a < b ? a : b;
    }
    int32_t first = direction > 0 ? 1 : w - 2, end = direction > 0 ? w - 1 : 0;
    for (int32_t x = first; x != end; x += direction) {
        if (!row[x])
            continue;
        uint16_t value = row[x];
        uint16_t around = least[x - 1] < least[x] ? least[x - 1] : least[x];
        around = least[x + 1] < around ? least[x + 1] : around;
        around = row[x - direction] < around ? row[x - direction] : around;
        row[x] = (uint16_t)(around + 1) < value ? (uint16_t)(around + 1) : value;
    }
}

static void distance_plane(distance_planes *p, int direction)
{
    int32_t first = direction > 0 ? 1 : p->height - 2, end = direction > 0 ? p->height - 1 : 0;
    for (int32_t y = first; y != end; y += direction)
        distance_row(p, y, direction);
}

/* A plane's distances written with openings 0 (all 3 bytes of each cell). */
static void write_distances(unsigned char *maps, size_t first_cell, const uint16_t *plane,
                            size_t count)
{
    unsigned char *at = maps + GB_PERSISTENCE_MAP_BYTES * first_cell;
    for (size_t n = 0; n < count; ++n, at += GB_PERSISTENCE_MAP_BYTES) {
        at[0] = (unsigned char)plane[n];
        at[1] = (unsigned char)(plane[n] >> 8);
        at[2] = 0;
    }
}

static gb_result chessboard_distance(const gb_cubical_complex *complex, unsigned char *maps,
                                     gb_error *error)
{
    distance_planes p = {.width = complex->size[0], .height = complex->size[1]};
    size_t plane_cells = complex->step[2];
    uint16_t *storage = calloc(2 * plane_cells + (size_t)p.width, sizeof *storage);
    if (!storage)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "persistence: out of memory");
    p.done = storage;
    p.plane = storage + plane_cells;
    p.least = storage + 2 * plane_cells;
    for (int32_t z = 0; z < complex->size[2]; ++z) {
        const uint8_t *faces = complex->faces + plane_cells * (size_t)z;
        for (size_t n = 0; n < plane_cells; ++n)
            p.plane[n] = faces[n] & GB_FACE_CUBE ? GB_PERSISTENCE_FAR : 0;
        distance_plane(&p, +1);
        write_distances(maps, plane_cells * (size_t)z, p.plane, plane_cells);
        uint16_t *swap = p.done;
        p.done = p.plane;
        p.plane = swap;
    }
    memset(p.done, 0, plane_cells * sizeof *p.done);
    for (int32_t z = complex->size[2]; z-- > 0;) {
        size_t first_cell = plane_cells * (size_t)z;
        for (size_t n = 0; n < plane_cells; ++n)
            p.plane[n] = gb_map_distance(maps, first_cell + n);
        distance_plane(&p, -1);
        write_distances(maps, first_cell, p.plane, plane_cells);
        uint16_t *swap = p.done;
        p.done = p.plane;
        p.plane = swap;
    }
    free(storage);
    return GB_OK;
}

/* Chessboard balls are cubes, so opening(x) = max { distance(y) : |x - y|
 * < distance(y) along each axis } is separable: the max over x's line of
 * the line maxima over its plane. Each pass takes, along one axis,
 * out(i) = max { in(j) : in(j) > |i - j| } of the previous pass's values
 * (the distances first): a value that passes carries its source's own
 * distance, and a larger value passes wherever a smaller one does, so the
 * maximum of each pass is all the next one needs. */

/* Lines of the y and z passes are taken BUNDLE at a time, adjacent in x,
 * so that each read of the maps uses whole cache lines. */
enum { BUNDLE = 16 };

/* Work space of one line of length n: the line read, the line written and
 * the candidates of one sweep. */
typedef struct opening_line {
    uint16_t *in, *out;     /* BUNDLE * n each, line b at b * n */
    uint16_t *value;        /* candidates: their values, decreasing, */
    int32_t *end;           /* the last index each reaches, increasing */
} opening_line;

/* out[i] = max(out[i], max { in[j] : j before i, in[j] > |i - j| }) where
 * "before" is in the order of step (+1 or -1). Sources join the queue of
 * candidates at its tail. A new source reaches farther than every older
 * one of a value no larger than its own, which it replaces; it is not
 * queued when the larger one before it reaches as far. So the values
 * decrease and the reaches grow along the queue, and its head is the
 * largest value still reaching i. */
static void sweep(const uint16_t *in, uint16_t *out, int n, int step, opening_line *space)
{
    int head = 0, tail = 0;
    for (int t = 0; t < n; ++t) {
        int i = step > 0 ? t : n - 1 - t;
        if (in[i]) {
            while (tail > head && space->value[tail - 1] <= in[i])
                --tail;
            int32_t end = t + in[i] - 1;
            if (tail == head || space->end[tail - 1] < end) {
                space->value[tail] = in[i];
                space->end[tail++] = end;
            }
        }
        while (head < tail && space->end[head] < t)
            ++head;
        if (head < tail && space->value[head] > out[i])
            out[i] = space->value[head];
    }
}

/* The opening pass along axis: reads the distances (first pass) or the
 * openings so far, writes the openings. */
static void opening_pass(const gb_cubical_complex *complex, unsigned char *maps, int axis,
                         opening_line *space)
{
    int n = complex->size[axis];
    int width_axis = axis == 0 ? 1 : 0, other_axis = axis == 2 ? 1 : 2;
    int bundle = axis == 0 ? 1 : BUNDLE;
    size_t stride = complex->step[axis];
    for (int32_t other = 0; other < complex->size[other_axis]; ++other)
        for (int32_t first = 0; first < complex->size[width_axis]; first += bundle) {
            int width = complex->size[width_axis] - first < bundle
                            ? complex->size[width_axis] - first : bundle;
            size_t base = complex->step[other_axis] * (size_t)other +
                          complex->step[width_axis] * (size_t)first;
            for (int p = 0; p < n; ++p)
                for (int b = 0; b < width; ++b) {
                    size_t cell = base + p * stride + b * complex->step[width_axis];
                    space->in[b * n + p] = axis == 0 ? gb_map_distance(maps, cell)
                                                     : gb_map_opening(maps, cell);
                }
            memset(space->out, 0, (size_t)width * n * sizeof *space->out);
            for (int b = 0; b < width; ++b) {
                sweep(space->in + b * n, space->out + b * n, n, +1, space);
                sweep(space->in + b * n, space->out + b * n, n, -1, space);
            }
            for (int p = 0; p < n; ++p)
                for (int b = 0; b < width; ++b)
                    set_opening(maps, base + p * stride + b * complex->step[width_axis],
                                space->out[b * n + p]);
        }
}

/* Three passes, x then y then z, after the distance map. */
static gb_result chessboard_opening(const gb_cubical_complex *complex, unsigned char *maps,
                                    gb_progress_callback progress, void *progress_user,
                                    gb_error *error)
{
    int longest = complex->size[0];
    for (int axis = 1; axis < 3; ++axis)
        longest = complex->size[axis] > longest ? complex->size[axis] : longest;
    /* one allocation: the 4-byte ends first, then the 2-byte lines and values */
    size_t n = (size_t)longest;
    int32_t *storage = malloc(n * (sizeof(int32_t) + (2 * BUNDLE + 1) * sizeof(uint16_t)));
    opening_line space = {0};
    gb_result result = GB_OK;
    if (!storage) {
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "opening: out of memory");
    } else {
        space.end = storage;
        space.in = (uint16_t *)(void *)(storage + n);
        space.out = space.in + BUNDLE * n;
        space.value = space.out + BUNDLE * n;
    }
    for (int axis = 0; axis < 3 && !result; ++axis) {
        opening_pass(complex, maps, axis, &space);
        if (progress && progress(progress_user, 0.5 + (axis + 1) / 6.0))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    }
    free(storage);
    return result;
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
    /* A chessboard distance or opening above GB_PERSISTENCE_FAR - 1 needs a
     * cube of that radius inside the lattice: refused, not saturated. */
    int smallest = complex->size[0];
    for (int axis = 1; axis < 3; ++axis)
        smallest = complex->size[axis] < smallest ? complex->size[axis] : smallest;
    if (smallest > 2 * (GB_PERSISTENCE_FAR - 1))
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "persistence: every side above %d voxels (the maps hold 12 bits)",
                       2 * (GB_PERSISTENCE_FAR - 1));
    persistence->maps = malloc(GB_PERSISTENCE_MAP_BYTES * cells);
    gb_result result = GB_OK;
    if (!persistence->maps)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                         "persistence: out of memory for %zu cells", cells);
    if (!result)
        result = chessboard_distance(complex, persistence->maps, error);
    if (!result) {
        if (progress && progress(progress_user, 0.5))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    }
    if (!result)
        result = chessboard_opening(complex, persistence->maps, progress, progress_user,
                                    error);
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
