/* topo_geometry_clusters_gpu.c — IUGC (Noël & Biri 2014, §V.B) in compute
 * shaders, the twin of gb_topo_geometry_clusters_build
 * (topo_geometry_clusters.c), which stays the reference: the same keys
 * (depth slice of Olsson et al. 2012, visibility cluster), the same tiles,
 * the same numbering. Three passes, nothing read back but the count:
 *
 *   tile    one workgroup (64 invocations, 16 pixels each) per
 *           GB_TOPO_TILE^2 tile: each fragment's key; the tile's distinct
 *           keys in order by extracting the smallest pending key round
 *           after round (shared atomicMin on slice, then on cluster), or,
 *           past 16 distinct keys, by a bitonic sort of the 1024 keys in
 *           shared memory compacted by a prefix sum; each fragment's rank
 *           among them goes to clusters.y for now, the tile's count to
 *           tile_counts
 *   scan    one workgroup: exclusive prefix sum of the tile counts (the
 *           tiles' first global cluster) and the total
 *   bounds  one workgroup per tile: boxes by shared atomicMin/Max on floats
 *           as ordered uints (each geometry cluster lies in one tile), the
 *           global index into clusters.y, then box and sphere per cluster
 *
 * The slice of a depth: the largest j with d <= slice_bound[j], a table the
 * CPU fills with gb_topo_depth_slice's boundaries (binary search over the
 * floats), so GPU and CPU keys agree bit for bit whatever the GPU's log.
 * Shared memory: tile 16.5 KiB, bounds 28 KiB (GL 4.5 guarantees 32 KiB).
 * Workgroups never wait on one another: each pass's inputs were written by
 * an earlier dispatch, behind glMemoryBarrier. Bindings: image unit 0,
 * texture unit GB_UNIT_GBUFFER_DEPTH, storage buffers 0-4 (bound at each
 * run). The caller owns the G-buffer; the module owns its buffers and
 * programs. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "topo.h"

_Static_assert(GB_TOPO_TILE == 32, "the shaders' TILE is GB_TOPO_TILE");

enum {
    TABLE_MAX = 1u << 16,       /* slice boundaries at most */
    UNIT_CLUSTERS_IMAGE = 0,
};
/* Slices beyond this reversed depth fall back to the GPU's log. */
static const float TABLE_MIN_DEPTH = 1e-30f;

#define GLSL_TILE_COMMON                                                          \
    "#version 450 core\n"                                                        \
    "layout(local_size_x = 64) in;\n"                                            \
    "layout(binding = 0, rg32ui) uniform uimage2D clusters;\n"                   \
    "const uint NO = 0xffffffffu;\n"                                             \
    "const uint TILE = 32u, PIXELS = TILE * TILE, THREADS = 64u,\n"              \
    "           PER = PIXELS / THREADS, ROUNDS = 16u;\n"                          \
    "ivec2 pixel_of(uint p) {\n"                                                 \
    "    return ivec2(gl_WorkGroupID.xy * TILE + uvec2(p % TILE, p / TILE));\n"  \
    "}\n"                                                                        \
    "uint tile_index() {\n"                                                      \
    "    return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;\n"    \
    "}\n"

/* Exclusive prefix sum of n over a workgroup of THREADS invocations
 * (Hillis-Steele, double-buffered in shared sums[2 THREADS]); *total. */
#define GLSL_PREFIX_SUM                                                           \
    "shared uint sums[2u * THREADS];\n"                                          \
    "uint prefix_sum(uint lid, uint n, out uint total) {\n"                      \
    "    uint from = 0u;\n"                                                      \
    "    sums[lid] = n;\n"                                                       \
    "    memoryBarrierShared();\n"                                               \
    "    barrier();\n"                                                           \
    "    for (uint offset = 1u; offset < THREADS; offset <<= 1u) {\n"            \
    "        uint v = sums[from + lid];\n"                                       \
    "        if (lid >= offset)\n"                                               \
    "            v += sums[from + lid - offset];\n"                              \
    "        sums[THREADS - from + lid] = v;\n"                                  \
    "        from = THREADS - from;\n"                                           \
    "        memoryBarrierShared();\n"                                           \
    "        barrier();\n"                                                       \
    "    }\n"                                                                    \
    "    total = sums[from + THREADS - 1u];\n"                                   \
    "    return sums[from + lid] - n;\n"                                         \
    "}\n"

