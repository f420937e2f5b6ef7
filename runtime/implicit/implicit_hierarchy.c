/* implicit_hierarchy.c — CreateGeometricHierarchy (Dong 2007, 4.1): the
 * segments that stand for UV charts, then one quadtree of elements a
 * segment: the elements split at the median of the first tangent axis, each
 * half at the median of the second, recursively; a node of at most four
 * elements has them as children. Above the segments' roots, one tree of
 * them all, split the same way along the longest axes (an addition: the
 * paper links every pair of charts, of which its models have few). */
#include "implicit_hierarchy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- segments: faces grown across shared edges by material and normal ---- */

typedef struct edge {
    uint32_t a, b, triangle;
} edge;

static int compare_edges(const void *x, const void *y)
{
    const edge *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    if (p->b != q->b)
        return p->b < q->b ? -1 : 1;
    return p->triangle < q->triangle ? -1 : p->triangle > q->triangle;
}

static void face_normal(const gb_scene *scene, uint32_t t, double n[3])
{
    const float *p[3];
    for (int k = 0; k < 3; ++k)
        p[k] = &scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + k]];
    gb_implicit_triangle_cross(p[0], p[1], p[2], n);
    double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
        n[k] = length > 0.0 ? n[k] / length : 0.0;
}

/* Edges sorted by their two vertices: triangles sharing an edge are
 * neighbours in the array. */
static edge *sorted_edges(const gb_scene *scene)
{
    edge *edges = malloc(3 * (size_t)scene->triangle_count * sizeof *edges + 1);
    if (!edges)
        return NULL;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = scene->indices[3 * (size_t)t + k];
            uint32_t b = scene->indices[3 * (size_t)t + (k + 1) % 3];
            edges[3 * (size_t)t + k] = (edge){a < b ? a : b, a < b ? b : a, t};
        }
    qsort(edges, 3 * (size_t)scene->triangle_count, sizeof *edges, compare_edges);
    return edges;
}

/* Position of each triangle's edges in the sorted array, to find neighbours. */
static uint32_t *edge_slots(const gb_scene *scene, const edge *edges)
{
    size_t count = 3 * (size_t)scene->triangle_count;
    uint32_t *slots = malloc(count * sizeof *slots + 1);
    uint32_t *used = calloc(scene->triangle_count + 1, sizeof *used);
    if (!slots || !used) {
        free(slots);
        free(used);
        return NULL;
    }
    for (size_t i = 0; i < count; ++i) {
        uint32_t t = edges[i].triangle;
        slots[3 * (size_t)t + used[t]++] = (uint32_t)i;
    }
    free(used);
    return slots;
}

static void grow_segment(const gb_scene *scene, const edge *edges, const uint32_t *slots,
                         uint32_t seed, uint32_t segment, uint32_t *stack, uint32_t *of)
{
    double seed_normal[3], n[3];
    double cos_limit = cos(GB_IMPLICIT_SEGMENT_DEGREES * M_PI / 180.0);
    face_normal(scene, seed, seed_normal);
    size_t count = 3 * (size_t)scene->triangle_count, top = 0;
    of[seed] = segment;
    stack[top++] = seed;
    while (top) {
        uint32_t t = stack[--top];
        for (int k = 0; k < 3; ++k) {
            size_t i = slots[3 * (size_t)t + k];
            while (i > 0 && edges[i - 1].a == edges[i].a && edges[i - 1].b == edges[i].b)
                --i;
            for (; i < count && edges[i].a == edges[slots[3 * (size_t)t + k]].a &&
                   edges[i].b == edges[slots[3 * (size_t)t + k]].b; ++i) {
                uint32_t u = edges[i].triangle;
                if (of[u] != GB_IMPLICIT_NO_NODE ||
                    scene->triangle_material[u] != scene->triangle_material[seed])
                    continue;
                face_normal(scene, u, n);
                if (n[0] * seed_normal[0] + n[1] * seed_normal[1] + n[2] * seed_normal[2] <
                    cos_limit)
                    continue;
                of[u] = segment;
                stack[top++] = u;
            }
        }
    }
}

