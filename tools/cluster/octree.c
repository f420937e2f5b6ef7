/* octree.c — leaves where the geometry is, their normals, the node pool
 * (octree.h). */
#include "octree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "bisection.h"
#include "triangle_box_overlap.h"

/* A triangle touching a cell: sorted by cell then triangle, so that the
 * normals are summed in one fixed order. */
typedef struct cell_hit {
    uint64_t key;
    uint32_t triangle;
} cell_hit;

typedef struct hit_list {
    cell_hit *hits;
    size_t count, capacity;
} hit_list;

static uint64_t morton_key(const uint32_t cell[3], uint32_t depth)
{
    uint64_t key = 0;
    for (uint32_t b = 0; b < depth; ++b)
        for (int k = 0; k < 3; ++k)
            key |= (uint64_t)(cell[k] >> b & 1u) << (3 * b + (uint32_t)k);
    return key;
}

/* The cell of a Morton key, morton_key's inverse. */
static void key_cell(uint64_t key, uint32_t depth, uint32_t cell[3])
{
    cell[0] = cell[1] = cell[2] = 0;
    for (uint32_t b = 0; b < depth; ++b)
        for (int k = 0; k < 3; ++k)
            cell[k] |= (uint32_t)(key >> (3 * b + (uint32_t)k) & 1u) << b;
}

void gb_octree_leaf_cell(const gb_octree_leaves *leaves, uint32_t i, uint32_t cell[3])
{
    key_cell(leaves->keys[i], leaves->depth, cell);
}

float gb_octree_leaf_edge(const gb_octree_leaves *leaves)
{
    return leaves->size / (float)(1u << leaves->depth);
}

/* The cube around the scene's bounds, a little larger so that no vertex lies
 * on its upper faces. */
static void bounding_cube(const gb_scene *scene, gb_octree_leaves *leaves)
{
    double extent = 0.0;
    for (int k = 0; k < 3; ++k)
        extent = fmax(extent, (double)scene->bounds_max[k] - scene->bounds_min[k]);
    double size = extent * 1.002 + 1e-6;
    for (int k = 0; k < 3; ++k) {
        double middle = 0.5 * ((double)scene->bounds_min[k] + scene->bounds_max[k]);
        leaves->origin[k] = (float)(middle - 0.5 * size);
    }
    leaves->size = (float)size;
}

static int push_hit(hit_list *list, uint64_t key, uint32_t triangle)
{
    if (!gb_array_reserve(&list->hits, &list->capacity, list->count + 1, sizeof *list->hits))
        return 0;
    list->hits[list->count++] = (cell_hit){key, triangle};
    return 1;
}

static void triangle_vertices(const gb_scene *scene, uint32_t t, double vertex[3][3])
{
    for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k)
            vertex[v][k] = scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + v] + k];
}

/* The cells of [low, high] of every axis that the triangle's bounds cover. */
static void cell_range(const gb_octree_leaves *leaves, const double vertex[3][3],
                       uint32_t low[3], uint32_t high[3])
{
    double edge = (double)leaves->size / (double)(1u << leaves->depth);
    double top = (double)((1u << leaves->depth) - 1);
    for (int k = 0; k < 3; ++k) {
        double a = fmin(vertex[0][k], fmin(vertex[1][k], vertex[2][k]));
        double b = fmax(vertex[0][k], fmax(vertex[1][k], vertex[2][k]));
        low[k] = (uint32_t)fmin(top, fmax(0.0, floor((a - leaves->origin[k]) / edge)));
        high[k] = (uint32_t)fmin(top, fmax(0.0, floor((b - leaves->origin[k]) / edge)));
    }
}

static int add_triangle_hits(const gb_scene *scene, uint32_t t, const gb_octree_leaves *leaves,
                             hit_list *list)
{
    double vertex[3][3], edge = (double)leaves->size / (double)(1u << leaves->depth);
    double half[3] = {0.5 * edge, 0.5 * edge, 0.5 * edge};
    triangle_vertices(scene, t, vertex);
    gb_triangle_boxes prepared;
    gb_triangle_boxes_prepare(&prepared, (const double(*)[3])vertex, half);
    uint32_t low[3], high[3], cell[3];
    cell_range(leaves, (const double(*)[3])vertex, low, high);
    for (cell[2] = low[2]; cell[2] <= high[2]; ++cell[2])
        for (cell[1] = low[1]; cell[1] <= high[1]; ++cell[1])
            for (cell[0] = low[0]; cell[0] <= high[0]; ++cell[0]) {
                double centre[3];
                for (int k = 0; k < 3; ++k)
                    centre[k] = leaves->origin[k] + ((double)cell[k] + 0.5) * edge;
                if (gb_triangle_boxes_overlap(&prepared, centre) &&
                    !push_hit(list, morton_key(cell, leaves->depth), t))
                    return 0;
            }
    return 1;
}

