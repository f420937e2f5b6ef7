/* cluster.c — the loop of vivianloc-2007 Figure 4 over the octree leaves, in
 * chunks: FLANN answers a chunk's KNN queries, then threads take its leaves
 * one by one, gather and cluster each into that leaf's own VDL slots
 * (cluster.h). */
#include "cluster.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gathering.h"
#include "halo.h"
#include "octree.h"
#include "threads.h"
#include "vdl.h"

enum { CHUNK_LEAVES = 2048 };

/* Zeroed fields take their defaults. */
static gb_result resolve_options(const gb_cluster_options *in, gb_cluster_options *o,
                                 gb_error *error)
{
    *o = in ? *in : (gb_cluster_options){0};
    o->depth = o->depth ? o->depth : GB_CLUSTER_DEFAULT_DEPTH;
    o->knn = o->knn ? o->knn : GB_CLUSTER_DEFAULT_KNN;
    o->vdls_max = o->vdls_max ? o->vdls_max : GB_CLUSTER_DEFAULT_VDLS;
    o->restarts = o->restarts ? o->restarts : 1;
    o->tolerance = o->tolerance != 0.0f ? o->tolerance : GB_CLUSTER_DEFAULT_TOLERANCE;
    if (o->threads <= 0) {
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        o->threads = cores > 0 ? (int)cores : 1;
    }
    if (o->depth > GB_LIGHT_OCTREE_MAX_DEPTH || o->vdls_max > GB_LIGHT_OCTREE_MAX_VDLS ||
        o->knn > 100000 || !(o->radius >= 0.0f) || !(o->tolerance <= 180.0f) ||
        o->threads > 256 || o->restarts > 64 || (o->part_count > 1 && o->part >= o->part_count))
        return gb_fail(error, GB_ERROR_ARGUMENT, "cluster: bad options (depth 1..%d, K "
                       "1..100000, K_max 1..%d, R >= 0, tolerance <= 180, restarts <= 64, "
                       "part < parts)",
                       GB_LIGHT_OCTREE_MAX_DEPTH, GB_LIGHT_OCTREE_MAX_VDLS);
    return GB_OK;
}

/* ---- one chunk of leaves ---- */

typedef struct chunk_job {
    const gb_octree_leaves *leaves;
    const gb_gathering *gathering;
    const gb_cluster_options *options;
    float max_radius, min_radius;
    uint32_t first, count;              /* leaves [first, first + count) */
    const float *centres;               /* count x 3 */
    const int *indices;                 /* count x K */
    const float *distances2;
    gb_light_octree_vdl *slots;         /* leaf_count x K_max */
    uint32_t *vdl_counts;               /* leaf_count */
    double *errors, *spreads, *gathered;    /* leaf_count */
    atomic_uint next;
    atomic_int failed;
} chunk_job;

static void cluster_leaf(chunk_job *job, gb_vdl_workspace *w, uint32_t *kept, uint32_t j)
{
    uint32_t leaf = job->first + j, K = job->gathering->knn;
    float radius = job->max_radius;
    uint32_t n = gb_gather_ellipsoid(job->gathering, &job->centres[3 * (size_t)j],
                                     &job->leaves->normals[3 * (size_t)leaf],
                                     &job->indices[(size_t)j * K],
                                     &job->distances2[(size_t)j * K], job->max_radius,
                                     job->min_radius, GB_CLUSTER_FLATTENING, kept, &radius);
    gb_vdl_workspace_load(w, job->gathering->map, kept, n);
    gb_random rng = gb_random_make(job->options->seed, leaf);
    gb_surface_normal normals[GB_SURFACE_NORMALS];
    vdl_target target = {.radius = radius, .normals = normals,
                         .tolerance = job->options->tolerance};
    memcpy(target.leaf_normal, &job->leaves->normals[3 * (size_t)leaf], sizeof target.leaf_normal);
    target.normal_count = gb_octree_shading_normals(job->leaves, leaf, normals);
    job->vdl_counts[leaf] = gb_vdls_from_photons(
        w, &target, &rng, &job->slots[(size_t)leaf * job->options->vdls_max],
        &job->errors[leaf]);
    job->spreads[leaf] = n ? gb_kmeans_spread(w->directions, w->weights, w->count,
                                              w->centroids, w->assignment)
                           : 0.0;
    job->gathered[leaf] = n;
}