static const char tile_shader[] =
    GLSL_TILE_COMMON
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(std430, binding = 0) readonly buffer SliceBounds { float slice_bound[]; };\n"
    "layout(std430, binding = 1) writeonly buffer TileCounts { uint tile_count[]; };\n"
    "uniform uint slice_count;\n"
    "uniform bool slices_exact;\n"
    "uniform float near;\n"
    "uniform float log_base;\n"
    "shared uvec2 keys[PIXELS];\n"
    "shared uvec2 distinct[PIXELS];\n"
    "bool less(uvec2 a, uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }\n"
    /* the largest j with d <= slice_bound[j] (slice_bound[0] = +inf), from
     * the GPU's own log, moved to the table's answer */
    "uint slice_of(float d) {\n"
    "    float k = log(max(near / d / near, 1.0)) / log_base;\n"
    "    uint j = k < float(slice_count) ? uint(k) : slice_count - 1u;\n"
    "    while (j + 1u < slice_count && d <= slice_bound[j + 1u])\n"
    "        ++j;\n"
    "    while (j > 0u && d > slice_bound[j])\n"
    "        --j;\n"
    "    if (j + 1u < slice_count || slices_exact)\n"
    "        return j;\n"
    "    return k < 4e9 ? max(uint(k), j) : 0xfffffffeu;\n"
    "}\n"
    "void sort_keys(uint lid) {\n"
    "    for (uint k = 2u; k <= PIXELS; k <<= 1u)\n"
    "        for (uint j = k >> 1u; j > 0u; j >>= 1u) {\n"
    "            for (uint q = lid; q < PIXELS / 2u; q += THREADS) {\n"
    "                uint i = (q / j) * 2u * j + q % j, l = i + j;\n"
    "                uvec2 a = keys[i], b = keys[l];\n"
    "                if ((i & k) == 0u ? less(b, a) : less(a, b)) {\n"
    "                    keys[i] = b;\n"
    "                    keys[l] = a;\n"
    "                }\n"
    "            }\n"
    "            memoryBarrierShared();\n"
    "            barrier();\n"
    "        }\n"
    "}\n"
    GLSL_PREFIX_SUM
    /* the sorted keys made distinct into distinct[]; returns how many */
    "uint compact(uint lid) {\n"
    "    uint n = 0u;\n"
    "    bool first[PER];\n"
    "    for (uint e = 0u; e < PER; ++e) {\n"
    "        uint i = PER * lid + e;\n"
    "        first[e] = keys[i].y != NO && (i == 0u || keys[i] != keys[i - 1u]);\n"
    "        n += first[e] ? 1u : 0u;\n"
    "    }\n"
    "    uint total;\n"
    "    uint at = prefix_sum(lid, n, total);\n"
    "    for (uint e = 0u; e < PER; ++e)\n"
    "        if (first[e])\n"
    "            distinct[at++] = keys[PER * lid + e];\n"
    "    memoryBarrierShared();\n"
    "    barrier();\n"
    "    return total;\n"
    "}\n"
    /* Few distinct keys (the common case): the smallest pending key of the
     * tile, round after round, by shared atomicMin on slice then cluster;
     * a fragment's rank is the round its key came out. Returns the count,
     * or NO when keys are left after ROUNDS rounds. */
    "shared uint min_slice[2], min_cluster[2], pending_left[2];\n"
    "uint extract_minima(uint lid, uvec2 mine[PER], inout uint rank[PER]) {\n"
    "    bool pending[PER];\n"
    "    for (uint r = 0u; r < PER; ++r)\n"
    "        pending[r] = mine[r].y != NO;\n"
    "    if (lid == 0u) {\n"
    "        min_slice[0] = NO;\n"
    "        min_cluster[0] = NO;\n"
    "        pending_left[0] = 0u;\n"
    "    }\n"
    "    memoryBarrierShared();\n"
    "    barrier();\n"
    "    for (uint round = 0u; round < ROUNDS; ++round) {\n"
    "        uint b = round & 1u;\n"
    "        uint least = NO;\n"
    "        for (uint r = 0u; r < PER; ++r)\n"
    "            if (pending[r])\n"
    "                least = min(least, mine[r].x);\n"
    "        if (least != NO)\n"
    "            atomicMin(min_slice[b], least);\n"
    "        memoryBarrierShared();\n"
    "        barrier();\n"
    "        if (lid == 0u) {\n"      /* every invocation is past last round's reads */
    "            min_slice[1u - b] = NO;\n"
    "            min_cluster[1u - b] = NO;\n"
    "            pending_left[1u - b] = 0u;\n"
    "        }\n"
    "        uint slice = min_slice[b];\n"
    "        least = NO;\n"
    "        for (uint r = 0u; r < PER; ++r)\n"
    "            if (pending[r] && mine[r].x == slice)\n"
    "                least = min(least, mine[r].y);\n"
    "        if (least != NO)\n"
    "            atomicMin(min_cluster[b], least);\n"
    "        memoryBarrierShared();\n"
    "        barrier();\n"
    "        uint left = 0u;\n"
    "        for (uint r = 0u; r < PER; ++r) {\n"
    "            if (pending[r] && mine[r] == uvec2(min_slice[b], min_cluster[b])) {\n"
    "                rank[r] = round;\n"
    "                pending[r] = false;\n"
    "            }\n"
    "            left += pending[r] ? 1u : 0u;\n"
    "        }\n"
    "        if (left > 0u)\n"
    "            atomicAdd(pending_left[b], left);\n"
    "        memoryBarrierShared();\n"
    "        barrier();\n"
    "        if (pending_left[b] == 0u)\n"
    "            return min_slice[b] == NO ? round : round + 1u;\n"
    "    }\n"
    "    return NO;\n"
    "}\n"
    "uint rank_of(uvec2 key, uint count) {\n"
    "    uint lo = 0u, hi = count;\n"
    "    while (lo < hi) {\n"
    "        uint mid = (lo + hi) / 2u;\n"
    "        if (less(distinct[mid], key)) lo = mid + 1u; else hi = mid;\n"
    "    }\n"
    "    return lo;\n"
    "}\n"
    "void main() {\n"
    "    uint lid = gl_LocalInvocationIndex;\n"
    "    ivec2 size = imageSize(clusters);\n"
    "    uvec2 mine[PER];\n"
    "    for (uint r = 0u; r < PER; ++r) {\n"
    "        uint p = lid + r * THREADS;\n"
    "        ivec2 pixel = pixel_of(p);\n"
    "        uvec2 key = uvec2(NO, NO);\n"
    "        if (pixel.x < size.x && pixel.y < size.y) {\n"
    "            float d = texelFetch(gbuffer_depth, pixel, 0).r;\n"
    "            uint c = imageLoad(clusters, pixel).x;\n"
    "            if (d > 0.0 && c != NO)\n"
    "                key = uvec2(slice_of(d), c);\n"
    "        }\n"
    "        keys[p] = key;\n"
    "        mine[r] = key;\n"
    "    }\n"
    "    uint rank[PER];\n"
    "    for (uint r = 0u; r < PER; ++r)\n"
    "        rank[r] = NO;\n"
    "    uint count = extract_minima(lid, mine, rank);\n"
    "    if (count == NO) {\n"     /* uniform: read from shared after a barrier */
    "        sort_keys(lid);\n"
    "        count = compact(lid);\n"
    "        for (uint r = 0u; r < PER; ++r)\n"
    "            rank[r] = mine[r].y == NO ? NO : rank_of(mine[r], count);\n"
    "    }\n"
    "    for (uint r = 0u; r < PER; ++r) {\n"
    "        ivec2 pixel = pixel_of(lid + r * THREADS);\n"
    "        if (pixel.x < size.x && pixel.y < size.y)\n"
    "            imageStore(clusters, pixel,\n"
    "                       uvec4(imageLoad(clusters, pixel).x, rank[r], 0u, 0u));\n"
    "    }\n"
    "    if (lid == 0u)\n"
    "        tile_count[tile_index()] = count;\n"
    "}\n";

