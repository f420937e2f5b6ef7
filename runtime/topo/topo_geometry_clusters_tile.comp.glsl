// IUGC (Noël & Biri 2014, §V.B), tile pass: each fragment's key (depth
// slice of Olsson et al. 2012, visibility cluster); the tile's distinct
// keys in order, by extracting the smallest pending key round after round
// or, past ROUNDS distinct keys, by a bitonic sort of the tile's keys
// compacted by a prefix sum; each fragment's rank among them to
// clusters.y, the tile's count to tile_count.
#version 450 core
#include "runtime/topo/topo_geometry_clusters_per_tile.glsl"
layout(binding = 2) uniform sampler2D gbuffer_depth;
layout(std430, binding = 0) readonly buffer SliceBounds { float slice_bound[]; };
layout(std430, binding = 1) writeonly buffer TileCounts { uint tile_count[]; };
uniform uint slice_count;
uniform bool slices_exact;
uniform float near;
uniform float log_base;
shared uvec2 keys[PIXELS];
shared uvec2 distinct[PIXELS];
bool less(uvec2 a, uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }
// the largest j with d <= slice_bound[j] (slice_bound[0] = +inf), from
// the GPU's own log, moved to the table's answer
uint slice_of(float d) {
    float k = log(max(near / d / near, 1.0)) / log_base;
    uint j = k < float(slice_count) ? uint(k) : slice_count - 1u;
    while (j + 1u < slice_count && d <= slice_bound[j + 1u])
        ++j;
    while (j > 0u && d > slice_bound[j])
        --j;
    if (j + 1u < slice_count || slices_exact)
        return j;
    return k < 4e9 ? max(uint(k), j) : 0xfffffffeu;
}
void sort_keys(uint lid) {
    for (uint k = 2u; k <= PIXELS; k <<= 1u)
        for (uint j = k >> 1u; j > 0u; j >>= 1u) {
            for (uint q = lid; q < PIXELS / 2u; q += THREADS) {
                uint i = (q / j) * 2u * j + q % j, l = i + j;
                uvec2 a = keys[i], b = keys[l];
                if ((i & k) == 0u ? less(b, a) : less(a, b)) {
                    keys[i] = b;
                    keys[l] = a;
                }
            }
            memoryBarrierShared();
            barrier();
        }
}
#include "runtime/topo/topo_geometry_clusters_prefix_sum.glsl"
// the sorted keys made distinct into distinct[]; returns how many
uint compact(uint lid) {
    uint n = 0u;
    bool first[PER];
    for (uint e = 0u; e < PER; ++e) {
        uint i = PER * lid + e;
        first[e] = keys[i].y != NO && (i == 0u || keys[i] != keys[i - 1u]);
        n += first[e] ? 1u : 0u;
    }
    uint total;
    uint at = prefix_sum(lid, n, total);
    for (uint e = 0u; e < PER; ++e)
        if (first[e])
            distinct[at++] = keys[PER * lid + e];
    memoryBarrierShared();
    barrier();
    return total;
}
// Few distinct keys (the common case): the smallest pending key of the
// tile, round after round, by shared atomicMin on slice then cluster;
// a fragment's rank is the round its key came out. Returns the count,
// or NO when keys are left after ROUNDS rounds.
shared uint min_slice[2], min_cluster[2], pending_left[2];
uint extract_minima(uint lid, uvec2 mine[PER], inout uint rank[PER]) {
    bool pending[PER];
    for (uint r = 0u; r < PER; ++r)
        pending[r] = mine[r].y != NO;
    if (lid == 0u) {
        min_slice[0] = NO;
        min_cluster[0] = NO;
        pending_left[0] = 0u;
    }
    memoryBarrierShared();
    barrier();
    for (uint round = 0u; round < ROUNDS; ++round) {
        uint b = round & 1u;
        uint least = NO;
        for (uint r = 0u; r < PER; ++r)
            if (pending[r])
                least = min(least, mine[r].x);
        if (least != NO)
            atomicMin(min_slice[b], least);
        memoryBarrierShared();
        barrier();
        if (lid == 0u) { // every invocation is past last round's reads
            min_slice[1u - b] = NO;
            min_cluster[1u - b] = NO;
            pending_left[1u - b] = 0u;
        }
        uint slice = min_slice[b];
        least = NO;
        for (uint r = 0u; r < PER; ++r)
            if (pending[r] && mine[r].x == slice)
                least = min(least, mine[r].y);
        if (least != NO)
            atomicMin(min_cluster[b], least);
        memoryBarrierShared();
        barrier();
        uint left = 0u;
        for (uint r = 0u; r < PER; ++r) {
            if (pending[r] && mine[r] == uvec2(min_slice[b], min_cluster[b])) {
                rank[r] = round;
                pending[r] = false;
            }
            left += pending[r] ? 1u : 0u;
        }
        if (left > 0u)
            atomicAdd(pending_left[b], left);
        memoryBarrierShared();
        barrier();
        if (pending_left[b] == 0u)
            return min_slice[b] == NO ? round : round + 1u;
    }
    return NO;
}
uint rank_of(uvec2 key, uint count) {
    uint lo = 0u, hi = count;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (less(distinct[mid], key)) lo = mid + 1u; else hi = mid;
    }
    return lo;
}
void main() {
    uint lid = gl_LocalInvocationIndex;
    ivec2 size = imageSize(clusters);
    uvec2 mine[PER];
    for (uint r = 0u; r < PER; ++r) {
        uint p = lid + r * THREADS;
        ivec2 pixel = pixel_of(p);
        uvec2 key = uvec2(NO, NO);
        if (pixel.x < size.x && pixel.y < size.y) {
            float d = texelFetch(gbuffer_depth, pixel, 0).r;
            uint c = imageLoad(clusters, pixel).x;
            if (d > 0.0 && c != NO)
                key = uvec2(slice_of(d), c);
        }
        keys[p] = key;
        mine[r] = key;
    }
    uint rank[PER];
    for (uint r = 0u; r < PER; ++r)
        rank[r] = NO;
    uint count = extract_minima(lid, mine, rank);
    if (count == NO) { // uniform: read from shared after a barrier
        sort_keys(lid);
        count = compact(lid);
        for (uint r = 0u; r < PER; ++r)
            rank[r] = mine[r].y == NO ? NO : rank_of(mine[r], count);
    }
    for (uint r = 0u; r < PER; ++r) {
        ivec2 pixel = pixel_of(lid + r * THREADS);
        if (pixel.x < size.x && pixel.y < size.y)
            imageStore(clusters, pixel,
                       uvec4(imageLoad(clusters, pixel).x, rank[r], 0u, 0u));
    }
    if (lid == 0u)
        tile_count[tile_index()] = count;
}
