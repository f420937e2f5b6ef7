/* topo_clusters.c — the visibility cluster of each fragment (Noël & Biri
 * 2014, §V.A): the fragment's position moved along its geometric normal
 * into the empty side → voxel → nearest skeleton node (thin's grid) →
 * segmented node → cluster. The three last steps are folded on the CPU, once,
 * into one cluster per voxel (a 3-D texture); a compute shader does the rest
 * each frame and writes the G-buffer's clusters.x. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "topo_clusters.h"

/* The fragment moves off its surface along its geometric normal ng until it
 * leaves the surface's voxels: voxelize marks every voxel a triangle touches,
 * so a plane's voxels reach |ng.x| + |ng.y| + |ng.z| voxels (up to sqrt 3)
 * from it along ng, and a point that much off the plane lies in an empty
 * voxel. Looking up closer is wrong, not just useless: thin's grid gives a
 * surface voxel the node of its best empty neighbour, often on the far side
 * of the wall (a box's inside). Then one and two voxels further, in case
 * another surface is in the way. When the bake's voxels are at hand, the
 * surface voxels' clusters are marked (gb_topo_voxel_clusters_mark_surface)
 * and only used when no empty voxel on the way has one: a fragment in a
 * corner, where the offset runs along the other wall, first takes the
 * nearest empty voxel with a cluster among the 27 around its first offset,
 * on its normal's side. */
enum { OFFSET_STEPS = 3, UNIT_VOXEL_CLUSTERS = 12 };
#define OFFSET_MARGIN 1.01f

void gb_topo_voxel_clusters_mark_surface(const gb_segmentation *s, int32_t *voxel_clusters,
                                         const uint8_t *surface)
{
    size_t n = (size_t)s->grid_size[0] * (size_t)s->grid_size[1] * (size_t)s->grid_size[2];
    for (size_t i = 0; i < n; ++i)
        if (surface[i] && voxel_clusters[i] >= 0)
            voxel_clusters[i] = GB_TOPO_SURFACE_CLUSTER(voxel_clusters[i]);
}

/* The cluster of the empty voxel among the 27 around p whose centre is
 * nearest p, on the side of x that ng points to; -1: none. */
static int32_t cluster_around(const gb_segmentation *s, const int32_t *voxel_clusters,
                              const float x[3], const float ng[3], const float p[3])
{
    int32_t base[3], best = -1;
    float h = (float)s->voxel_size, best_d2 = INFINITY;
    for (int a = 0; a < 3; ++a)
        base[a] = (int32_t)floorf((p[a] - (float)s->world_origin[a]) / h);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int32_t v[3] = {base[0] + dx, base[1] + dy, base[2] + dz};
                float centre[3], side = 0.0f, d2 = 0.0f;
                int inside = 1;
                for (int a = 0; a < 3; ++a) {
                    inside &= v[a] >= 0 && v[a] < s->grid_size[a];
                    centre[a] = (float)s->world_origin[a] + ((float)v[a] + 0.5f) * h;
                    side += (centre[a] - x[a]) * ng[a];
                    d2 += (centre[a] - p[a]) * (centre[a] - p[a]);
                }
                if (!inside || side <= 0.0f || d2 >= best_d2)
                    continue;
                int32_t c = voxel_clusters[(size_t)v[0] + (size_t)s->grid_size[0] *
                                           ((size_t)v[1] + (size_t)s->grid_size[1] * (size_t)v[2])];
                if (c >= 0) {
                    best = c;
                    best_d2 = d2;
                }
            }
    return best;
}

static int32_t voxel_cluster(const gb_segmentation *s, const int32_t *voxel_clusters,
                             const float p[3])
{
    size_t index = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
        float v = floorf((p[a] - (float)s->world_origin[a]) / (float)s->voxel_size);
        if (!(v >= 0.0f && v < (float)s->grid_size[a]))
            return -1;
        index += (size_t)v * stride;
        stride *= (size_t)s->grid_size[a];
    }
    return voxel_clusters[index];
}

int32_t gb_topo_surface_cluster(const gb_segmentation *s, const int32_t *voxel_clusters,
                                const float x[3], const float ng[3])
{
    float l1 = fabsf(ng[0]) + fabsf(ng[1]) + fabsf(ng[2]), first[3];
    int32_t on_surface = -1;
    for (int step = 0; step < OFFSET_STEPS; ++step) {
        float p[3], t = (OFFSET_MARGIN * l1 + (float)step) * (float)s->voxel_size;
        for (int a = 0; a < 3; ++a)
            p[a] = x[a] + ng[a] * t;
        if (step == 0)
            memcpy(first, p, sizeof first);
        int32_t c = voxel_cluster(s, voxel_clusters, p);
        if (c >= 0)
            return c;
        if (c < -1 && on_surface < 0)
            on_surface = GB_TOPO_SURFACE_CLUSTER(c);
    }
    int32_t around = cluster_around(s, voxel_clusters, x, ng, first);
    return around >= 0 ? around : on_surface;
}

static const char compute_shader[] =
#include "runtime/topo/topo_clusters.comp.glsl.inc"
    ;

gb_result gb_topo_cluster_pass_create(const gb_segmentation *s, const int32_t *voxel_clusters,
                                      gb_topo_cluster_pass *pass, gb_error *error)
{
    memset(pass, 0, sizeof *pass);
    gb_result result = gb_gl_compute_program("visibility clusters", compute_shader,
                                               &pass->program, error);
    if (result != GB_OK)
        return result;
    const int32_t *n = s->grid_size;
    glCreateTextures(GL_TEXTURE_3D, 1, &pass->voxel_clusters);
    glTextureStorage3D(pass->voxel_clusters, 1, GL_R32I, n[0], n[1], n[2]);
    glTextureSubImage3D(pass->voxel_clusters, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED_INTEGER,
                        GL_INT, voxel_clusters);
    glTextureParameteri(pass->voxel_clusters, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(pass->voxel_clusters, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    GLuint p = pass->program;
    glProgramUniform3f(p, glGetUniformLocation(p, "grid_origin"), (float)s->world_origin[0],
                       (float)s->world_origin[1], (float)s->world_origin[2]);
    glProgramUniform1f(p, glGetUniformLocation(p, "voxel_size"), (float)s->voxel_size);
    glProgramUniform3i(p, glGetUniformLocation(p, "grid_size"), n[0], n[1], n[2]);
    return GB_OK;
}

void gb_topo_cluster_pass_run(const gb_topo_cluster_pass *pass, GLuint depth, GLuint normal,
                              GLuint clusters, int width, int height,
                              const float view_to_world[16], const float tan_half_fov[2],
                              float near)
{
    GLuint p = pass->program;
    glUseProgram(p);
    gb_gbuffer_set_view(p, view_to_world, tan_half_fov, near);
    glBindTextureUnit(GB_UNIT_GBUFFER_NORMAL, normal);
    glBindTextureUnit(GB_UNIT_GBUFFER_DEPTH, depth);
    glBindTextureUnit(UNIT_VOXEL_CLUSTERS, pass->voxel_clusters);
    glBindImageTexture(0, clusters, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32UI);
    glDispatchCompute((GLuint)(width + 7) / 8, (GLuint)(height + 7) / 8, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void gb_topo_cluster_pass_destroy(gb_topo_cluster_pass *pass)
{
    if (pass->program)
        glDeleteProgram(pass->program);
    if (pass->voxel_clusters)
        glDeleteTextures(1, &pass->voxel_clusters);
    memset(pass, 0, sizeof *pass);
}