static int compare_hits(const void *a, const void *b)
{
    const cell_hit *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->triangle > y->triangle) - (x->triangle < y->triangle);
}

/* Twice the triangle's area times its unit normal. */
static void area_normal(const gb_scene *scene, uint32_t t, double n[3])
{
    double v[3][3];
    triangle_vertices(scene, t, v);
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

static int normalize_into(const double n[3], float out[3])
{
    double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0.0) || !isfinite(length))
        return 0;
    for (int k = 0; k < 3; ++k)
        out[k] = (float)(n[k] / length);
    return 1;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The point of triangle v nearest to p (Ericson, Real-Time Collision
 * Detection §5.1.5: by the Voronoi region of p). */
static void closest_point_on_triangle(const double v[3][3], const double p[3], double out[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; ++k) {
        ab[k] = v[1][k] - v[0][k];
        ac[k] = v[2][k] - v[0][k];
        ap[k] = p[k] - v[0][k];
        bp[k] = p[k] - v[1][k];
        cp[k] = p[k] - v[2][k];
    }
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    double s = 0.0, t = 0.0;                      /* out = v0 + s ab + t ac */
    if (d1 <= 0.0 && d2 <= 0.0)
        s = 0.0, t = 0.0;
    else if (d3 >= 0.0 && d4 <= d3)
        s = 1.0, t = 0.0;
    else if (d6 >= 0.0 && d5 <= d6)
        s = 0.0, t = 1.0;
    else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        s = d1 / (d1 - d3);
    else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        t = d2 / (d2 - d6);
    else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6)), s = 1.0 - t;
    else
        s = vb / (va + vb + vc), t = vc / (va + vb + vc);
    for (int k = 0; k < 3; ++k)
        out[k] = v[0][k] + s * ab[k] + t * ac[k];
}

/* The gathering point of a cell: the area-weighted mean of the points of its
 * triangles nearest to its centre (on a plane through the cell: the centre
 * projected onto it), so that the photons lie around it, not beside it. */
static void leaf_point(const gb_scene *scene, const gb_octree_leaves *leaves,
                       const cell_hit *hits, size_t first, size_t end, float point[3])
{
    double centre[3], sum[3] = {0.0, 0.0, 0.0}, weight = 0.0, v[3][3], q[3], n[3];
    double edge = (double)leaves->size / (double)(1u << leaves->depth);
    uint32_t cell[3];
    key_cell(hits[first].key, leaves->depth, cell);
    for (int k = 0; k < 3; ++k)
        centre[k] = leaves->origin[k] + ((double)cell[k] + 0.5) * edge;
    for (size_t i = first; i < end; ++i) {
        triangle_vertices(scene, hits[i].triangle, v);
        closest_point_on_triangle((const double(*)[3])v, centre, q);
        area_normal(scene, hits[i].triangle, n);
        double area = sqrt(dot3(n, n));
        for (int k = 0; k < 3; ++k)
            sum[k] += area * q[k];
        weight += area;
    }
    for (int k = 0; k < 3; ++k)
        point[k] = (float)(weight > 0.0 ? sum[k] / weight : centre[k]);
}

/* The area-weighted normal of hits[first, end): all of one cell. When the
 * normals cancel (the two sides of a thin wall), the first triangle's. */
static void mean_normal(const gb_scene *scene, const cell_hit *hits, size_t first, size_t end,
                        float normal[3])
{
    double sum[3] = {0.0, 0.0, 0.0}, n[3];
    for (size_t i = first; i < end; ++i) {
        area_normal(scene, hits[i].triangle, n);
        for (int k = 0; k < 3; ++k)
            sum[k] += n[k];
    }
    double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    area_normal(scene, hits[first].triangle, n);
    double first_length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (length > 1e-6 * first_length && normalize_into(sum, normal))
        return;
    if (!normalize_into(n, normal))
        normal[0] = 0.0f, normal[1] = 0.0f, normal[2] = 1.0f;
}

