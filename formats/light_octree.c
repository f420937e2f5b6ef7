/* light_octree.c — the light octree file (formats/light_octree.h,
 * formats/FORMATS.md "Light octree"). Every section is an array of fixed
 * layout written and read in place, which needs a little-endian host. */
#include "light_octree.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "container_kind.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "light octrees are read in place: gibake needs a little-endian host"
#endif

_Static_assert(sizeof(gb_light_octree_header) == 128, "header is 128 bytes");
_Static_assert(sizeof(gb_light_octree_node) == 32, "node is 32 bytes");
_Static_assert(sizeof(gb_light_octree_leaf) == 16, "leaf is 16 bytes");
_Static_assert(sizeof(gb_light_octree_vdl) == 16, "VDL is 16 bytes");

enum { ALIGNMENT = 16 };

/* ---- header ---- */

static int is_finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static gb_result check_parameters(const gb_light_octree_header *h, const char *path,
                                  gb_error *error)
{
    if (h->knn < 1 || !(h->radius > 0.0f) || !isfinite(h->radius))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad gathering parameters (K %u, R %g)",
                       path, h->knn, (double)h->radius);
    if (h->vdls_max < 1 || h->vdls_max > GB_LIGHT_OCTREE_MAX_VDLS)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: K_max %u is not in 1..%d", path,
                       h->vdls_max, GB_LIGHT_OCTREE_MAX_VDLS);
    if (!(h->tolerance >= -1.0f && h->tolerance <= 180.0f) ||
        !(h->flattening > 0.0f && h->flattening <= 1.0f))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad tolerance %g or flattening %g", path,
                       (double)h->tolerance, (double)h->flattening);
    return GB_OK;
}

static gb_result check_header(const gb_light_octree_header *h, const char *path,
                              gb_error *error)
{
    if (h->depth < 1 || h->depth > GB_LIGHT_OCTREE_MAX_DEPTH)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: depth %u is not in 1..%d", path, h->depth,
                       GB_LIGHT_OCTREE_MAX_DEPTH);
    if (!is_finite3(h->origin) || !(h->size > 0.0f) || !isfinite(h->size))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad octree bounds", path);
    if (h->node_count < 1 || h->leaf_count < 1 || h->leaf_count > 1u << (3 * h->depth) ||
        (uint64_t)h->node_count > (uint64_t)h->leaf_count * h->depth)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u nodes and %u leaves for depth %u", path,
                       h->node_count, h->leaf_count, h->depth);
    if (h->vdl_count > (uint64_t)h->leaf_count * h->vdls_max)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u VDLs for %u leaves", path,
                       h->vdl_count, h->leaf_count);
    if (h->interpolation > GB_LIGHT_OCTREE_SURFACE)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: interpolation %u is not 0 or 1", path,
                       h->interpolation);
    for (int i = 0; i < 10; ++i)
        if (h->reserved[i])
            return gb_fail(error, GB_ERROR_FORMAT, "%s: reserved header field is not zero",
                           path);
    return check_parameters(h, path, error);
}

/* ---- tree ---- */

typedef struct tree_walk {
    const gb_light_octree *octree;
    uint8_t *node_seen, *leaf_seen;
    const char *path;
    gb_error *error;
} tree_walk;

static gb_result check_leaf_reached(tree_walk *w, uint32_t leaf, const uint32_t cell[3])
{
    const gb_light_octree_header *h = &w->octree->header;
    if (leaf >= h->leaf_count)
        return gb_fail(w->error, GB_ERROR_FORMAT, "%s: leaf index %u out of range (%u leaves)",
                       w->path, leaf, h->leaf_count);
    if (w->leaf_seen[leaf]++)
        return gb_fail(w->error, GB_ERROR_FORMAT, "%s: leaf %u is reached twice", w->path,
                       leaf);
    if (w->octree->leaves[leaf].cell != gb_light_octree_pack_cell(cell))
        return gb_fail(w->error, GB_ERROR_FORMAT, "%s: leaf %u names another cell than its "
                       "place in the tree", w->path, leaf);
    return GB_OK;
}

