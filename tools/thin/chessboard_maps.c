/* chessboard_maps.c — the chessboard distance and opening maps (see
 * chessboard_maps.h).
 *
 * Distance: the two raster passes of the 3x3x3 unit mask, exact for the
 * chessboard metric. Forward, a cube takes the least of its 13 earlier
 * neighbours plus one (the 9 of the plane before, the 3 of the row before,
 * the cell before); backward, the same with the 13 later ones.
 *
 * Opening: chessboard balls are cubes, so opening(x) = max { distance(y) :
 * |x - y| < distance(y) along each axis } is separable: the max over x's
 * line of the line maxima over its plane. Each pass takes, along one axis,
 * out(i) = max { in(j) : in(j) > |i - j| } of the previous pass's values
 * (the distances first): a value that passes carries its source's own
 * distance, and a larger value passes wherever a smaller one does, so the
 * maximum of each pass is all the next one needs.
 *
 * The work goes a plane at a time in 16-bit buffers: the forward pass
 * writes each plane's distances to the maps; the backward pass reads them
 * back and finishes them. Then, on threads (the planes and rows shared
 * out, each thread with its own buffers), a pass takes the openings along
 * x and y of each plane, and a last one takes them along z. */
#include "chessboard_maps.h"

#include <stdlib.h>
#include <string.h>

#include "threads.h"

/* Lines of the z pass are taken BUNDLE at a time, adjacent in x, so that
 * each read of the maps uses whole cache lines. */
enum { BUNDLE = 16 };

typedef struct planes {
    int32_t width, height;      /* of a plane: the lattice's x and y sizes */
    uint16_t *done;             /* distances of the plane the pass left: the one
                                   before (forward) or after (backward) */
    uint16_t *plane;            /* distances of the plane of the pass */
    uint16_t *openings;         /* openings of the plane of the pass */
    uint16_t *least;            /* a row: the least of the 4 rows beside it */
    /* one line of the openings: the values read and written, and the
     * candidates of a sweep */
    uint16_t *in, *out;         /* BUNDLE lines each, line b at b * longest */
    uint16_t *value;            /* candidates: their values, decreasing, */
    int32_t *end;               /* the last index each reaches, increasing */
    int32_t longest;            /* the longest side of the lattice */
} planes;

/* ---- distance ---- */

/* The row's distances from the least of the 12 neighbours beside it, taken
 * for the whole row at once, and the cell before it in the pass's order
 * (direction +1 or -1 along x). Cubes lie at least a cell inside the
 * lattice on every axis, so the edge rows and columns stay 0. */
static void distance_row(planes *p, int32_t y, int direction)
{
    int32_t w = p->width;
    const uint16_t *done = p->done + (size_t)y * w;
    const uint16_t *beside = p->plane + (size_t)(y - direction) * w;
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
        uint16_t around = least[x - 1] < least[x] ? least[x - 1] : least[x];
        around = least[x + 1] < around ? least[x + 1] : around;
        around = row[x - direction] < around ? row[x - direction] : around;
        if (around + 1 < row[x])
            row[x] = (uint16_t)(around + 1);
    }
}

static void distance_plane(planes *p, int direction)
{
    int32_t first = direction > 0 ? 1 : p->height - 2, end = direction > 0 ? p->height - 1 : 0;
    for (int32_t y = first; y != end; y += direction)
        distance_row(p, y, direction);
}

static void next_plane(planes *p)
{
    uint16_t *swap = p->done;
    p->done = p->plane;
    p->plane = swap;
}

/* ---- opening ---- */

/* out[i] = max(out[i], max { in[j] : j before i, in[j] > |i - j| }) where
 * "before" is in the order of step (+1 or -1). Sources join the queue of
 * candidates at its tail. A new source reaches farther than every older
 * one of a value no larger than its own, which it replaces; it is not
 * queued when the larger one before it reaches as far. So the values
 * decrease and the reaches grow along the queue, and its head is the
 * largest value still reaching i. */