/* The leaf's normal as the file holds it (16-bit octahedral,
 * light_octree.h), so that its VDLs are chosen for the normal the runtime
 * shades with. */
static void leaf_normal(const gb_scene *scene, const cell_hit *hits, size_t first, size_t end,
                        float normal[3])
{
    mean_normal(scene, hits, first, end, normal);
    gb_photon_unpack_direction(gb_photon_pack_direction(normal), normal);
}

/* The groups of the normals of hits[first, end) (surface_normals.h). */
static uint32_t cell_surfaces(const gb_scene *scene, const cell_hit *hits, size_t first,
                              size_t end, gb_surface_normal out[GB_SURFACE_NORMALS])
{
    gb_surface_normal groups[GB_SURFACE_NORMALS_GATHERED];
    uint32_t count = 0;
    for (size_t i = first; i < end; ++i) {
        double n[3];
        float unit[3];
        area_normal(scene, hits[i].triangle, n);
        if (normalize_into(n, unit))
            gb_surface_normals_add(groups, &count, GB_SURFACE_NORMALS_GATHERED, unit,
                                   (float)(0.5 * sqrt(dot3(n, n))));
    }
    gb_surface_normals_keep_largest(groups, &count, GB_SURFACE_NORMALS);
    memcpy(out, groups, count * sizeof *groups);
    return count;
}

static gb_result reduce_hits(const gb_scene *scene, hit_list *list, gb_octree_leaves *leaves,
                             gb_error *error)
{
    qsort(list->hits, list->count, sizeof *list->hits, compare_hits);
    size_t cells = 0;
    for (size_t i = 0; i < list->count; ++i)
        cells += i == 0 || list->hits[i].key != list->hits[i - 1].key;
    leaves->keys = malloc((cells ? cells : 1) * sizeof *leaves->keys);
    leaves->normals = malloc((cells ? cells : 1) * 3 * sizeof *leaves->normals);
    leaves->points = malloc((cells ? cells : 1) * 3 * sizeof *leaves->points);
    leaves->surfaces = malloc((cells ? cells : 1) * GB_SURFACE_NORMALS * sizeof *leaves->surfaces);
    leaves->surface_counts = malloc((cells ? cells : 1) * sizeof *leaves->surface_counts);
    if (!leaves->keys || !leaves->normals || !leaves->points || !leaves->surfaces ||
        !leaves->surface_counts)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree: out of memory");
    for (size_t i = 0, end; i < list->count; i = end) {
        for (end = i + 1; end < list->count && list->hits[end].key == list->hits[i].key;)
            ++end;
        leaves->keys[leaves->count] = list->hits[i].key;
        leaf_normal(scene, list->hits, i, end, &leaves->normals[3 * (size_t)leaves->count]);
        leaf_point(scene, leaves, list->hits, i, end, &leaves->points[3 * (size_t)leaves->count]);
        leaves->surface_counts[leaves->count] = cell_surfaces(
            scene, list->hits, i, end,
            &leaves->surfaces[(size_t)leaves->count * GB_SURFACE_NORMALS]);
        ++leaves->count;
    }
    return GB_OK;
}

gb_result gb_octree_build(const gb_scene *scene, uint32_t depth, gb_octree_leaves *leaves,
                          gb_error *error)
{
    memset(leaves, 0, sizeof *leaves);
    if (depth < 1 || depth > GB_LIGHT_OCTREE_MAX_DEPTH)
        return gb_fail(error, GB_ERROR_ARGUMENT, "octree: depth %u is not in 1..%d", depth,
                       GB_LIGHT_OCTREE_MAX_DEPTH);
    if (scene->triangle_count == 0)
        return gb_fail(error, GB_ERROR_INVALID, "octree: the scene has no triangle");
    leaves->depth = depth;
    bounding_cube(scene, leaves);
    hit_list list = {0};
    gb_result result = GB_OK;
    for (uint32_t t = 0; t < scene->triangle_count && result == GB_OK; ++t)
        if (!add_triangle_hits(scene, t, leaves, &list))
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree: out of memory");
    if (result == GB_OK)
        result = reduce_hits(scene, &list, leaves, error);
    free(list.hits);
    if (result != GB_OK)
        gb_octree_leaves_free(leaves);
    return result;
}

