// The light octree's irradiance at a world point (Vivianloc 2007, §4.2): the
// VDL sums of the 8 leaves around it (each walked from the root, Figure 6),
// trilinear between the leaf centres over those with VDLs (the holes of
// Fig. 16c), octree.h's convention. The display (octree_display.frag.glsl)
// and the render into the atlas (octree_atlas_render.frag.glsl) include it;
// common/light_octree_shading.c is its CPU twin. The includer sets the
// buffers (octree.c's upload) and the uniforms origin, cell_size, depth,
// surface_interpolation.
layout(std430, binding = 0) readonly buffer Nodes { uint nodes[]; };
layout(std430, binding = 1) readonly buffer Leaves { uint leaves[]; };
layout(std430, binding = 2) readonly buffer Vdls { uint vdls[]; };
uniform vec3 origin;
uniform float cell_size;
uniform int depth;
uniform bool surface_interpolation;  // the octree's header: GB_LIGHT_OCTREE_SURFACE
const uint NONE = 0xffffffffu;
const float PI = 3.14159265358979;
const float MIN_COS = 0.25;
const float MIN_WEIGHT = 1e-6;
const float MIN_SURFACE = 1e-3;
const float PLANE_ONE = 32767.0;
const float SURFACE_REACH = 0.25;
// gb_light_octree_find_leaf: depth node fetches from the root.
uint find_leaf(ivec3 cell) {
    if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(1 << depth))))
        return NONE;
    uint node = 0u;
    for (int level = 0; level < depth; ++level) {
        ivec3 bit = (cell >> (depth - 1 - level)) & 1;
        node = nodes[8u * node + uint(bit.x | bit.y << 1 | bit.z << 2)];
        if (node == NONE)
            return NONE;
    }
    return node;
}
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/octree/octree_vdl_direction.glsl"
// Sum of the leaf's VDLs, E max(0, n.w) / max(|nl.w|, MIN_COS) (octree.h),
// and the leaf's normal nl; false for no leaf or no VDL.
bool leaf_light(uint leaf, vec3 n, vec3 ng, out vec3 sum, out vec3 nl) {
    sum = vec3(0.0);
    nl = vec3(0.0);
    if (leaf == NONE || (leaves[4u * leaf + 2u] & 0xffffu) == 0u)
        return false;
    uint first = leaves[4u * leaf + 1u], end = first + (leaves[4u * leaf + 2u] & 0xffffu);
    nl = vdl_direction(leaves[4u * leaf]);
    for (uint i = first; i < end; ++i) {
        vec3 w = vdl_direction(vdls[4u * i + 3u]);
        float c = dot(n, w) / max(abs(dot(nl, w)), MIN_COS);
        if (c > 0.0 && dot(ng, w) > 0.0)
            sum += uintBitsToFloat(uvec3(vdls[4u * i], vdls[4u * i + 1u],
                                         vdls[4u * i + 2u])) * c;
    }
    return true;
}
// How far x is from the leaf's surface in cell edges: its distance from
// the leaf's plane plus 1 - |n_leaf.ng|; offset = x - the leaf's centre in
// cell edges (gb_light_octree_irradiance's surface_distance).
float surface_distance(uint leaf, vec3 nl, vec3 offset, vec3 ng) {
    float plane = float(int(leaves[4u * leaf + 2u]) >> 16) / PLANE_ONE;
    return abs(dot(nl, offset) - plane) + (1.0 - abs(dot(nl, ng)));
}
// Trilinear between the 8 leaf centres around x, renormalised over the
// neighbours that have VDLs. Each weight is at least MIN_WEIGHT: at a
// leaf centre the weights of the other 7 vanish, and when that leaf has
// no VDLs the pixel would be black (tests/unit/test_octree_display.c);
// there the floor makes it the mean of the others, and elsewhere it
// changes the result by under 10^-5. With surface interpolation each is
// also scaled by max(1 - (s - s_min) / SURFACE_REACH, MIN_SURFACE), s the
// leaf's surface_distance and s_min the least of the 8: a leaf of another
// surface lends x almost nothing; that factor fades to 1 (trust to 0) as
// s_min grows from half a reach to one: where no leaf holds x, trilinear
// (light_octree_shading.h).
vec3 interpolate(vec3 x, vec3 n, vec3 ng) {
    vec3 g = (x - origin) / cell_size - 0.5;
    vec3 base = floor(g), f = g - base;
    float w[8], distance[8];
    vec3 sums[8];
    bool lit[8];
    float nearest = 1e30;
    for (int c = 0; c < 8; ++c) {
        ivec3 o = ivec3(c & 1, (c >> 1) & 1, c >> 2);
        vec3 t = mix(1.0 - f, f, vec3(o));
        w[c] = max(t.x * t.y * t.z, MIN_WEIGHT);
        uint leaf = find_leaf(ivec3(base) + o);
        vec3 nl;
        lit[c] = leaf_light(leaf, n, ng, sums[c], nl);
        distance[c] = lit[c] && surface_interpolation ? surface_distance(leaf, nl, f - vec3(o), ng)
                                                      : 0.0;
        if (lit[c])
            nearest = min(nearest, distance[c]);
    }
    vec3 total = vec3(0.0);
    float weight = 0.0;
    float trust = clamp(2.0 - 2.0 * nearest / SURFACE_REACH, 0.0, 1.0);
    for (int c = 0; c < 8; ++c) {
        if (!lit[c])
            continue;
        float factor = max(1.0 - (distance[c] - nearest) / SURFACE_REACH, MIN_SURFACE);
        float surface = 1.0 - trust * (1.0 - factor);
        total += w[c] * surface * sums[c];
        weight += w[c] * surface;
    }
    return weight > 0.0 ? total / weight : vec3(0.0);
}