static const char scan_shader[] =
    "#version 450 core\n"
    "layout(local_size_x = 256) in;\n"
    "layout(std430, binding = 1) readonly buffer TileCounts { uint tile_count[]; };\n"
    "layout(std430, binding = 2) writeonly buffer TileOffsets { uint tile_offset[]; };\n"
    "layout(std430, binding = 3) writeonly buffer Total { uint total; };\n"
    "uniform uint tiles;\n"
    "const uint THREADS = 256u;\n"
    GLSL_PREFIX_SUM
    "void main() {\n"
    "    uint lid = gl_LocalInvocationIndex;\n"
    "    uint per = (tiles + THREADS - 1u) / THREADS;\n"
    "    uint begin = min(lid * per, tiles), end = min(begin + per, tiles);\n"
    "    uint n = 0u;\n"
    "    for (uint t = begin; t < end; ++t)\n"
    "        n += tile_count[t];\n"
    "    uint sum;\n"
    "    uint at = prefix_sum(lid, n, sum);\n"
    "    for (uint t = begin; t < end; ++t) {\n"
    "        tile_offset[t] = at;\n"
    "        at += tile_count[t];\n"
    "    }\n"
    "    if (lid == THREADS - 1u)\n"
    "        total = sum;\n"
    "}\n";

