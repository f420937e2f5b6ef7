/* photon_map.h — a photon map on disk: the file kind "PHOT"
 * (formats/FORMATS.md, "Photon map"). `photons` writes it, `cluster` reads it
 * in place: the photons are four arrays (struct of arrays), each a section of
 * the container, 16-byte aligned, so a reader uses them straight from the
 * mapped file with no copy (positions can go to FLANN as they are).
 *
 * A photon is 32 bytes:
 *   position   f32 x 3    where it hit a surface (world units)
 *   power      f32 x 3    W, linear RGB
 *   direction  u32        unit vector from the hit toward where the photon
 *                         came from (common/brdf.h's wi), octahedral 2 x 16
 *                         bits: at most 0.003 degrees off
 *   normal     u32        the triangle's geometric normal turned to the side
 *                         the photon arrived from, octahedral 2 x 12 bits (at
 *                         most 0.05 degrees off), and in the top 8 bits the
 *                         bounce count: reflections before this hit (0: the
 *                         photon came straight from a light)
 * Photons are in the order they were traced: by emitted photon index, then
 * by bounce, so the shards of a run, concatenated, are the run itself.
 *
 *   gb_photon_arrays a;
 *   gb_photon_map_allocate(&map, count, &a, &error);   // fill a.positions, ...
 *   gb_photon_map_write("out.phot", &map, &error);     // checks, temp file, rename
 *   gb_photon_map_read("out.phot", &map, &error);      // checks every byte
 *   gb_photon_map_free(&map);                          // either kind of map
 *
 * A map owns its storage: the arrays of gb_photon_map_allocate, or the file
 * mapping of gb_photon_map_read (views, read-only). The arrays are in the
 * host's byte order, so this module builds only on little-endian hosts (the
 * file is little-endian).
 */
#ifndef GB_PHOTON_MAP_H
#define GB_PHOTON_MAP_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "container.h"
#include "result.h"

enum {
    GB_PHOTON_MAP_VERSION = 1,
    GB_PHOTON_MAX_BOUNCES = 255,        /* the bounce count is 8 bits */
    GB_PHOTON_SIZE = 32,                /* bytes per stored photon in the file */
};

/* Which photons a run stores. */
typedef enum gb_photon_store {
    GB_PHOTON_STORE_INDIRECT = 0,       /* bounce count >= 1: the runtime draws direct light */
    GB_PHOTON_STORE_ALL = 1,            /* every hit, the first included */
} gb_photon_store;

typedef struct gb_photon_map_header {
    uint64_t emitted_count;     /* photons emitted by the whole run: the powers sum, over
                                   them, to emitted_power */
    uint64_t first_photon;      /* this file holds the photons emitted with indices */
    uint64_t end_photon;        /*   first_photon .. end_photon - 1 */
    uint64_t scene_hash;        /* gb_scene.hash of the scene traced */
    uint64_t seed;
    uint32_t shard_index;       /* this file is shard shard_index of shard_count; */
    uint32_t shard_count;       /*   a whole run is 0 of 1 */
    uint32_t bounces;           /* most reflections of a path, 1 .. 255 */
    uint32_t store;             /* gb_photon_store */
    uint32_t roulette_start;    /* reflections before Russian roulette starts */
    double emitted_power[3];    /* W: the total power of the scene's lights */
    float bounds_min[3];        /* the scene's bounds: every photon lies inside */
    float bounds_max[3];
} gb_photon_map_header;

typedef struct gb_photon_map {
    gb_photon_map_header header;
    uint64_t count;                 /* photons stored */
    const float *positions;         /* count x 3 */
    const float *powers;            /* count x 3 */
    const uint32_t *directions;     /* count: gb_photon_unpack_direction */
    const uint32_t *normals;        /* count: gb_photon_unpack_normal, gb_photon_bounce */
    void *storage;                  /* owned: the arrays' block, or NULL */
    gb_container container;         /* owned: the file the arrays view, when read */
} gb_photon_map;

/* The writable arrays of a map being built. */
typedef struct gb_photon_arrays {
    float *positions;
    float *powers;
    uint32_t *directions;
    uint32_t *normals;
} gb_photon_arrays;

/* Gives *map (whose header the caller fills, before or after) room for count
 * photons, 16-byte aligned arrays in one block; *map is reset first, so it
 * must not own anything. */
gb_result gb_photon_map_allocate(gb_photon_map *map, uint64_t count, gb_photon_arrays *arrays,
                                 gb_error *error);

/* Checks everything FORMATS.md lists: header fields and their consistency,
 * then every photon (finite position inside the bounds, finite power >= 0
 * and not black, valid packed vectors, arriving from the normal's side,
 * bounce count within the header's). path names the map in messages. */
gb_result gb_photon_map_check(const gb_photon_map *map, const char *path, gb_error *error);

/* Checks the map, then writes it (temporary file, rename). */
gb_result gb_photon_map_write(const char *path, const gb_photon_map *map, gb_error *error);

/* Maps the file and checks every byte; on failure *map is zeroed and needs no
 * freeing. */
gb_result gb_photon_map_read(const char *path, gb_photon_map *map, gb_error *error);

/* The same on a caller's buffer, which must be 16-byte aligned and outlive
 * the map (tests, fuzzing). */
gb_result gb_photon_map_parse(const void *bytes, size_t size, const char *path,
                              gb_photon_map *map, gb_error *error);

/* GB_ERROR_STALE unless the map was traced in the scene of this hash. */
gb_result gb_photon_map_check_scene(const gb_photon_map *map, uint64_t scene_hash,
                                    const char *path, gb_error *error);

void gb_photon_map_free(gb_photon_map *map);

