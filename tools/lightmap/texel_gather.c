/* texel_gather.c — the lightmap's texels by final gather, the side each
 * triangle keeps chosen by probes (texel_gather.h). */
#include "texel_gather.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "final_gather.h"
#include "texel_surface.h"
#include "work_queue.h"

static const double INSET = 1e-3;    /* weights_inside */

typedef struct pass {
    const gb_texel_gather *options;
    gb_final_gather gather;
    int32_t *openness;              /* probes: per texel, back side's minus front side's */
    const int8_t *kept;             /* gather: per triangle, 1 for the back side */
    gb_image *image;
    _Atomic uint64_t rays;
} pass;

/* The random state of stream k (0, 1: the sides' probes; 2: the gather)
 * of texel i. */
static gb_path_state texel_state(const pass *p, size_t i, int k)
{
    gb_path_state state = {.rng = gb_random_make(p->options->seed, 3 * (uint64_t)i + (uint64_t)k)};
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
        gb_texel_barycentric(p->options->atlas, t, i, row, w);
        weights_inside(w);
        rays += visit(p, texel, t, w);
    }
    atomic_fetch_add(&p->rays, rays);
}

/* How far triangle t's rays leave its surface (surface.h's offset). */
static float offset_of(const pass *p, uint32_t t)
{
    return p->gather.paths.surfaces->records[t].offset;
}

static uint64_t probe_texel(pass *p, size_t texel, uint32_t t, const double w[3])
{
    uint64_t rays = 0;
    int openness[2];
    for (int k = 0; k < 2; ++k) {
        gb_texel_surface s = gb_texel_surface_at(p->options->scene, t, w, k ? -1.0f : 1.0f);
        gb_path_state state = texel_state(p, texel, k);
        openness[k] = gb_final_gather_openness(&p->gather, &s, offset_of(p, t),
                                               GB_TEXEL_GATHER_PROBES, &state);
        rays += state.rays;
    }
    p->openness[texel] = openness[1] - openness[0];
    return rays;
}

static uint64_t gather_texel(pass *p, size_t texel, uint32_t t, const double w[3])
{
    float side = p->kept[t] ? -1.0f : 1.0f;
    gb_texel_surface s = gb_texel_surface_at(p->options->scene, t, w, side);
    gb_path_state state = texel_state(p, texel, 2);
    gb_final_gather_irradiance(&p->gather, &s, offset_of(p, t),
                               p->options->rays, &state, p->image->pixels + 3 * texel);
    return state.rays;
}

static int probe_row(void *context, uint64_t row)
{
    visit_row(context, (uint32_t)row, probe_texel);
    return 0;
}

static int gather_row(void *context, uint64_t row)
{
    visit_row(context, (uint32_t)row, gather_texel);
    return 0;
}

/* kept[t]: 1 when the back of triangle t is the more open over its texels. */
static gb_result keep_sides(const pass *p, int8_t *kept, gb_error *error)
{
    const gb_texel_cover *cover = p->options->cover;
    uint32_t triangles = p->options->scene->triangle_count;
    int64_t *votes = calloc(triangles, sizeof *votes);
    if (!votes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    for (size_t k = 0; k < (size_t)cover->width * cover->height; ++k)
        if (cover->triangle[k] != GB_TEXEL_NONE)
            votes[cover->triangle[k]] += p->openness[k];
    for (uint32_t t = 0; t < triangles; ++t)
        kept[t] = votes[t] > 0;
    free(votes);
    return GB_OK;
}

static float scene_diagonal(const gb_scene *scene)
{
    float squares = 0.0f;
    for (int k = 0; k < 3; ++k)
        squares += (scene->bounds_max[k] - scene->bounds_min[k]) *
                   (scene->bounds_max[k] - scene->bounds_min[k]);
    return sqrtf(squares);
}

static gb_result run_rows(const gb_texel_gather *options, gb_work_item_function row,
                          pass *p, int with_progress, int *threads, gb_error *error)
{
    gb_work_queue queue = {.item_count = options->cover->height, .threads = options->threads,
                           .progress = with_progress ? options->progress : NULL,
                           .progress_user = options->progress_user};
    if (gb_work_queue_run(&queue, row, p, threads) != GB_OK)
        return gb_fail(error, GB_ERROR_INTERRUPTED, "lightmap: interrupted");
    return GB_OK;
}

gb_result gb_texel_gather_bake(const gb_texel_gather *options, gb_image *image, uint64_t *rays,
                               int *threads, gb_error *error)
{
    gb_path_tables tables;
    gb_result result = gb_path_tables_build(options->scene, options->threads, &tables, error);
    const gb_texel_cover *cover = options->cover;
    pass p = {
        .options = options,
        .gather = {.paths = gb_path_tracer_over(options->scene, &tables),
                   .octree = options->octree,
                   .max_bounces = GB_TEXEL_GATHER_PATH_BOUNCES,
                   .octree_bounces = options->octree_bounces,
                   .near_distance = GB_TEXEL_GATHER_NEAR_FRACTION *
                                    scene_diagonal(options->scene)},
        .openness = malloc((size_t)cover->width * cover->height * sizeof(int32_t)),
        .image = image,
    };
    int8_t *kept = malloc(options->scene->triangle_count + 1);
    p.kept = kept;
    if (result == GB_OK && (!p.openness || !kept))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    if (result == GB_OK)
        result = run_rows(options, probe_row, &p, 0, threads, error);
    if (result == GB_OK)
        result = keep_sides(&p, kept, error);
    if (result == GB_OK)
        result = run_rows(options, gather_row, &p, 1, threads, error);
    *rays += p.rays;
    free(kept);
    free(p.openness);
    gb_path_tables_free(&tables);
    return result;
}