/* Walks node `node` of level `level` whose cell (at that level) is `cell`. */
static gb_result walk_node(tree_walk *w, uint32_t node, uint32_t level, const uint32_t cell[3])
{
    const gb_light_octree_header *h = &w->octree->header;
    if (node >= h->node_count)
        return gb_fail(w->error, GB_ERROR_FORMAT, "%s: node index %u out of range (%u nodes)",
                       w->path, node, h->node_count);
    if (w->node_seen[node]++)
        return gb_fail(w->error, GB_ERROR_FORMAT, "%s: node %u is reached twice", w->path,
                       node);
    gb_result result = GB_OK;
    for (uint32_t c = 0; c < 8 && result == GB_OK; ++c) {
        uint32_t child = w->octree->nodes[node].child[c];
        if (child == GB_LIGHT_OCTREE_NONE)
            continue;
        uint32_t sub[3] = {2 * cell[0] + (c & 1), 2 * cell[1] + (c >> 1 & 1),
                           2 * cell[2] + (c >> 2 & 1)};
        result = level + 1 == h->depth ? check_leaf_reached(w, child, sub)
                                       : walk_node(w, child, level + 1, sub);
    }
    return result;
}

static gb_result check_tree(const gb_light_octree *octree, const char *path, gb_error *error)
{
    const gb_light_octree_header *h = &octree->header;
    tree_walk w = {octree, calloc(h->node_count, 1), calloc(h->leaf_count, 1), path, error};
    gb_result result = GB_OK;
    if (!w.node_seen || !w.leaf_seen)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    const uint32_t root[3] = {0, 0, 0};
    if (result == GB_OK)
        result = walk_node(&w, 0, 0, root);
    for (uint32_t i = 0; result == GB_OK && i < h->node_count; ++i)
        if (!w.node_seen[i])
            result = gb_fail(error, GB_ERROR_FORMAT, "%s: node %u is not in the tree", path, i);
    for (uint32_t i = 0; result == GB_OK && i < h->leaf_count; ++i)
        if (!w.leaf_seen[i])
            result = gb_fail(error, GB_ERROR_FORMAT, "%s: leaf %u is not in the tree", path, i);
    free(w.node_seen);
    free(w.leaf_seen);
    return result;
}

/* ---- leaves and VDLs ---- */

/* gb_photon_pack_direction never writes a 0 field (its grid is -32767 ..
 * 32767 biased by 32768). */
static int is_packed_direction(uint32_t packed)
{
    return (packed & 0xFFFFu) != 0 && (packed >> 16) != 0;
}

static gb_result check_leaf(const gb_light_octree *octree, uint32_t i, uint32_t expected_first,
                            const char *path, gb_error *error)
{
    const gb_light_octree_leaf *leaf = &octree->leaves[i];
    if (!is_packed_direction(leaf->normal) || leaf->plane == INT16_MIN)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: leaf %u: bad packed normal or plane", path,
                       i);
    if (leaf->first_vdl != expected_first || leaf->vdl_count > octree->header.vdls_max ||
        leaf->vdl_count > octree->header.vdl_count - expected_first)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: leaf %u: VDL range %u + %u is not the "
                       "next %s", path, i, leaf->first_vdl, leaf->vdl_count,
                       leaf->vdl_count > octree->header.vdls_max ? "(more than K_max)"
                                                                 : "in the VDL array");
    return GB_OK;
}

static gb_result check_vdl(const gb_light_octree_vdl *vdl, uint32_t i, const char *path,
                           gb_error *error)
{
    const float *e = vdl->irradiance;
    if (!is_finite3(e) || e[0] < 0.0f || e[1] < 0.0f || e[2] < 0.0f)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: VDL %u: irradiance is not finite and >= 0",
                       path, i);
    if (!is_packed_direction(vdl->direction))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: VDL %u: bad packed direction", path, i);
    return GB_OK;
}

static gb_result check_leaves_and_vdls(const gb_light_octree *octree, const char *path,
                                       gb_error *error)
{
    const gb_light_octree_header *h = &octree->header;
    uint32_t next = 0;
    gb_result result = GB_OK;
    for (uint32_t i = 0; i < h->leaf_count && result == GB_OK; ++i) {
        result = check_leaf(octree, i, next, path, error);
        next += octree->leaves[i].vdl_count;
    }
    if (result == GB_OK && next != h->vdl_count)
        result = gb_fail(error, GB_ERROR_FORMAT, "%s: leaves hold %u VDLs, the header says %u",
                         path, next, h->vdl_count);
    for (uint32_t i = 0; i < h->vdl_count && result == GB_OK; ++i)
        result = check_vdl(&octree->vdls[i], i, path, error);
    return result;
}

gb_result gb_light_octree_check(const gb_light_octree *octree, const char *path,
                                gb_error *error)
{
    gb_result result = check_header(&octree->header, path, error);
    if (result == GB_OK)
        result = check_leaves_and_vdls(octree, path, error);
    if (result == GB_OK)
        result = check_tree(octree, path, error);
    return result;
}

