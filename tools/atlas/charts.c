/* charts.c — adjacency over shared edges and charts grown within a normal
 * cone (charts.h). */
#include "charts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "triangle_geometry.h"

/* ---- adjacency ---- */

typedef struct edge_use {
    uint32_t low, high;         /* vertex indices, low < high */
    uint32_t triangle;
    uint8_t edge;               /* 0..2 */
    uint8_t forward;            /* 1 if the triangle runs low -> high */
} edge_use;

static int by_edge(const void *a, const void *b)
{
    const edge_use *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    if (x->high != y->high)
        return x->high < y->high ? -1 : 1;
    return (x->triangle > y->triangle) - (x->triangle < y->triangle);
}

static int by_position(const void *a, const void *b, void *positions)
{
    const float *p = positions;
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    for (int k = 0; k < 3; ++k)
        if (p[3 * (size_t)i + k] != p[3 * (size_t)j + k])
            return p[3 * (size_t)i + k] < p[3 * (size_t)j + k] ? -1 : 1;
    return (i > j) - (i < j);
}

/* welded[v]: the lowest index of a vertex at v's very position. */
static uint32_t *weld(const gb_scene *scene)
{
    uint32_t n = scene->vertex_count;
    uint32_t *order = malloc((n ? n : 1) * sizeof *order);
    uint32_t *welded = malloc((n ? n : 1) * sizeof *welded);
    if (!order || !welded) {
        free(order);
        free(welded);
        return NULL;
    }
    for (uint32_t v = 0; v < n; ++v)
        order[v] = v;
    qsort_r(order, n, sizeof *order, by_position, scene->positions);
    for (uint32_t i = 0, first = 0; i < n; ++i) {
        const float *p = scene->positions + 3 * (size_t)order[i];
        const float *q = scene->positions + 3 * (size_t)order[first];
        if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
            first = i;
        welded[order[i]] = order[first];  /* order[first]: the lowest (ties by index) */
    }
    free(order);
    return welded;
}

gb_result gb_mesh_adjacency_build(const gb_scene *scene, gb_mesh_adjacency *adjacency,
                                  gb_error *error)
{
    size_t uses_count = 3 * (size_t)scene->triangle_count;
    edge_use *uses = malloc(uses_count * sizeof *uses);
    uint32_t *welded = weld(scene);
    adjacency->triangle_count = scene->triangle_count;
    adjacency->neighbours = malloc(uses_count * sizeof *adjacency->neighbours);
    if (!uses || !welded || !adjacency->neighbours) {
        free(uses);
        free(welded);
        gb_mesh_adjacency_free(adjacency);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (adjacency)");
    }
    for (size_t i = 0; i < uses_count; ++i) {
        uint32_t t = (uint32_t)(i / 3), e = (uint32_t)(i % 3);
        uint32_t a = welded[scene->indices[3 * (size_t)t + e]];
        uint32_t b = welded[scene->indices[3 * (size_t)t + (e + 1) % 3]];
        uses[i] = (edge_use){a < b ? a : b, a < b ? b : a, t, (uint8_t)e, (uint8_t)(a < b)};
        adjacency->neighbours[i] = GB_NO_NEIGHBOUR;
    }
    qsort(uses, uses_count, sizeof *uses, by_edge);
    for (size_t i = 0; i < uses_count;) {
        size_t j = i + 1;
        while (j < uses_count && uses[j].low == uses[i].low && uses[j].high == uses[i].high)
            ++j;
        if (j - i == 2 && uses[i].forward != uses[i + 1].forward &&
            uses[i].triangle != uses[i + 1].triangle) {
            adjacency->neighbours[3 * (size_t)uses[i].triangle + uses[i].edge] =
                uses[i + 1].triangle;
            adjacency->neighbours[3 * (size_t)uses[i + 1].triangle + uses[i + 1].edge] =
                uses[i].triangle;
        }
        i = j;
    }
    free(uses);
    free(welded);
    return GB_OK;
}

void gb_mesh_adjacency_free(gb_mesh_adjacency *adjacency)
{
    free(adjacency->neighbours);
    adjacency->neighbours = NULL;
    adjacency->triangle_count = 0;
}

int gb_mesh_adjacency_edge_to(const gb_mesh_adjacency *adjacency, uint32_t n, uint32_t t)
{
    for (int e = 0; e < 3; ++e)
        if (adjacency->neighbours[3 * (size_t)n + e] == t)
            return e;
    return -1;
}

/* ---- growing ---- */

/* A normal exactly on the cone (a cylinder's column at 60 degrees from
 * the seed's) must not go in or out by rounding, so the test has slack. */