/* One of the threads of run_chunk: leaves taken one at a time. */
static void chunk_worker(void *context, int thread, int thread_count)
{
    (void)thread;
    (void)thread_count;
    chunk_job *job = context;
    uint32_t K = job->gathering->knn;
    gb_vdl_workspace w;
    uint32_t *kept = malloc((K ? K : 1) * sizeof *kept);
    if (!kept || gb_vdl_workspace_create(&w, K, job->options->vdls_max, NULL) != GB_OK) {
        free(kept);
        atomic_store(&job->failed, 1);
        return;
    }
    w.kmeans.restarts = job->options->restarts;
    for (uint32_t j; (j = atomic_fetch_add(&job->next, 1)) < job->count;)
        cluster_leaf(job, &w, kept, j);
    gb_vdl_workspace_free(&w);
    free(kept);
}

static gb_result run_chunk(chunk_job *job, int threads, gb_error *error)
{
    atomic_store(&job->next, 0);
    gb_run_threads(chunk_worker, job, threads);
    if (atomic_load(&job->failed))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    return GB_OK;
}

/* ---- every leaf ---- */

void gb_cluster_part_leaves(uint32_t leaf_count, uint32_t part, uint32_t part_count,
                            uint32_t *first, uint32_t *end)
{
    if (part_count <= 1 || part >= part_count) {
        *first = 0;
        *end = leaf_count;
        return;
    }
    *first = (uint32_t)((uint64_t)leaf_count * part / part_count);
    *end = (uint32_t)((uint64_t)leaf_count * (part + 1) / part_count);
}

/* R: the option, or by default a multiple of the leaf edge. */
static float gathering_radius(const gb_octree_leaves *leaves, const gb_cluster_options *o)
{
    return o->radius > 0.0f ? o->radius
                            : GB_CLUSTER_DEFAULT_RADIUS_LEAVES * gb_octree_leaf_edge(leaves);
}

typedef struct leaf_results {
    gb_light_octree_vdl *slots;
    uint32_t *vdl_counts;
    double *errors, *spreads, *gathered;
} leaf_results;

static gb_result allocate_results(uint32_t leaf_count, uint32_t vdls_max, leaf_results *r,
                                  gb_error *error)
{
    size_t n = leaf_count ? leaf_count : 1;
    r->slots = malloc(n * vdls_max * sizeof *r->slots);
    r->vdl_counts = calloc(n, sizeof *r->vdl_counts);
    r->errors = calloc(n, sizeof *r->errors);
    r->spreads = calloc(n, sizeof *r->spreads);
    r->gathered = calloc(n, sizeof *r->gathered);
    if (!r->slots || !r->vdl_counts || !r->errors || !r->spreads || !r->gathered)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    return GB_OK;
}

static void free_results(leaf_results *r)
{
    free(r->slots);
    free(r->vdl_counts);
    free(r->errors);
    free(r->spreads);
    free(r->gathered);
}

typedef struct chunk_buffers {
    float *centres;
    int *indices;
    float *distances2;
} chunk_buffers;

static gb_result cluster_chunk(chunk_job *job, chunk_buffers *b, gb_cluster_stats *stats,
                               gb_error *error)
{
    for (uint32_t j = 0; j < job->count; ++j)
        memcpy(&b->centres[3 * (size_t)j], &job->leaves->points[3 * (size_t)(job->first + j)],
               3 * sizeof(float));
    double start = gb_seconds();
    gb_result result = gb_gathering_knn(job->gathering, b->centres, job->count, b->indices,
                                        b->distances2, error);
    double middle = gb_seconds();
    if (result == GB_OK)
        result = run_chunk(job, job->options->threads, error);
    stats->query_seconds += middle - start;
    stats->kmeans_seconds += gb_seconds() - middle;
    stats->queries += job->count;
    return result;
}

