/* skeleton.c — the `.skel` file: writer, reader and checks (byte layout in
 * FORMATS.md, "Skeleton file"). Every field is written little-endian byte by
 * byte (little_endian.h), so the file does not depend on the host. */
#include "skeleton.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "container.h"
#include "container_kind.h"
#include "little_endian.h"
#include "voxel_frame.h"

enum {
    HEADER_SIZE = 88,
    NODE_SIZE = 16,
    EDGE_SIZE = 8,
};

static void encode_header(const gb_skeleton *s, unsigned char header[HEADER_SIZE])
{
    memset(header, 0, HEADER_SIZE);
    gb_put_u32(header + 0, s->node_count);
    gb_put_u32(header + 4, s->edge_count);
    gb_voxel_frame_put(header + 8, s->voxel_size, s->world_origin, s->grid_size);
    gb_put_u32(header + 52, s->resolution);
    gb_put_u64(header + 56, s->scene_hash);
    gb_put_f64(header + 64, s->persistence);
    gb_put_f64(header + 72, s->min_lifespan);
    gb_put_u32(header + 80, s->iterations);
    gb_put_u32(header + 84, s->cavities_broken);
}

static void decode_header(const unsigned char header[HEADER_SIZE], gb_skeleton *s)
{
    s->node_count = gb_get_u32(header + 0);
    s->edge_count = gb_get_u32(header + 4);
    gb_voxel_frame_get(header + 8, &s->voxel_size, s->world_origin, s->grid_size);
    s->resolution = gb_get_u32(header + 52);
    s->scene_hash = gb_get_u64(header + 56);
    s->persistence = gb_get_f64(header + 64);
    s->min_lifespan = gb_get_f64(header + 72);
    s->iterations = gb_get_u32(header + 80);
    s->cavities_broken = gb_get_u32(header + 84);
}

static gb_result check_header(const gb_skeleton *s, const char *path, gb_error *error)
{
    gb_result result = gb_voxel_frame_check(s->voxel_size, s->world_origin, s->grid_size, path,
                                            error);
    if (!result && (!isfinite(s->persistence) || !isfinite(s->min_lifespan)))
        return gb_fail(error, GB_ERROR_INVALID, "%s: persistence parameters are not finite",
                       path);
    return result;
}

static gb_result check_nodes(const gb_skeleton *s, const char *path, gb_error *error)
{
    for (uint32_t n = 0; n < s->node_count; ++n) {
        const gb_skeleton_node *node = &s->nodes[n];
        if (!isfinite(node->position[0]) || !isfinite(node->position[1]) ||
            !isfinite(node->position[2]))
            return gb_fail(error, GB_ERROR_INVALID, "%s: node %u: position is not finite", path,
                           n);
        if (!isfinite(node->radius) || node->radius < 0.0f)
            return gb_fail(error, GB_ERROR_INVALID, "%s: node %u: radius %g is not valid", path,
                           n, (double)node->radius);
    }
    return GB_OK;
}

gb_result gb_skeleton_check_edges(const uint32_t *edges, uint32_t edge_count, uint32_t node_count,
                                  const char *path, gb_error *error)
{
    for (uint32_t e = 0; e < edge_count; ++e) {
        uint32_t a = edges[2 * e], b = edges[2 * e + 1];
        if (a >= b || b >= node_count)
            return gb_fail(error, GB_ERROR_INVALID,
                           "%s: edge %u (%u, %u) is not an ordered pair of the %u nodes", path,
                           e, a, b, node_count);
        if (e > 0) {
            uint32_t pa = edges[2 * e - 2], pb = edges[2 * e - 1];
            if (pa > a || (pa == a && pb >= b))
                return gb_fail(error, GB_ERROR_INVALID,
                               "%s: edge %u is out of order or repeated", path, e);
        }
    }
    return GB_OK;
}

gb_result gb_skeleton_validate(const gb_skeleton *skeleton, const char *path, gb_error *error)
{
    if ((skeleton->node_count && !skeleton->nodes) || (skeleton->edge_count && !skeleton->edges))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: skeleton arrays missing", path);
    gb_result result = check_header(skeleton, path, error);
    if (!result)
        result = check_nodes(skeleton, path, error);
    if (!result)
        result = gb_skeleton_check_edges(skeleton->edges, skeleton->edge_count,
                                         skeleton->node_count, path, error);
    return result;
}

