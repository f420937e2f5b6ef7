/* atlas_build.c — the atlas steps in order, the fixed-point UVs and the
 * repair rounds (atlas_build.h). */
#include "atlas_build.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "charts.h"
#include "discs.h"
#include "merge.h"
#include "overlap.h"
#include "packing.h"
#include "parameterize.h"
#include "triangle_geometry.h"

typedef struct builder {
    const gb_scene *scene;
    gb_atlas_options options;
    gb_mesh_adjacency adjacency;
    uint32_t *local_of;         /* discs.h's scratch */
    gb_chart_list list;
    gb_parameterize_context parameterize;
    gb_packing packing;
    int64_t *fixed;             /* 6 per scene triangle: its UVs in fixed point */
    uint32_t *chart_of;         /* per scene triangle: its chart in list */
    gb_atlas_stats *stats;
} builder;

static gb_result out_of_memory(gb_error *error)
{
    return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
}

/* ---- charts, then their UVs ---- */

/* The grown charts as lists (CSR: order by chart, starts), each
 * parameterised into the list. */
static gb_result parameterize_charts(builder *b, const uint32_t *grown, uint32_t grown_count,
                                     gb_error *error)
{
    uint32_t n = b->scene->triangle_count;
    uint32_t *starts = calloc((size_t)grown_count + 1, sizeof *starts);
    uint32_t *order = malloc((size_t)n * sizeof *order);
    gb_result result = starts && order ? GB_OK : out_of_memory(error);
    for (uint32_t t = 0; result == GB_OK && t < n; ++t)
        ++starts[grown[t] + 1];
    for (uint32_t c = 0; result == GB_OK && c < grown_count; ++c)
        starts[c + 1] += starts[c];
    for (uint32_t t = 0; result == GB_OK && t < n; ++t)
        order[starts[grown[t]]++] = t;
    for (uint32_t c = grown_count; result == GB_OK && c > 0; --c)
        starts[c] = starts[c - 1];
    if (result == GB_OK)
        starts[0] = 0;
    for (uint32_t c = 0; result == GB_OK && c < grown_count; ++c) {
        if (b->options.progress && b->options.progress(b->options.progress_user,
                                                       (double)c / grown_count))
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "interrupted");
        else
            result = gb_parameterize_piece(&b->parameterize, order + starts[c],
                                           starts[c + 1] - starts[c], &b->list, error);
    }
    free(order);
    free(starts);
    return result;
}

/* How the charts are packed: the options', with the margin of the
 * fixed-point rounding (atlas_build.h): a corner moves by at most half a
 * unit of 2^-24 of the atlas's side, and the side is at most size (or
 * GB_ATLAS_MAX_SIZE at a density asked for); twice that is the margin. */
static gb_packing_options packing_options(const builder *b)
{
    double side = b->options.texels_per_unit > 0.0 ? GB_ATLAS_MAX_SIZE : b->options.size;
    return (gb_packing_options){.texels_per_unit = b->options.texels_per_unit,
                                .size = b->options.size,
                                .padding = b->options.padding,
                                .margin = side / (double)GB_OVERLAP_ONE};
}

/* The small charts joined to neighbours (merge.h) at the density of a
 * first packing by rects (or the one asked for). */
static gb_result merge_charts(builder *b, gb_error *error)
{
    gb_packing_options o = packing_options(b);
    double density = o.texels_per_unit;
    gb_result result = GB_OK;
    if (!(density > 0.0)) {
        result = gb_packing_orient(&b->list, error);
        if (result == GB_OK)
            result = gb_pack_rects(&b->list, &o, &b->packing, error);
        density = b->packing.texels_per_unit;
        gb_packing_free(&b->packing);
    }
    if (result == GB_OK)
        result = gb_charts_merge(&b->parameterize, &b->list, density, o.padding,
                                 &b->stats->merged, error);
    return result;
}

/* ---- fixed point ---- */

static int64_t to_fixed(double texel, uint32_t size)
{
    double x = round(texel / size * (double)GB_OVERLAP_ONE);
    return x < 0.0 ? 0 : x > (double)GB_OVERLAP_ONE ? GB_OVERLAP_ONE : (int64_t)x;
}

