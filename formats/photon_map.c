/* photon_map.c — the photon map file (formats/photon_map.h, formats/FORMATS.md
 * "Photon map"). The header is encoded little-endian byte by byte; the photon
 * arrays are written and read in place, which needs a little-endian host. */
#include "photon_map.h"
#include "little_endian.h"

#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "container_kind.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "photon maps are read in place: gibake needs a little-endian host"
#endif

enum {
    HEADER_SIZE = 128,
    ALIGNMENT = 16,
    /* byte offsets inside the header */
    AT_EMITTED = 0,
    AT_FIRST = 8,
    AT_END = 16,
    AT_COUNT = 24,
    AT_SCENE_HASH = 32,
    AT_SEED = 40,
    AT_SHARD_INDEX = 48,
    AT_SHARD_COUNT = 52,
    AT_BOUNCES = 56,
    AT_STORE = 60,
    AT_ROULETTE = 64,
    AT_RESERVED_A = 68,
    AT_POWER = 72,
    AT_BOUNDS_MIN = 96,
    AT_BOUNDS_MAX = 108,
    AT_RESERVED_B = 120,
};

/* The most a packed vector may fall behind its surface: quantisation of the
 * direction and the normal moves their dot product by less than 0.002. */
#define BEHIND_TOLERANCE (-0.01f)

/* ---- little-endian fields ---- */

/* ---- building a map ---- */

static size_t aligned_size(size_t size)
{
    return (size + (ALIGNMENT - 1)) & ~(size_t)(ALIGNMENT - 1);
}

gb_result gb_photon_map_allocate(gb_photon_map *map, uint64_t count, gb_photon_arrays *arrays,
                                 gb_error *error)
{
    *map = (gb_photon_map){0};
    *arrays = (gb_photon_arrays){0};
    if (count > (SIZE_MAX / 2) / GB_PHOTON_SIZE)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photon map: %llu photons do not fit in "
                       "memory", (unsigned long long)count);
    size_t vectors = aligned_size((size_t)count * 3 * sizeof(float));
    size_t words = aligned_size((size_t)count * sizeof(uint32_t));
    unsigned char *block = aligned_alloc(ALIGNMENT, 2 * vectors + 2 * words + ALIGNMENT);
    if (!block)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photon map: out of memory for %llu "
                       "photons", (unsigned long long)count);
    arrays->positions = (float *)block;
    arrays->powers = (float *)(block + vectors);
    arrays->directions = (uint32_t *)(block + 2 * vectors);
    arrays->normals = (uint32_t *)(block + 2 * vectors + words);
    map->storage = block;
    map->count = count;
    map->positions = arrays->positions;
    map->powers = arrays->powers;
    map->directions = arrays->directions;
    map->normals = arrays->normals;
    return GB_OK;
}

void gb_photon_map_release_pages(const gb_photon_map *map)
{
    if (map->container.mapping)
        madvise(map->container.mapping, map->container.mapping_size, MADV_DONTNEED);
}

void gb_photon_map_free(gb_photon_map *map)
{
    free(map->storage);
    gb_container_close(&map->container);
    *map = (gb_photon_map){0};
}

void gb_photon_shard_range(uint64_t emitted, uint32_t index, uint32_t count, uint64_t *first,
                           uint64_t *end)
{
    uint64_t size = emitted / count, extra = emitted % count;
    *first = size * index + (index < extra ? index : extra);
    *end = *first + size + (index < extra ? 1 : 0);
}

/* ---- checks ---- */

static int is_finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static gb_result check_shard(const gb_photon_map_header *h, const char *path, gb_error *error)
{
    if (h->emitted_count == 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: no photon emitted", path);
    if (h->shard_count == 0 || h->shard_index >= h->shard_count)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: shard %u of %u does not exist", path,
                       (unsigned)h->shard_index, (unsigned)h->shard_count);
    uint64_t first, end;
    gb_photon_shard_range(h->emitted_count, h->shard_index, h->shard_count, &first, &end);
    if (h->first_photon != first || h->end_photon != end)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: photons %llu..%llu are not shard %u/%u of "
                       "%llu (%llu..%llu)", path, (unsigned long long)h->first_photon,
                       (unsigned long long)h->end_photon, (unsigned)h->shard_index,
                       (unsigned)h->shard_count, (unsigned long long)h->emitted_count,
                       (unsigned long long)first, (unsigned long long)end);
    return GB_OK;
}