static unsigned char *encode_nodes(const gb_skeleton *s)
{
    unsigned char *bytes = malloc(s->node_count ? (size_t)s->node_count * NODE_SIZE : 1);
    if (!bytes)
        return NULL;
    for (uint32_t n = 0; n < s->node_count; ++n) {
        unsigned char *p = bytes + (size_t)n * NODE_SIZE;
        for (int a = 0; a < 3; ++a)
            gb_put_f32(p + 4 * a, s->nodes[n].position[a]);
        gb_put_f32(p + 12, s->nodes[n].radius);
    }
    return bytes;
}

static unsigned char *encode_edges(const gb_skeleton *s)
{
    unsigned char *bytes = malloc(s->edge_count ? (size_t)s->edge_count * EDGE_SIZE : 1);
    if (!bytes)
        return NULL;
    for (size_t i = 0; i < 2 * (size_t)s->edge_count; ++i)
        gb_put_u32(bytes + 4 * i, s->edges[i]);
    return bytes;
}

gb_result gb_skeleton_write(const char *path, const gb_skeleton *skeleton, gb_error *error)
{
    gb_result result = gb_skeleton_validate(skeleton, path, error);
    if (result)
        return result;
    unsigned char header[HEADER_SIZE];
    encode_header(skeleton, header);
    unsigned char *nodes = encode_nodes(skeleton), *edges = encode_edges(skeleton);
    const gb_container_array arrays[] = {
        {"header", 1, HEADER_SIZE, header},
        {"nodes", skeleton->node_count, NODE_SIZE, nodes},
        {"edges", skeleton->edge_count, EDGE_SIZE, edges},
    };
    if (!nodes || !edges)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    else
        result = gb_container_write_arrays(path, "SKEL", GB_SKELETON_VERSION, arrays, 3, error);
    free(nodes);
    free(edges);
    return result;
}

static gb_result decode_arrays(const gb_section *nodes, const gb_section *edges,
                               const char *path, gb_skeleton *s, gb_error *error)
{
    s->nodes = malloc(s->node_count ? (size_t)s->node_count * sizeof *s->nodes : 1);
    s->edges = malloc(s->edge_count ? (size_t)s->edge_count * 2 * sizeof *s->edges : 1);
    if (!s->nodes || !s->edges)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    const unsigned char *p = nodes->data;
    for (uint32_t n = 0; n < s->node_count; ++n, p += NODE_SIZE) {
        for (int a = 0; a < 3; ++a)
            s->nodes[n].position[a] = gb_get_f32(p + 4 * a);
        s->nodes[n].radius = gb_get_f32(p + 12);
    }
    p = edges->data;
    for (size_t i = 0; i < 2 * (size_t)s->edge_count; ++i)
        s->edges[i] = gb_get_u32(p + 4 * i);
    return GB_OK;
}

/* Fills the skeleton from a checked SKEL container (container_kind.h). */
static gb_result decode_container(const gb_container *c, const char *path, void *object,
                                  gb_error *error)
{
    gb_skeleton *s = object;
    const gb_section *header, *nodes, *edges;
    gb_result result =
        gb_container_find_array(c, "header", 1, HEADER_SIZE, 1, path, &header, error);
    if (result)
        return result;
    decode_header(header->data, s);
    result = gb_container_find_array(c, "nodes", s->node_count, NODE_SIZE, 1, path, &nodes,
                                     error);
    if (!result)
        result = gb_container_find_array(c, "edges", s->edge_count, EDGE_SIZE, 1,
                                         path, &edges, error);
    if (!result)
        result = decode_arrays(nodes, edges, path, s, error);
    if (!result)
        result = gb_skeleton_validate(s, path, error);
    if (result)
        gb_skeleton_free(s);
    return result;
}

static const gb_container_kind skeleton_kind = {
    "SKEL", GB_SKELETON_VERSION, sizeof(gb_skeleton), decode_container, 0};

gb_result gb_skeleton_parse(const void *bytes, size_t size, const char *path,
                            gb_skeleton *skeleton, gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &skeleton_kind, skeleton, error);
}

gb_result gb_skeleton_read(const char *path, gb_skeleton *skeleton, gb_error *error)
{
    return gb_container_kind_read(path, &skeleton_kind, skeleton, error);
}

void gb_skeleton_free(gb_skeleton *skeleton)
{
    if (!skeleton)
        return;
    free(skeleton->nodes);
    free(skeleton->edges);
    memset(skeleton, 0, sizeof *skeleton);
}