/* Every chart's corners into b->fixed, b->chart_of filled. */
static gb_result place_charts(builder *b, gb_error *error)
{
    size_t largest = 0;
    for (uint32_t i = 0; i < b->list.count; ++i)
        if (b->list.charts[i].triangle_count > largest)
            largest = b->list.charts[i].triangle_count;
    double *texels = malloc(6 * largest * sizeof *texels);
    if (!texels)
        return out_of_memory(error);
    for (uint32_t i = 0; i < b->list.count; ++i) {
        const gb_chart *chart = &b->list.charts[i];
        gb_packing_texels(&b->list, &b->packing, i, texels);
        for (uint32_t k = 0; k < chart->triangle_count; ++k) {
            uint32_t t = chart->triangles[k];
            b->chart_of[t] = i;
            for (int c = 0; c < 3; ++c) {
                b->fixed[6 * (size_t)t + 2 * c] =
                    to_fixed(texels[6 * (size_t)k + 2 * c], b->packing.width);
                b->fixed[6 * (size_t)t + 2 * c + 1] =
                    to_fixed(texels[6 * (size_t)k + 2 * c + 1], b->packing.height);
            }
        }
    }
    free(texels);
    return GB_OK;
}

/* ---- repairs ---- */

/* Chart i's triangles with keep[k] set, in their connected parts, appended
 * as charts with the UVs they had. */
static gb_result keep_parts(builder *b, uint32_t i, const uint8_t *keep, gb_error *error)
{
    const gb_chart *chart = &b->list.charts[i];
    gb_chart_mesh m;
    gb_result result = gb_chart_mesh_build(b->scene, &b->adjacency, chart->triangles,
                                           chart->triangle_count, b->local_of, &m, error);
    if (result != GB_OK)
        return result;
    uint32_t *part = malloc(chart->triangle_count * sizeof *part), parts = 0;
    result = part ? gb_chart_mesh_components(&m, keep, part, &parts, error)
                  : out_of_memory(error);
    for (uint32_t p = 0; result == GB_OK && p < parts; ++p) {
        uint32_t count = 0;
        for (uint32_t k = 0; k < m.triangle_count; ++k)
            count += keep[k] && part[k] == p;
        gb_chart *piece = gb_chart_list_append(&b->list, count);
        if (!piece) {
            result = out_of_memory(error);
            break;
        }
        chart = &b->list.charts[i];  /* the list may have moved */
        for (uint32_t k = 0, j = 0; k < m.triangle_count; ++k)
            if (keep[k] && part[k] == p) {
                piece->triangles[j] = chart->triangles[k];
                memcpy(piece->uvs + 6 * (size_t)j, chart->uvs + 6 * (size_t)k,
                       6 * sizeof *piece->uvs);
                piece->area += gb_triangle_area(b->scene, chart->triangles[k]);
                ++j;
            }
    }
    free(part);
    gb_chart_mesh_free(&m);
    return result;
}

/* Chart i's triangles whose fixed-point area is not positive, each laid
 * alone; the rest kept in its parts; chart i removed. */
static gb_result lay_collapsed_alone(builder *b, uint32_t i, const uint8_t *collapsed_flag,
                                     gb_error *error)
{
    const gb_chart *chart = &b->list.charts[i];
    uint8_t *keep = malloc(chart->triangle_count);
    if (!keep)
        return out_of_memory(error);
    gb_result result = GB_OK;
    for (uint32_t k = 0; k < chart->triangle_count; ++k)
        keep[k] = !collapsed_flag[chart->triangles[k]];
    result = keep_parts(b, i, keep, error);
    for (uint32_t k = 0; result == GB_OK && k < b->list.charts[i].triangle_count; ++k)
        if (!keep[k])
            result = gb_chart_list_add_flat(b->scene, b->list.charts[i].triangles[k], &b->list,
                                            error);
    free(keep);
    if (result == GB_OK)
        gb_chart_list_remove(&b->list, i);
    return result;
}

/* Chart i split in two and each half parameterised again; chart i removed. */
static gb_result split_again(builder *b, uint32_t i, gb_error *error)
{
    const gb_chart *chart = &b->list.charts[i];
    uint32_t count = chart->triangle_count;
    uint32_t *source = malloc(count * sizeof *source), *part = malloc(count * sizeof *part);
    uint32_t *triangles = malloc(count * sizeof *triangles);
    gb_chart_mesh m = {0};
    gb_result result = source && part && triangles ? GB_OK : out_of_memory(error);
    if (result == GB_OK) {
        memcpy(source, chart->triangles, count * sizeof *source);
        result = gb_chart_mesh_build(b->scene, &b->adjacency, source, count, b->local_of, &m,
                                     error);
    }
    uint32_t parts = 0;
    if (result == GB_OK)
        result = gb_chart_mesh_split(&m, part, &parts, error);
    if (result == GB_OK)
        gb_chart_list_remove(&b->list, i);
    for (uint32_t p = 0; result == GB_OK && p < parts; ++p) {
        uint32_t n = 0;
        for (uint32_t k = 0; k < count; ++k)
            if (part[k] == p)
                triangles[n++] = source[k];
        result = gb_parameterize_piece(&b->parameterize, triangles, n, &b->list, error);
    }
    gb_chart_mesh_free(&m);
    free(part);
    free(triangles);
    free(source);
    return result;
}

