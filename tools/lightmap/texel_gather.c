/* texel_gather.c — the lightmap's texels by final gather, the side each
 * triangle keeps chosen by probes (texel_gather.h). */
#include "texel_gather.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "final_gather.h"
#include "texel_interpolation.h"
#include "texel_surface.h"
#include "work_queue.h"

static const double INSET = 1e-3;    /* weights_inside */

typedef struct pass {
    const gb_texel_gather *options;
    gb_final_gather gather;
    uint32_t *texels;               /* probes: per triangle, the texels it covers */
    int8_t *kept;                   /* per triangle, 1 for the back side: the probes' */
    float *distance;                /* gather: per texel, its R (texel_interpolation.h) */
    int top_stride;                 /* 1 when every texel gathers */
    int stride;                     /* the pass's: its texels' gb_texel_stride */
    gb_image *image;
    _Atomic uint64_t rays;
} pass;

/* The random state of texel i's gather. */
static gb_path_state texel_state(const pass *p, size_t i)
{
    gb_path_state state = {.rng = gb_random_make(p->options->seed, (uint64_t)i)};
    return state;
}

/* The random state of the probes of triangle t's side k (0 the front),
 * streams after the texels'. */
static gb_path_state probe_state(const pass *p, uint32_t t, int k)
{
    uint64_t texels = (uint64_t)p->options->cover->width * p->options->cover->height;
    gb_path_state state = {.rng = gb_random_make(p->options->seed,
                                                 texels + 2 * (uint64_t)t + (uint64_t)k)};
    return state;
}

/* Weights w moved into their triangle: a texel of the reach (its centre
 * past the triangle's edge) stands for the nearest part of the triangle,
 * not for the plane beyond it, which may lie behind another wall or inside
 * a solid, whose darkness would bleed into the chart's edge through the
 * display's bilinear reads. Negative weights go to 0, then every weight
 * moves 10^-3 of the way to the centroid, so that no ray starts on the
 * wall an edge meets. */
static void weights_inside(double w[3])
{
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
        sum += w[c] = w[c] > 0.0 ? w[c] : 0.0;
    for (int c = 0; c < 3; ++c)
        w[c] = (1.0 - INSET) * (sum > 0.0 ? w[c] / sum : 1.0 / 3.0) + INSET / 3.0;
}

/* The weights of texel (i, j)'s centre in triangle t, moved inside. */
static void texel_weights(const pass *p, uint32_t t, uint32_t i, uint32_t j, double w[3])
{
    gb_texel_barycentric(p->options->atlas, t, i, j, w);
    weights_inside(w);
}

/* Calls visit(p, texel, triangle, weights) for each covered texel of row
 * `row` (weights_inside), and counts the rays its states traced. */
typedef uint64_t (*texel_visit)(pass *p, size_t texel, uint32_t t, const double w[3]);

static void visit_row(pass *p, uint32_t row, texel_visit visit)
{
    const gb_texel_cover *cover = p->options->cover;
    uint64_t rays = 0;
    for (uint32_t i = 0; i < cover->width; ++i) {
        size_t texel = (size_t)row * cover->width + i;
        uint32_t t = cover->triangle[texel];
        if (t == GB_TEXEL_NONE)
            continue;
        double w[3];
        texel_weights(p, t, i, row, w);
        rays += visit(p, texel, t, w);
    }
    atomic_fetch_add(&p->rays, rays);
}

/* How far triangle t's rays leave its surface (surface.h's offset). */
static float offset_of(const pass *p, uint32_t t)
{
    return p->gather.paths.surfaces->records[t].offset;
}

/* Weights of a point drawn uniformly over a triangle, moved inside
 * (weights_inside). */
static void uniform_weights(gb_path_state *state, double w[3])
{
    double r = sqrt(gb_path_uniform(state)), u = gb_path_uniform(state);
    w[0] = 1.0 - r;
    w[1] = r * (1.0 - u);
    w[2] = r * u;
    weights_inside(w);
}