static const char bounds_shader[] =
    GLSL_TILE_COMMON
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(std430, binding = 1) readonly buffer TileCounts { uint tile_count[]; };\n"
    "layout(std430, binding = 2) readonly buffer TileOffsets { uint tile_offset[]; };\n"
    "struct GeometryCluster { vec4 sphere; uvec4 info; };\n"
    "layout(std430, binding = 3) writeonly buffer Clusters { GeometryCluster spheres[]; };\n"
    "struct Box { vec4 lo; vec4 hi; };\n"
    "layout(std430, binding = 4) writeonly buffer Boxes { Box boxes[]; };\n"
    "uniform mat4 view_to_world;\n"
    "uniform vec2 tan_half_fov;\n"
    "uniform float near;\n"
    "shared uint box[6u * PIXELS];\n"
    "shared uint visibility[PIXELS];\n"
    /* floats as uints in the same order */
    "uint ordered(float f) {\n"
    "    uint u = floatBitsToUint(f);\n"
    "    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;\n"
    "}\n"
    "float unordered(uint u) {\n"
    "    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);\n"
    "}\n"
    GB_GLSL_WORLD_POSITION
    "void main() {\n"
    "    uint lid = gl_LocalInvocationIndex;\n"
    "    uint t = tile_index();\n"
    "    uint count = tile_count[t], first = tile_offset[t];\n"
    "    ivec2 size = imageSize(clusters);\n"
    "    for (uint j = lid; j < count; j += THREADS)\n"
    "        for (uint a = 0u; a < 3u; ++a) {\n"
    "            box[6u * j + a] = 0xffffffffu;\n"
    "            box[6u * j + 3u + a] = 0u;\n"
    "        }\n"
    "    memoryBarrierShared();\n"
    "    barrier();\n"
    /* PER neighbours in a row: their box first, one set of atomics per cluster */
    "    uint held = NO;\n"
    "    vec3 lo = vec3(0.0), hi = vec3(0.0);\n"
    "    for (uint r = 0u; r <= PER; ++r) {\n"
    "        ivec2 pixel = pixel_of(PER * lid + min(r, PER - 1u));\n"
    "        uvec2 ids = uvec2(NO, NO);\n"
    "        if (r < PER && pixel.x < size.x && pixel.y < size.y)\n"
    "            ids = imageLoad(clusters, pixel).xy;\n"
    "        if (held != NO && ids.y != held)\n"
    "            for (uint a = 0u; a < 3u; ++a) {\n"
    "                atomicMin(box[6u * held + a], ordered(lo[a]));\n"
    "                atomicMax(box[6u * held + 3u + a], ordered(hi[a]));\n"
    "            }\n"
    "        if (ids.y == NO) {\n"
    "            held = NO;\n"
    "            continue;\n"
    "        }\n"
    "        vec3 p = world_position(pixel, size, texelFetch(gbuffer_depth, pixel, 0).r);\n"
    "        lo = ids.y == held ? min(lo, p) : p;\n"
    "        hi = ids.y == held ? max(hi, p) : p;\n"
    "        held = ids.y;\n"
    "        visibility[ids.y] = ids.x;\n"   /* the same for every fragment of it */
    "        imageStore(clusters, pixel, uvec4(ids.x, first + ids.y, 0u, 0u));\n"
    "    }\n"
    "    memoryBarrierShared();\n"
    "    barrier();\n"
    "    for (uint j = lid; j < count; j += THREADS) {\n"
    "        vec3 lo, hi;\n"
    "        for (uint a = 0u; a < 3u; ++a) {\n"
    "            lo[a] = unordered(box[6u * j + a]);\n"
    "            hi[a] = unordered(box[6u * j + 3u + a]);\n"
    "        }\n"
    "        vec3 h = 0.5 * (hi - lo);\n"
    "        float radius = sqrt(h.x * h.x + h.y * h.y + h.z * h.z);\n"
    "        spheres[first + j] = GeometryCluster(vec4(0.5 * (lo + hi), radius),\n"
    "                                             uvec4(visibility[j], 0u, 0u, 0u));\n"
    "        boxes[first + j] = Box(vec4(lo, 0.0), vec4(hi, 0.0));\n"
    "    }\n"
    "}\n";