/* ---- rounds ---- */

/* Marks in flag (per chart) the charts with a collapsed triangle (their
 * triangles in collapsed, per scene triangle); returns how many triangles. */
static uint32_t find_collapsed(const builder *b, uint8_t *collapsed, uint8_t *flag)
{
    uint32_t count = 0;
    for (uint32_t t = 0; t < b->scene->triangle_count; ++t) {
        collapsed[t] = !(gb_fixed_twice_area(b->fixed + 6 * (size_t)t) > 0);
        if (collapsed[t]) {
            ++count;
            flag[b->chart_of[t]] = 1;
        }
    }
    return count;
}

/* Marks in flag the charts with two of their own triangles overlapping;
 * fails on a pair of different charts. */
static gb_result find_self_overlaps(builder *b, uint8_t *flag, uint32_t *found, gb_error *error)
{
    enum { CAPACITY = 4096 };
    uint32_t *pairs = malloc(2 * CAPACITY * sizeof *pairs);
    uint64_t count = 0;
    if (!pairs)
        return out_of_memory(error);
    gb_result result = gb_find_overlaps(b->fixed, b->scene->triangle_count, pairs, CAPACITY,
                                        &count, error);
    *found = 0;
    for (uint64_t k = 0; result == GB_OK && k < count && k < CAPACITY; ++k) {
        uint32_t s = pairs[2 * k], t = pairs[2 * k + 1];
        if (b->chart_of[s] != b->chart_of[t])
            result = gb_fail(error, GB_ERROR_INVALID, "triangles %u and %u of charts %u "
                             "and %u overlap in the atlas (a packing error)", s, t,
                             b->chart_of[s], b->chart_of[t]);
        else if (!flag[b->chart_of[s]]) {
            flag[b->chart_of[s]] = 2;
            ++*found;
        }
    }
    if (result == GB_OK && count > CAPACITY && *found == 0)
        result = gb_fail(error, GB_ERROR_INVALID, "%llu overlapping triangle pairs",
                         (unsigned long long)count);
    free(pairs);
    return result;
}

/* Charts flagged 1 lose their collapsed triangles, charts flagged 2 are
 * split again; highest index first, so that removing one (the last moved
 * into its place) leaves the others where they were. */
static gb_result repair(builder *b, const uint8_t *flag, const uint8_t *collapsed,
                        gb_error *error)
{
    gb_result result = GB_OK;
    for (uint32_t i = b->list.count; result == GB_OK && i-- > 0;)
        if (flag[i] == 1)
            result = lay_collapsed_alone(b, i, collapsed, error);
        else if (flag[i] == 2)
            result = split_again(b, i, error);
    return result;
}

/* Packs, places, and repairs until nothing needs it. */
static gb_result pack_until_sound(builder *b, gb_error *error)
{
    gb_packing_options packing = packing_options(b);
    uint8_t *collapsed = malloc(b->scene->triangle_count);
    gb_result result = collapsed ? GB_OK : out_of_memory(error);
    for (uint32_t round = 0; result == GB_OK; ++round) {
        if (round == GB_ATLAS_BUILD_ROUNDS) {
            result = gb_fail(error, GB_ERROR_UNSUPPORTED, "still collapsed or "
                             "overlapping triangles after %d packings", GB_ATLAS_BUILD_ROUNDS);
            break;
        }
        packing.hint = b->packing.texels_per_unit;  /* the last round's, or 0 */
        gb_packing_free(&b->packing);
        uint8_t *flag = calloc(b->list.count ? b->list.count : 1, 1);
        result = flag ? gb_packing_orient(&b->list, error) : out_of_memory(error);
        if (result == GB_OK)
            result = gb_pack(&b->list, &packing, &b->packing, error);
        if (result == GB_OK)
            result = place_charts(b, error);
        uint32_t lost = 0, overlapping = 0;
        if (result == GB_OK)
            lost = find_collapsed(b, collapsed, flag);
        if (result == GB_OK && !lost)
            result = find_self_overlaps(b, flag, &overlapping, error);
        b->stats->rounds = round + 1;
        b->stats->collapsed += lost;
        b->stats->self_overlaps += overlapping;
        if (result == GB_OK && !lost && !overlapping) {
            free(flag);
            break;
        }
        if (result == GB_OK)
            result = repair(b, flag, collapsed, error);
        free(flag);
    }
    free(collapsed);
    return result;
}

