/* visibility_clusters.c — the stack-based greedy growth of visibility
 * clusters over the segmented skeleton. */
#include "visibility_clusters.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "adjacency.h"

enum { NO_CLUSTER = UINT32_MAX };

typedef struct growth {
    const gb_segmentation *s;
    gb_adjacency graph;
    uint32_t *cluster;          /* out->cluster */
    uint32_t *stack, top;
    uint32_t *queue;            /* the ball traversal */
    uint32_t *visit;            /* traversal stamp of each node */
    uint32_t stamp;
    double alpha;               /* fraction */
    double max_radius;          /* largest maxball in the cluster */
} growth;

typedef struct ranked_node {
    float radius;
    uint32_t index;
} ranked_node;

/* Larger maxball first, then the smaller index. */
static int compare_by_maxball(const void *a, const void *b)
{
    const ranked_node *x = a, *y = b;
    if (x->radius != y->radius)
        return x->radius > y->radius ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

static double squared_distance(const gb_segmentation *s, uint32_t a, uint32_t b)
{
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        double d = (double)s->nodes[a].position[i] - (double)s->nodes[b].position[i];
        d2 += d * d;
    }
    return d2;
}

static void push(growth *g, uint32_t node, uint32_t c)
{
    g->cluster[node] = c;
    g->stack[g->top++] = node;
}

/* Neighbours that are not curvature nodes and whose maxball is within alpha. */
static void push_similar_neighbours(growth *g, uint32_t m, uint32_t c)
{
    double tolerance = g->alpha * g->max_radius;
    for (uint32_t k = g->graph.offsets[m]; k < g->graph.offsets[m + 1]; ++k) {
        uint32_t x = g->graph.neighbours[k];
        if (g->cluster[x] != NO_CLUSTER || g->s->nodes[x].node_class == GB_NODE_CURVATURE)
            continue;
        if (fabs((double)g->s->nodes[x].radius - g->max_radius) <= tolerance)
            push(g, x, c);
    }
}

/* Nodes in the maximal ball of m reachable from m inside it, through nodes
 * that are not in another cluster. */
static void push_ball(growth *g, uint32_t m, uint32_t c)
{
    double r = g->s->nodes[m].radius, r2 = r * r;
    uint32_t head = 0, tail = 0;
    ++g->stamp;
    g->visit[m] = g->stamp;
    g->queue[tail++] = m;
    while (head < tail) {
        uint32_t u = g->queue[head++];
        for (uint32_t k = g->graph.offsets[u]; k < g->graph.offsets[u + 1]; ++k) {
            uint32_t x = g->graph.neighbours[k];
            if (g->visit[x] == g->stamp)
                continue;
            g->visit[x] = g->stamp;
            if (squared_distance(g->s, x, m) > r2 ||
                (g->cluster[x] != NO_CLUSTER && g->cluster[x] != c))
                continue;
            if (g->cluster[x] == NO_CLUSTER)
                push(g, x, c);
            g->queue[tail++] = x;
        }
    }
}

static void grow_cluster(growth *g, uint32_t seed, uint32_t c)
{
    g->max_radius = g->s->nodes[seed].radius;
    push(g, seed, c);
    while (g->top) {
        uint32_t m = g->stack[--g->top];
        g->max_radius = fmax(g->max_radius, g->s->nodes[m].radius);
        push_similar_neighbours(g, m, c);
        push_ball(g, m, c);
    }
}

static void free_growth(growth *g, ranked_node *order)
{
    gb_adjacency_free(&g->graph);
    free(g->stack);
    free(g->queue);
    free(g->visit);
    free(order);
}

gb_result gb_visibility_clusters(gb_segmentation *out, double alpha, gb_error *error)
{
    uint32_t count = out->node_count;
    growth g = {.s = out, .alpha = alpha / 100.0};
    gb_result result = gb_adjacency_build(count, out->edges, out->edge_count, &g.graph, error);
    if (result)
        return result;
    size_t bytes = count ? count * sizeof(uint32_t) : 1;
    out->cluster = malloc(bytes);
    g.cluster = out->cluster;
    g.stack = malloc(bytes);
    g.queue = malloc(bytes);
    g.visit = calloc(count ? count : 1, sizeof *g.visit);
    ranked_node *order = malloc(count ? count * sizeof *order : 1);
    if (!out->cluster || !g.stack || !g.queue || !g.visit || !order) {
        free_growth(&g, order);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u nodes", count);
    }
    for (uint32_t n = 0; n < count; ++n) {
        out->cluster[n] = NO_CLUSTER;
        order[n] = (ranked_node){out->nodes[n].radius, n};
    }
    qsort(order, count, sizeof *order, compare_by_maxball);
    out->cluster_count = 0;
    for (uint32_t i = 0; i < count; ++i)
        if (out->cluster[order[i].index] == NO_CLUSTER)
            grow_cluster(&g, order[i].index, out->cluster_count++);
    free_growth(&g, order);
    return GB_OK;
}
