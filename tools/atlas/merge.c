/* merge.c — small charts joined to a neighbour (merge.h). */
#include "merge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "min_area_rect.h"

static gb_result out_of_memory(gb_error *error)
{
    return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (merging charts)");
}

/* The extents of the chart's smallest rectangle (world units) into e. */
static int rect_extents(const gb_chart *chart, double e[2])
{
    size_t n = 3 * (size_t)chart->triangle_count;
    double *points = malloc(2 * n * sizeof *points), *hull = malloc(2 * (n + 1) * sizeof *hull);
    if (!points || !hull) {
        free(points);
        free(hull);
        return 0;
    }
    memcpy(points, chart->uvs, 2 * n * sizeof *points);
    double c, s, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    gb_min_area_rect(points, n, hull, &c, &s);
    for (size_t k = 0; k < n; ++k) {
        double p[2] = {c * chart->uvs[2 * k] + s * chart->uvs[2 * k + 1],
                       -s * chart->uvs[2 * k] + c * chart->uvs[2 * k + 1]};
        for (int d = 0; d < 2; ++d) {
            lo[d] = fmin(lo[d], p[d]);
            hi[d] = fmax(hi[d], p[d]);
        }
    }
    e[0] = hi[0] - lo[0];
    e[1] = hi[1] - lo[1];
    free(points);
    free(hull);
    return 1;
}

/* The rect's sides in texels (at least 1) into side; 0 when out of memory. */
static int rect_sides(const gb_chart *chart, double density, double side[2])
{
    double e[2];
    if (!rect_extents(chart, e))
        return 0;
    for (int d = 0; d < 2; ++d)
        side[d] = fmax(1.0, ceil(e[d] * density));
    return 1;
}

double gb_chart_cost(const gb_chart *chart, double density, uint32_t padding)
{
    double side[2];
    if (!rect_sides(chart, density, side))
        return INFINITY;
    return (side[0] + 2.0 * padding) * (side[1] + 2.0 * padding);
}

/* Whether a chart pays more for its gutter than for its rect. */
static int is_small(const gb_chart *chart, double density, uint32_t padding)
{
    double side[2];
    return rect_sides(chart, density, side) &&
           (side[0] + 2.0 * padding) * (side[1] + 2.0 * padding) > 2.0 * side[0] * side[1];
}

typedef struct merger {
    const gb_parameterize_context *context;
    gb_chart_list *list;
    double density;
    uint32_t padding;
    uint32_t *chart_of;         /* per scene triangle: its chart in list */
    double *cost;               /* per chart */
} merger;

typedef struct neighbour {
    uint32_t chart, edges;
} neighbour;

static int by_chart(const void *a, const void *b)
{
    const neighbour *x = a, *y = b;
    return (x->chart > y->chart) - (x->chart < y->chart);
}

static int by_edges_descending(const void *a, const void *b)
{
    const neighbour *x = a, *y = b;
    if (x->edges != y->edges)
        return x->edges > y->edges ? -1 : 1;
    return by_chart(a, b);
}

/* The charts across chart i's edges, most shared edges first, into
 * *found (the caller frees); their number. -1 when out of memory. */
static int64_t neighbours_of(const merger *m, uint32_t i, neighbour **found)
{
    const gb_chart *chart = &m->list->charts[i];
    const gb_mesh_adjacency *adjacency = m->context->adjacency;
    neighbour *all = malloc((3 * (size_t)chart->triangle_count + 1) * sizeof *all);
    if (!all)
        return -1;
    size_t count = 0;
    for (uint32_t k = 0; k < chart->triangle_count; ++k)
        for (int e = 0; e < 3; ++e) {
            uint32_t n = adjacency->neighbours[3 * (size_t)chart->triangles[k] + e];
            if (n != GB_NO_NEIGHBOUR && m->chart_of[n] != i)
                all[count++] = (neighbour){m->chart_of[n], 1};
        }
    qsort(all, count, sizeof *all, by_chart);
    size_t unique = 0;
    for (size_t k = 0; k < count; ++k)
        if (unique && all[unique - 1].chart == all[k].chart)
            ++all[unique - 1].edges;
        else
            all[unique++] = all[k];
    qsort(all, unique, sizeof *all, by_edges_descending);
    *found = all;
    return (int64_t)unique;
}

/* Charts i and j as one, when that is sound and cheaper: the union in j's
 * place, i emptied (triangle_count 0); *joined 1. */