/* kept[t]: 1 when the back of triangle t is the more open, by probes at
 * points drawn over it, one direction each. */
static int probe_triangle(void *context, uint64_t item)
{
    pass *p = context;
    uint32_t t = (uint32_t)item;
    uint32_t texels = p->texels[t];
    uint32_t probes = texels == 0                            ? 0
                      : texels < GB_TEXEL_GATHER_MIN_PROBES ? GB_TEXEL_GATHER_MIN_PROBES
                      : texels > GB_TEXEL_GATHER_MAX_PROBES ? GB_TEXEL_GATHER_MAX_PROBES
                                                            : texels;
    int openness[2] = {0, 0};
    uint64_t rays = 0;
    for (int k = 0; k < 2; ++k) {
        gb_path_state state = probe_state(p, t, k);
        for (uint32_t m = 0; m < probes; ++m) {
            double w[3];
            uniform_weights(&state, w);
            gb_texel_surface s = gb_texel_surface_at(p->options->scene, t, w, k ? -1.0f : 1.0f);
            openness[k] += gb_final_gather_openness(&p->gather, &s, offset_of(p, t), 1, &state);
        }
        rays += state.rays;
    }
    p->kept[t] = openness[1] > openness[0];
    atomic_fetch_add(&p->rays, rays);
    return 0;
}

/* The surface at weights w of triangle t, on the side it keeps. */
static gb_texel_surface kept_surface(const pass *p, uint32_t t, const double w[3])
{
    return gb_texel_surface_at(p->options->scene, t, w, p->kept[t] ? -1.0f : 1.0f);
}

/* Texel (i, j) as the mean of its corners (texel_interpolation.h) when
 * Ward's error allows; 0 when it must gather. */
static int interpolate_texel(pass *p, uint32_t i, uint32_t j, uint32_t t,
                             const gb_texel_surface *s)
{
    const gb_texel_cover *cover = p->options->cover;
    const uint32_t *charts = p->options->atlas->charts;
    gb_texel_corner corners[4];
    int count = gb_texel_corners(i, j, p->stride, cover->width, cover->height, corners);
    float value[3] = {0.0f, 0.0f, 0.0f}, distance = INFINITY;
    for (int k = 0; k < count; ++k) {
        size_t corner = (size_t)corners[k].j * cover->width + corners[k].i;
        uint32_t tk = cover->triangle[corner];
        if (tk == GB_TEXEL_NONE || charts[tk] != charts[t] || p->kept[tk] != p->kept[t])
            return 0;
        double wk[3];
        texel_weights(p, tk, corners[k].i, corners[k].j, wk);
        gb_texel_surface sk = kept_surface(p, tk, wk);
        if (gb_ward_error(s->x, s->n, sk.x, sk.n, p->distance[corner]) > p->options->accuracy)
            return 0;
        for (int c = 0; c < 3; ++c)
            value[c] += (float)corners[k].weight * p->image->pixels[3 * corner + c];
        distance = fminf(distance, p->distance[corner]);
    }
    if (count == 0)
        return 0;
    size_t texel = (size_t)j * cover->width + i;
    for (int c = 0; c < 3; ++c)
        p->image->pixels[3 * texel + c] = value[c];
    p->distance[texel] = distance;
    return 1;
}

static uint64_t gather_texel(pass *p, size_t texel, uint32_t t, const double w[3])
{
    uint32_t i = (uint32_t)(texel % p->options->cover->width);
    uint32_t j = (uint32_t)(texel / p->options->cover->width);
    if (gb_texel_stride(i, j, p->top_stride) != p->stride)
        return 0;
    gb_texel_surface s = kept_surface(p, t, w);
    if (p->stride < p->top_stride && interpolate_texel(p, i, j, t, &s))
        return 0;
    gb_path_state state = texel_state(p, texel);
    p->distance[texel] = gb_final_gather_irradiance(&p->gather, &s, offset_of(p, t),
                                                    p->options->rays, &state,
                                                    p->image->pixels + 3 * texel);
    return state.rays;
}