/* Gives a read map's pages back to the kernel (madvise): the process's
 * resident set shrinks by the file's size, and a later read of the photons
 * maps them in again. Does nothing to an allocated map. */
void gb_photon_map_release_pages(const gb_photon_map *map);

/* The photon indices [*first, *end) of shard `index` of `count` for a run of
 * emitted photons: contiguous, disjoint, covering the run in order, sizes
 * differing by at most one. */
void gb_photon_shard_range(uint64_t emitted, uint32_t index, uint32_t count, uint64_t *first,
                           uint64_t *end);

/* ---- packing of unit vectors (octahedral, Cigolle et al. 2014) ----
 * Each coordinate of the octahedral square [-1, 1]^2 is a signed integer q
 * with |q| <= 2^(bits-1) - 1 (so 0 and +-1 are exact: axis-aligned vectors
 * survive unchanged), stored as q + 2^(bits-1): never 0. */

static inline float gb_photon_sign(float x)
{
    return x < 0.0f ? -1.0f : 1.0f;
}

/* Unit v to the square [-1, 1]^2. */
static inline void gb_octahedral_fold(const float v[3], float *x, float *y)
{
    float l1 = fabsf(v[0]) + fabsf(v[1]) + fabsf(v[2]);
    float a = l1 > 0.0f ? v[0] / l1 : 0.0f, b = l1 > 0.0f ? v[1] / l1 : 0.0f;
    if (v[2] < 0.0f) {
        float fa = (1.0f - fabsf(b)) * gb_photon_sign(a);
        b = (1.0f - fabsf(a)) * gb_photon_sign(b);
        a = fa;
    }
    *x = a;
    *y = b;
}

/* The square back to a vector of the octahedron |x| + |y| + |z| = 1. */
static inline void gb_octahedral_unfold_unnormalized(float x, float y, float v[3])
{
    float z = 1.0f - fabsf(x) - fabsf(y);
    if (z < 0.0f) {
        float fx = (1.0f - fabsf(y)) * gb_photon_sign(x);
        y = (1.0f - fabsf(x)) * gb_photon_sign(y);
        x = fx;
    }
    v[0] = x;
    v[1] = y;
    v[2] = z;
}

/* The square back to a unit vector. */
static inline void gb_octahedral_unfold(float x, float y, float v[3])
{
    gb_octahedral_unfold_unnormalized(x, y, v);
    float length = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= length;
    v[1] /= length;
    v[2] /= length;
}

static inline float gb_octahedral_limit(int bits)
{
    return (float)((1u << (bits - 1)) - 1u);
}

static inline float gb_octahedral_dequantize(uint32_t stored, int bits)
{
    return (float)((int32_t)stored - (int32_t)(1u << (bits - 1))) / gb_octahedral_limit(bits);
}

/* The stored pair (x | y << bits) nearest in angle to v: of the four corners
 * of the quantisation cell around v's folded point, the one that decodes
 * closest to v ("precise" octahedral encoding, Cigolle et al. 2014 §3).
 * Candidates are compared by cos^2 = dot^2 / length^2 cross-multiplied, in
 * double: they differ by less than a float's precision. */
static inline uint32_t gb_octahedral_pack(const float v[3], int bits)
{
    float x, y, limit = gb_octahedral_limit(bits);
    gb_octahedral_fold(v, &x, &y);
    int32_t qx = (int32_t)floorf(x * limit), qy = (int32_t)floorf(y * limit);
    int32_t bias = 1 << (bits - 1), top = (int32_t)limit;
    double best_dot2 = -1.0, best_length2 = 1.0;
    uint32_t best = 0;
    for (int corner = 0; corner < 4; ++corner) {
        int32_t cx = qx + (corner & 1), cy = qy + (corner >> 1);
        if (cx > top || cy > top || cx < -top || cy < -top)
            continue;
        float d[3];
        gb_octahedral_unfold_unnormalized((float)cx / limit, (float)cy / limit, d);
        double dot = (double)d[0] * v[0] + (double)d[1] * v[1] + (double)d[2] * v[2];
        double length2 = (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2];
        double dot2 = dot > 0.0 ? dot * dot : 0.0;
        if (dot2 * best_length2 > best_dot2 * length2) {
            best_dot2 = dot2;
            best_length2 = length2;
            best = (uint32_t)(cx + bias) | (uint32_t)(cy + bias) << bits;
        }
    }
    return best;
}

/* Unit direction -> u32: x in bits 0..15, y in bits 16..31. */
static inline uint32_t gb_photon_pack_direction(const float v[3])
{
    return gb_octahedral_pack(v, 16);
}

static inline void gb_photon_unpack_direction(uint32_t packed, float v[3])
{
    gb_octahedral_unfold(gb_octahedral_dequantize(packed & 0xFFFFu, 16),
                         gb_octahedral_dequantize(packed >> 16, 16), v);
}

/* Unit normal and bounce count (<= 255) -> u32: x in bits 0..11, y in bits
 * 12..23, the bounce count in bits 24..31. */
static inline uint32_t gb_photon_pack_normal(const float n[3], unsigned bounce)
{
    return gb_octahedral_pack(n, 12) | (uint32_t)(bounce & 0xFFu) << 24;
}

static inline void gb_photon_unpack_normal(uint32_t packed, float n[3])
{
    gb_octahedral_unfold(gb_octahedral_dequantize(packed & 0xFFFu, 12),
                         gb_octahedral_dequantize((packed >> 12) & 0xFFFu, 12), n);
}

static inline unsigned gb_photon_bounce(uint32_t packed_normal)
{
    return packed_normal >> 24;
}

#endif
