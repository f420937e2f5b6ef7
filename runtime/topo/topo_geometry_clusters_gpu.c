/* topo_geometry_clusters_gpu.c — IUGC (Noël & Biri 2014, §V.B) in compute
 * shaders, the twin of gb_topo_geometry_clusters_build
 * (topo_geometry_clusters.c), which stays the reference: the same keys
 * (depth slice of Olsson et al. 2012, visibility cluster), the same tiles,
 * the same numbering. Three passes, nothing read back but the count
 * (topo_geometry_clusters_PASS.comp.glsl):
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

static const char tile_shader[] =
#include "runtime/topo/topo_geometry_clusters_tile.comp.glsl.inc"
    ;

static const char scan_shader[] =
#include "runtime/topo/topo_geometry_clusters_scan.comp.glsl.inc"
    ;

static const char bounds_shader[] =
#include "runtime/topo/topo_geometry_clusters_bounds.comp.glsl.inc"
    ;

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
    gb_gbuffer_set_view(p, f->view_to_world, f->tan_half_fov, f->near);
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
