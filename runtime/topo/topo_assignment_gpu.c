/* topo_assignment_gpu.c — LA (Noël & Biri 2014, §V.C) in compute shaders,
 * the twin of gb_topo_assign (topo_assignment.c): one invocation per
 * geometry cluster walks the VPLs in order, first counting its entries,
 * then (after a prefix sum of the counts on the CPU) writing them, so that
 * each cluster's list is the CPU's, in the same order. */
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"
#include "topo.h"

static const char count_shader[] =
#include "runtime/topo/topo_assignment_count.comp.glsl.inc"
    ;

static const char write_shader[] =
#include "runtime/topo/topo_assignment_write.comp.glsl.inc"
    ;

gb_result gb_topo_la_gpu_create(const gb_vpl_set *vpls, const int32_t *vpl_cluster,
                                const gb_topo_gates *gates, gb_topo_la_gpu *la, gb_error *error)
{
    memset(la, 0, sizeof *la);
    gb_result result = gb_gl_compute_program("LA count", count_shader, &la->count_program,
                                               error);
    if (result == GB_OK)
        result = gb_gl_compute_program("LA write", write_shader, &la->write_program, error);
    if (result != GB_OK)
        return result;
    la->vpl_count = vpls->count;
    la->vpl_cluster = gb_gl_buffer(vpl_cluster, (GLsizeiptr)(vpls->count * sizeof(int32_t)));
    la->group_offsets = gb_gl_buffer(gates->group_offsets,
                                  (GLsizeiptr)((gates->cluster_count + 1) * sizeof(uint32_t)));
    la->clusters = gb_gl_buffer(NULL, 16);
    return GB_OK;
}

static void grow(GLuint buffer, GLsizeiptr *capacity, GLsizeiptr size)
{
    if (size > *capacity) {
        *capacity = size + size / 2;
        glNamedBufferData(buffer, *capacity, NULL, GL_DYNAMIC_DRAW);
    }
}

static void dispatch(GLuint program, const gb_topo_la_gpu *la, uint32_t count, int gates_on)
{
    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "cluster_count"), count);
    glProgramUniform1ui(program, glGetUniformLocation(program, "vpl_count"), la->vpl_count);
    glProgramUniform1i(program, glGetUniformLocation(program, "gates_on"), gates_on);
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Geometry clusters as the shader reads them: sphere, then the visibility
 * cluster. */
static float *pack_clusters(const gb_geometry_clusters *clusters)
{
    float *data = calloc((size_t)clusters->count * 8 + 8, sizeof *data);
    if (!data)
        return NULL;
    for (uint32_t i = 0; i < clusters->count; ++i) {
        memcpy(&data[8 * i], clusters->clusters[i].centre, 3 * sizeof(float));
        data[8 * i + 3] = clusters->clusters[i].radius;
        memcpy(&data[8 * i + 4], &clusters->clusters[i].visibility_cluster, sizeof(uint32_t));
    }
    return data;
}

gb_result gb_topo_la_gpu_run(gb_topo_la_gpu *la, const gb_geometry_clusters *clusters,
                             gb_topo_visibility visibility, gb_topo_gather_pass *gather,
                             gb_topo_assignment *out, gb_error *error)
{
    uint32_t n = clusters->count;
    float *packed = pack_clusters(clusters);
    if (!packed)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    grow(la->clusters, &la->clusters_size, (GLsizeiptr)n * 8 * (GLsizeiptr)sizeof(float));
    glNamedBufferSubData(la->clusters, 0, (GLsizeiptr)n * 8 * (GLsizeiptr)sizeof(float), packed);
    free(packed);
    return gb_topo_la_gpu_run_resident(la, la->clusters, n, visibility, gather, out, error);
}

gb_result gb_topo_la_gpu_run_resident(gb_topo_la_gpu *la, GLuint clusters, uint32_t n,
                                      gb_topo_visibility visibility, gb_topo_gather_pass *gather,
                                      gb_topo_assignment *out, gb_error *error)
{
    uint32_t *ranges = realloc(out->ranges, ((size_t)n + 1) * 2 * sizeof *ranges);
    if (!ranges)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    out->ranges = ranges;
    out->cluster_count = n;
    grow(gather->range_buffer, &gather->range_size, (GLsizeiptr)(n + 1) * 8);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, gather->vpl_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, gather->gate_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, gather->range_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, clusters);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, la->vpl_cluster);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, la->group_offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, gather->route_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, gather->group_buffer);
    int gates_on = visibility == GB_TOPO_FULL;
    if (n)
        dispatch(la->count_program, la, n, gates_on);
    glGetNamedBufferSubData(gather->range_buffer, 0, (GLsizeiptr)n * 8, ranges);
    uint32_t total = 0;
    for (uint32_t i = 0; i < n; ++i) {     /* exclusive prefix sum of the counts */
        ranges[2 * i] = total;
        total += ranges[2 * i + 1];
    }
    out->entry_count = total;
    glNamedBufferSubData(gather->range_buffer, 0, (GLsizeiptr)n * 8, ranges);
    grow(gather->entry_buffer, &gather->entry_size, (GLsizeiptr)(total + 1) * 8);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, gather->entry_buffer);
    if (n)
        dispatch(la->write_program, la, n, gates_on);
    return GB_OK;
}

gb_result gb_topo_la_gpu_read(const gb_topo_gather_pass *gather, gb_topo_assignment *out,
                              gb_error *error)
{
    gb_topo_entry *entries = realloc(out->entries, (out->entry_count + 1u) * sizeof *entries);
    if (!entries)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    out->entries = entries;
    out->entry_capacity = out->entry_count + 1u;
    glGetNamedBufferSubData(gather->entry_buffer, 0,
                            (GLsizeiptr)out->entry_count * (GLsizeiptr)sizeof *entries, entries);
    return GB_OK;
}

void gb_topo_la_gpu_destroy(gb_topo_la_gpu *la)
{
    if (la->count_program)
        glDeleteProgram(la->count_program);
    if (la->write_program)
        glDeleteProgram(la->write_program);
    GLuint buffers[] = {la->vpl_cluster, la->group_offsets, la->clusters};
    for (int i = 0; i < 3; ++i)
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
    memset(la, 0, sizeof *la);
}
