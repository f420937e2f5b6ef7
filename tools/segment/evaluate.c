/* evaluate.c — how well visibility clusters and gates predict visibility:
 * random pairs of surface points, the prediction from their clusters, the
 * truth from an Embree shadow ray (segment.h, gb_segment_evaluate). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "embree_scene.h"
#include "gate_pairs.h"
#include "random.h"
#include "scene_triangles.h"
#include "segment.h"

/* Pairs whose cosine at either end is below this exchange no light: drawn again. */
#define GRAZING_COSINE 1e-3f
enum { MAX_ATTEMPTS = 64 };

typedef struct surface_point {
    gb_vec3 position;
    gb_vec3 normal;             /* geometric, unit */
} surface_point;

typedef struct evaluation {
    const gb_scene *scene;
    const gb_segmentation *seg;
    const int32_t *nearest;
    gb_embree_scene *rays;
    double *area_cdf;           /* triangle_count prefix sums of areas */
    gb_gate_pairs gates;        /* for the one-gate predictor */
    float epsilon;              /* ray offset off the surfaces */
    uint64_t ray_count;
} evaluation;

static gb_result build_tables(evaluation *ev, gb_error *error)
{
    const gb_scene *scene = ev->scene;
    ev->area_cdf = malloc((scene->triangle_count + 1) * sizeof *ev->area_cdf);
    if (!ev->area_cdf)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for the sampling tables");
    double total = 0.0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        total += gb_triangle_area(scene, t);
        ev->area_cdf[t] = total;
    }
    if (!(total > 0.0))
        return gb_fail(error, GB_ERROR_INVALID, "the scene has no surface to sample");
    return gb_gate_pairs_build(ev->seg, &ev->gates, error);
}

/* The first triangle whose cumulated area exceeds u * total. */
static uint32_t pick_triangle(const evaluation *ev, double u)
{
    uint32_t count = ev->scene->triangle_count;
    double target = u * ev->area_cdf[count - 1];
    uint32_t low = 0, high = count - 1;
    while (low < high) {
        uint32_t middle = low + (high - low) / 2;
        if (ev->area_cdf[middle] > target)
            high = middle;
        else
            low = middle + 1;
    }
    return low;
}

static surface_point sample_point(const evaluation *ev, gb_random *rng)
{
    const gb_scene *scene = ev->scene;
    uint32_t t = pick_triangle(ev, gb_random_float(rng));
    const uint32_t *v = scene->indices + 3 * (size_t)t;
    gb_vec3 a = gb_vec3_load(scene->positions + 3 * (size_t)v[0]);
    gb_vec3 b = gb_vec3_load(scene->positions + 3 * (size_t)v[1]);
    gb_vec3 c = gb_vec3_load(scene->positions + 3 * (size_t)v[2]);
    float su = sqrtf(gb_random_float(rng)), u2 = gb_random_float(rng);
    float b1 = su * (1.0f - u2), b2 = su * u2;
    surface_point p;
    p.position = gb_vec3_madd(gb_vec3_madd(a, gb_vec3_sub(b, a), b1), gb_vec3_sub(c, a), b2);
    p.normal = gb_triangle_normal(scene, t);
    return p;
}

/* The normal of p turned towards q. */
static gb_vec3 facing(const surface_point *p, gb_vec3 q)
{
    return gb_vec3_dot(p->normal, gb_vec3_sub(q, p->position)) < 0.0f
               ? gb_vec3_negate(p->normal) : p->normal;
}

/* Looked up |normal|_1 voxels off the surface (out of the voxels the
 * surface itself touches, whose node thin takes from whichever side is
 * nearer a node, often the far side of the wall), then one and two voxels
 * further; the runtime's lookup (runtime/topo/topo_clusters.c). */
static int32_t cluster_near(const evaluation *ev, gb_vec3 position, gb_vec3 normal)
{
    float l1 = fabsf(normal.x) + fabsf(normal.y) + fabsf(normal.z);
    for (int step = 0; step < 3; ++step) {
        gb_vec3 off = gb_vec3_madd(position, normal,
                                   (1.01f * l1 + (float)step) * (float)ev->seg->voxel_size);
        double at[3] = {off.x, off.y, off.z};
        int32_t c = gb_segmentation_cluster_at(ev->seg, ev->nearest, at);
        if (c >= 0)
            return c;
    }
    double on[3] = {position.x, position.y, position.z};
    return gb_segmentation_cluster_at(ev->seg, ev->nearest, on);
}

/* Whether the segment [p, q] crosses the disk of gate g. */
static int crosses_gate(const gb_visibility_gate *g, gb_vec3 p, gb_vec3 q)
{
    gb_vec3 n = gb_vec3_load(g->normal), c = gb_vec3_load(g->centre), d = gb_vec3_sub(q, p);
    float denominator = gb_vec3_dot(d, n);
    if (denominator == 0.0f)
        return 0;
    float t = gb_vec3_dot(gb_vec3_sub(c, p), n) / denominator;
    if (!(t >= 0.0f && t <= 1.0f))
        return 0;
    gb_vec3 x = gb_vec3_madd(p, d, t);
    return gb_vec3_length(gb_vec3_sub(x, c)) <= g->radius;
}

static int through_one_gate(const evaluation *ev, uint32_t a, uint32_t b, gb_vec3 p, gb_vec3 q)
{
    uint32_t first, count = gb_gate_pairs_find(&ev->gates, a, b, &first);
    for (uint32_t i = first; i < first + count; ++i)
        if (crosses_gate(&ev->seg->gates[ev->gates.pairs[i].gate], p, q))
            return 1;
    return 0;
}

