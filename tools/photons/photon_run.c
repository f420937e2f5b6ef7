/* photon_run.c — gb_photons_trace: the photons of a run (or of one shard),
 * traced on threads in chunks of consecutive photon indices. Each chunk
 * keeps its own photons; once every path is done the chunks are joined in
 * index order, so the map is the same whatever thread traced which chunk. */
#include <stdatomic.h>
#include <stdlib.h>
#include <time.h>

#include "light_emission.h"
#include "flux_probes.h"
#include "photons.h"
#include "trace.h"
#include "work_queue.h"

enum { CHUNK_PHOTONS = 4096 };

typedef struct run_job {
    const gb_photons_tracer *tracer;
    const gb_light_emission *emission;
    uint64_t emitted_count;     /* of the whole run: the powers' share */
    uint64_t seed;
    uint64_t first, end;        /* this shard's photon indices */
    uint64_t chunk_count;
    gb_photons_sink *chunks;    /* chunk_count */
    atomic_int out_of_memory;
    atomic_uint_fast64_t rays, stored, escaped, nonfinite;
} run_job;

static void add_counters(run_job *job, const gb_photons_counters *c)
{
    atomic_fetch_add(&job->rays, c->rays);
    atomic_fetch_add(&job->stored, c->stored);
    atomic_fetch_add(&job->escaped, c->escaped);
    atomic_fetch_add(&job->nonfinite, c->nonfinite);
}

/* A work-queue item. Photon i draws from stream i of the seed: the thread
 * does not matter. Returns nonzero (stop) when out of memory. */
static int trace_chunk(void *context, uint64_t chunk)
{
    run_job *job = context;
    uint64_t begin = job->first + chunk * CHUNK_PHOTONS;
    uint64_t end = job->end - begin > CHUNK_PHOTONS ? begin + CHUNK_PHOTONS : job->end;
    gb_photons_counters counters = {0};
    int stop = 0;
    if (job->emission->emitter_count == 0)     /* no light: every photon is dark */
        end = begin;
    for (uint64_t i = begin; i < end && !stop; ++i) {
        gb_random rng = gb_random_make(job->seed, i);
        gb_emitted_ray ray;
        gb_light_emission_sample(job->emission, job->emitted_count, &rng, &ray);
        stop = !gb_photons_trace_path(job->tracer, &ray, &rng, &job->chunks[chunk], &counters);
    }
    if (stop)
        atomic_store(&job->out_of_memory, 1);
    add_counters(job, &counters);
    return stop;
}

static gb_result run_threads(run_job *job, const gb_photons_options *options, int *used,
                             gb_error *error)
{
    gb_work_queue queue = {.item_count = job->chunk_count, .threads = options->threads,
                           .progress = options->progress,
                           .progress_user = options->progress_user};
    if (gb_work_queue_run(&queue, trace_chunk, job, used) == GB_OK)
        return GB_OK;
    if (atomic_load(&job->out_of_memory))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photons: out of memory for the photons");
    return gb_fail(error, GB_ERROR_INTERRUPTED, "photons: interrupted");
}

/* ---- the map ---- */

static void fill_header(const gb_scene *scene, const gb_photons_options *options,
                        const gb_photons_tracer *tracer, const run_job *job,
                        gb_photon_map_header *h)
{
    h->emitted_count = job->emitted_count;
    h->first_photon = job->first;
    h->end_photon = job->end;
    h->scene_hash = scene->hash;
    h->seed = options->seed;
    h->shard_index = options->shard_index;
    h->shard_count = options->shard_count ? options->shard_count : 1;
    h->bounces = tracer->bounces;
    h->store = tracer->store;
    h->roulette_start = tracer->roulette_start;
    for (int k = 0; k < 3; ++k) {
        h->emitted_power[k] = job->emission->power[k];
        h->bounds_min[k] = scene->bounds_min[k];
        h->bounds_max[k] = scene->bounds_max[k];
    }
}

static void copy_record(const gb_photons_record *r, gb_photon_arrays *a, uint64_t i)
{
    for (int k = 0; k < 3; ++k) {
        a->positions[3 * i + k] = r->position[k];
        a->powers[3 * i + k] = r->power[k];
    }
    a->directions[i] = r->direction;
    a->normals[i] = r->normal;
}