static gb_result check_tracing(const gb_photon_map_header *h, uint64_t count, const char *path,
                               gb_error *error)
{
    if (h->bounces < 1 || h->bounces > GB_PHOTON_MAX_BOUNCES)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bounces %u is outside 1..%d", path,
                       (unsigned)h->bounces, GB_PHOTON_MAX_BOUNCES);
    if (h->store != GB_PHOTON_STORE_INDIRECT && h->store != GB_PHOTON_STORE_ALL)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: unknown store mode %u", path,
                       (unsigned)h->store);
    if (h->roulette_start > h->bounces)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: roulette start %u is above bounces %u",
                       path, (unsigned)h->roulette_start, (unsigned)h->bounces);
    uint64_t paths = h->end_photon - h->first_photon;
    if (paths > UINT64_MAX / (h->bounces + 1u) || count > paths * (h->bounces + 1u))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %llu photons stored from %llu paths of at "
                       "most %u hits", path, (unsigned long long)count,
                       (unsigned long long)paths, (unsigned)h->bounces + 1u);
    return GB_OK;
}

static gb_result check_power_and_bounds(const gb_photon_map_header *h, uint64_t count,
                                        const char *path, gb_error *error)
{
    double largest = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(h->emitted_power[k]) || h->emitted_power[k] < 0.0)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: emitted power is not finite and "
                           "non-negative", path);
        largest = h->emitted_power[k] > largest ? h->emitted_power[k] : largest;
    }
    if (!(largest > 0.0) && count > 0)     /* zero: a scene with no light, no photon */
        return gb_fail(error, GB_ERROR_FORMAT, "%s: emitted power is zero but %llu photons "
                       "are stored", path, (unsigned long long)count);
    if (!is_finite3(h->bounds_min) || !is_finite3(h->bounds_max))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: scene bounds are not finite", path);
    for (int k = 0; k < 3; ++k)
        if (h->bounds_min[k] > h->bounds_max[k])
            return gb_fail(error, GB_ERROR_FORMAT, "%s: scene bounds are empty", path);
    return GB_OK;
}

static gb_result check_header(const gb_photon_map *map, const char *path, gb_error *error)
{
    const gb_photon_map_header *h = &map->header;
    gb_result result = check_shard(h, path, error);
    if (result == GB_OK)
        result = check_tracing(h, map->count, path, error);
    if (result == GB_OK)
        result = check_power_and_bounds(h, map->count, path, error);
    return result;
}

/* How far outside the bounds a hit point may fall by rounding. */
static float bounds_tolerance(const gb_photon_map_header *h)
{
    float magnitude = 0.0f;
    for (int k = 0; k < 3; ++k)
        magnitude = fmaxf(magnitude, fmaxf(fabsf(h->bounds_min[k]), fabsf(h->bounds_max[k])));
    return magnitude * 0x1p-16f;
}

static int inside_bounds(const gb_photon_map_header *h, const float p[3], float tolerance)
{
    for (int k = 0; k < 3; ++k)
        if (!(p[k] >= h->bounds_min[k] - tolerance && p[k] <= h->bounds_max[k] + tolerance))
            return 0;
    return 1;
}

static int valid_power(const float power[3])
{
    for (int k = 0; k < 3; ++k)
        if (!isfinite(power[k]) || power[k] < 0.0f)
            return 0;
    return power[0] > 0.0f || power[1] > 0.0f || power[2] > 0.0f;
}

/* Every stored half of a packed vector is nonzero (FORMATS.md). */
static int valid_packing(uint32_t direction, uint32_t normal)
{
    return (direction & 0xFFFFu) && (direction >> 16) && (normal & 0xFFFu) &&
           ((normal >> 12) & 0xFFFu);
}

