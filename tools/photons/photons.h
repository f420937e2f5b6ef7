/* photons.h — the photon map of a scene, traced with Embree: the input of
 * the light octree (vivianloc-2007 §3.1; §4.1 took it from a modified
 * Yafaray, gibake traces it itself). The `photons` tool parses options and
 * calls gb_photons_trace, or gb_photons_merge for --merge.
 *
 * A run emits `count` photons from every light of the scene
 * (common/light_emission.h), follows each path (trace.h) and stores a photon
 * at every hit after at least one reflection (or at every hit with
 * GB_PHOTON_STORE_ALL). The powers of the photons a run emits sum to the
 * scene's emitted power (in expectation).
 *
 * Determinism: photon i (0 <= i < count) draws every random number from PCG32
 * stream i of the seed, whichever thread traces it, and the map lists photons
 * by i then by bounce. So the same seed gives the same map whatever the
 * threads; shard I of N traces the I-th of N contiguous ranges of i
 * (gb_photon_shard_range), and gb_photons_merge of the N shards gives exactly
 * the map of the whole run.
 *
 * -n auto (tolerance > 0): runs of 2^16, 2^17, ... photons are traced, one
 * after another with one BVH, until the flux probes (flux_probes.h) of a run
 * differ from the previous run's by less than the tolerance, or 2^30
 * photons; the last run is the map, byte for byte the map of `-n` its
 * count. It costs about twice that run. The chosen count depends on the
 * seed and the scene, never on the threads. Not with shards: they need the
 * count.
 *
 * Options: a zeroed gb_photons_options means the defaults. The caller owns
 * the map it gets (gb_photon_map_free).
 */
#ifndef GB_PHOTONS_H
#define GB_PHOTONS_H

#include <stdint.h>

#include "photon_map.h"
#include "progress.h"
#include "scene.h"

enum {
    GB_PHOTONS_DEFAULT_BOUNCES = 16,
    GB_PHOTONS_ROULETTE_START = 2,      /* reflections before Russian roulette */
};

#define GB_PHOTONS_DEFAULT_COUNT 1000000ull
#define GB_PHOTONS_MAX_COUNT (1ull << 40)
/* -n auto: the first count tried, the last, and the tolerance by default */
#define GB_PHOTONS_AUTO_FIRST_COUNT (1ull << 16)
#define GB_PHOTONS_AUTO_LAST_COUNT (1ull << 30)
#define GB_PHOTONS_DEFAULT_TOLERANCE 0.05

typedef struct gb_photons_options {
    uint64_t count;             /* photons emitted by the whole run; 0: 1 000 000 */
    unsigned bounces;           /* most reflections of a path, <= 255; 0: 16 */
    gb_photon_store store;      /* 0: GB_PHOTON_STORE_INDIRECT */
    uint64_t seed;
    int threads;                /* 0: every core */
    uint32_t shard_index;       /* trace shard shard_index of shard_count; */
    uint32_t shard_count;       /*   0: the whole run (0 of 1) */
    double tolerance;           /* > 0: -n auto, count is chosen (below) */
    gb_progress_callback progress; /* fraction done, from the calling thread; may be NULL */
    void *progress_user;
} gb_photons_options;

typedef struct gb_photons_stats {
    uint64_t paths;             /* photons emitted by this shard */
    uint64_t rays;              /* rtcIntersect1 calls */
    uint64_t stored;
    uint64_t escaped;           /* paths that left the scene */
    uint64_t nonfinite;         /* paths ended by a power that overflowed */
    double seconds;             /* tracing, without the BVH build */
    double cpu_seconds;         /* CPU time of the process while tracing */
    double build_seconds;       /* Embree BVH, light and surface tables */
    int threads;
    uint32_t passes;            /* -n auto: runs traced (the last is the map) */
    double change;              /* -n auto: the flux probes' change at the end */
} gb_photons_stats;

/* Traces the photons of options' shard into *map (allocated here). stats may
 * be NULL. A scene with no light gives a map of no photon and emitted power
 * 0, the right answer (the tool warns). Fails on bad options
 * (GB_ERROR_ARGUMENT), or a progress callback asking to stop
 * (GB_ERROR_INTERRUPTED). */
gb_result gb_photons_trace(const gb_scene *scene, const gb_photons_options *options,
                           gb_photon_map *map, gb_photons_stats *stats, gb_error *error);

/* Joins the shards 0..N-1 of one run, given in any order, into *merged: the
 * map the whole run gives. Every shard of the run must be there once, and all
 * made alike (scene, seed, count, bounces, store, bounds, power); names[i]
 * names shards[i] in messages. */
gb_result gb_photons_merge(const gb_photon_map *shards, uint32_t count,
                           const char *const *names, gb_photon_map *merged, gb_error *error);

#endif
