/* fuzz_light_octree.c — libFuzzer target for the `.lot` reader
 * (formats/light_octree.c): any input gives either an octree that passes
 * gb_light_octree_check, or an error "fuzz: ...", never a crash or a read
 * out of bounds (run under ASan/UBSan by `make fuzz`). The input is copied
 * into a 16-byte aligned buffer, as a mapped file is; every leaf and VDL of
 * a parsed octree is read, and the root-to-leaf walk the runtime does
 * (gb_light_octree_find_leaf) is run from the centre of every leaf's cell
 * and from a point outside the cube and a NaN point.
 *
 * Every payload is CRC-checked by the container, so almost every mutation
 * would stop there: each input is parsed as it is, then again with its
 * checksums recomputed (fix_checksums.h), which lets the mutations reach
 * the octree's own checks.
 */
#include "light_octree.h"
#include "photon_map.h"

#include <stddef.h>
#include <stdint.h>

#include "fuzz_reader.h"

/* Sums what the runtime reads; traps when the walk to a leaf's own cell
 * does not end at that leaf. */
static float walk(const gb_light_octree *octree)
{
    const gb_light_octree_header *h = &octree->header;
    float sum = 0.0f, edge = h->size / (float)(1u << h->depth);
    for (uint32_t i = 0; i < h->leaf_count; ++i) {
        const gb_light_octree_leaf *leaf = &octree->leaves[i];
        float p[3], normal[3];
        uint32_t cell[3];
        gb_light_octree_leaf_cell(leaf, cell);
        for (int k = 0; k < 3; ++k)
            p[k] = h->origin[k] + ((float)cell[k] + 0.5f) * edge;
        uint32_t found = gb_light_octree_find_leaf(octree, p);
        if (found != i && found != GB_LIGHT_OCTREE_NONE && found >= h->leaf_count)
            __builtin_trap(); /* the walk never leaves the arrays */
        for (uint32_t v = leaf->first_vdl; v < leaf->first_vdl + leaf->vdl_count; ++v) {
            float d[3];
            gb_photon_unpack_direction(octree->vdls[v].direction, d);
            sum += octree->vdls[v].irradiance[1] + d[2];
        }
        gb_light_octree_leaf_normal(leaf, normal);
        sum += normal[0];
    }
    const float outside[3] = {h->origin[0] - h->size, h->origin[1], h->origin[2] + 2 * h->size};
    const float nan[3] = {h->origin[0], __builtin_nanf(""), h->origin[2]};
    return sum + (float)gb_light_octree_find_leaf(octree, outside) +
           (float)gb_light_octree_find_leaf(octree, nan);
}

static int is_empty(const gb_light_octree *octree)
{
    return !octree->nodes && !octree->leaves && !octree->vdls && !octree->header.leaf_count;
}

GB_FUZZ_READER(parse, gb_light_octree, gb_light_octree_parse, gb_light_octree_check,
               gb_light_octree_free, walk, is_empty)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_fuzz_parse_twice(data, size, parse);
    return 0;
}