/* Joins the chunks in index order into the map, freeing each once copied. */
static gb_result join_chunks(run_job *job, gb_photon_map *map, gb_error *error)
{
    uint64_t total = 0;
    for (uint64_t c = 0; c < job->chunk_count; ++c)
        total += job->chunks[c].count;
    gb_photon_arrays arrays;
    gb_result result = gb_photon_map_allocate(map, total, &arrays, error);
    if (result != GB_OK)
        return result;
    uint64_t i = 0;
    for (uint64_t c = 0; c < job->chunk_count; ++c) {
        for (size_t j = 0; j < job->chunks[c].count; ++j)
            copy_record(&job->chunks[c].records[j], &arrays, i++);
        gb_photons_sink_free(&job->chunks[c]);
    }
    return GB_OK;
}

/* ---- options and set-up ---- */

static gb_result check_options(const gb_photons_options *o, gb_error *error)
{
    uint32_t shards = o->shard_count ? o->shard_count : 1;
    if (o->count > GB_PHOTONS_MAX_COUNT)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: %llu photons is more than %llu",
                       (unsigned long long)o->count, (unsigned long long)GB_PHOTONS_MAX_COUNT);
    if (o->bounces > GB_PHOTON_MAX_BOUNCES)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: bounces %u is more than %d",
                       o->bounces, GB_PHOTON_MAX_BOUNCES);
    if (o->store != GB_PHOTON_STORE_INDIRECT && o->store != GB_PHOTON_STORE_ALL)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: unknown store mode %d",
                       (int)o->store);
    if (o->shard_index >= shards)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: shard %u of %u does not exist "
                       "(shards count from 0)", (unsigned)o->shard_index, (unsigned)shards);
    if (o->tolerance > 0.0 && shards > 1)
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: -n auto cannot be sharded: the "
                       "shards need the count");
    if (!(o->tolerance >= 0.0 && o->tolerance < 1.0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "photons: tolerance %g is not in [0, 1)",
                       o->tolerance);
    return GB_OK;
}

static void make_tracer(const gb_photons_options *o, gb_photons_tracer *tracer)
{
    tracer->bounces = o->bounces ? o->bounces : GB_PHOTONS_DEFAULT_BOUNCES;
    tracer->roulette_start = GB_PHOTONS_ROULETTE_START < tracer->bounces
                                 ? GB_PHOTONS_ROULETTE_START
                                 : tracer->bounces;
    tracer->store = o->store;
}

typedef struct run_tables {
    gb_light_emission emission;
    gb_surface_table surfaces;
    gb_embree_scene *rays;
} run_tables;

static void free_tables(run_tables *t)
{
    gb_embree_scene_destroy(t->rays);
    if (t->surfaces.records)
        gb_surface_table_free(&t->surfaces);
    gb_light_emission_free(&t->emission);
}

/* The lights, the surfaces and the BVH. */
static gb_result build_tables(const gb_scene *scene, const gb_photons_options *options,
                              run_tables *t, gb_error *error)
{
    *t = (run_tables){0};
    gb_result result = gb_surface_table_build(scene, &t->surfaces, error);
    if (result == GB_OK)
        result = gb_light_emission_build(scene, &t->surfaces, GB_SKY_EMITTED, &t->emission, error);
    if (result == GB_OK)
        result = gb_embree_scene_create(scene, options->threads, &t->rays, error);
    if (result != GB_OK)
        free_tables(t);
    return result;
}

typedef struct run_times {
    double seconds, cpu_seconds, build_seconds;
} run_times;

static void fill_stats(const run_job *job, const run_times *times, int threads,
                       gb_photons_stats *stats)
{
    if (!stats)
        return;
    stats->paths = job->end - job->first;
    stats->rays = atomic_load(&job->rays);
    stats->stored = atomic_load(&job->stored);
    stats->escaped = atomic_load(&job->escaped);
    stats->nonfinite = atomic_load(&job->nonfinite);
    stats->seconds = times->seconds;
    stats->cpu_seconds = times->cpu_seconds;
    stats->build_seconds = times->build_seconds;
    stats->threads = threads;
}

