/* light_octree_shading.c — the light octree's irradiance at a point, the
 * CPU twin of runtime/octree/octree_irradiance.glsl (light_octree_shading.h).
 * Each function is named after the shader's and does what it does. */
#include "light_octree_shading.h"

#include <math.h>

#include "photon_map.h"
#include "vec3.h"

/* find_leaf: the leaf of integer cell, or GB_LIGHT_OCTREE_NONE; depth node
 * fetches from the root. */
static uint32_t find_leaf(const gb_light_octree *octree, const int cell[3])
{
    int depth = (int)octree->header.depth, resolution = 1 << depth;
    for (int k = 0; k < 3; ++k)
        if (cell[k] < 0 || cell[k] >= resolution)
            return GB_LIGHT_OCTREE_NONE;
    uint32_t node = 0;
    for (int level = 0; level < depth; ++level) {
        int shift = depth - 1 - level;
        int child = (cell[0] >> shift & 1) | (cell[1] >> shift & 1) << 1 |
                    (cell[2] >> shift & 1) << 2;
        node = octree->nodes[node].child[child];
        if (node == GB_LIGHT_OCTREE_NONE)
            return GB_LIGHT_OCTREE_NONE;
    }
    return node;
}

float gb_light_octree_vdl_gain(const float n[3], const float leaf_normal[3], const float w[3])
{
    return gb_dot3(n, w) / fmaxf(fabsf(gb_dot3(leaf_normal, w)), GB_LIGHT_OCTREE_MIN_COS);
}

/* leaf_light: the sum of the leaf's VDLs, E max(0, n.w) / max(|nl.w|,
 * MIN_COS), those from behind ng dropped, and the leaf's normal nl; 0 (and
 * sum 0) for no leaf or a leaf without VDLs, else 1. */
static int leaf_light(const gb_light_octree *octree, uint32_t index, const float n[3],
                      const float ng[3], float sum[3], float leaf_normal[3])
{
    sum[0] = sum[1] = sum[2] = 0.0f;
    if (index == GB_LIGHT_OCTREE_NONE || octree->leaves[index].vdl_count == 0)
        return 0;
    const gb_light_octree_leaf *leaf = &octree->leaves[index];
    gb_light_octree_leaf_normal(leaf, leaf_normal);
    for (uint32_t i = leaf->first_vdl; i < leaf->first_vdl + leaf->vdl_count; ++i) {
        const gb_light_octree_vdl *vdl = &octree->vdls[i];
        float w[3];
        gb_photon_unpack_direction(vdl->direction, w);
        float c = gb_light_octree_vdl_gain(n, leaf_normal, w);
        if (c > 0.0f && gb_dot3(ng, w) > 0.0f)
            for (int k = 0; k < 3; ++k)
                sum[k] += vdl->irradiance[k] * c;
    }
    return 1;
}

/* surface_distance: how far x is from the leaf's surface, in cell edges:
 * its distance from the leaf's plane plus 1 - |n_leaf.ng| (a leaf of
 * another orientation is another surface); offset = x - the leaf's centre
 * in cell edges. */
static float surface_distance(const gb_light_octree_leaf *leaf, const float leaf_normal[3],
                              const float offset[3], const float ng[3])
{
    float plane = (float)leaf->plane / GB_LIGHT_OCTREE_PLANE_ONE;
    return fabsf(gb_dot3(leaf_normal, offset) - plane) +
           (1.0f - fabsf(gb_dot3(leaf_normal, ng)));
}

/* interpolate: trilinear between the 8 leaf centres around x, over those
 * with VDLs, each weight at least MIN_WEIGHT, times its surface factor
 * when the octree's interpolation is GB_LIGHT_OCTREE_SURFACE. */
void gb_light_octree_irradiance(const gb_light_octree *octree, const float x[3],
                                const float n[3], const float ng[3], float out_rgb[3])
{
    const gb_light_octree_header *h = &octree->header;
    float cell_size = h->size / (float)(1u << h->depth);
    float base[3], f[3], total[3] = {0.0f, 0.0f, 0.0f}, weight = 0.0f;
    float resolution = (float)(1u << h->depth);
    for (int k = 0; k < 3; ++k) {
        float g = (x[k] - h->origin[k]) / cell_size - 0.5f;
        base[k] = floorf(g);
        f[k] = g - base[k];
        /* far outside the cube all 8 cells are outside too; clamped, the
         * integer cell stays representable */
        base[k] = fminf(fmaxf(base[k], -2.0f), resolution + 1.0f);
    }
    float w[8], distance[8], sums[8][3], nearest = INFINITY;
    int lit[8];
    for (int c = 0; c < 8; ++c) {
        int o[3] = {c & 1, (c >> 1) & 1, c >> 2}, cell[3];
        float t = 1.0f, offset[3], leaf_normal[3];
        for (int k = 0; k < 3; ++k) {
            t *= o[k] ? f[k] : 1.0f - f[k];
            cell[k] = (int)base[k] + o[k];
            offset[k] = f[k] - (float)o[k];
        }
        w[c] = fmaxf(t, GB_LIGHT_OCTREE_MIN_WEIGHT);
        uint32_t index = find_leaf(octree, cell);
        lit[c] = leaf_light(octree, index, n, ng, sums[c], leaf_normal);
        distance[c] = 0.0f;
        if (lit[c] && h->interpolation == GB_LIGHT_OCTREE_SURFACE)
            distance[c] = surface_distance(&octree->leaves[index], leaf_normal, offset, ng);
        if (lit[c])
            nearest = fminf(nearest, distance[c]);
    }
    float trust = fminf(fmaxf(2.0f - 2.0f * nearest / GB_LIGHT_OCTREE_SURFACE_REACH, 0.0f), 1.0f);
    for (int c = 0; c < 8; ++c) {
        if (!lit[c])
            continue;
        float factor = fmaxf(1.0f - (distance[c] - nearest) / GB_LIGHT_OCTREE_SURFACE_REACH,
                             GB_LIGHT_OCTREE_MIN_SURFACE);
        float surface = 1.0f - trust * (1.0f - factor);
        for (int k = 0; k < 3; ++k)
            total[k] += w[c] * surface * sums[c][k];
        weight += w[c] * surface;
    }
    for (int k = 0; k < 3; ++k)
        out_rgb[k] = weight > 0.0f ? total[k] / weight : 0.0f;
}
