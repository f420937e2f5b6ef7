// IUGC's workgroup a tile: 64 invocations over the 32 x 32 pixels of a
// tile (TILE is GB_TOPO_TILE, as topo_geometry_clusters_gpu.c asserts),
// PER pixels each; pixel_of(p), the tile's pixel p, and tile_index().
layout(local_size_x = 64) in;
layout(binding = 0, rg32ui) uniform uimage2D clusters;
const uint NO = 0xffffffffu;
const uint TILE = 32u, PIXELS = TILE * TILE, THREADS = 64u,
           PER = PIXELS / THREADS, ROUNDS = 16u;
ivec2 pixel_of(uint p) {
    return ivec2(gl_WorkGroupID.xy * TILE + uvec2(p % TILE, p / TILE));
}
uint tile_index() {
    return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}