/* ---- node pool ---- */

typedef struct node_pool {
    const gb_octree_leaves *leaves;
    gb_light_octree_node *nodes;
    uint32_t count;
} node_pool;

static unsigned child_digit(uint64_t key, uint32_t depth, uint32_t level)
{
    return (unsigned)(key >> (3 * (depth - 1 - level)) & 7u);
}

/* The node of `level` over leaves [first, end) (which share their digits
 * above level); returns its index. Nodes are numbered in preorder. */
static uint32_t build_node(node_pool *pool, uint32_t level, uint32_t first, uint32_t end)
{
    uint32_t index = pool->count++;
    gb_light_octree_node *node = &pool->nodes[index];
    for (int c = 0; c < 8; ++c)
        node->child[c] = GB_LIGHT_OCTREE_NONE;
    uint32_t depth = pool->leaves->depth;
    for (uint32_t i = first, j; i < end; i = j) {
        unsigned c = child_digit(pool->leaves->keys[i], depth, level);
        for (j = i + 1; j < end && child_digit(pool->leaves->keys[j], depth, level) == c;)
            ++j;
        uint32_t child = level + 1 == depth ? i : build_node(pool, level + 1, i, j);
        pool->nodes[index].child[c] = child;
    }
    return index;
}

gb_result gb_octree_nodes(const gb_octree_leaves *leaves, gb_light_octree_node **nodes,
                          uint32_t *node_count, gb_error *error)
{
    /* every level above the leaves has at most one node per leaf */
    size_t capacity = (size_t)leaves->count * leaves->depth + 1;
    node_pool pool = {leaves, malloc(capacity * sizeof *pool.nodes), 0};
    if (!pool.nodes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree: out of memory");
    build_node(&pool, 0, 0, leaves->count);
    *nodes = pool.nodes;
    *node_count = pool.count;
    return GB_OK;
}

typedef struct key_query {
    const uint64_t *keys;
    uint64_t key;
} key_query;

static int at_or_below_key(const void *user, size_t i)
{
    const key_query *query = user;
    return query->keys[i] <= query->key;
}

/* The leaf of cell, or UINT32_MAX: by bisection over the sorted keys. */
static uint32_t leaf_at(const gb_octree_leaves *leaves, const uint32_t cell[3])
{
    key_query query = {leaves->keys, morton_key(cell, leaves->depth)};
    size_t i = gb_bisection_last(leaves->count, at_or_below_key, &query);
    return leaves->keys[i] == query.key ? (uint32_t)i : UINT32_MAX;
}

uint32_t gb_octree_shading_normals(const gb_octree_leaves *leaves, uint32_t i,
                                   gb_surface_normal out[GB_SURFACE_NORMALS])
{
    gb_surface_normal groups[GB_SURFACE_NORMALS_GATHERED];
    uint32_t count = 0, cell[3], resolution = 1u << leaves->depth;
    gb_octree_leaf_cell(leaves, i, cell);
    for (int d = 0; d < 27; ++d) {
        uint32_t around[3];
        int inside = 1;
        for (int k = 0; k < 3; ++k) {
            int offset = d / (k == 0 ? 1 : k == 1 ? 3 : 9) % 3 - 1;
            around[k] = cell[k] + (uint32_t)offset;     /* wraps below 0: outside */
            inside &= around[k] < resolution;
        }
        uint32_t leaf = inside ? leaf_at(leaves, around) : UINT32_MAX;
        if (leaf == UINT32_MAX)
            continue;
        const gb_surface_normal *s = &leaves->surfaces[(size_t)leaf * GB_SURFACE_NORMALS];
        for (uint32_t g = 0; g < leaves->surface_counts[leaf]; ++g)
            gb_surface_normals_add(groups, &count, GB_SURFACE_NORMALS_GATHERED, s[g].normal,
                                   s[g].area);
    }
    gb_surface_normals_keep_largest(groups, &count, GB_SURFACE_NORMALS);
    memcpy(out, groups, count * sizeof *groups);
    return count;
}

void gb_octree_leaves_free(gb_octree_leaves *leaves)
{
    free(leaves->keys);
    free(leaves->normals);
    free(leaves->points);
    free(leaves->surfaces);
    free(leaves->surface_counts);
    memset(leaves, 0, sizeof *leaves);
}
