/* light_octree.h — the light octree on disk: the file kind "LOCT"
 * (formats/FORMATS.md, "Light octree"). `cluster` writes it (vivianloc-2007
 * §3.1), the runtime reads it in place and walks it like the paper's GPU
 * octree (§4.2.1, Figure 5): from the root, one node fetch per level, δ
 * fetches reach a leaf; the leaf gives a range of the VDL array.
 *
 * Sections (each 16-byte aligned, host = file byte order, little-endian):
 *   header  gb_light_octree_header (128 bytes)
 *   nodes   gb_light_octree_node x node_count: node 0 is the root (level 0);
 *           a child of a node of level l < depth - 1 is a node index, of a
 *           node of level depth - 1 a leaf index; GB_LIGHT_OCTREE_NONE where
 *           there is no geometry. Child c covers the octant with x in bit 0,
 *           y in bit 1, z in bit 2 (1: the upper half).
 *   leaves  gb_light_octree_leaf x leaf_count, in Morton order of their cell
 *   vdls    gb_light_octree_vdl x vdl_count: leaf i's VDLs are
 *           vdls[first_vdl .. first_vdl + vdl_count), brightest first, and
 *           the leaves' ranges follow each other in leaf order.
 *
 *   gb_light_octree_read("x.lot", &octree, &error);   // checks every index
 *   gb_light_octree_free(&octree);
 * A gb_light_octree owns its storage (malloc'ed arrays, or the mapping).
 */
#ifndef GB_LIGHT_OCTREE_H
#define GB_LIGHT_OCTREE_H

#include <stddef.h>
#include <stdint.h>

#include "container.h"
#include "photon_map.h"
#include "result.h"

enum {
    GB_LIGHT_OCTREE_VERSION = 3,   /* 3: 16-byte leaves; 2: tolerance in place of 1's spread */
    GB_LIGHT_OCTREE_MAX_DEPTH = 10,     /* leaf cells keep 3 x 10 bits */
    GB_LIGHT_OCTREE_MAX_VDLS = 64,      /* per leaf */
};

#define GB_LIGHT_OCTREE_NONE 0xFFFFFFFFu

enum {
    GB_LIGHT_OCTREE_TRILINEAR = 0,      /* the paper's: trilinear over the 8 leaves */
    GB_LIGHT_OCTREE_SURFACE = 1,        /* weighed by how well each leaf holds the surface */
};

typedef struct gb_light_octree_header {
    uint32_t depth;             /* δ: leaves are the cells of a 2^δ grid, 1 .. 10 */
    uint32_t node_count;
    uint32_t leaf_count;
    uint32_t vdl_count;
    float origin[3];            /* the octree's cube: origin .. origin + size */
    float size;
    uint64_t scene_hash;        /* gb_scene.hash of the scene clustered */
    uint64_t photon_count;      /* photons in the map clustered */
    uint64_t emitted_count;     /* photons emitted by the run that traced it */
    uint64_t seed;              /* k-means++ seeding */
    uint32_t knn;               /* K: most photons gathered per leaf */
    float radius;               /* R: largest gathering radius (world units) */
    uint32_t vdls_max;          /* K_max: most VDLs per leaf */
    float tolerance;            /* relative irradiance error a leaf's VDL count was
                                   chosen for (tools/cluster/vdl.h); negative:
                                   K_max always */
    float flattening;           /* ellipsoid: normal semi-axis / tangent semi-axis */
    uint32_t interpolation;     /* between leaves: GB_LIGHT_OCTREE_TRILINEAR or
                                   GB_LIGHT_OCTREE_SURFACE (light_octree_shading.h) */
    uint32_t reserved[10];      /* zero */
} gb_light_octree_header;

typedef struct gb_light_octree_node {
    uint32_t child[8];
} gb_light_octree_node;

/* A leaf: what the runtime reads to shade in it, in 16 bytes. Its normal
 * and cell are packed: read them with gb_light_octree_leaf_normal and
 * gb_light_octree_leaf_cell. */
typedef struct gb_light_octree_leaf {
    uint32_t normal;            /* unit: area-weighted normal of its geometry,
                                   octahedral 2 x 16 bits as a VDL's direction */
    uint32_t first_vdl;
    uint16_t vdl_count;         /* 0 .. vdls_max: 0 when no photon was gathered */
    int16_t plane;              /* where its surface lies: the plane of the normal
                                   through the point the leaf gathered at, as
                                   n.(x - cell centre) = plane / 32767 cell edges;
                                   -32767 .. 32767 */
    uint32_t cell;              /* integer cell, 0 .. 2^depth - 1 per axis: x in
                                   bits 0..9, y in 10..19, z in 20..29 */
} gb_light_octree_leaf;

#define GB_LIGHT_OCTREE_PLANE_ONE 32767.0f  /* plane of one cell edge */

static inline uint32_t gb_light_octree_pack_cell(const uint32_t cell[3])
{
    return cell[0] | cell[1] << 10 | cell[2] << 20;
}

static inline void gb_light_octree_leaf_cell(const gb_light_octree_leaf *leaf, uint32_t cell[3])
{
    cell[0] = leaf->cell & 0x3FFu;
    cell[1] = leaf->cell >> 10 & 0x3FFu;
    cell[2] = leaf->cell >> 20 & 0x3FFu;
}

static inline void gb_light_octree_leaf_normal(const gb_light_octree_leaf *leaf, float n[3])
{
    gb_photon_unpack_direction(leaf->normal, n);
}

/* A virtual directional light: irradiance (W/m^2, linear RGB) arriving from
 * direction (unit, toward the light; octahedral 2 x 16 bits as photon_map.h's
 * gb_photon_pack_direction). */
typedef struct gb_light_octree_vdl {
    float irradiance[3];
    uint32_t direction;
} gb_light_octree_vdl;

typedef struct gb_light_octree {
    gb_light_octree_header header;
    const gb_light_octree_node *nodes;
    const gb_light_octree_leaf *leaves;
    const gb_light_octree_vdl *vdls;
    void *storage;              /* owned: the arrays when built in memory, or NULL */
    gb_container container;     /* owned: the file the arrays view, when read */
} gb_light_octree;

/* Checks the header and every index: the nodes form a tree from the root
 * reaching each leaf exactly once at the cell it names, the VDL ranges are
 * contiguous and in bounds, packed normals and directions valid,
 * irradiances finite and >= 0. */
gb_result gb_light_octree_check(const gb_light_octree *octree, const char *path,
                                gb_error *error);
/* Checks, then writes (temporary file, rename). */
gb_result gb_light_octree_write(const char *path, const gb_light_octree *octree,
                                gb_error *error);
/* Maps and checks; on failure *octree is zeroed and needs no freeing. */
gb_result gb_light_octree_read(const char *path, gb_light_octree *octree, gb_error *error);
/* The same on a 16-byte aligned buffer that outlives the octree. */
gb_result gb_light_octree_parse(const void *bytes, size_t size, const char *path,
                                gb_light_octree *octree, gb_error *error);
/* GB_ERROR_STALE unless made from the scene of this hash. */
gb_result gb_light_octree_check_scene(const gb_light_octree *octree, uint64_t scene_hash,
                                      const char *path, gb_error *error);
void gb_light_octree_free(gb_light_octree *octree);

/* The leaf index of the point p, or GB_LIGHT_OCTREE_NONE: walks depth nodes. */
uint32_t gb_light_octree_find_leaf(const gb_light_octree *octree, const float p[3]);

#endif