gb_result gb_implicit_segment_faces(const gb_scene *scene, gb_implicit_model *model,
                                    gb_error *error)
{
    edge *edges = sorted_edges(scene);
    uint32_t *slots = edges ? edge_slots(scene, edges) : NULL;
    uint32_t *stack = malloc((size_t)scene->triangle_count * sizeof *stack + 1);
    model->triangle_segment = malloc((size_t)scene->triangle_count * sizeof(uint32_t) + 1);
    if (!edges || !slots || !stack || !model->triangle_segment) {
        free(edges);
        free(slots);
        free(stack);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    uint32_t *of = model->triangle_segment;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        of[t] = GB_IMPLICIT_NO_NODE;
    model->segment_count = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        if (of[t] == GB_IMPLICIT_NO_NODE)
            grow_segment(scene, edges, slots, t, model->segment_count++, stack, of);
    free(edges);
    free(slots);
    free(stack);
    return GB_OK;
}

/* ---- the quadtree of a segment ---- */

typedef struct keyed {
    float key;
    uint32_t element;
} keyed;

static int compare_keyed(const void *x, const void *y)
{
    const keyed *p = x, *q = y;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->element < q->element ? -1 : p->element > q->element;
}

/* Sorts elements[0, count) by their coordinate along axis. */
static void sort_along(const gb_implicit_model *model, uint32_t *elements, uint32_t count,
                       const float axis[3], keyed *scratch)
{
    for (uint32_t i = 0; i < count; ++i) {
        const float *p = model->nodes[elements[i]].position;
        scratch[i] = (keyed){p[0] * axis[0] + p[1] * axis[1] + p[2] * axis[2], elements[i]};
    }
    qsort(scratch, count, sizeof *scratch, compare_keyed);
    for (uint32_t i = 0; i < count; ++i)
        elements[i] = scratch[i].element;
}

typedef struct builder {
    gb_implicit_model *model;
    float tangent[2][3];
    keyed *scratch;
    uint32_t child_count;       /* used in model->children */
} builder;

/* A parent's position, normal, area and box from its children. */
void gb_implicit_summarise(gb_implicit_model *model, gb_implicit_node *node)
{
    double p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, area = 0.0;
    for (int k = 0; k < 3; ++k) {
        node->box_min[k] = INFINITY;
        node->box_max[k] = -INFINITY;
    }
    for (uint32_t c = 0; c < node->child_count; ++c) {
        const gb_implicit_node *child = &model->nodes[model->children[node->first_child + c]];
        double w = child->area > 0.0f ? child->area : 0.0;
        area += w;
        for (int k = 0; k < 3; ++k) {
            p[k] += (w > 0.0 ? w : 1e-30) * child->position[k];
            n[k] += w * child->normal[k];
            node->box_min[k] = fminf(node->box_min[k], child->box_min[k]);
            node->box_max[k] = fmaxf(node->box_max[k], child->box_max[k]);
        }
    }
    double weight = 0.0, length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (uint32_t c = 0; c < node->child_count; ++c) {
        float a = model->nodes[model->children[node->first_child + c]].area;
        weight += a > 0.0f ? a : 1e-30;
    }
    for (int k = 0; k < 3; ++k) {
        node->position[k] = (float)(p[k] / weight);
        node->normal[k] = length > 0.0 ? (float)(n[k] / length) : 0.0f;
    }
    node->area = (float)area;
}

static uint32_t add_node(builder *b, const uint32_t *children, uint32_t count, uint32_t segment)
{
    gb_implicit_model *model = b->model;
    uint32_t index = model->node_count++;
    gb_implicit_node *node = &model->nodes[index];
    memset(node, 0, sizeof *node);
    node->first_child = b->child_count;
    node->child_count = count;
    node->segment = segment;
    memcpy(&model->children[b->child_count], children, count * sizeof *children);
    b->child_count += count;
    gb_implicit_summarise(model, node);
    return index;
}

/* The node over elements[0, count), all of one segment. */
static uint32_t build_quadtree(builder *b, uint32_t *elements, uint32_t count, uint32_t segment)
{
    if (count == 1)
        return elements[0];
    if (count <= 4)
        return add_node(b, elements, count, segment);
    sort_along(b->model, elements, count, b->tangent[0], b->scratch);
    uint32_t half = count / 2, bounds[5] = {0, 0, half, 0, count};
    sort_along(b->model, elements, half, b->tangent[1], b->scratch);
    sort_along(b->model, elements + half, count - half, b->tangent[1], b->scratch);
    bounds[1] = half / 2;
    bounds[3] = half + (count - half) / 2;
    uint32_t quadrants[4], used = 0;
    for (int q = 0; q < 4; ++q)
        if (bounds[q + 1] > bounds[q])
            quadrants[used++] = build_quadtree(b, elements + bounds[q], bounds[q + 1] - bounds[q],
                                               segment);
    return add_node(b, quadrants, used, segment);
}

/* Two unit axes orthogonal to the segment's mean normal. */
static void tangent_axes(const float n[3], float t[2][3])
{
    float helper[3] = {0, 0, 0};
    helper[fabsf(n[0]) < 0.6f ? 0 : fabsf(n[1]) < 0.6f ? 1 : 2] = 1.0f;
    float d = helper[0] * n[0] + helper[1] * n[1] + helper[2] * n[2];
    float length = 0.0f;
    for (int k = 0; k < 3; ++k) {
        t[0][k] = helper[k] - d * n[k];
        length += t[0][k] * t[0][k];
    }
    length = sqrtf(length);
    for (int k = 0; k < 3; ++k)
        t[0][k] = length > 0.0f ? t[0][k] / length : (k == 0);
    t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
    t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
    t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
}

static void segment_normal(const gb_implicit_model *model, const uint32_t *elements,
                           uint32_t count, float n[3])
{
    double sum[3] = {0, 0, 0};
    for (uint32_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k)
            sum[k] += (double)model->nodes[elements[i]].area * model->nodes[elements[i]].normal[k];
    double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    for (int k = 0; k < 3; ++k)
        n[k] = length > 0.0 ? (float)(sum[k] / length) : (k == 2);
}

/* ---- the tree over the segments' roots ---- */

/* The axis along which the nodes' positions spread most. */
static void longest_axis(const gb_implicit_model *model, const uint32_t *nodes, uint32_t count,
                         float axis[3])
{
    float low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
            low[k] = fminf(low[k], model->nodes[nodes[i]].position[k]);
            high[k] = fmaxf(high[k], model->nodes[nodes[i]].position[k]);
        }
    int longest = 0;
    for (int k = 1; k < 3; ++k)
        if (high[k] - low[k] > high[longest] - low[longest])
            longest = k;
    for (int k = 0; k < 3; ++k)
        axis[k] = k == longest;
}

