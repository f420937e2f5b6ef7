/* segmentation.c — the `.seg` file: writer, reader, checks and the point →
 * cluster lookup (byte layout in FORMATS.md, "Segmentation file"). Every
 * field is written little-endian byte by byte, so the file does not depend
 * on the host. */
#include "segmentation.h"
#include "little_endian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "container.h"
#include "container_kind.h"
#include "skeleton.h"
#include "voxel_frame.h"

enum {
    HEADER_SIZE = 88,
    NODE_SIZE = 24,
    EDGE_SIZE = 8,
    CLUSTER_SIZE = 4,
    MAP_SIZE = 4,
    GATE_SIZE = 40,
};

/* ---- checks ---- */

static int finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static gb_result check_header(const gb_segmentation *s, const char *path, gb_error *error)
{
    gb_result result = gb_voxel_frame_check(s->voxel_size, s->world_origin, s->grid_size, path,
                                            error);
    if (result)
        return result;
    if (!(s->alpha >= 0.0 && s->alpha <= 100.0))
        return gb_fail(error, GB_ERROR_INVALID, "%s: alpha %g is not in [0, 100]", path,
                       s->alpha);
    if (s->node_count > s->skeleton_node_count)
        return gb_fail(error, GB_ERROR_INVALID, "%s: %u segmented nodes but %u skeleton nodes",
                       path, s->node_count, s->skeleton_node_count);
    if (s->cluster_count > s->node_count || (s->node_count && !s->cluster_count))
        return gb_fail(error, GB_ERROR_INVALID, "%s: %u clusters for %u nodes", path,
                       s->cluster_count, s->node_count);
    if (s->gates_fitted > 1)
        return gb_fail(error, GB_ERROR_INVALID, "%s: gates fitted %u is neither 0 nor 1", path,
                       s->gates_fitted);
    uint64_t c = s->cluster_count, pairs = c ? c * (c - 1) / 2 : 0;
    if (s->gate_count > s->edge_count + (s->gates_fitted ? pairs : 0))
        return gb_fail(error, GB_ERROR_INVALID, "%s: %u gates for %u edges and %u clusters",
                       path, s->gate_count, s->edge_count, s->cluster_count);
    return GB_OK;
}

static gb_result check_nodes(const gb_segmentation *s, const char *path, gb_error *error)
{
    for (uint32_t n = 0; n < s->node_count; ++n) {
        const gb_segmented_node *node = &s->nodes[n];
        if (node->skeleton_node >= s->skeleton_node_count ||
            (n > 0 && node->skeleton_node <= s->nodes[n - 1].skeleton_node))
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: node %u: skeleton node %u is out of range or out of order",
                           path, n, node->skeleton_node);
        if (node->node_class < GB_NODE_TOPOLOGY || node->node_class > GB_NODE_COVERAGE)
            return gb_fail(error, GB_ERROR_INVALID, "%s: node %u: class %u is not valid", path,
                           n, node->node_class);
        if (!finite3(node->position) || !isfinite(node->radius) || node->radius < 0.0f)
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: node %u: position or radius is not valid", path, n);
    }
    return GB_OK;
}

static gb_result check_clusters(const gb_segmentation *s, const char *path, gb_error *error)
{
    uint8_t *used = calloc(s->cluster_count ? s->cluster_count : 1, 1);
    if (!used)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    gb_result result = GB_OK;
    uint32_t used_count = 0;
    for (uint32_t n = 0; n < s->node_count && !result; ++n) {
        uint32_t c = s->cluster[n];
        if (c >= s->cluster_count)
            result = gb_fail(error, GB_ERROR_INVALID,
                             "%s: node %u: cluster %u is out of range (%u clusters)", path, n, c,
                             s->cluster_count);
        else if (!used[c]) {
            used[c] = 1;
            ++used_count;
        }
    }
    if (!result && used_count != s->cluster_count)
        result = gb_fail(error, GB_ERROR_INVALID, "%s: %u of the %u clusters have no node", path,
                         s->cluster_count - used_count, s->cluster_count);
    free(used);
    return result;
}

