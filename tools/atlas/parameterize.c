/* parameterize.c — pieces into discs into LSCM charts (parameterize.h). */
#include "parameterize.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "discs.h"
#include "lscm.h"
#include "min_area_rect.h"
#include "overlap.h"
#include "triangle_geometry.h"

/* ---- the list ---- */

gb_chart *gb_chart_list_append(gb_chart_list *list, uint32_t count)
{
    if (!gb_array_reserve(&list->charts, &list->capacity, (size_t)list->count + 1,
                          sizeof *list->charts))
        return NULL;
    gb_chart *chart = &list->charts[list->count];
    chart->triangle_count = count;
    chart->triangles = malloc(count * sizeof *chart->triangles);
    chart->uvs = malloc(6 * (size_t)count * sizeof *chart->uvs);
    chart->area = 0.0;
    if (!chart->triangles || !chart->uvs) {
        free(chart->triangles);
        free(chart->uvs);
        return NULL;
    }
    ++list->count;
    return chart;
}

void gb_chart_list_remove(gb_chart_list *list, uint32_t i)
{
    free(list->charts[i].triangles);
    free(list->charts[i].uvs);
    list->charts[i] = list->charts[--list->count];
}

void gb_chart_list_free(gb_chart_list *list)
{
    while (list->count)
        gb_chart_list_remove(list, list->count - 1);
    free(list->charts);
    memset(list, 0, sizeof *list);
}

static gb_result out_of_memory(gb_error *error)
{
    return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (charts)");
}

/* ---- one triangle laid flat ---- */

/* Corners p (3 x 3 doubles) laid flat into uv (6): the longest edge, from
 * corner a to corner a+1, along +u, the third corner above it (v > 0), so
 * the corners 0, 1, 2 run counterclockwise. */
static void lay_flat(const double p[3][3], double uv[6])
{
    int a = 0;
    double longest = -1.0;
    for (int e = 0; e < 3; ++e) {
        double d[3] = {p[(e + 1) % 3][0] - p[e][0], p[(e + 1) % 3][1] - p[e][1],
                       p[(e + 1) % 3][2] - p[e][2]};
        double length = gb_length3(d);
        if (length > longest) {
            longest = length;
            a = e;
        }
    }
    int b = (a + 1) % 3, c = (a + 2) % 3;
    double n[3];
    gb_triangle_cross(p[a], p[b], p[c], n);
    double along[3] = {p[c][0] - p[a][0], p[c][1] - p[a][1], p[c][2] - p[a][2]};
    double edge[3] = {p[b][0] - p[a][0], p[b][1] - p[a][1], p[b][2] - p[a][2]};
    double x = longest > 0.0
                   ? (along[0] * edge[0] + along[1] * edge[1] + along[2] * edge[2]) / longest
                   : 0.0;
    double y = longest > 0.0 ? gb_length3(n) / longest : 0.0;
    uv[2 * a] = 0.0;
    uv[2 * a + 1] = 0.0;
    uv[2 * b] = longest;
    uv[2 * b + 1] = 0.0;
    uv[2 * c] = x;
    uv[2 * c + 1] = y;
}

gb_result gb_chart_list_add_flat(const gb_scene *scene, uint32_t t, gb_chart_list *list,
                                 gb_error *error)
{
    gb_chart *chart = gb_chart_list_append(list, 1);
    if (!chart)
        return out_of_memory(error);
    double p[3][3];
    for (int c = 0; c < 3; ++c)
        gb_triangle_corner(scene, t, c, p[c]);
    chart->triangles[0] = t;
    lay_flat(p, chart->uvs);
    chart->area = gb_triangle_area(scene, t);
    return GB_OK;
}

/* ---- LSCM of a disc ---- */

/* The chart of the disc m from LSCM's per-vertex UVs: scaled to the world
 * area, mirrored if need be; folded[i] set for triangles of UV area <= 0
 * (in fixed point over the chart's box, overlap.h), *overlaps the pairs
 * of its triangles that overlap when none is folded. Returns the number
 * folded, or -1 if the map is unusable (zero or non-finite total area). */