static void sweep(const uint16_t *in, uint16_t *out, int n, int step, planes *p)
{
    int head = 0, tail = 0;
    for (int t = 0; t < n; ++t) {
        int i = step > 0 ? t : n - 1 - t;
        if (in[i]) {
            while (tail > head && p->value[tail - 1] <= in[i])
                --tail;
            int32_t end = t + in[i] - 1;
            if (tail == head || p->end[tail - 1] < end) {
                p->value[tail] = in[i];
                p->end[tail++] = end;
            }
        }
        while (head < tail && p->end[head] < t)
            ++head;
        if (head < tail && p->value[head] > out[i])
            out[i] = p->value[head];
    }
}

/* out(i) = max { in(j) : in(j) > |i - j| } along one line of n. */
static void line_opening(const uint16_t *in, uint16_t *out, int n, planes *p)
{
    memset(out, 0, (size_t)n * sizeof *out);
    sweep(in, out, n, +1, p);
    sweep(in, out, n, -1, p);
}

/* The openings of the plane's distances along x (its rows), then along y
 * (its columns, read into a line). */
static void plane_openings(planes *p)
{
    int32_t w = p->width, h = p->height;
    for (int32_t y = 0; y < h; ++y)
        line_opening(p->plane + (size_t)y * w, p->openings + (size_t)y * w, w, p);
    for (int32_t x = 0; x < w; ++x) {
        for (int32_t y = 0; y < h; ++y)
            p->in[y] = p->openings[(size_t)y * w + x];
        line_opening(p->in, p->out, h, p);
        for (int32_t y = 0; y < h; ++y)
            p->openings[(size_t)y * w + x] = p->out[y];
    }
}

/* ---- the maps ---- */

static void write_cells(unsigned char *maps, size_t first_cell, const uint16_t *distance,
                        const uint16_t *opening, size_t count)
{
    unsigned char *at = maps + GB_CHESSBOARD_MAP_BYTES * first_cell;
    for (size_t n = 0; n < count; ++n, at += GB_CHESSBOARD_MAP_BYTES) {
        uint16_t o = opening ? opening[n] : 0;
        at[0] = (unsigned char)distance[n];
        at[1] = (unsigned char)((distance[n] >> 8 & 0x0f) | (o & 0x0f) << 4);
        at[2] = (unsigned char)(o >> 4);
    }
}

static void set_opening(unsigned char *maps, size_t cell, uint16_t opening)
{
    unsigned char *at = maps + GB_CHESSBOARD_MAP_BYTES * cell;
    at[1] = (unsigned char)((at[1] & 0x0f) | (opening & 0x0f) << 4);
    at[2] = (unsigned char)(opening >> 4);
}

/* The openings along z of the maps' openings so far, BUNDLE lines at a
 * time, in the rows y = first, first + every, ... */
static void opening_along_z(const gb_cubical_complex *complex, unsigned char *maps, planes *p,
                            int32_t first_row, int32_t every)
{
    int n = complex->size[2];
    size_t plane = complex->step[2];
    for (int32_t y = first_row; y < complex->size[1]; y += every)
        for (int32_t first = 0; first < complex->size[0]; first += BUNDLE) {
            int width = complex->size[0] - first < BUNDLE ? complex->size[0] - first : BUNDLE;
            size_t base = complex->step[1] * (size_t)y + (size_t)first;
            for (int z = 0; z < n; ++z)
                for (int b = 0; b < width; ++b)
                    p->in[b * p->longest + z] = gb_map_opening(maps, base + z * plane + b);
            for (int b = 0; b < width; ++b)
                line_opening(p->in + b * p->longest, p->out + b * p->longest, n, p);
            for (int z = 0; z < n; ++z)
                for (int b = 0; b < width; ++b)
                    set_opening(maps, base + z * plane + b, p->out[b * p->longest + z]);
        }
}