static gb_result check_node_map(const gb_segmentation *s, const char *path, gb_error *error)
{
    for (uint32_t k = 0; k < s->skeleton_node_count; ++k)
        if (s->node_map[k] >= s->node_count)
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: skeleton node %u maps to node %u, but there are %u", path, k,
                           s->node_map[k], s->node_count);
    for (uint32_t n = 0; n < s->node_count; ++n)
        if (s->node_map[s->nodes[n].skeleton_node] != n)
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: node %u does not map to itself in the node map", path, n);
    return GB_OK;
}

static int clusters_of_edge(const gb_segmentation *s, const gb_visibility_gate *g)
{
    return g->clusters[0] == s->cluster[s->edges[2 * g->edge]] &&
           g->clusters[1] == s->cluster[s->edges[2 * g->edge + 1]];
}

/* The paper's disk of edge e: at its middle, along it, with the min radius. */
static int paper_disk(const gb_segmentation *s, const gb_visibility_gate *g)
{
    const gb_segmented_node *a = &s->nodes[s->edges[2 * g->edge]];
    const gb_segmented_node *b = &s->nodes[s->edges[2 * g->edge + 1]];
    double length2 = 0.0, along = 0.0, norm2 = 0.0, off2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        double d = (double)b->position[i] - a->position[i];
        double middle = 0.5 * ((double)a->position[i] + b->position[i]);
        length2 += d * d;
        along += d * g->normal[i];
        norm2 += (double)g->normal[i] * g->normal[i];
        off2 += (g->centre[i] - middle) * (g->centre[i] - middle);
    }
    double length = sqrt(length2);
    double scale = 1.0 + length + fabs(a->position[0]) + fabs(a->position[1]) +
                   fabs(a->position[2]);
    return length > 0.0 && fabs(norm2 - 1.0) <= 1e-4 && along >= 0.9999 * length &&
           sqrt(off2) <= 1e-5 * scale && g->radius == fminf(a->radius, b->radius);
}

/* A disk fitted to an opening: unit normal, centre in the voxel frame (give
 * or take a voxel), radius at least min_radius. */
static int fitted_disk(const gb_segmentation *s, const gb_visibility_gate *g, float min_radius)
{
    double norm2 = 0.0;
    int inside = 1;
    for (int i = 0; i < 3; ++i) {
        double low = s->world_origin[i] - s->voxel_size;
        double high = s->world_origin[i] + (s->grid_size[i] + 1.0) * s->voxel_size;
        norm2 += (double)g->normal[i] * g->normal[i];
        inside &= g->centre[i] >= low && g->centre[i] <= high;
    }
    return fabs(norm2 - 1.0) <= 1e-4 && inside && g->radius >= min_radius;
}

static int finite_gate(const gb_visibility_gate *g)
{
    return finite3(g->centre) && finite3(g->normal) && isfinite(g->radius);
}

/* The paper's disk, or with gates_fitted a fitted one of at least the
 * paper's radius; the clusters of the edge's nodes. */
static int edge_gate_valid(const gb_segmentation *s, const gb_visibility_gate *g)
{
    float paper_radius = fminf(s->nodes[s->edges[2 * g->edge]].radius,
                               s->nodes[s->edges[2 * g->edge + 1]].radius);
    return finite_gate(g) && clusters_of_edge(s, g) &&
           (paper_disk(s, g) || (s->gates_fitted && fitted_disk(s, g, paper_radius)));
}

/* The edge gates come first, sorted by edge, and exactly the edges between
 * two clusters have one; *count of them. */
