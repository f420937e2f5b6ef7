// IUGC, bounds pass (a workgroup a tile): each geometry cluster's box by
// shared atomicMin/Max on floats as ordered uints (a cluster lies in one
// tile), its global index into clusters.y, then its box and sphere.
#version 450 core
#include "runtime/topo/topo_geometry_clusters_per_tile.glsl"
layout(binding = 2) uniform sampler2D gbuffer_depth;
layout(std430, binding = 1) readonly buffer TileCounts { uint tile_count[]; };
layout(std430, binding = 2) readonly buffer TileOffsets { uint tile_offset[]; };
struct GeometryCluster { vec4 sphere; uvec4 info; };
layout(std430, binding = 3) writeonly buffer Clusters { GeometryCluster spheres[]; };
struct Box { vec4 lo; vec4 hi; };
layout(std430, binding = 4) writeonly buffer Boxes { Box boxes[]; };
uniform mat4 view_to_world;
uniform vec2 tan_half_fov;
uniform float near;
shared uint box[6u * PIXELS];
shared uint visibility[PIXELS];
// floats as uints in the same order
uint ordered(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float unordered(uint u) {
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}
#include "runtime/gbuffer_world_position.glsl"
void main() {
    uint lid = gl_LocalInvocationIndex;
    uint t = tile_index();
    uint count = tile_count[t], first = tile_offset[t];
    ivec2 size = imageSize(clusters);
    for (uint j = lid; j < count; j += THREADS)
        for (uint a = 0u; a < 3u; ++a) {
            box[6u * j + a] = 0xffffffffu;
            box[6u * j + 3u + a] = 0u;
        }
    memoryBarrierShared();
    barrier();
// PER neighbours in a row: their box first, one set of atomics per cluster
    uint held = NO;
    vec3 lo = vec3(0.0), hi = vec3(0.0);
    for (uint r = 0u; r <= PER; ++r) {
        ivec2 pixel = pixel_of(PER * lid + min(r, PER - 1u));
        uvec2 ids = uvec2(NO, NO);
        if (r < PER && pixel.x < size.x && pixel.y < size.y)
            ids = imageLoad(clusters, pixel).xy;
        if (held != NO && ids.y != held)
            for (uint a = 0u; a < 3u; ++a) {
                atomicMin(box[6u * held + a], ordered(lo[a]));
                atomicMax(box[6u * held + 3u + a], ordered(hi[a]));
            }
        if (ids.y == NO) {
            held = NO;
            continue;
        }
        vec3 p = world_position(pixel, size, texelFetch(gbuffer_depth, pixel, 0).r);
        lo = ids.y == held ? min(lo, p) : p;
        hi = ids.y == held ? max(hi, p) : p;
        held = ids.y;
        visibility[ids.y] = ids.x; // the same for every fragment of it
        imageStore(clusters, pixel, uvec4(ids.x, first + ids.y, 0u, 0u));
    }
    memoryBarrierShared();
    barrier();
    for (uint j = lid; j < count; j += THREADS) {
        vec3 lo, hi;
        for (uint a = 0u; a < 3u; ++a) {
            lo[a] = unordered(box[6u * j + a]);
            hi[a] = unordered(box[6u * j + 3u + a]);
        }
        vec3 h = 0.5 * (hi - lo);
        float radius = sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
        spheres[first + j] = GeometryCluster(vec4(0.5 * (lo + hi), radius),
                                             uvec4(visibility[j], 0u, 0u, 0u));
        boxes[first + j] = Box(vec4(lo, 0.0), vec4(hi, 0.0));
    }
}
