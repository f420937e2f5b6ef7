/* merge.c — gb_photons_merge: the shards of one run joined, in shard order,
 * into the map the whole run gives (photons.h). Shard I holds the photons of
 * the I-th contiguous range of photon indices, in index order, so their
 * concatenation in shard order is the run's own order. */
#include <stdlib.h>
#include <string.h>

#include "photons.h"

/* Whether two shards come from the same run: every header field but the
 * shard's own (index, range) and the stored count. */
static int same_run(const gb_photon_map_header *a, const gb_photon_map_header *b)
{
    return a->emitted_count == b->emitted_count && a->scene_hash == b->scene_hash &&
           a->seed == b->seed && a->shard_count == b->shard_count &&
           a->bounces == b->bounces && a->store == b->store &&
           a->roulette_start == b->roulette_start &&
           memcmp(a->emitted_power, b->emitted_power, sizeof a->emitted_power) == 0 &&
           memcmp(a->bounds_min, b->bounds_min, sizeof a->bounds_min) == 0 &&
           memcmp(a->bounds_max, b->bounds_max, sizeof a->bounds_max) == 0;
}

/* order[I] = the position in shards of shard I, after checking that the
 * shards are exactly 0..N-1 of one run. */
static gb_result order_shards(const gb_photon_map *shards, uint32_t count,
                              const char *const *names, uint32_t *order, gb_error *error)
{
    const gb_photon_map_header *first = &shards[0].header;
    if (first->shard_count != count)
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: is shard %u of %u, but %u files were "
                       "given", names[0], (unsigned)first->shard_index,
                       (unsigned)first->shard_count, (unsigned)count);
    for (uint32_t i = 0; i < count; ++i)
        order[i] = UINT32_MAX;
    for (uint32_t i = 0; i < count; ++i) {
        const gb_photon_map_header *h = &shards[i].header;
        if (!same_run(first, h))
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: not a shard of the run of %s "
                           "(scene, seed, count, bounces or store differ)", names[i],
                           names[0]);
        if (h->shard_index >= count)
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: shard %u of %u does not exist",
                           names[i], (unsigned)h->shard_index, (unsigned)count);
        if (order[h->shard_index] != UINT32_MAX)
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: shard %u/%u is also %s", names[i],
                           (unsigned)h->shard_index, (unsigned)h->shard_count,
                           names[order[h->shard_index]]);
        order[h->shard_index] = i;
    }
    return GB_OK;
}

static void copy_shard(const gb_photon_map *shard, gb_photon_arrays *a, uint64_t at)
{
    uint64_t n = shard->count;
    if (n == 0)
        return;
    memcpy(a->positions + 3 * at, shard->positions, n * 3 * sizeof(float));
    memcpy(a->powers + 3 * at, shard->powers, n * 3 * sizeof(float));
    memcpy(a->directions + at, shard->directions, n * sizeof(uint32_t));
    memcpy(a->normals + at, shard->normals, n * sizeof(uint32_t));
}

static gb_result join(const gb_photon_map *shards, uint32_t count, const uint32_t *order,
                      gb_photon_map *merged, gb_error *error)
{
    uint64_t total = 0;
    for (uint32_t i = 0; i < count; ++i)
        total += shards[i].count;
    gb_photon_arrays arrays;
    gb_result result = gb_photon_map_allocate(merged, total, &arrays, error);
    if (result != GB_OK)
        return result;
    uint64_t at = 0;
    for (uint32_t s = 0; s < count; ++s) {
        copy_shard(&shards[order[s]], &arrays, at);
        at += shards[order[s]].count;
    }
    merged->header = shards[order[0]].header;
    merged->header.shard_index = 0;
    merged->header.shard_count = 1;
    merged->header.first_photon = 0;
    merged->header.end_photon = merged->header.emitted_count;
    return GB_OK;
}

gb_result gb_photons_merge(const gb_photon_map *shards, uint32_t count,
                           const char *const *names, gb_photon_map *merged, gb_error *error)
{
    *merged = (gb_photon_map){0};
    if (count == 0)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: nothing to merge");
    uint32_t *order = malloc(count * sizeof *order);
    if (!order)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photons: out of memory");
    gb_result result = order_shards(shards, count, names, order, error);
    if (result == GB_OK)
        result = join(shards, count, order, merged, error);
    free(order);
    return result;
}
