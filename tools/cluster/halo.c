/* halo.c — the photons a part of the leaves can gather (halo.h). */
#include "halo.h"

#include <math.h>
#include <string.h>

/* The box of points [first, end), grown by R and a little for rounding;
 * empty (lower above upper) when the range is. */
static void grown_box(const float *points, uint32_t first, uint32_t end, float R,
                      float lower[3], float upper[3])
{
    for (int a = 0; a < 3; ++a) {
        lower[a] = INFINITY;
        upper[a] = -INFINITY;
    }
    for (uint32_t i = first; i < end; ++i)
        for (int a = 0; a < 3; ++a) {
            lower[a] = fminf(lower[a], points[3 * (size_t)i + a]);
            upper[a] = fmaxf(upper[a], points[3 * (size_t)i + a]);
        }
    for (int a = 0; a < 3 && first < end; ++a) {
        float margin = R + 1e-5f * (fabsf(lower[a]) + fabsf(upper[a]) + R);
        lower[a] -= margin;
        upper[a] += margin;
    }
}

static int inside(const float p[3], const float lower[3], const float upper[3])
{
    return p[0] >= lower[0] && p[0] <= upper[0] && p[1] >= lower[1] && p[1] <= upper[1] &&
           p[2] >= lower[2] && p[2] <= upper[2];
}

static void copy_photon(const gb_photon_map *map, uint64_t from, gb_photon_arrays *to,
                        uint64_t at)
{
    memcpy(&to->positions[3 * at], &map->positions[3 * from], 3 * sizeof(float));
    memcpy(&to->powers[3 * at], &map->powers[3 * from], 3 * sizeof(float));
    to->directions[at] = map->directions[from];
    to->normals[at] = map->normals[from];
}

gb_result gb_cluster_halo(const gb_photon_map *map, const float *points, uint32_t first,
                          uint32_t end, float R, gb_photon_map *halo, gb_error *error)
{
    memset(halo, 0, sizeof *halo);
    float lower[3], upper[3];
    grown_box(points, first, end, R, lower, upper);
    uint64_t count = 0;
    for (uint64_t i = 0; i < map->count; ++i)
        count += (uint64_t)inside(&map->positions[3 * i], lower, upper);
    gb_photon_arrays arrays;
    gb_result result = gb_photon_map_allocate(halo, count, &arrays, error);
    if (result != GB_OK)
        return result;
    halo->header = map->header;
    for (uint64_t i = 0, at = 0; i < map->count; ++i)
        if (inside(&map->positions[3 * i], lower, upper))
            copy_photon(map, i, &arrays, at++);
    return GB_OK;
}