/* ---- the file ---- */

/* The angles a triangle's written UVs hold: corners_measured counts the
 * corners whose two edges are at least GB_ATLAS_MEASURED_EDGE UV steps
 * long, sum and largest their distortion (degrees); needle_corners counts
 * the others. */
typedef struct corner_distortion {
    double sum, largest;
    uint64_t corners_measured, needle_corners;
} corner_distortion;

/* Adds the corners of triangle t at its written UVs (uv: 6 floats). */
static void add_triangle_distortion(const gb_scene *scene, uint32_t t, const float *uv,
                                    uint32_t width, uint32_t height, corner_distortion *d)
{
    double q[6], p[9], edge[3];
    double step = (double)(width > height ? width : height) / (double)GB_OVERLAP_ONE;
    for (int c = 0; c < 3; ++c) {
        q[2 * c] = (double)uv[2 * c] * width;
        q[2 * c + 1] = (double)uv[2 * c + 1] * height;
        gb_triangle_corner(scene, t, c, p + 3 * c);
    }
    for (int c = 0; c < 3; ++c) /* edge c: from corner c to corner c + 1 */
        edge[c] = hypot(q[2 * ((c + 1) % 3)] - q[2 * c], q[2 * ((c + 1) % 3) + 1] - q[2 * c + 1]);
    for (int c = 0; c < 3; ++c) {
        if (fmin(edge[c], edge[(c + 2) % 3]) < GB_ATLAS_MEASURED_EDGE * step) {
            ++d->needle_corners;
            continue;
        }
        double a = fabs(gb_corner_angle(q, c, 2) - gb_corner_angle(p, c, 3)) * 180.0 / M_PI;
        d->sum += a;
        d->largest = fmax(d->largest, a);
        ++d->corners_measured;
    }
}

static void fill_records(const builder *b, gb_atlas *atlas, gb_atlas_chart *records)
{
    const gb_atlas_header *h = &atlas->header;
    corner_distortion all = {0};
    double twice_area = 0.0;
    for (uint32_t i = 0; i < b->list.count; ++i) {
        const gb_chart *chart = &b->list.charts[i];
        gb_atlas_chart *r = &records[i];
        corner_distortion d = {0};
        for (uint32_t k = 0; k < chart->triangle_count; ++k) {
            uint32_t t = chart->triangles[k];
            const int64_t *f = b->fixed + 6 * (size_t)t;
            add_triangle_distortion(b->scene, t, atlas->uvs + 6 * (size_t)t, h->width,
                                    h->height, &d);
            twice_area += (double)gb_fixed_twice_area(f) / GB_OVERLAP_ONE / GB_OVERLAP_ONE *
                          h->width * h->height;
        }
        r->triangle_count = chart->triangle_count;
        r->area = (float)chart->area;
        r->max_angle_distortion = (float)d.largest;
        r->mean_angle_distortion =
            d.corners_measured ? (float)fmin(d.sum / (double)d.corners_measured, d.largest) : 0.0f;
        memcpy(r->rect, b->packing.rects + 4 * (size_t)i, sizeof r->rect);
        b->stats->lone_triangles += chart->triangle_count == 1;
        all.sum += d.sum;
        all.largest = fmax(all.largest, d.largest);
        all.corners_measured += d.corners_measured;
        all.needle_corners += d.needle_corners;
    }
    b->stats->max_angle_distortion = all.largest;
    b->stats->mean_angle_distortion =
        all.corners_measured ? all.sum / (double)all.corners_measured : 0.0;
    b->stats->needle_corners = all.needle_corners;
    b->stats->fill_ratio = 0.5 * twice_area / ((double)h->width * h->height);
}