gb_result gb_light_octree_check_scene(const gb_light_octree *octree, uint64_t scene_hash,
                                      const char *path, gb_error *error)
{
    if (octree->header.scene_hash == scene_hash)
        return GB_OK;
    return gb_fail(error, GB_ERROR_STALE, "%s: made from another scene (hash %016" PRIx64
                   ", the scene's is %016" PRIx64 ")", path, octree->header.scene_hash,
                   scene_hash);
}

/* ---- writing ---- */

gb_result gb_light_octree_write(const char *path, const gb_light_octree *octree,
                                gb_error *error)
{
    gb_result result = gb_light_octree_check(octree, path, error);
    if (result != GB_OK)
        return result;
    const gb_light_octree_header *h = &octree->header;
    const gb_container_array arrays[] = {
        {"header", 1, sizeof *h, h},
        {"nodes", h->node_count, sizeof *octree->nodes, octree->nodes},
        {"leaves", h->leaf_count, sizeof *octree->leaves, octree->leaves},
        {"vdls", h->vdl_count, sizeof *octree->vdls, octree->vdls},
    };
    return gb_container_write_arrays(path, "LOCT", GB_LIGHT_OCTREE_VERSION, arrays, 4, error);
}

/* ---- reading ---- */

static gb_result view_sections(const gb_container *container, const char *path,
                               gb_light_octree *octree, gb_error *error)
{
    const gb_section *header;
    gb_result result = gb_container_find_array(container, "header", 1, sizeof octree->header,
                                               ALIGNMENT, path, &header, error);
    if (result != GB_OK)
        return result;
    memcpy(&octree->header, header->data, sizeof octree->header);
    const gb_light_octree_header *h = &octree->header;
    gb_container_array arrays[] = {
        {"nodes", h->node_count, sizeof *octree->nodes, NULL},
        {"leaves", h->leaf_count, sizeof *octree->leaves, NULL},
        {"vdls", h->vdl_count, sizeof *octree->vdls, NULL},
    };
    result = gb_container_find_arrays(container, arrays, 3, ALIGNMENT, path, error);
    octree->nodes = arrays[0].data;
    octree->leaves = arrays[1].data;
    octree->vdls = arrays[2].data;
    return result;
}

/* Fills the octree from a checked LOCT container, which it then keeps: its
 * arrays are views into it (container_kind.h). */
static gb_result adopt_container(const gb_container *container, const char *path, void *object,
                                 gb_error *error)
{
    gb_light_octree *octree = object;
    if (container->version < GB_LIGHT_OCTREE_VERSION)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: format version %u, from an older cluster (32-byte leaves); "
                       "cluster it again", path, (unsigned)container->version);
    if (container->section_count != 4)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u sections, expected 4", path,
                       (unsigned)container->section_count);
    gb_result result = view_sections(container, path, octree, error);
    if (result == GB_OK)
        result = gb_light_octree_check(octree, path, error);
    if (result == GB_OK)
        octree->container = *container;
    return result;
}

static const gb_container_kind light_octree_kind = {
    "LOCT", GB_LIGHT_OCTREE_VERSION, sizeof(gb_light_octree), adopt_container, 1};

gb_result gb_light_octree_read(const char *path, gb_light_octree *octree, gb_error *error)
{
    return gb_container_kind_read(path, &light_octree_kind, octree, error);
}

gb_result gb_light_octree_parse(const void *bytes, size_t size, const char *path,
                                gb_light_octree *octree, gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &light_octree_kind, octree, error);
}

void gb_light_octree_free(gb_light_octree *octree)
{
    free(octree->storage);
    if (octree->container.sections || octree->container.mapping)
        gb_container_close(&octree->container);
    *octree = (gb_light_octree){0};
}

uint32_t gb_light_octree_find_leaf(const gb_light_octree *octree, const float p[3])
{
    const gb_light_octree_header *h = &octree->header;
    uint32_t resolution = 1u << h->depth, cell[3];
    for (int k = 0; k < 3; ++k) {
        float x = (p[k] - h->origin[k]) / h->size * (float)resolution;
        if (!(x >= 0.0f) || x >= (float)resolution)
            return GB_LIGHT_OCTREE_NONE;
        cell[k] = (uint32_t)x;
    }
    uint32_t index = 0;
    for (uint32_t level = 0; level < h->depth && index != GB_LIGHT_OCTREE_NONE; ++level) {
        uint32_t shift = h->depth - 1 - level;
        uint32_t c = (cell[0] >> shift & 1) | (cell[1] >> shift & 1) << 1 |
                     (cell[2] >> shift & 1) << 2;
        index = octree->nodes[index].child[c];
    }
    return index;
}