static gb_result trace_job(run_job *job, const gb_photons_options *options, int *threads,
                           gb_photon_map *map, gb_error *error)
{
    job->chunk_count = (job->end - job->first + CHUNK_PHOTONS - 1) / CHUNK_PHOTONS;
    job->chunks = calloc(job->chunk_count ? job->chunk_count : 1, sizeof *job->chunks);
    if (!job->chunks)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photons: out of memory");
    gb_result result = run_threads(job, options, threads, error);
    if (result == GB_OK)
        result = join_chunks(job, map, error);
    for (uint64_t c = 0; c < job->chunk_count; ++c)
        gb_photons_sink_free(&job->chunks[c]);
    free(job->chunks);
    return result;
}

/* One run of emitted_count photons (this shard's part of it) into *map. */
static gb_result trace_run(const gb_scene *scene, const gb_photons_options *options,
                           const gb_photons_tracer *tracer, const run_tables *tables,
                           uint64_t emitted_count, gb_photon_map *map, run_job *job,
                           int *threads, gb_error *error)
{
    *job = (run_job){.tracer = tracer, .emission = &tables->emission, .seed = options->seed,
                     .emitted_count = emitted_count};
    gb_photon_shard_range(emitted_count, options->shard_index,
                          options->shard_count ? options->shard_count : 1, &job->first,
                          &job->end);
    gb_result result = trace_job(job, options, threads, map, error);
    if (result == GB_OK)
        fill_header(scene, options, tracer, job, &map->header);
    return result;
}

/* -n auto: runs of doubling counts until the flux probes settle; the last
 * run's map and job are kept. */
static gb_result trace_until_converged(const gb_scene *scene, const gb_photons_options *options,
                                       const gb_photons_tracer *tracer,
                                       const run_tables *tables, gb_photon_map *map,
                                       run_job *job, int *threads, uint32_t *passes,
                                       double *change, gb_error *error)
{
    gb_flux_probes earlier = {0}, later = {0};
    gb_result result = GB_OK;
    *change = 1.0;
    *passes = 0;
    for (uint64_t count = GB_PHOTONS_AUTO_FIRST_COUNT;
         result == GB_OK && count <= GB_PHOTONS_AUTO_LAST_COUNT && *change >= options->tolerance;
         count *= 2) {
        gb_photon_map_free(map);
        result = trace_run(scene, options, tracer, tables, count, map, job, threads, error);
        gb_flux_probes_free(&earlier);
        earlier = later;
        later = (gb_flux_probes){0};
        if (result == GB_OK)
            result = gb_flux_probes_measure(map, &later, error);
        if (result == GB_OK && ++*passes > 1)
            *change = gb_flux_probes_change(&earlier, &later);
    }
    gb_flux_probes_free(&earlier);
    gb_flux_probes_free(&later);
    return result;
}

gb_result gb_photons_trace(const gb_scene *scene, const gb_photons_options *options,
                           gb_photon_map *map, gb_photons_stats *stats, gb_error *error)
{
    *map = (gb_photon_map){0};
    gb_result result = check_options(options, error);
    if (result != GB_OK)
        return result;
    double start = gb_seconds();
    run_tables tables;
    result = build_tables(scene, options, &tables, error);
    if (result != GB_OK)
        return result;
    gb_photons_tracer tracer = {.rays = tables.rays, .surfaces = &tables.surfaces};
    make_tracer(options, &tracer);
    double traced = gb_seconds(), cpu = gb_cpu_seconds();
    int threads = 1;
    uint32_t passes = 1;
    double change = 0.0;
    run_job job = {0};
    if (options->tolerance > 0.0)
        result = trace_until_converged(scene, options, &tracer, &tables, map, &job, &threads,
                                       &passes, &change, error);
    else
        result = trace_run(scene, options, &tracer, &tables,
                           options->count ? options->count : GB_PHOTONS_DEFAULT_COUNT, map,
                           &job, &threads, error);
    run_times times = {gb_seconds() - traced, gb_cpu_seconds() - cpu, traced - start};
    fill_stats(&job, &times, threads, stats);
    if (stats) {
        stats->passes = passes;
        stats->change = change;
    }
    if (result != GB_OK)
        gb_photon_map_free(map);
    free_tables(&tables);
    return result;
}