static int64_t normalise(const gb_scene *scene, const gb_chart_mesh *m, const double *vertex_uvs,
                         gb_chart *chart, uint8_t *folded, uint64_t *overlaps)
{
    double uv_area = 0.0, world_area = 0.0;
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        double *uv = chart->uvs + 6 * (size_t)i;
        for (int c = 0; c < 3; ++c) {
            uv[2 * c] = vertex_uvs[2 * (size_t)m->corners[3 * i + c]];
            uv[2 * c + 1] = vertex_uvs[2 * (size_t)m->corners[3 * i + c] + 1];
        }
        uv_area += 0.5 * gb_uv_twice_area(uv);
        world_area += gb_triangle_area(scene, m->triangles[i]);
    }
    if (!isfinite(uv_area) || uv_area == 0.0 || !(world_area > 0.0))
        return -1;
    double scale = sqrt(world_area / fabs(uv_area)), mirror = uv_area < 0.0 ? -1.0 : 1.0;
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        double *uv = chart->uvs + 6 * (size_t)i;
        for (int c = 0; c < 3; ++c) {
            uv[2 * c] *= scale;
            uv[2 * c + 1] *= scale * mirror;
        }
        chart->triangles[i] = m->triangles[i];
    }
    chart->area = world_area;
    uint32_t folds = 0;
    if (gb_chart_uvs_check(chart->uvs, m->triangle_count, folded, &folds, overlaps, NULL) != GB_OK)
        return -1;
    return folds;
}

/* ---- the work list ---- */

typedef struct piece {
    uint32_t *triangles;
    uint32_t count;
} piece;

typedef struct pieces {
    piece *items;
    uint32_t count;
    size_t capacity;
} pieces;

/* Pushes the triangles of m with part[i] == label. */
static int push_part(pieces *work, const gb_chart_mesh *m, const uint32_t *part, uint32_t label)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < m->triangle_count; ++i)
        count += part[i] == label;
    if (!count)
        return 1;
    if (!gb_array_reserve(&work->items, &work->capacity, (size_t)work->count + 1,
                          sizeof *work->items))
        return 0;
    uint32_t *triangles = malloc(count * sizeof *triangles);
    if (!triangles)
        return 0;
    count = 0;
    for (uint32_t i = 0; i < m->triangle_count; ++i)
        if (part[i] == label)
            triangles[count++] = m->triangles[i];
    work->items[work->count++] = (piece){triangles, count};
    return 1;
}

/* m split in its parts, each pushed. */
static gb_result push_split(pieces *work, const gb_chart_mesh *m, gb_error *error)
{
    uint32_t *part = malloc(m->triangle_count * sizeof *part), parts = 0;
    if (!part)
        return out_of_memory(error);
    gb_result result = gb_chart_mesh_split(m, part, &parts, error);
    for (uint32_t p = 0; result == GB_OK && p < parts; ++p)
        if (!push_part(work, m, part, p))
            result = out_of_memory(error);
    free(part);
    return result;
}

/* The chart's smallest rectangle's area less its UV area (world units),
 * and the share of that rectangle its triangles cover in *fill. */
static double rect_waste(const gb_chart *chart, double *fill)
{
    size_t n = 3 * (size_t)chart->triangle_count;
    double *points = malloc(2 * n * sizeof *points), *hull = malloc(2 * (n + 1) * sizeof *hull);
    double waste = 0.0;
    *fill = 1.0;
    if (points && hull) {
        memcpy(points, chart->uvs, 2 * n * sizeof *points);
        double c, s, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, area = 0.0;
        gb_min_area_rect(points, n, hull, &c, &s);
        for (size_t k = 0; k < n; ++k) {
            double x = c * chart->uvs[2 * k] + s * chart->uvs[2 * k + 1];
            double y = -s * chart->uvs[2 * k] + c * chart->uvs[2 * k + 1];
            lo[0] = fmin(lo[0], x);
            hi[0] = fmax(hi[0], x);
            lo[1] = fmin(lo[1], y);
            hi[1] = fmax(hi[1], y);
        }
        for (uint32_t i = 0; i < chart->triangle_count; ++i)
            area += 0.5 * gb_uv_twice_area(chart->uvs + 6 * (size_t)i);
        double rect = (hi[0] - lo[0]) * (hi[1] - lo[1]);
        waste = rect - area;
        *fill = rect > 0.0 ? area / rect : 1.0;
    }
    free(points);
    free(hull);
    return waste;
}

/* Why an LSCM chart is not kept. */
enum { SOUND, FAILED, FOLDED, OVERLAPPING, DISTORTED };

/* The chart of the disc m by LSCM appended to list, and in *status
 * whether it is sound; the caller removes it when it is not. */
static gb_result lscm_chart(const gb_scene *scene, const gb_chart_mesh *m, double max_distortion,
                            gb_chart_list *list, int *status, gb_error *error)
{
    double *vertex_uvs = malloc(2 * (size_t)m->vertex_count * sizeof *vertex_uvs);
    uint8_t *folded = malloc(m->triangle_count);
    gb_chart *chart = vertex_uvs && folded ? gb_chart_list_append(list, m->triangle_count) : NULL;
    gb_result result = chart ? GB_OK : out_of_memory(error);
    int64_t folds = -1;
    uint64_t overlaps = 0;
    if (result == GB_OK &&
        gb_lscm_parameterize(m->vertex_count, m->positions, m->triangle_count, m->corners,
                             vertex_uvs, NULL) == GB_OK)
        folds = normalise(scene, m, vertex_uvs, chart, folded, &overlaps);
    *status = folds < 0 ? FAILED : folds > 0 ? FOLDED : overlaps > 0 ? OVERLAPPING
              : gb_chart_max_distortion(scene, chart) > max_distortion ? DISTORTED : SOUND;
    free(folded);
    free(vertex_uvs);
    return result;
}