static int gather_row(void *context, uint64_t row)
{
    pass *p = context;
    if (row % (uint64_t)p->stride == 0)
        visit_row(p, (uint32_t)row, gather_texel);
    return 0;
}

/* texels[t]: the texels triangle t covers. */
static void count_texels(const gb_texel_cover *cover, uint32_t *texels)
{
    for (size_t k = 0; k < (size_t)cover->width * cover->height; ++k)
        if (cover->triangle[k] != GB_TEXEL_NONE)
            ++texels[cover->triangle[k]];
}

static float scene_diagonal(const gb_scene *scene)
{
    float squares = 0.0f;
    for (int k = 0; k < 3; ++k)
        squares += (scene->bounds_max[k] - scene->bounds_min[k]) *
                   (scene->bounds_max[k] - scene->bounds_min[k]);
    return sqrtf(squares);
}

/* The progress of pass `pass` of `passes`, as a fraction of them all. */
typedef struct pass_progress {
    const gb_texel_gather *options;
    int pass, passes;
} pass_progress;

static int report_pass_progress(void *user, double fraction)
{
    const pass_progress *progress = user;
    return progress->options->progress(progress->options->progress_user,
                                       (progress->pass + fraction) / progress->passes);
}

/* run(p, k) for k in 0 .. items - 1 on the work queue. */
static gb_result run_items(const gb_texel_gather *options, uint64_t items,
                           gb_work_item_function run, pass *p, pass_progress *progress,
                           int *threads, gb_error *error)
{
    gb_work_queue queue = {.item_count = items, .threads = options->threads,
                           .progress = progress && options->progress ? report_pass_progress
                                                                     : NULL,
                           .progress_user = progress};
    if (gb_work_queue_run(&queue, run, p, threads) != GB_OK)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "lightmap: interrupted");
    return GB_OK;
}

/* The gather passes, coarsest lattice first (texel_interpolation.h). */
static gb_result run_gather_passes(pass *p, int *threads, gb_error *error)
{
    pass_progress progress = {.options = p->options};
    for (int stride = p->top_stride; stride >= 1; stride /= 2)
        ++progress.passes;
    gb_result result = GB_OK;
    for (p->stride = p->top_stride; p->stride >= 1 && result == GB_OK;
         p->stride /= 2, ++progress.pass)
        result = run_items(p->options, p->options->cover->height, gather_row, p, &progress,
                           threads, error);
    return result;
}

gb_result gb_texel_gather_bake(const gb_texel_gather *options, gb_image *image, uint64_t *rays,
                               int *threads, gb_error *error)
{
    gb_path_tables tables;
    gb_result result = gb_path_tables_build(options->scene, options->threads, &tables, error);
    const gb_texel_cover *cover = options->cover;
    size_t texels = (size_t)cover->width * cover->height;
    pass p = {
        .options = options,
        .gather = {.paths = gb_path_tracer_over(options->scene, &tables),
                   .octree = options->octree,
                   .max_bounces = GB_TEXEL_GATHER_PATH_BOUNCES,
                   .octree_bounces = options->octree_bounces,
                   .near_distance = GB_TEXEL_GATHER_NEAR_FRACTION *
                                    scene_diagonal(options->scene)},
        .texels = calloc(options->scene->triangle_count + 1, sizeof(uint32_t)),
        .kept = malloc(options->scene->triangle_count + 1),
        .distance = malloc(texels * sizeof(float)),
        .top_stride = options->accuracy > 0.0 ? GB_TEXEL_TOP_STRIDE : 1,
        .image = image,
    };
    if (result == GB_OK && (!p.texels || !p.kept || !p.distance))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    if (result == GB_OK) {
        count_texels(cover, p.texels);
        result = run_items(options, options->scene->triangle_count, probe_triangle, &p, NULL,
                           threads, error);
    }
    if (result == GB_OK)
        result = run_gather_passes(&p, threads, error);
    *rays += p.rays;
    free(p.texels);
    free(p.kept);
    free(p.distance);
    gb_path_tables_free(&tables);
    return result;
}