static gb_result check_photon(const gb_photon_map *map, uint64_t i, float tolerance,
                              const char *path, gb_error *error)
{
    const gb_photon_map_header *h = &map->header;
    const float *position = &map->positions[3 * i], *power = &map->powers[3 * i];
    uint32_t direction = map->directions[i], normal = map->normals[i];
    unsigned long long index = (unsigned long long)i;
    if (!is_finite3(position) || !inside_bounds(h, position, tolerance))
        return gb_fail(error, GB_ERROR_INVALID, "%s: photon %llu lies outside the scene", path,
                       index);
    if (!valid_power(power))
        return gb_fail(error, GB_ERROR_INVALID, "%s: photon %llu: power must be finite, "
                       "non-negative and not black", path, index);
    if (!valid_packing(direction, normal))
        return gb_fail(error, GB_ERROR_INVALID, "%s: photon %llu: a packed vector holds a "
                       "zero field", path, index);
    unsigned bounce = gb_photon_bounce(normal);
    if (bounce > h->bounces || (h->store == GB_PHOTON_STORE_INDIRECT && bounce == 0))
        return gb_fail(error, GB_ERROR_INVALID, "%s: photon %llu: bounce count %u outside "
                       "%u..%u", path, index, bounce, h->store == GB_PHOTON_STORE_INDIRECT,
                       (unsigned)h->bounces);
    float d[3], n[3];
    gb_photon_unpack_direction(direction, d);
    gb_photon_unpack_normal(normal, n);
    if (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] < BEHIND_TOLERANCE)
        return gb_fail(error, GB_ERROR_INVALID, "%s: photon %llu arrives from behind its "
                       "surface", path, index);
    return GB_OK;
}

gb_result gb_photon_map_check(const gb_photon_map *map, const char *path, gb_error *error)
{
    if (map->count && (!map->positions || !map->powers || !map->directions || !map->normals))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: %llu photons without arrays", path,
                       (unsigned long long)map->count);
    gb_result result = check_header(map, path, error);
    float tolerance = bounds_tolerance(&map->header);
    for (uint64_t i = 0; result == GB_OK && i < map->count; ++i)
        result = check_photon(map, i, tolerance, path, error);
    return result;
}

gb_result gb_photon_map_check_scene(const gb_photon_map *map, uint64_t scene_hash,
                                    const char *path, gb_error *error)
{
    if (map->header.scene_hash != scene_hash)
        return gb_fail(error, GB_ERROR_STALE, "%s: traced in another scene (hash %016llx, the "
                       "scene's is %016llx)", path, (unsigned long long)map->header.scene_hash,
                       (unsigned long long)scene_hash);
    return GB_OK;
}

/* ---- writing ---- */

static void encode_header(const gb_photon_map *map, unsigned char *bytes)
{
    const gb_photon_map_header *h = &map->header;
    memset(bytes, 0, HEADER_SIZE);
    gb_put_u64(bytes + AT_EMITTED, h->emitted_count);
    gb_put_u64(bytes + AT_FIRST, h->first_photon);
    gb_put_u64(bytes + AT_END, h->end_photon);
    gb_put_u64(bytes + AT_COUNT, map->count);
    gb_put_u64(bytes + AT_SCENE_HASH, h->scene_hash);
    gb_put_u64(bytes + AT_SEED, h->seed);
    gb_put_u32(bytes + AT_SHARD_INDEX, h->shard_index);
    gb_put_u32(bytes + AT_SHARD_COUNT, h->shard_count);
    gb_put_u32(bytes + AT_BOUNCES, h->bounces);
    gb_put_u32(bytes + AT_STORE, h->store);
    gb_put_u32(bytes + AT_ROULETTE, h->roulette_start);
    for (int k = 0; k < 3; ++k) {
        gb_put_f64(bytes + AT_POWER + 8 * k, h->emitted_power[k]);
        gb_put_f32(bytes + AT_BOUNDS_MIN + 4 * k, h->bounds_min[k]);
        gb_put_f32(bytes + AT_BOUNDS_MAX + 4 * k, h->bounds_max[k]);
    }
}