static GLuint new_buffer(GLsizeiptr size)
{
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, size > 0 ? size : 16, NULL, GL_DYNAMIC_DRAW);
    return buffer;
}

gb_result gb_topo_iugc_gpu_create(gb_topo_iugc_gpu *iugc, gb_error *error)
{
    memset(iugc, 0, sizeof *iugc);
    gb_result result = gb_gl_compute_program("IUGC tiles", tile_shader, &iugc->tile_program,
                                               error);
    if (result == GB_OK)
        result = gb_gl_compute_program("IUGC scan", scan_shader, &iugc->scan_program, error);
    if (result == GB_OK)
        result = gb_gl_compute_program("IUGC bounds", bounds_shader, &iugc->bounds_program,
                                         error);
    if (result != GB_OK) {
        gb_topo_iugc_gpu_destroy(iugc);
        return result;
    }
    GLuint *buffers[] = {&iugc->slice_bounds, &iugc->tile_counts, &iugc->tile_offsets,
                         &iugc->total, &iugc->clusters, &iugc->boxes};
    for (int i = 0; i < 6; ++i)
        *buffers[i] = new_buffer(16);
    return GB_OK;
}

static float float_of(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The largest positive float d with gb_topo_depth_slice(d) >= j (the slice
 * does not grow with d); 0 when none. */
static float slice_bound(const gb_topo_frame_input *f, uint32_t j)
{
    uint32_t lo = 1, hi = 0x7f7fffffu;      /* smallest and largest positive floats */
    if (gb_topo_depth_slice(f, float_of(lo)) < j)
        return 0.0f;
    if (gb_topo_depth_slice(f, float_of(hi)) >= j)
        return FLT_MAX;
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (gb_topo_depth_slice(f, float_of(mid)) >= j)
            lo = mid;
        else
            hi = mid;
    }
    return float_of(lo);
}