static gb_result allocate_planes(planes *p, const gb_cubical_complex *complex, gb_error *error)
{
    memset(p, 0, sizeof *p);
    p->width = complex->size[0];
    p->height = complex->size[1];
    p->longest = complex->size[0];
    for (int axis = 1; axis < 3; ++axis)
        p->longest = complex->size[axis] > p->longest ? complex->size[axis] : p->longest;
    size_t plane = complex->step[2], line = (size_t)p->longest;
    /* one allocation: the 4-byte ends first, then the 2-byte buffers */
    p->end = calloc(1, line * sizeof(int32_t) +
                           (3 * plane + line * (2 * BUNDLE + 2)) * sizeof(uint16_t));
    if (!p->end)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "chessboard maps: out of memory");
    p->done = (uint16_t *)(void *)(p->end + line);
    p->plane = p->done + plane;
    p->openings = p->plane + plane;
    p->least = p->openings + plane;
    p->value = p->least + line;
    p->in = p->value + line;
    p->out = p->in + BUNDLE * line;
    return GB_OK;
}

/* ---- the openings, on threads ---- */

typedef struct openings_job {
    const gb_cubical_complex *complex;
    unsigned char *maps;
    planes *buffers;            /* a thread's own */
} openings_job;

/* Thread's planes (every thread_count-th): their openings along x and y. */
static void openings_along_x_and_y(void *context, int thread, int thread_count)
{
    const openings_job *job = context;
    planes *p = &job->buffers[thread];
    size_t plane = job->complex->step[2];
    for (int32_t z = thread; z < job->complex->size[2]; z += thread_count) {
        size_t first_cell = plane * (size_t)z;
        for (size_t n = 0; n < plane; ++n)
            p->plane[n] = gb_map_distance(job->maps, first_cell + n);
        plane_openings(p);
        write_cells(job->maps, first_cell, p->plane, p->openings, plane);
    }
}

static void openings_along_z(void *context, int thread, int thread_count)
{
    const openings_job *job = context;
    opening_along_z(job->complex, job->maps, &job->buffers[thread], thread, thread_count);
}

static gb_result report(gb_progress_callback progress, void *progress_user, double done,
                        gb_error *error)
{
    if (progress && progress(progress_user, done))
        return gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
    return GB_OK;
}

gb_result gb_chessboard_maps(const gb_cubical_complex *complex, unsigned char *maps,
                             int thread_count, gb_progress_callback progress,
                             void *progress_user, gb_error *error)
{
    thread_count = thread_count < 1 ? 1 : thread_count > GB_CHESSBOARD_MAX_THREADS
                                              ? GB_CHESSBOARD_MAX_THREADS
                                              : thread_count;
    planes buffers[GB_CHESSBOARD_MAX_THREADS];
    int allocated = 0;
    gb_result result = GB_OK;
    while (!result && allocated < thread_count)
        result = allocate_planes(&buffers[allocated++], complex, error);
    if (result)
        --allocated;
    planes *p = &buffers[0];
    size_t plane = complex->step[2];
    for (int32_t z = 0; !result && z < complex->size[2]; ++z) {
        const uint8_t *faces = complex->faces + plane * (size_t)z;
        for (size_t n = 0; n < plane; ++n)
            p->plane[n] = faces[n] & GB_FACE_CUBE ? GB_CHESSBOARD_FAR : 0;
        distance_plane(p, +1);
        write_cells(maps, plane * (size_t)z, p->plane, NULL, plane);
        next_plane(p);
    }
    if (!result) {
        result = report(progress, progress_user, 1 / 4.0, error);
        memset(p->done, 0, plane * sizeof *p->done);
    }
    for (int32_t z = complex->size[2]; !result && z-- > 0;) {
        size_t first_cell = plane * (size_t)z;
        for (size_t n = 0; n < plane; ++n)
            p->plane[n] = gb_map_distance(maps, first_cell + n);
        distance_plane(p, -1);
        write_cells(maps, first_cell, p->plane, NULL, plane);
        next_plane(p);
    }
    openings_job job = {complex, maps, buffers};
    if (!result)
        result = report(progress, progress_user, 2 / 4.0, error);
    if (!result) {
        gb_run_threads(openings_along_x_and_y, &job, thread_count);
        result = report(progress, progress_user, 3 / 4.0, error);
    }
    if (!result) {
        gb_run_threads(openings_along_z, &job, thread_count);
        result = report(progress, progress_user, 1.0, error);
    }
    for (int t = 0; t < allocated; ++t)
        free(buffers[t].end);
    return result;
}