static gb_result make_atlas(const builder *b, gb_atlas *atlas, gb_error *error)
{
    uint32_t n = b->scene->triangle_count;
    size_t uv_bytes = 6 * (size_t)n * sizeof(float), chart_bytes = (size_t)n * sizeof(uint32_t);
    size_t record_bytes = (size_t)b->list.count * sizeof(gb_atlas_chart);
    memset(atlas, 0, sizeof *atlas);
    char *storage = malloc(uv_bytes + chart_bytes + record_bytes);
    if (!storage)
        return out_of_memory(error);
    float *uvs = (float *)storage;
    uint32_t *charts = (uint32_t *)(storage + uv_bytes);
    gb_atlas_chart *records = (gb_atlas_chart *)(storage + uv_bytes + chart_bytes);
    for (size_t k = 0; k < 6 * (size_t)n; ++k)  /* exact: 24 bits at most */
        uvs[k] = (float)((double)b->fixed[k] / (double)GB_OVERLAP_ONE);
    memcpy(charts, b->chart_of, chart_bytes);
    atlas->header = (gb_atlas_header){.scene_hash = b->scene->hash,
                                      .triangle_count = n,
                                      .chart_count = b->list.count,
                                      .width = b->packing.width,
                                      .height = b->packing.height,
                                      .texels_per_unit = (float)b->packing.texels_per_unit,
                                      .padding = b->options.padding};
    atlas->uvs = uvs;
    atlas->charts = charts;
    atlas->chart_records = records;
    atlas->storage = storage;
    memset(records, 0, record_bytes);
    fill_records(b, atlas, records);
    return gb_atlas_check(atlas, "the atlas built", error);
}

/* ---- the whole ---- */

static gb_result build(builder *b, gb_atlas *atlas, gb_error *error)
{
    uint32_t n = b->scene->triangle_count;
    uint32_t *grown = malloc((size_t)n * sizeof *grown), grown_count = 0;
    b->local_of = malloc((size_t)n * sizeof *b->local_of);
    b->fixed = malloc(6 * (size_t)n * sizeof *b->fixed);
    b->chart_of = malloc((size_t)n * sizeof *b->chart_of);
    if (!grown || !b->local_of || !b->fixed || !b->chart_of) {
        free(grown);
        return out_of_memory(error);
    }
    double area = 0.0;
    for (uint32_t t = 0; t < n; ++t) {
        b->local_of[t] = GB_NO_NEIGHBOUR;
        area += gb_triangle_area(b->scene, t);
    }
    b->parameterize = (gb_parameterize_context){b->scene, &b->adjacency, b->local_of,
                                                area * GB_ATLAS_MAX_WASTE,
                                                GB_ATLAS_MAX_DISTORTION, {0}};
    gb_result result = gb_mesh_adjacency_build(b->scene, &b->adjacency, error);
    if (result == GB_OK)
        result = gb_charts_grow(b->scene, &b->adjacency, b->options.cone_degrees, grown,
                                &grown_count, error);
    b->stats->grown_charts = grown_count;
    if (result == GB_OK)
        result = parameterize_charts(b, grown, grown_count, error);
    free(grown);
    if (result == GB_OK)
        result = merge_charts(b, error);
    if (result == GB_OK)
        result = pack_until_sound(b, error);
    if (result == GB_OK)
        result = make_atlas(b, atlas, error);
    return result;
}

gb_result gb_atlas_build(const gb_scene *scene, const gb_atlas_options *options,
                         gb_atlas *atlas, gb_atlas_stats *stats, gb_error *error)
{
    double start = gb_seconds();
    gb_atlas_stats ignored;
    builder b = {.scene = scene, .options = *options, .stats = stats ? stats : &ignored};
    memset(b.stats, 0, sizeof *b.stats);
    if (!(b.options.cone_degrees > 0.0))
        b.options.cone_degrees = GB_ATLAS_DEFAULT_CONE;
    if (b.options.size == 0)
        b.options.size = GB_ATLAS_DEFAULT_SIZE;
    memset(atlas, 0, sizeof *atlas);
    gb_result result = build(&b, atlas, error);
    if (result != GB_OK)
        gb_atlas_free(atlas);
    if (result != GB_OK && error && scene->path) {  /* "SCENE: what is wrong" */
        gb_error reason = *error;
        gb_fail(error, result, "%s: %s", scene->path, reason.message);
    }
    b.stats->charts = b.list.count;
    b.stats->lscm_failures = b.parameterize.stats.lscm_failures;
    b.stats->splits = b.parameterize.stats.splits;
    b.stats->folded = b.parameterize.stats.folded;
    b.stats->overlapping = b.parameterize.stats.overlapping;
    b.stats->wasteful = b.parameterize.stats.wasteful;
    b.stats->distorted = b.parameterize.stats.distorted;
    gb_packing_free(&b.packing);
    gb_chart_list_free(&b.list);
    gb_mesh_adjacency_free(&b.adjacency);
    free(b.local_of);
    free(b.fixed);
    free(b.chart_of);
    b.stats->seconds = gb_seconds() - start;
    if (result == GB_OK && options->progress)
        options->progress(options->progress_user, 1.0);
    return result;
}
