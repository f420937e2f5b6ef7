/* part_merge.c — gb_cluster_merge (cluster.h): the octrees of --shard 0/N
 * .. N-1/N made one, each leaf's VDLs from the part its leaf belongs to
 * (gb_cluster_part_leaves), packed in leaf order as cluster.c's assemble
 * packs them, so that the bytes are those of one whole run. */
#include <stdlib.h>
#include <string.h>

#include "cluster.h"

/* The same octree but for its VDLs: header, nodes, leaves' cells and normals. */
static int same_octree(const gb_light_octree *a, const gb_light_octree *b)
{
    gb_light_octree_header ha = a->header, hb = b->header;
    ha.vdl_count = hb.vdl_count = 0;
    if (memcmp(&ha, &hb, sizeof ha) != 0 ||
        memcmp(a->nodes, b->nodes, (size_t)ha.node_count * sizeof *a->nodes) != 0)
        return 0;
    for (uint32_t i = 0; i < ha.leaf_count; ++i)
        if (a->leaves[i].normal != b->leaves[i].normal || a->leaves[i].cell != b->leaves[i].cell)
            return 0;
    return 1;
}

static gb_result check_parts(const gb_light_octree *parts, const char *const *names,
                             uint32_t count, gb_error *error)
{
    if (count < 2)
        return gb_fail(error, GB_ERROR_ARGUMENT, "cluster --merge: give the N octrees of "
                       "--shard 0/N .. N-1/N, N at least 2 (got %u)", count);
    for (uint32_t p = 1; p < count; ++p)
        if (!same_octree(&parts[0], &parts[p]))
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: not a part of the octree of %s "
                           "(another scene, depth or options)", names[p], names[0]);
    uint32_t leaf_count = parts[0].header.leaf_count;
    for (uint32_t p = 0; p < count; ++p) {
        uint32_t first, end;
        gb_cluster_part_leaves(leaf_count, p, count, &first, &end);
        for (uint32_t i = 0; i < leaf_count; ++i)
            if ((i < first || i >= end) && parts[p].leaves[i].vdl_count)
                return gb_fail(error, GB_ERROR_ARGUMENT, "%s: VDLs in leaf %u, outside its "
                               "leaves: not part %u of %u (give the parts in order, all of "
                               "them)", names[p], i, p, count);
    }
    return GB_OK;
}

gb_result gb_cluster_merge(const gb_light_octree *parts, const char *const *names,
                           uint32_t count, gb_light_octree *merged, gb_error *error)
{
    memset(merged, 0, sizeof *merged);
    gb_result result = check_parts(parts, names, count, error);
    if (result != GB_OK)
        return result;
    gb_light_octree_header h = parts[0].header;
    h.vdl_count = 0;
    for (uint32_t p = 0; p < count; ++p)
        h.vdl_count += parts[p].header.vdl_count;
    size_t node_bytes = (size_t)h.node_count * sizeof *merged->nodes;
    size_t leaf_bytes = (size_t)h.leaf_count * sizeof *merged->leaves;
    unsigned char *block = malloc(node_bytes + leaf_bytes + (size_t)h.vdl_count * 16 + 16);
    if (!block)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    gb_light_octree_node *n = (void *)block;
    gb_light_octree_leaf *l = (void *)(block + node_bytes);
    gb_light_octree_vdl *v = (void *)(block + node_bytes + leaf_bytes);
    memcpy(n, parts[0].nodes, node_bytes);
    for (uint32_t p = 0, next = 0; p < count; ++p) {
        uint32_t first, end;
        gb_cluster_part_leaves(h.leaf_count, p, count, &first, &end);
        for (uint32_t i = first; i < end; ++i) {
            const gb_light_octree_leaf *from = &parts[p].leaves[i];
            l[i] = *from;
            l[i].first_vdl = next;
            memcpy(&v[next], &parts[p].vdls[from->first_vdl], from->vdl_count * sizeof *v);
            next += from->vdl_count;
        }
    }
    merged->header = h;
    merged->storage = block;
    merged->nodes = n;
    merged->leaves = l;
    merged->vdls = v;
    return GB_OK;
}