static gb_result check_edge_gates(const gb_segmentation *s, const char *path, uint32_t *count,
                                  gb_error *error)
{
    uint32_t next_gate = 0;
    for (uint32_t e = 0; e < s->edge_count; ++e) {
        int crosses = s->cluster[s->edges[2 * e]] != s->cluster[s->edges[2 * e + 1]];
        int has_gate = next_gate < s->gate_count && s->gates[next_gate].edge == e;
        if (crosses != has_gate)
            return gb_fail(error, GB_ERROR_INVALID, "%s: edge %u joins %s but has %s", path,
                           e, crosses ? "two clusters" : "one cluster",
                           has_gate ? "a gate" : "no gate");
        if (!has_gate)
            continue;
        if (!edge_gate_valid(s, &s->gates[next_gate]))
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: gate %u does not match edge %u (centre, normal, radius or "
                           "clusters)", path, next_gate, e);
        ++next_gate;
    }
    *count = next_gate;
    return GB_OK;
}

/* The clusters of a gate as one key, the smaller in the high half. */
static uint64_t cluster_pair(const gb_visibility_gate *g)
{
    uint32_t a = g->clusters[0], b = g->clusters[1];
    return (uint64_t)(a < b ? a : b) << 32 | (a < b ? b : a);
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The cluster pairs of gates [0, count), sorted; NULL when out of memory. */
static uint64_t *sorted_pairs(const gb_segmentation *s, uint32_t count)
{
    uint64_t *pairs = malloc((count ? count : 1) * sizeof *pairs);
    if (!pairs)
        return NULL;
    for (uint32_t g = 0; g < count; ++g)
        pairs[g] = cluster_pair(&s->gates[g]);
    qsort(pairs, count, sizeof *pairs, compare_u64);
    return pairs;
}

/* Gate g, an opening gate after the first: no edge, clusters a < b in
 * increasing pairs, a fitted disk. */
static gb_result check_opening_gate(const gb_segmentation *s, uint32_t first, uint32_t g,
                                    const char *path, gb_error *error)
{
    const gb_visibility_gate *gate = &s->gates[g];
    const uint32_t *c = gate->clusters;
    if (gate->edge != GB_SEGMENTATION_NO_EDGE)
        return gb_fail(error, GB_ERROR_INVALID, "%s: gate %u names a missing or repeated edge",
                       path, g);
    if (!s->gates_fitted)
        return gb_fail(error, GB_ERROR_INVALID,
                       "%s: gate %u is an opening gate, but the gates are not fitted", path, g);
    if (!(c[0] < c[1] && c[1] < s->cluster_count))
        return gb_fail(error, GB_ERROR_INVALID,
                       "%s: opening gate %u: clusters (%u, %u) are not an ordered pair of the "
                       "%u clusters", path, g, c[0], c[1], s->cluster_count);
    if (g > first && cluster_pair(&s->gates[g - 1]) >= cluster_pair(gate))
        return gb_fail(error, GB_ERROR_INVALID, "%s: opening gate %u is out of order or repeated",
                       path, g);
    if (!finite_gate(gate) || !fitted_disk(s, gate, 0.0f))
        return gb_fail(error, GB_ERROR_INVALID,
                       "%s: opening gate %u: centre, normal or radius is not valid", path, g);
    return GB_OK;
}

/* The opening gates after the edge_gates, each on a pair of clusters that
 * no edge gate joins. */
static gb_result check_opening_gates(const gb_segmentation *s, uint32_t edge_gates,
                                     const char *path, gb_error *error)
{
    if (edge_gates == s->gate_count)
        return GB_OK;
    uint64_t *pairs = sorted_pairs(s, edge_gates);
    if (!pairs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    gb_result result = GB_OK;
    for (uint32_t g = edge_gates; g < s->gate_count && !result; ++g) {
        uint64_t key = cluster_pair(&s->gates[g]);
        result = check_opening_gate(s, edge_gates, g, path, error);
        if (!result && bsearch(&key, pairs, edge_gates, sizeof *pairs, compare_u64))
            result = gb_fail(error, GB_ERROR_INVALID,
                             "%s: opening gate %u joins clusters %u and %u, which an edge "
                             "gate joins already", path, g, s->gates[g].clusters[0],
                             s->gates[g].clusters[1]);
    }
    free(pairs);
    return result;
}

static gb_result check_gates(const gb_segmentation *s, const char *path, gb_error *error)
{
    uint32_t edge_gates = 0;
    gb_result result = check_edge_gates(s, path, &edge_gates, error);
    if (!result)
        result = check_opening_gates(s, edge_gates, path, error);
    return result;
}

gb_result gb_segmentation_validate(const gb_segmentation *s, const char *path, gb_error *error)
{
    if ((s->node_count && (!s->nodes || !s->cluster)) || (s->edge_count && !s->edges) ||
        (s->skeleton_node_count && !s->node_map) || (s->gate_count && !s->gates))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: segmentation arrays missing", path);
    gb_result result = check_header(s, path, error);
    if (!result)
        result = check_nodes(s, path, error);
    if (!result)
        result = gb_skeleton_check_edges(s->edges, s->edge_count, s->node_count, path, error);
    if (!result)
        result = check_clusters(s, path, error);
    if (!result)
        result = check_node_map(s, path, error);
    if (!result)
        result = check_gates(s, path, error);
    return result;
}

/* ---- encoding ---- */

static void encode_header(const gb_segmentation *s, uint8_t header[HEADER_SIZE])
{
    memset(header, 0, HEADER_SIZE);
    gb_put_u32(header + 0, s->skeleton_node_count);
    gb_put_u32(header + 4, s->node_count);
    gb_put_u32(header + 8, s->edge_count);
    gb_put_u32(header + 12, s->cluster_count);
    gb_put_u32(header + 16, s->gate_count);
    gb_put_u32(header + 20, s->resolution);
    gb_put_f64(header + 24, s->alpha);
    gb_put_u64(header + 32, s->scene_hash);
    gb_voxel_frame_put(header + 40, s->voxel_size, s->world_origin, s->grid_size);
    gb_put_u32(header + 84, s->gates_fitted);
}

static void decode_header(const uint8_t header[HEADER_SIZE], gb_segmentation *s)
{
    s->skeleton_node_count = gb_get_u32(header + 0);
    s->node_count = gb_get_u32(header + 4);
    s->edge_count = gb_get_u32(header + 8);
    s->cluster_count = gb_get_u32(header + 12);
    s->gate_count = gb_get_u32(header + 16);
    s->resolution = gb_get_u32(header + 20);
    s->alpha = gb_get_f64(header + 24);
    s->scene_hash = gb_get_u64(header + 32);
    gb_voxel_frame_get(header + 40, &s->voxel_size, s->world_origin, s->grid_size);
    s->gates_fitted = gb_get_u32(header + 84);
}

static void encode_node(const gb_segmented_node *node, uint8_t *p)
{
    gb_put_u32(p, node->skeleton_node);
    gb_put_u32(p + 4, node->node_class);
    for (int a = 0; a < 3; ++a)
        gb_put_f32(p + 8 + 4 * a, node->position[a]);
    gb_put_f32(p + 20, node->radius);
}

static void decode_node(const uint8_t *p, gb_segmented_node *node)
{
    node->skeleton_node = gb_get_u32(p);
    node->node_class = gb_get_u32(p + 4);
    for (int a = 0; a < 3; ++a)
        node->position[a] = gb_get_f32(p + 8 + 4 * a);
    node->radius = gb_get_f32(p + 20);
}

static void encode_gate(const gb_visibility_gate *gate, uint8_t *p)
{
    for (int a = 0; a < 3; ++a) {
        gb_put_f32(p + 4 * a, gate->centre[a]);
        gb_put_f32(p + 12 + 4 * a, gate->normal[a]);
    }
    gb_put_f32(p + 24, gate->radius);
    gb_put_u32(p + 28, gate->clusters[0]);
    gb_put_u32(p + 32, gate->clusters[1]);
    gb_put_u32(p + 36, gate->edge);
}

static void decode_gate(const uint8_t *p, gb_visibility_gate *gate)
{
    for (int a = 0; a < 3; ++a) {
        gate->centre[a] = gb_get_f32(p + 4 * a);
        gate->normal[a] = gb_get_f32(p + 12 + 4 * a);
    }
    gate->radius = gb_get_f32(p + 24);
    gate->clusters[0] = gb_get_u32(p + 28);
    gate->clusters[1] = gb_get_u32(p + 32);
    gate->edge = gb_get_u32(p + 36);
}

static void encode_u32s(const uint32_t *values, size_t count, uint8_t *p)
{
    for (size_t i = 0; i < count; ++i)
        gb_put_u32(p + 4 * i, values[i]);
}

static void decode_u32s(const uint8_t *p, size_t count, uint32_t *values)
{
    for (size_t i = 0; i < count; ++i)
        values[i] = gb_get_u32(p + 4 * i);
}

/* The payloads of the five array sections, in one allocation. */
typedef struct payloads {
    uint8_t *bytes;
    uint8_t *nodes, *edges, *clusters, *node_map, *gates;
    uint64_t node_bytes, edge_bytes, cluster_bytes, map_bytes, gate_bytes;
} payloads;

static int encode_payloads(const gb_segmentation *s, payloads *p)
{
    p->node_bytes = (uint64_t)s->node_count * NODE_SIZE;
    p->edge_bytes = (uint64_t)s->edge_count * EDGE_SIZE;
    p->cluster_bytes = (uint64_t)s->node_count * CLUSTER_SIZE;
    p->map_bytes = (uint64_t)s->skeleton_node_count * MAP_SIZE;
    p->gate_bytes = (uint64_t)s->gate_count * GATE_SIZE;
    uint64_t total = p->node_bytes + p->edge_bytes + p->cluster_bytes + p->map_bytes +
                     p->gate_bytes;
    p->bytes = malloc(total ? (size_t)total : 1);
    if (!p->bytes)
        return -1;
    p->nodes = p->bytes;
    p->edges = p->nodes + p->node_bytes;
    p->clusters = p->edges + p->edge_bytes;
    p->node_map = p->clusters + p->cluster_bytes;
    p->gates = p->node_map + p->map_bytes;
    for (uint32_t n = 0; n < s->node_count; ++n)
        encode_node(&s->nodes[n], p->nodes + (size_t)n * NODE_SIZE);
    encode_u32s(s->edges, 2 * (size_t)s->edge_count, p->edges);
    encode_u32s(s->cluster, s->node_count, p->clusters);
    encode_u32s(s->node_map, s->skeleton_node_count, p->node_map);
    for (uint32_t g = 0; g < s->gate_count; ++g)
        encode_gate(&s->gates[g], p->gates + (size_t)g * GATE_SIZE);
    return 0;
}

gb_result gb_segmentation_write(const char *path, const gb_segmentation *segmentation,
                                gb_error *error)
{
    gb_result result = gb_segmentation_validate(segmentation, path, error);
    if (result)
        return result;
    uint8_t header[HEADER_SIZE];
    encode_header(segmentation, header);
    payloads p = {0};
    if (encode_payloads(segmentation, &p))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    const gb_container_array arrays[] = {
        {"header", 1, HEADER_SIZE, header},
        {"nodes", 1, p.node_bytes, p.nodes},
        {"edges", 1, p.edge_bytes, p.edges},
        {"clusters", 1, p.cluster_bytes, p.clusters},
        {"node_map", 1, p.map_bytes, p.node_map},
        {"gates", 1, p.gate_bytes, p.gates},
    };
    if (!result)
        result = gb_container_write_arrays(path, "SEGM", GB_SEGMENTATION_VERSION, arrays, 6,
                                           error);
    free(p.bytes);
    return result;
}

/* ---- decoding ---- */

static gb_result allocate_arrays(gb_segmentation *s, const char *path, gb_error *error)
{
    s->nodes = malloc(s->node_count ? (size_t)s->node_count * sizeof *s->nodes : 1);
    s->edges = malloc(s->edge_count ? (size_t)s->edge_count * 2 * sizeof *s->edges : 1);
    s->cluster = malloc(s->node_count ? (size_t)s->node_count * sizeof *s->cluster : 1);
    s->node_map = malloc(s->skeleton_node_count
                             ? (size_t)s->skeleton_node_count * sizeof *s->node_map : 1);
    s->gates = malloc(s->gate_count ? (size_t)s->gate_count * sizeof *s->gates : 1);
    if (!s->nodes || !s->edges || !s->cluster || !s->node_map || !s->gates)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    return GB_OK;
}

static gb_result decode_arrays(const gb_container *c, const char *path, gb_segmentation *s,
                               gb_error *error)
{
    const gb_section *nodes, *edges, *clusters, *map, *gates;
    gb_result result =
        gb_container_find_array(c, "nodes", s->node_count, NODE_SIZE, 1, path, &nodes, error);
    if (!result)
        result = gb_container_find_array(c, "edges", s->edge_count, EDGE_SIZE, 1, path, &edges,
                                         error);
    if (!result)
        result = gb_container_find_array(c, "clusters", s->node_count, CLUSTER_SIZE, 1, path,
                                         &clusters, error);
    if (!result)
        result = gb_container_find_array(c, "node_map", s->skeleton_node_count, MAP_SIZE, 1,
                                         path, &map, error);
    if (!result)
        result = gb_container_find_array(c, "gates", s->gate_count, GATE_SIZE, 1, path, &gates,
                                         error);
    if (!result)
        result = allocate_arrays(s, path, error);
    if (result)
        return result;
    for (uint32_t n = 0; n < s->node_count; ++n)
        decode_node((const uint8_t *)nodes->data + (size_t)n * NODE_SIZE, &s->nodes[n]);
    decode_u32s(edges->data, 2 * (size_t)s->edge_count, s->edges);
    decode_u32s(clusters->data, s->node_count, s->cluster);
    decode_u32s(map->data, s->skeleton_node_count, s->node_map);
    for (uint32_t g = 0; g < s->gate_count; ++g)
        decode_gate((const uint8_t *)gates->data + (size_t)g * GATE_SIZE, &s->gates[g]);
    return GB_OK;
}

/* Fills the segmentation from a checked SEGM container (container_kind.h). */
static gb_result decode_container(const gb_container *c, const char *path, void *object,
                                  gb_error *error)
{
    gb_segmentation *s = object;
    if (c->version < GB_SEGMENTATION_VERSION)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: format version %u, from an older segment whose gates the runtime "
                       "fitted at load; bake it again (segment --voxels --grid)", path,
                       (unsigned)c->version);
    const gb_section *header;
    gb_result result =
        gb_container_find_array(c, "header", 1, HEADER_SIZE, 1, path, &header, error);
    if (result)
        return result;
    decode_header(header->data, s);
    result = check_header(s, path, error);
    if (!result)
        result = decode_arrays(c, path, s, error);
    if (!result)
        result = gb_segmentation_validate(s, path, error);
    if (result)
        gb_segmentation_free(s);
    return result;
}

static const gb_container_kind segmentation_kind = {
    "SEGM", GB_SEGMENTATION_VERSION, sizeof(gb_segmentation), decode_container, 0};

gb_result gb_segmentation_parse(const void *bytes, size_t size, const char *path,
                                gb_segmentation *segmentation, gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &segmentation_kind, segmentation, error);
}