#define GB_CONE_SLACK 1e-9

/* A binary min-heap of candidates, by key then triangle index. */
typedef struct candidate {
    double key;
    uint32_t triangle;
} candidate;

typedef struct heap {
    candidate *items;
    size_t count, capacity;
} heap;

static int before(candidate a, candidate b)
{
    return a.key < b.key || (a.key == b.key && a.triangle < b.triangle);
}

static int heap_push(heap *h, candidate c)
{
    if (!gb_array_reserve(&h->items, &h->capacity, h->count + 1, sizeof *h->items))
        return 0;
    size_t i = h->count++;
    while (i > 0 && before(c, h->items[(i - 1) / 2])) {
        h->items[i] = h->items[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->items[i] = c;
    return 1;
}

static candidate heap_pop(heap *h)
{
    candidate top = h->items[0], last = h->items[--h->count];
    size_t i = 0;
    for (;;) {
        size_t child = 2 * i + 1;
        if (child >= h->count)
            break;
        if (child + 1 < h->count && before(h->items[child + 1], h->items[child]))
            ++child;
        if (!before(h->items[child], last))
            break;
        h->items[i] = h->items[child];
        i = child;
    }
    if (h->count)
        h->items[i] = last;
    return top;
}

typedef struct grower {
    const gb_mesh_adjacency *adjacency;
    const double *normals;      /* 3 per triangle, unit or zero */
    uint32_t *chart_of;
    double cos_cone;
    heap candidates;
} grower;

/* The key of triangle t in a chart seeded with normal seed: 1 - n . seed
 * (0 for a triangle without a normal), or a negative value if t may not
 * join. */
static double key_of(const grower *g, uint32_t t, const double seed[3])
{
    const double *n = g->normals + 3 * (size_t)t;
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0)
        return 0.0;
    double dot = n[0] * seed[0] + n[1] * seed[1] + n[2] * seed[2];
    return dot >= g->cos_cone - GB_CONE_SLACK ? fmax(0.0, 1.0 - dot) : -1.0;
}

/* One chart from seed; 0 when out of memory. */
static int grow_one(grower *g, uint32_t seed, uint32_t chart)
{
    const double *n = g->normals + 3 * (size_t)seed;
    double normal[3] = {n[0], n[1], n[2]};
    g->candidates.count = 0;
    if (!heap_push(&g->candidates, (candidate){0.0, seed}))
        return 0;
    while (g->candidates.count) {
        uint32_t t = heap_pop(&g->candidates).triangle;
        if (g->chart_of[t] != GB_NO_NEIGHBOUR)
            continue;
        g->chart_of[t] = chart;
        for (int e = 0; e < 3; ++e) {
            uint32_t m = g->adjacency->neighbours[3 * (size_t)t + e];
            if (m == GB_NO_NEIGHBOUR || g->chart_of[m] != GB_NO_NEIGHBOUR)
                continue;
            double key = key_of(g, m, normal);
            if (key >= 0.0 && !heap_push(&g->candidates, (candidate){key, m}))
                return 0;
        }
    }
    return 1;
}

static int by_area_descending(const void *a, const void *b, void *areas)
{
    const double *area = areas;
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    if (area[x] != area[y])
        return area[x] > area[y] ? -1 : 1;
    return (x > y) - (x < y);
}

gb_result gb_charts_grow(const gb_scene *scene, const gb_mesh_adjacency *adjacency,
                         double cone_degrees, uint32_t *chart_of, uint32_t *chart_count,
                         gb_error *error)
{
    uint32_t n = scene->triangle_count;
    double *normals = malloc(3 * (size_t)n * sizeof *normals);
    double *areas = malloc((size_t)n * sizeof *areas);
    uint32_t *order = malloc((size_t)n * sizeof *order);
    grower g = {adjacency, normals, chart_of, cos(cone_degrees * M_PI / 180.0), {0}};
    int ok = normals && areas && order;
    for (uint32_t t = 0; ok && t < n; ++t) {
        areas[t] = gb_triangle_normal(scene, t, normals + 3 * (size_t)t);
        order[t] = t;
        chart_of[t] = GB_NO_NEIGHBOUR;
    }
    if (ok)
        qsort_r(order, n, sizeof *order, by_area_descending, areas);
    *chart_count = 0;
    for (uint32_t i = 0; ok && i < n; ++i)
        if (chart_of[order[i]] == GB_NO_NEIGHBOUR)
            ok = grow_one(&g, order[i], (*chart_count)++);
    free(g.candidates.items);
    free(order);
    free(areas);
    free(normals);
    return ok ? GB_OK : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (charts)");
}