/* The table of slice boundaries for this frame's projection (kept while
 * near, the field of view and the height stay). */
static gb_result fill_slice_table(gb_topo_iugc_gpu *iugc, const gb_topo_frame_input *f,
                                  gb_error *error)
{
    if (iugc->slice_count && iugc->table_near == f->near &&
        iugc->table_tan_y == f->tan_half_fov[1] && iugc->table_height == f->height)
        return GB_OK;
    uint32_t wanted = gb_topo_depth_slice(f, TABLE_MIN_DEPTH);
    uint32_t n = wanted < TABLE_MAX - 1 ? wanted + 2 : TABLE_MAX;
    float *bounds = malloc(n * sizeof *bounds);
    if (!bounds)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "IUGC: out of memory");
    bounds[0] = INFINITY;
    uint32_t count = 1;
    iugc->slices_exact = 0;
    while (count < n) {
        float b = slice_bound(f, count);
        if (b == 0.0f) {            /* no positive depth is this far */
            iugc->slices_exact = 1;
            break;
        }
        bounds[count++] = b;
    }
    glNamedBufferData(iugc->slice_bounds, (GLsizeiptr)(count * sizeof *bounds), bounds,
                      GL_STATIC_DRAW);
    free(bounds);
    iugc->slice_count = count;
    iugc->table_near = f->near;
    iugc->table_tan_y = f->tan_half_fov[1];
    iugc->table_height = f->height;
    return GB_OK;
}

/* Room for the tiles of the frame and one cluster per pixel at most. */
static void fit_buffers(gb_topo_iugc_gpu *iugc, uint32_t tiles, uint32_t pixels)
{
    if (tiles > iugc->tile_count) {
        glNamedBufferData(iugc->tile_counts, (GLsizeiptr)tiles * 4, NULL, GL_DYNAMIC_DRAW);
        glNamedBufferData(iugc->tile_offsets, (GLsizeiptr)tiles * 4, NULL, GL_DYNAMIC_DRAW);
        iugc->tile_count = tiles;
    }
    if (pixels > iugc->capacity) {
        glNamedBufferData(iugc->clusters, (GLsizeiptr)pixels * 32, NULL, GL_DYNAMIC_DRAW);
        glNamedBufferData(iugc->boxes, (GLsizeiptr)pixels * 32, NULL, GL_DYNAMIC_DRAW);
        iugc->capacity = pixels;
    }
}

static void run_tiles(const gb_topo_iugc_gpu *iugc, const gb_topo_frame_input *f,
                      uint32_t tiles_x, uint32_t tiles_y)
{
    GLuint p = iugc->tile_program;
    glUseProgram(p);
    glProgramUniform1ui(p, glGetUniformLocation(p, "slice_count"), iugc->slice_count);
    glProgramUniform1i(p, glGetUniformLocation(p, "slices_exact"), iugc->slices_exact);
    glProgramUniform1f(p, glGetUniformLocation(p, "near"), f->near);
    glProgramUniform1f(p, glGetUniformLocation(p, "log_base"),
                       logf(1.0f + 2.0f * f->tan_half_fov[1] / (float)tiles_y));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, iugc->slice_bounds);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, iugc->tile_counts);
    glDispatchCompute(tiles_x, tiles_y, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

static void run_scan(const gb_topo_iugc_gpu *iugc, uint32_t tiles)
{
    GLuint p = iugc->scan_program;
    glUseProgram(p);
    glProgramUniform1ui(p, glGetUniformLocation(p, "tiles"), tiles);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, iugc->tile_counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, iugc->tile_offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, iugc->total);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

static void run_bounds(const gb_topo_iugc_gpu *iugc, const gb_topo_frame_input *f,
                       uint32_t tiles_x, uint32_t tiles_y)
{
    GLuint p = iugc->bounds_program;
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "view_to_world"), 1, GL_FALSE,
                              f->view_to_world);
    glProgramUniform2f(p, glGetUniformLocation(p, "tan_half_fov"), f->tan_half_fov[0],
                       f->tan_half_fov[1]);
    glProgramUniform1f(p, glGetUniformLocation(p, "near"), f->near);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, iugc->tile_counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, iugc->tile_offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, iugc->clusters);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, iugc->boxes);
    glDispatchCompute(tiles_x, tiles_y, 1);
    /* LA reads the spheres, IL samples clusters.y, tests read both back */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