gb_result gb_segmentation_read(const char *path, gb_segmentation *segmentation, gb_error *error)
{
    return gb_container_kind_read(path, &segmentation_kind, segmentation, error);
}

void gb_segmentation_free(gb_segmentation *segmentation)
{
    if (!segmentation)
        return;
    free(segmentation->nodes);
    free(segmentation->edges);
    free(segmentation->cluster);
    free(segmentation->node_map);
    free(segmentation->gates);
    memset(segmentation, 0, sizeof *segmentation);
}

/* ---- the nearest-node grid and the lookup ---- */

static int same_length(double a, double b)
{
    return fabs(a - b) <= 1e-9 * (fabs(a) + fabs(b)) + 1e-12;
}

gb_result gb_segmentation_check_frame(const gb_segmentation *s, const gb_voxel_grid *frame,
                                      const char *path, gb_error *error)
{
    if (frame->scene_hash != s->scene_hash)
        return gb_fail(error, GB_ERROR_STALE,
                       "%s: made from another scene than the segmentation (hash %016llx, "
                       "expected %016llx)", path, (unsigned long long)frame->scene_hash,
                       (unsigned long long)s->scene_hash);
    int same = same_length(frame->voxel_size, s->voxel_size);
    for (int a = 0; a < 3; ++a)
        same = same && frame->size[a] == s->grid_size[a] &&
               same_length(frame->world_origin[a], s->world_origin[a]);
    if (!same)
        return gb_fail(error, GB_ERROR_STALE,
                       "%s: its voxel frame is not the segmentation's (%d x %d x %d voxels "
                       "of %g, expected %d x %d x %d of %g)", path, (int)frame->size[0],
                       (int)frame->size[1], (int)frame->size[2], frame->voxel_size,
                       (int)s->grid_size[0], (int)s->grid_size[1], (int)s->grid_size[2],
                       s->voxel_size);
    return GB_OK;
}