static gb_result cluster_leaves(const gb_octree_leaves *leaves, const gb_gathering *gathering,
                                const gb_cluster_options *o, leaf_results *r,
                                gb_cluster_stats *stats, gb_error *error)
{
    size_t K = gathering->knn ? gathering->knn : 1;
    chunk_buffers b = {malloc(3 * CHUNK_LEAVES * sizeof(float)),
                       malloc(CHUNK_LEAVES * K * sizeof(int)),
                       malloc(CHUNK_LEAVES * K * sizeof(float))};
    gb_result result = GB_OK;
    if (!b.centres || !b.indices || !b.distances2)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    float edge = gb_octree_leaf_edge(leaves);
    chunk_job job = {.leaves = leaves, .gathering = gathering, .options = o,
                     .max_radius = gathering_radius(leaves, o), .min_radius = 1e-4f * edge,
                     .centres = b.centres, .indices = b.indices, .distances2 = b.distances2,
                     .slots = r->slots, .vdl_counts = r->vdl_counts, .errors = r->errors, .spreads = r->spreads,
                     .gathered = r->gathered};
    uint32_t begin, end;
    gb_cluster_part_leaves(leaves->count, o->part, o->part_count, &begin, &end);
    for (uint32_t first = begin; first < end && result == GB_OK; first += CHUNK_LEAVES) {
        job.first = first;
        job.count = end - first < CHUNK_LEAVES ? end - first : CHUNK_LEAVES;
        result = cluster_chunk(&job, &b, stats, error);
        if (result == GB_OK && o->progress &&
            o->progress(o->progress_user, (double)(first + job.count - begin) / (end - begin)))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "cluster: interrupted");
    }
    free(b.centres);
    free(b.indices);
    free(b.distances2);
    return result;
}

/* ---- the octree ---- */

static void fill_header(const gb_scene *scene, const gb_photon_map *map,
                        const gb_octree_leaves *leaves, const gb_cluster_options *o,
                        gb_light_octree_header *h)
{
    memset(h, 0, sizeof *h);
    h->depth = leaves->depth;
    memcpy(h->origin, leaves->origin, sizeof h->origin);
    h->size = leaves->size;
    h->scene_hash = scene->hash;
    h->photon_count = map->count;
    h->emitted_count = map->header.emitted_count;
    h->seed = o->seed;
    h->knn = o->knn;
    h->radius = gathering_radius(leaves, o);
    h->vdls_max = o->vdls_max;
    h->tolerance = o->tolerance < 0.0f ? -1.0f : o->tolerance;
    h->flattening = GB_CLUSTER_FLATTENING;
    h->interpolation = o->interpolation;
}

/* The leaf's plane (light_octree.h): the offset along its normal of the
 * point it gathered at from its cell's centre, in cell edges (under
 * sqrt(3)/2: the point is on a triangle touching the cell), fixed point. */
static int16_t leaf_plane(const gb_octree_leaves *leaves, uint32_t i, const uint32_t cell[3])
{
    double edge = (double)leaves->size / (double)(1u << leaves->depth), offset = 0.0;
    for (int k = 0; k < 3; ++k)
        offset += leaves->normals[3 * (size_t)i + k] *
                  (leaves->points[3 * (size_t)i + k] -
                   (leaves->origin[k] + ((double)cell[k] + 0.5) * edge));
    offset = fmax(-1.0, fmin(1.0, offset / edge));
    return (int16_t)lrint(offset * GB_LIGHT_OCTREE_PLANE_ONE);
}

/* Packs nodes, leaves and the VDLs of every leaf, one after the other, into
 * one block owned by the octree. */
static gb_result assemble(const gb_octree_leaves *leaves, const gb_light_octree_node *nodes,
                          const leaf_results *r, gb_light_octree *octree, gb_error *error)
{
    gb_light_octree_header *h = &octree->header;
    h->vdl_count = 0;
    for (uint32_t i = 0; i < leaves->count; ++i)
        h->vdl_count += r->vdl_counts[i];
    size_t node_bytes = (size_t)h->node_count * sizeof *octree->nodes;
    size_t leaf_bytes = (size_t)h->leaf_count * sizeof *octree->leaves;
    unsigned char *block = malloc(node_bytes + leaf_bytes + (size_t)h->vdl_count * 16 + 16);
    if (!block)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    gb_light_octree_node *n = (void *)block;
    gb_light_octree_leaf *l = (void *)(block + node_bytes);
    gb_light_octree_vdl *v = (void *)(block + node_bytes + leaf_bytes);
    memcpy(n, nodes, node_bytes);
    for (uint32_t i = 0, next = 0; i < leaves->count; ++i) {
        uint32_t cell[3];
        gb_octree_leaf_cell(leaves, i, cell);
        l[i].normal = gb_photon_pack_direction(&leaves->normals[3 * (size_t)i]);
        l[i].plane = leaf_plane(leaves, i, cell);
        l[i].cell = gb_light_octree_pack_cell(cell);
        l[i].first_vdl = next;
        l[i].vdl_count = r->vdl_counts[i];
        memcpy(&v[next], &r->slots[(size_t)i * h->vdls_max], r->vdl_counts[i] * sizeof *v);
        next += r->vdl_counts[i];
    }
    octree->storage = block;
    octree->nodes = n;
    octree->leaves = l;
    octree->vdls = v;
    return GB_OK;
}