gb_result gb_topo_iugc_gpu_run(gb_topo_iugc_gpu *iugc, GLuint depth, GLuint clusters,
                               const gb_topo_frame_input *f, uint32_t *count, gb_error *error)
{
    *count = 0;
    gb_result result = fill_slice_table(iugc, f, error);
    if (result != GB_OK)
        return result;
    uint32_t tiles_x = (uint32_t)(f->width + GB_TOPO_TILE - 1) / GB_TOPO_TILE;
    uint32_t tiles_y = (uint32_t)(f->height + GB_TOPO_TILE - 1) / GB_TOPO_TILE;
    fit_buffers(iugc, tiles_x * tiles_y, (uint32_t)f->width * (uint32_t)f->height);
    /* the visibility clusters were stored through an image: make them visible */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(GB_UNIT_GBUFFER_DEPTH, depth);
    glBindImageTexture(UNIT_CLUSTERS_IMAGE, clusters, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32UI);
    run_tiles(iugc, f, tiles_x, tiles_y);
    run_scan(iugc, tiles_x * tiles_y);
    run_bounds(iugc, f, tiles_x, tiles_y);
    glGetNamedBufferSubData(iugc->total, 0, sizeof *count, count);
    return GB_OK;
}

gb_result gb_topo_iugc_gpu_read(const gb_topo_iugc_gpu *iugc, uint32_t count,
                                gb_geometry_clusters *out, gb_error *error)
{
    float *spheres = malloc(((size_t)count + 1) * 8 * sizeof *spheres);
    float *boxes = malloc(((size_t)count + 1) * 8 * sizeof *boxes);
    gb_geometry_cluster *clusters = realloc(out->clusters, ((size_t)count + 1) * sizeof *clusters);
    if (clusters) {
        out->clusters = clusters;
        out->capacity = count + 1;
    }
    if (!spheres || !boxes || !clusters) {
        free(spheres);
        free(boxes);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "IUGC: out of memory");
    }
    glGetNamedBufferSubData(iugc->clusters, 0, (GLsizeiptr)count * 32, spheres);
    glGetNamedBufferSubData(iugc->boxes, 0, (GLsizeiptr)count * 32, boxes);
    for (uint32_t i = 0; i < count; ++i) {
        gb_geometry_cluster *g = &clusters[i];
        memcpy(g->centre, &spheres[8 * i], 3 * sizeof(float));
        g->radius = spheres[8 * i + 3];
        memcpy(&g->visibility_cluster, &spheres[8 * i + 4], sizeof(uint32_t));
        memcpy(g->box_min, &boxes[8 * i], 3 * sizeof(float));
        memcpy(g->box_max, &boxes[8 * i + 4], 3 * sizeof(float));
    }
    out->count = count;
    free(spheres);
    free(boxes);
    return GB_OK;
}

void gb_topo_iugc_gpu_destroy(gb_topo_iugc_gpu *iugc)
{
    GLuint programs[] = {iugc->tile_program, iugc->scan_program, iugc->bounds_program};
    for (int i = 0; i < 3; ++i)
        if (programs[i])
            glDeleteProgram(programs[i]);
    GLuint buffers[] = {iugc->slice_bounds, iugc->tile_counts, iugc->tile_offsets,
                        iugc->total, iugc->clusters, iugc->boxes};
    for (int i = 0; i < 6; ++i)
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
    memset(iugc, 0, sizeof *iugc);
}