static size_t voxel_count(const gb_segmentation *s)
{
    return (size_t)s->grid_size[0] * (size_t)s->grid_size[1] * (size_t)s->grid_size[2];
}

gb_result gb_segmentation_check_grid(const gb_segmentation *s, const gb_voxel_grid *frame,
                                     const int32_t *nearest, const char *path, gb_error *error)
{
    gb_result result = gb_segmentation_check_frame(s, frame, path, error);
    if (result != GB_OK)
        return result;
    size_t count = voxel_count(s);
    for (size_t v = 0; v < count; ++v)
        if (nearest[v] < -1 || (nearest[v] >= 0 && (uint32_t)nearest[v] >= s->skeleton_node_count))
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: voxel %zu names node %d, but the skeleton has %u nodes", path, v,
                           (int)nearest[v], s->skeleton_node_count);
    return GB_OK;
}

int32_t gb_segmentation_cluster_at(const gb_segmentation *s, const int32_t *nearest,
                                   const double point[3])
{
    size_t index = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
        double v = floor((point[a] - s->world_origin[a]) / s->voxel_size);
        if (!(v >= 0.0 && v < (double)s->grid_size[a]))
            return -1;
        index += (size_t)v * stride;
        stride *= (size_t)s->grid_size[a];
    }
    int32_t node = nearest[index];
    if (node < 0 || (uint32_t)node >= s->skeleton_node_count)
        return -1;
    return (int32_t)s->cluster[s->node_map[node]];
}

int32_t *gb_segmentation_voxel_clusters(const gb_segmentation *s, const int32_t *nearest)
{
    size_t n = voxel_count(s);
    int32_t *clusters = malloc((n ? n : 1) * sizeof *clusters);
    if (!clusters)
        return NULL;
    for (size_t i = 0; i < n; ++i) {
        int32_t node = nearest[i];
        clusters[i] = node >= 0 && (uint32_t)node < s->skeleton_node_count
                          ? (int32_t)s->cluster[s->node_map[node]]
                          : -1;
    }
    return clusters;
}