static void summarize(const leaf_results *r, uint32_t leaf_count, gb_cluster_stats *s)
{
    double gathered = 0.0, error = 0.0, spread = 0.0;
    uint32_t lit = 0;
    for (uint32_t i = 0; i < leaf_count; ++i) {
        ++s->vdl_histogram[r->vdl_counts[i]];
        s->vdls += r->vdl_counts[i];
        gathered += r->gathered[i];
        if (r->vdl_counts[i]) {
            error += r->errors[i];
            spread += r->spreads[i];
            ++lit;
        }
    }
    s->leaves = leaf_count;
    s->mean_gathered = leaf_count ? gathered / leaf_count : 0.0;
    s->mean_error = lit ? error / lit : 0.0;
    s->mean_spread = lit ? spread / lit : 0.0;
}

static gb_result check_inputs(const gb_scene *scene, const gb_photon_map *map,
                              gb_error *error)
{
    gb_result result = gb_photon_map_check_scene(map, scene->hash, "photon map", error);
    if (result == GB_OK)
        result = gb_photon_map_check(map, "photon map", error);
    return result;
}

/* The photons the part's leaves can gather (halo.h); the whole map's pages
 * are given back, as the part reads only the halo from then on. */
static gb_result part_halo(const gb_photon_map *map, const gb_octree_leaves *leaves,
                           const gb_cluster_options *o, gb_photon_map *halo, gb_error *error)
{
    uint32_t first, end;
    gb_cluster_part_leaves(leaves->count, o->part, o->part_count, &first, &end);
    gb_result result = gb_cluster_halo(map, leaves->points, first, end,
                                       gathering_radius(leaves, o), halo, error);
    if (result == GB_OK)
        gb_photon_map_release_pages(map);
    return result;
}

static gb_result build_octree(const gb_scene *scene, const gb_photon_map *map,
                              const gb_cluster_options *o, const gb_octree_leaves *leaves,
                              gb_light_octree *octree, gb_cluster_stats *stats,
                              gb_error *error)
{
    gb_light_octree_node *nodes = NULL;
    fill_header(scene, map, leaves, o, &octree->header);
    octree->header.leaf_count = leaves->count;
    gb_result result = gb_octree_nodes(leaves, &nodes, &octree->header.node_count, error);
    double start = gb_seconds();
    gb_photon_map halo = {0};
    const gb_photon_map *gathered = map;
    if (result == GB_OK && o->part_count > 1) {
        result = part_halo(map, leaves, o, &halo, error);
        gathered = &halo;
    }
    gb_gathering gathering = {0};
    uint32_t K = map->count < o->knn ? (uint32_t)map->count : o->knn;
    if (result == GB_OK)
        result = gb_gathering_build(gathered, K, o->threads, &gathering, error);
    stats->index_seconds = gb_seconds() - start;
    stats->indexed = gathered->count;
    leaf_results r = {0};
    if (result == GB_OK)
        result = allocate_results(leaves->count, o->vdls_max, &r, error);
    if (result == GB_OK)
        result = cluster_leaves(leaves, &gathering, o, &r, stats, error);
    if (result == GB_OK)
        result = assemble(leaves, nodes, &r, octree, error);
    if (result == GB_OK)
        summarize(&r, leaves->count, stats);
    gb_gathering_free(&gathering);
    gb_photon_map_free(&halo);
    free_results(&r);
    free(nodes);
    return result;
}

gb_result gb_cluster_build(const gb_scene *scene, const gb_photon_map *map,
                           const gb_cluster_options *options, gb_light_octree *octree,
                           gb_cluster_stats *stats, gb_error *error)
{
    memset(octree, 0, sizeof *octree);
    gb_cluster_stats local;
    stats = stats ? stats : &local;
    memset(stats, 0, sizeof *stats);
    double start = gb_seconds();
    gb_cluster_options o;
    gb_result result = resolve_options(options, &o, error);
    if (result == GB_OK)
        result = check_inputs(scene, map, error);
    stats->threads = o.threads;
    gb_octree_leaves leaves = {0};
    if (result == GB_OK)
        result = gb_octree_build(scene, o.depth, &leaves, error);
    stats->octree_seconds = gb_seconds() - start;
    if (result == GB_OK)
        result = build_octree(scene, map, &o, &leaves, octree, stats, error);
    gb_octree_leaves_free(&leaves);
    if (result != GB_OK)
        gb_light_octree_free(octree);
    stats->seconds = gb_seconds() - start;
    return result;
}
