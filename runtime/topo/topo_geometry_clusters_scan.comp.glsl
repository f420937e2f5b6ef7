// IUGC, scan pass (one workgroup): the exclusive prefix sum of the tiles'
// counts, each tile's first global cluster, and the total.
#version 450 core
layout(local_size_x = 256) in;
layout(std430, binding = 1) readonly buffer TileCounts { uint tile_count[]; };
layout(std430, binding = 2) writeonly buffer TileOffsets { uint tile_offset[]; };
layout(std430, binding = 3) writeonly buffer Total { uint total; };
uniform uint tiles;
const uint THREADS = 256u;
#include "runtime/topo/topo_geometry_clusters_prefix_sum.glsl"
void main() {
    uint lid = gl_LocalInvocationIndex;
    uint per = (tiles + THREADS - 1u) / THREADS;
    uint begin = min(lid * per, tiles), end = min(begin + per, tiles);
    uint n = 0u;
    for (uint t = begin; t < end; ++t)
        n += tile_count[t];
    uint sum;
    uint at = prefix_sum(lid, n, sum);
    for (uint t = begin; t < end; ++t) {
        tile_offset[t] = at;
        at += tile_count[t];
    }
    if (lid == THREADS - 1u)
        total = sum;
}