/* A disc m by LSCM: a chart appended, or m split when CGAL fails, when a
 * triangle folds, when two overlap, when a corner is distorted beyond the
 * bound or when the chart wastes its rectangle. */
static gb_result map_disc(const gb_parameterize_context *context, const gb_chart_mesh *m,
                          gb_chart_list *list, pieces *work, gb_parameterize_stats *stats,
                          gb_error *error)
{
    int status;
    gb_result result = lscm_chart(context->scene, m, context->max_distortion, list, &status,
                                  error);
    if (result != GB_OK)
        return result;
    double fill = 1.0;
    int wasteful = status == SOUND && context->max_waste > 0.0 &&
                   rect_waste(&list->charts[list->count - 1], &fill) > context->max_waste &&
                   fill < GB_MIN_RECT_FILL;
    stats->lscm_failures += status == FAILED;
    stats->folded += status == FOLDED;
    stats->overlapping += status == OVERLAPPING;
    stats->distorted += status == DISTORTED;
    stats->wasteful += wasteful;
    stats->lscm_charts += status == SOUND && !wasteful;
    if (status != SOUND || wasteful) {
        gb_chart_list_remove(list, list->count - 1);
        result = push_split(work, m, error);
    }
    return result;
}

gb_result gb_parameterize_disc(const gb_parameterize_context *context, const uint32_t *triangles,
                               uint32_t count, gb_chart_list *list, int *mapped, gb_error *error)
{
    gb_chart_mesh m;
    *mapped = 0;
    gb_result result = gb_chart_mesh_build(context->scene, context->adjacency, triangles, count,
                                           context->local_of, &m, error);
    if (result != GB_OK)
        return result;
    int status = FAILED;
    if (gb_chart_mesh_is_disc(&m))
        result = lscm_chart(context->scene, &m, context->max_distortion, list, &status, error);
    if (result == GB_OK && gb_chart_mesh_is_disc(&m) && status != SOUND)
        gb_chart_list_remove(list, list->count - 1);
    *mapped = result == GB_OK && status == SOUND;
    gb_chart_mesh_free(&m);
    return result;
}

/* The largest angle distortion of a chart's corners (degrees). */
double gb_chart_max_distortion(const gb_scene *scene, const gb_chart *chart)
{
    double largest = 0.0, sum = 0.0;
    for (uint32_t k = 0; k < chart->triangle_count; ++k)
        largest = fmax(largest, gb_triangle_angle_distortion(scene, chart->triangles[k],
                                                             chart->uvs + 6 * (size_t)k, &sum));
    return largest;
}

/* One piece off the work list: laid flat, split, or mapped. */
static gb_result do_piece(gb_parameterize_context *context, piece p, gb_chart_list *list,
                          pieces *work, gb_error *error)
{
    const gb_scene *scene = context->scene;
    gb_parameterize_stats *stats = &context->stats;
    if (p.count == 1)
        return gb_chart_list_add_flat(scene, p.triangles[0], list, error);
    gb_chart_mesh m;
    gb_result result = gb_chart_mesh_build(scene, context->adjacency, p.triangles, p.count,
                                           context->local_of, &m, error);
    if (result != GB_OK)
        return result;
    if (!gb_chart_mesh_is_disc(&m)) {
        ++stats->splits;
        result = push_split(work, &m, error);
    } else {
        result = map_disc(context, &m, list, work, stats, error);
    }
    gb_chart_mesh_free(&m);
    return result;
}

gb_result gb_parameterize_piece(gb_parameterize_context *context, const uint32_t *triangles,
                                uint32_t count, gb_chart_list *list, gb_error *error)
{
    pieces work = {0};
    uint32_t *first = malloc(count * sizeof *first);
    if (!first)
        return out_of_memory(error);
    memcpy(first, triangles, count * sizeof *first);
    work.items = malloc(sizeof *work.items);
    if (!work.items) {
        free(first);
        return out_of_memory(error);
    }
    work.capacity = 1;
    work.items[work.count++] = (piece){first, count};
    gb_result result = GB_OK;
    while (work.count) {
        piece p = work.items[--work.count];
        if (result == GB_OK)
            result = do_piece(context, p, list, &work, error);
        free(p.triangles);
    }
    free(work.items);
    return result;
}
