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
 * checksums recomputed (the container layout of formats/FORMATS.md), which
 * lets the mutations reach the octree's own checks.
 */
#include "light_octree.h"
#include "photon_map.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static volatile float sink;

/* Sums what the runtime reads; traps when the walk to a leaf's own cell
 * does not end at that leaf. */
static float walk(const gb_light_octree *octree)
{
    const gb_light_octree_header *h = &octree->header;
    float sum = 0.0f, edge = h->size / (float)(1u << h->depth);
    for (uint32_t i = 0; i < h->leaf_count; ++i) {
        const gb_light_octree_leaf *leaf = &octree->leaves[i];
        float p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = h->origin[k] + ((float)leaf->cell[k] + 0.5f) * edge;
        uint32_t found = gb_light_octree_find_leaf(octree, p);
        if (found != i && found != GB_LIGHT_OCTREE_NONE && found >= h->leaf_count)
            __builtin_trap(); /* the walk never leaves the arrays */
        for (uint32_t v = leaf->first_vdl; v < leaf->first_vdl + leaf->vdl_count; ++v) {
            float d[3];
            gb_photon_unpack_direction(octree->vdls[v].direction, d);
            sum += octree->vdls[v].irradiance[1] + d[2];
        }
        sum += leaf->normal[0];
    }
    const float outside[3] = {h->origin[0] - h->size, h->origin[1], h->origin[2] + 2 * h->size};
    const float nan[3] = {h->origin[0], __builtin_nanf(""), h->origin[2]};
    return sum + (float)gb_light_octree_find_leaf(octree, outside) +
           (float)gb_light_octree_find_leaf(octree, nan);
}

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get_u64(const unsigned char *p)
{
    return get_u32(p) | (uint64_t)get_u32(p + 4) << 32;
}

static void put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

/* Recomputes the payload and header CRC-32s of a container (32-byte header,
 * 48-byte table entries: offset at 24, size at 32, CRC at 40; the header's
 * CRC at 28 covers its first 28 bytes and the table) where they fit. */
static void fix_checksums(unsigned char *bytes, size_t size)
{
    if (size < 32)
        return;
    uint64_t count = get_u32(bytes + 24);
    if (count > (size - 32) / 48)
        return;
    for (uint64_t i = 0; i < count; ++i) {
        unsigned char *entry = bytes + 32 + i * 48;
        uint64_t offset = get_u64(entry + 24), length = get_u64(entry + 32);
        if (offset <= size && length <= size - offset && length <= UINT32_MAX)
            put_u32(entry + 40, (uint32_t)crc32(crc32(0L, Z_NULL, 0), bytes + offset,
                                                (uInt)length));
    }
    uLong crc = crc32(crc32(0L, Z_NULL, 0), bytes, 28);
    put_u32(bytes + 28, (uint32_t)crc32(crc, bytes + 32, (uInt)(count * 48)));
}

static void parse(const unsigned char *aligned, size_t size)
{
    gb_light_octree octree;
    gb_error error;
    if (gb_light_octree_parse(aligned, size, "fuzz", &octree, &error) == GB_OK) {
        if (gb_light_octree_check(&octree, "fuzz", &error) != GB_OK)
            __builtin_trap(); /* a parsed octree is always valid */
        sink += walk(&octree);
        gb_light_octree_free(&octree);
    } else if (strncmp(error.message, "fuzz: ", 6) != 0 || octree.nodes || octree.leaves ||
               octree.vdls || octree.header.leaf_count) {
        __builtin_trap(); /* failures name the input and leave an empty octree */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    unsigned char *aligned = aligned_alloc(16, (size + 16) & ~(size_t)15);
    if (!aligned)
        return 0;
    memcpy(aligned, data, size);
    parse(aligned, size);
    fix_checksums(aligned, size);
    parse(aligned, size);
    free(aligned);
    return 0;
}
