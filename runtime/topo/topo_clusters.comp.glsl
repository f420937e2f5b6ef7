// The visibility cluster of each fragment (Noël & Biri 2014, §V.A), the
// twin of gb_topo_surface_cluster (topo_clusters.c says why): its world
// point moved off the surface along ng, in up to 3 steps, looked up in the
// voxels' clusters; else the nearest empty voxel with a cluster around the
// first offset, on ng's side; else the surface voxel's own. Into the
// G-buffer's clusters.x.
#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
#include "runtime/gbuffer_textures.glsl"
layout(binding = 12) uniform isampler3D voxel_clusters;
layout(rg32ui, binding = 0) writeonly uniform uimage2D clusters;
uniform vec3 grid_origin;
uniform float voxel_size;
uniform ivec3 grid_size;
const uint NO_CLUSTER = 0xffffffffu;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/gbuffer_world_position.glsl"
int voxel_cluster(vec3 p) {
    ivec3 v = ivec3(floor((p - grid_origin) / voxel_size));
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, grid_size)))
        return -1;
    return texelFetch(voxel_clusters, v, 0).r;
}
int cluster_around(vec3 x, vec3 ng, vec3 p) {
    ivec3 base = ivec3(floor((p - grid_origin) / voxel_size));
    int best = -1;
    float best_d2 = 3.0e38;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec3 v = base + ivec3(dx, dy, dz);
                vec3 centre = grid_origin + (vec3(v) + 0.5) * voxel_size;
                float d2 = dot(centre - p, centre - p);
                if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, grid_size)) ||
                    dot(centre - x, ng) <= 0.0 || d2 >= best_d2)
                    continue;
                int c = texelFetch(voxel_clusters, v, 0).r;
                if (c >= 0) {
                    best = c;
                    best_d2 = d2;
                }
            }
    return best;
}
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(clusters);
    if (pixel.x >= size.x || pixel.y >= size.y)
        return;
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    int c = -1;
    if (depth > 0.0) {
        vec3 x = world_position(pixel, size, depth);
        vec3 ng = normalize(mat3(view_to_world) *
                            oct_decode(texelFetch(gbuffer_normal, pixel, 0).zw));
        float l1 = abs(ng.x) + abs(ng.y) + abs(ng.z);
        int on_surface = -1;
        for (int step = 0; step < 3 && c < 0; ++step) {
            int v = voxel_cluster(x + ng * ((1.01 * l1 + float(step)) * voxel_size));
            if (v >= 0)
                c = v;
            else if (v < -1 && on_surface < 0)
                on_surface = -v - 2;
        }
        if (c < 0)
            c = cluster_around(x, ng, x + ng * (1.01 * l1 * voxel_size));
        if (c < 0)
            c = on_surface;
    }
    imageStore(clusters, pixel, uvec4(c >= 0 ? uint(c) : NO_CLUSTER, NO_CLUSTER, 0u, 0u));
}