static int visible(evaluation *ev, gb_vec3 p, gb_vec3 q)
{
    gb_vec3 d = gb_vec3_sub(q, p);
    float distance = gb_vec3_length(d);
    if (!(distance > 0.0f))
        return 1;
    return !gb_embree_occluded(ev->rays, p, gb_vec3_scale(d, 1.0f / distance), 0.0f, distance,
                               &ev->ray_count);
}

static void score(gb_visibility_score *s, int predicted, int truth)
{
    if (predicted)
        ++*(truth ? &s->true_positive : &s->false_positive);
    else
        ++*(truth ? &s->false_negative : &s->true_negative);
}

/* Whether a and b can exchange light: neither lies (nearly) in the other's
 * plane, where the cosines of the geometric term vanish. */
static int facing_pair(const surface_point *a, const surface_point *b)
{
    gb_vec3 d = gb_vec3_sub(b->position, a->position);
    float length = gb_vec3_length(d);
    float limit = GRAZING_COSINE * length;
    return length > 0.0f && fabsf(gb_vec3_dot(a->normal, d)) >= limit &&
           fabsf(gb_vec3_dot(b->normal, d)) >= limit;
}

/* Draws pairs from the stream until one faces; 0 when none did. */
static int sample_pair(const evaluation *ev, gb_random *rng, surface_point *a, surface_point *b,
                       gb_segment_evaluation *out)
{
    for (int attempt = 0; attempt < MAX_ATTEMPTS; ++attempt) {
        *a = sample_point(ev, rng);
        *b = sample_point(ev, rng);
        if (facing_pair(a, b))
            return 1;
        ++out->grazing;
    }
    return 0;
}

static void evaluate_pair(evaluation *ev, uint64_t seed, uint64_t i, gb_segment_evaluation *out)
{
    gb_random rng = gb_random_make(seed, i);
    surface_point a, b;
    if (!sample_pair(ev, &rng, &a, &b, out))
        return;
    gb_vec3 na = facing(&a, b.position), nb = facing(&b, a.position);
    gb_vec3 p = gb_vec3_madd(a.position, na, ev->epsilon);
    gb_vec3 q = gb_vec3_madd(b.position, nb, ev->epsilon);
    int truth = visible(ev, p, q);
    int32_t ca = cluster_near(ev, a.position, na), cb = cluster_near(ev, b.position, nb);
    int located = ca >= 0 && cb >= 0, same = located && ca == cb;
    int gate = located && !same && through_one_gate(ev, (uint32_t)ca, (uint32_t)cb, p, q);
    ++out->pairs;
    out->visible += truth;
    out->unlocated += !located;
    score(&out->same_cluster, same, truth);
    score(&out->one_gate, same || gate, truth);
}

static gb_result run_pairs(evaluation *ev, const gb_segment_evaluate_options *options,
                           gb_segment_evaluation *out, gb_error *error)
{
    uint32_t pairs = options && options->pairs ? options->pairs : GB_SEGMENT_DEFAULT_PAIRS;
    uint64_t seed = options ? options->seed : 0;
    for (uint32_t i = 0; i < pairs; ++i) {
        if (options && options->progress && (i & 1023) == 0 &&
            options->progress(options->progress_user, (double)i / pairs))
            return gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
        evaluate_pair(ev, seed, i, out);
    }
    if (options && options->progress)
        options->progress(options->progress_user, 1.0);
    return GB_OK;
}

static float scene_epsilon(const gb_scene *scene)
{
    float d2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
        float d = scene->bounds_max[a] - scene->bounds_min[a];
        d2 += d * d;
    }
    return 1e-4f * sqrtf(d2);
}

gb_result gb_segment_evaluate(const gb_scene *scene, const gb_segmentation *segmentation,
                              const int32_t *nearest, const gb_segment_evaluate_options *options,
                              gb_segment_evaluation *out, gb_error *error)
{
    memset(out, 0, sizeof *out);
    if (scene->hash != segmentation->scene_hash)
        return gb_fail(error, GB_ERROR_STALE,
                       "the segmentation was made from another scene (hash %016llx, the "
                       "scene's is %016llx)", (unsigned long long)segmentation->scene_hash,
                       (unsigned long long)scene->hash);
    if (!scene->triangle_count)
        return gb_fail(error, GB_ERROR_INVALID, "the scene has no triangle");
    double start = gb_seconds();
    evaluation ev = {.scene = scene, .seg = segmentation, .nearest = nearest,
                     .epsilon = scene_epsilon(scene)};
    gb_result result = build_tables(&ev, error);
    if (!result)
        result = gb_embree_scene_create(scene, 1, &ev.rays, error);
    if (!result)
        result = run_pairs(&ev, options, out, error);
    if (ev.rays)
        gb_embree_scene_destroy(ev.rays);
    free(ev.area_cdf);
    gb_gate_pairs_free(&ev.gates);
    out->seconds = gb_seconds() - start;
    return result;
}

double gb_visibility_precision(const gb_visibility_score *s)
{
    uint64_t predicted = s->true_positive + s->false_positive;
    return predicted ? (double)s->true_positive / (double)predicted : 1.0;
}

double gb_visibility_recall(const gb_visibility_score *s)
{
    uint64_t actual = s->true_positive + s->false_negative;
    return actual ? (double)s->true_positive / (double)actual : 1.0;
}