static void sort_along_longest(builder *b, uint32_t *nodes, uint32_t count)
{
    float axis[3];
    longest_axis(b->model, nodes, count, axis);
    sort_along(b->model, nodes, count, axis, b->scratch);
}

/* The node over nodes[0, count), roots of different segments: split in
 * halves along the longest axis, each half again along its own. Without
 * it every pair of the roots is linked: 10^8 pairs for Sponza's 15 692
 * segments. */
static uint32_t build_scene_tree(builder *b, uint32_t *nodes, uint32_t count)
{
    if (count == 1)
        return nodes[0];
    if (count <= 4)
        return add_node(b, nodes, count, GB_IMPLICIT_SEVERAL_SEGMENTS);
    uint32_t half = count / 2, bounds[5] = {0, half / 2, half, half + (count - half) / 2, count};
    sort_along_longest(b, nodes, count);
    sort_along_longest(b, nodes, half);
    sort_along_longest(b, nodes + half, count - half);
    uint32_t quarters[4];
    for (int q = 0; q < 4; ++q)
        quarters[q] = build_scene_tree(b, nodes + bounds[q], bounds[q + 1] - bounds[q]);
    return add_node(b, quarters, 4, GB_IMPLICIT_SEVERAL_SEGMENTS);
}

/* Elements are numbered segment by segment (implicit_elements.c). */
gb_result gb_implicit_create_geometric_hierarchy(gb_implicit_model *model, gb_error *error)
{
    uint32_t elements = model->element_count;
    /* A tree over E leaves with 2..4 children a node has fewer than E nodes. */
    gb_implicit_node *nodes = realloc(model->nodes, (2 * (size_t)elements + 1) * sizeof *nodes);
    if (nodes)
        model->nodes = nodes;
    model->children = malloc((2 * (size_t)elements + 1) * sizeof *model->children);
    model->roots = malloc(((size_t)model->segment_count + 1) * sizeof *model->roots);
    uint32_t *order = malloc(((size_t)elements + 1) * sizeof *order);
    keyed *scratch = malloc(((size_t)elements + 1) * sizeof *scratch);
    if (!nodes || !model->children || !model->roots || !order || !scratch) {
        free(order);
        free(scratch);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    builder b = {.model = model, .scratch = scratch};
    model->node_count = elements;
    model->root_count = 0;
    for (uint32_t first = 0; first < elements;) {
        uint32_t segment = model->nodes[first].segment, end = first;
        while (end < elements && model->nodes[end].segment == segment)
            ++end;
        for (uint32_t i = first; i < end; ++i)
            order[i] = i;
        float n[3];
        segment_normal(model, order + first, end - first, n);
        tangent_axes(n, b.tangent);
        model->roots[model->root_count++] = build_quadtree(&b, order + first, end - first, segment);
        first = end;
    }
    memcpy(order, model->roots, model->root_count * sizeof *order);
    model->top = build_scene_tree(&b, order, model->root_count);
    free(order);
    free(scratch);
    return GB_OK;
}