static gb_result try_join(merger *m, uint32_t i, uint32_t j, int *joined, gb_error *error)
{
    gb_chart_list *list = m->list;
    uint32_t a = list->charts[i].triangle_count, b = list->charts[j].triangle_count;
    *joined = 0;
    if (a + b > GB_MERGE_MAX_TRIANGLES)
        return GB_OK;
    uint32_t *triangles = malloc((size_t)(a + b) * sizeof *triangles);
    if (!triangles)
        return out_of_memory(error);
    memcpy(triangles, list->charts[i].triangles, a * sizeof *triangles);
    memcpy(triangles + a, list->charts[j].triangles, b * sizeof *triangles);
    int mapped = 0;
    gb_result result = gb_parameterize_disc(m->context, triangles, a + b, list, &mapped, error);
    free(triangles);
    if (result != GB_OK || !mapped)
        return result;
    gb_chart *u = &list->charts[list->count - 1];
    double cost = gb_chart_cost(u, m->density, m->padding);
    if (!(cost < m->cost[i] + m->cost[j])) {
        gb_chart_list_remove(list, list->count - 1);
        return GB_OK;
    }
    /* the union into j's place, i emptied */
    gb_chart old = list->charts[j];
    list->charts[j] = *u;
    *u = old;
    gb_chart_list_remove(list, list->count - 1);
    free(list->charts[i].triangles);
    free(list->charts[i].uvs);
    list->charts[i] = (gb_chart){0};
    for (uint32_t k = 0; k < list->charts[j].triangle_count; ++k)
        m->chart_of[list->charts[j].triangles[k]] = j;
    m->cost[j] = cost;
    m->cost[i] = 0.0;
    *joined = 1;
    return GB_OK;
}

static int by_cost(const void *a, const void *b, void *costs)
{
    const double *cost = costs;
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    if (cost[x] != cost[y])
        return cost[x] < cost[y] ? -1 : 1;
    return (x > y) - (x < y);
}

/* One pass over the small charts by increasing cost; *joins counted. */
static gb_result merge_pass(merger *m, uint32_t *order, uint32_t *joins, gb_error *error)
{
    uint32_t count = m->list->count;
    for (uint32_t i = 0; i < count; ++i)
        order[i] = i;
    qsort_r(order, count, sizeof *order, by_cost, m->cost);
    gb_result result = GB_OK;
    for (uint32_t k = 0; result == GB_OK && k < count; ++k) {
        uint32_t i = order[k];
        const gb_chart *chart = &m->list->charts[i];
        if (chart->triangle_count == 0 || !is_small(chart, m->density, m->padding))
            continue;
        neighbour *near = NULL;
        int64_t found = neighbours_of(m, i, &near);
        if (found < 0)
            result = out_of_memory(error);
        int joined = 0;
        for (int64_t n = 0; result == GB_OK && !joined && n < found && n < GB_MERGE_CANDIDATES;
             ++n)
            result = try_join(m, i, near[n].chart, &joined, error);
        *joins += joined;
        free(near);
    }
    return result;
}

gb_result gb_charts_merge(const gb_parameterize_context *context, gb_chart_list *list,
                          double density, uint32_t padding, uint32_t *merged, gb_error *error)
{
    uint32_t n = context->scene->triangle_count, count = list->count;
    merger m = {context, list, density, padding, malloc((size_t)n * sizeof *m.chart_of),
                malloc((count ? count : 1) * sizeof *m.cost)};
    uint32_t *order = malloc((count ? count : 1) * sizeof *order);
    gb_result result = m.chart_of && m.cost && order ? GB_OK : out_of_memory(error);
    *merged = 0;
    for (uint32_t i = 0; result == GB_OK && i < count; ++i) {
        for (uint32_t k = 0; k < list->charts[i].triangle_count; ++k)
            m.chart_of[list->charts[i].triangles[k]] = i;
        m.cost[i] = gb_chart_cost(&list->charts[i], density, padding);
    }
    for (int pass = 0; result == GB_OK && pass < GB_MERGE_PASSES; ++pass) {
        uint32_t joins = 0;
        result = merge_pass(&m, order, &joins, error);
        *merged += joins;
        if (!joins)
            break;
    }
    /* the emptied charts out, highest index first (the last moves in) */
    for (uint32_t i = list->count; i-- > 0;)
        if (list->charts[i].triangle_count == 0)
            gb_chart_list_remove(list, i);
    free(order);
    free(m.cost);
    free(m.chart_of);
    return result;
}