gb_result gb_photon_map_write(const char *path, const gb_photon_map *map, gb_error *error)
{
    gb_result result = gb_photon_map_check(map, path, error);
    if (result != GB_OK)
        return result;
    unsigned char header[HEADER_SIZE];
    encode_header(map, header);
    const gb_container_array arrays[] = {
        {"header", 1, HEADER_SIZE, header},
        {"positions", map->count, 3 * sizeof(float), map->positions},
        {"powers", map->count, 3 * sizeof(float), map->powers},
        {"directions", map->count, sizeof(uint32_t), map->directions},
        {"normals", map->count, sizeof(uint32_t), map->normals},
    };
    return gb_container_write_arrays(path, "PHOT", GB_PHOTON_MAP_VERSION, arrays, 5, error);
}

/* ---- reading ---- */

static gb_result decode_header(const gb_container *container, const char *path,
                               gb_photon_map *map, gb_error *error)
{
    const gb_section *section;
    gb_result result = gb_container_find_array(container, "header", 1, HEADER_SIZE, 1, path,
                                               &section, error);
    if (result != GB_OK)
        return result;
    const unsigned char *bytes = section->data;
    gb_photon_map_header *h = &map->header;
    if (gb_get_u32(bytes + AT_RESERVED_A) || gb_get_u64(bytes + AT_RESERVED_B))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: reserved header field is not zero", path);
    h->emitted_count = gb_get_u64(bytes + AT_EMITTED);
    h->first_photon = gb_get_u64(bytes + AT_FIRST);
    h->end_photon = gb_get_u64(bytes + AT_END);
    map->count = gb_get_u64(bytes + AT_COUNT);
    h->scene_hash = gb_get_u64(bytes + AT_SCENE_HASH);
    h->seed = gb_get_u64(bytes + AT_SEED);
    h->shard_index = gb_get_u32(bytes + AT_SHARD_INDEX);
    h->shard_count = gb_get_u32(bytes + AT_SHARD_COUNT);
    h->bounces = gb_get_u32(bytes + AT_BOUNCES);
    h->store = gb_get_u32(bytes + AT_STORE);
    h->roulette_start = gb_get_u32(bytes + AT_ROULETTE);
    for (int k = 0; k < 3; ++k) {
        h->emitted_power[k] = gb_get_f64(bytes + AT_POWER + 8 * k);
        h->bounds_min[k] = gb_get_f32(bytes + AT_BOUNDS_MIN + 4 * k);
        h->bounds_max[k] = gb_get_f32(bytes + AT_BOUNDS_MAX + 4 * k);
    }
    return GB_OK;
}

static gb_result view_arrays(const gb_container *container, const char *path,
                             gb_photon_map *map, gb_error *error)
{
    uint64_t n = map->count;
    gb_container_array arrays[] = {
        {"positions", n, 12, NULL},
        {"powers", n, 12, NULL},
        {"directions", n, 4, NULL},
        {"normals", n, 4, NULL},
    };
    gb_result result = gb_container_find_arrays(container, arrays, 4, ALIGNMENT, path, error);
    map->positions = arrays[0].data;
    map->powers = arrays[1].data;
    map->directions = arrays[2].data;
    map->normals = arrays[3].data;
    return result;
}

/* Fills the map from a checked PHOT container, which it then keeps: its
 * arrays are views into it (container_kind.h). */
static gb_result adopt_container(const gb_container *container, const char *path, void *object,
                                 gb_error *error)
{
    gb_photon_map *map = object;
    if (container->section_count != 5)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u sections, expected 5", path,
                       (unsigned)container->section_count);
    gb_result result = decode_header(container, path, map, error);
    if (result == GB_OK)
        result = view_arrays(container, path, map, error);
    if (result == GB_OK)
        result = gb_photon_map_check(map, path, error);
    if (result == GB_OK)
        map->container = *container;
    return result;
}

static const gb_container_kind photon_map_kind = {
    "PHOT", GB_PHOTON_MAP_VERSION, sizeof(gb_photon_map), adopt_container, 1};

gb_result gb_photon_map_read(const char *path, gb_photon_map *map, gb_error *error)
{
    return gb_container_kind_read(path, &photon_map_kind, map, error);
}

gb_result gb_photon_map_parse(const void *bytes, size_t size, const char *path,
                              gb_photon_map *map, gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &photon_map_kind, map, error);
}
