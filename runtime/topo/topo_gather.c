/* topo_gather.c — IL (Noël & Biri 2014, §V.D): each fragment gathers the
 * VPLs LA assigned to its geometry cluster (G-buffer clusters.y). A VPL
 * stored with a route lights the fragment only when the fragment lies in the
 * cone from the VPL through each gate's disk of the route: the implicit
 * shadow. A VPL is stored once, with the group of routes from its cluster
 * to the fragment's: one route containing the fragment lights it.
 *
 * The geometric term G = cos(VPL) cos(x) / r^2 is that of a virtual
 * spherical light (Hasan, Krivanek, Walter, Bala 2009): the VPL's power
 * spread over a sphere of radius R, seen from x through its solid angle
 *   Omega(r) = 2 pi (1 - sqrt(1 - R^2 / r^2)), the hemisphere for r <= R,
 * so that 1/r^2 becomes Omega / (pi R^2): 1/r^2 far away (within 1 % past
 * r = 5 R), 2 / R^2 within R, smooth and increasing in between. The
 * cosines stay those of the centre's direction (VSLs integrate them over
 * the cone; the closed form keeps the gather one term a VPL). Instant
 * radiosity's bound 1/max(r, r_clamp)^2 (Kollig & Keller 2004), which this
 * replaces, with r_clamp one voxel left bright splotches where VPLs lie
 * near the surfaces they light (the box's corners) and removed the energy
 * within r_clamp; the sphere spreads it over its surroundings instead.
 * R is gb_topo_vsl_radius: the disc GB_TOPO_VSL_SHARE VPLs would cover if
 * they tiled the scene's surfaces evenly, at least one voxel: a sphere that
 * spans several VPLs' share of the surface blurs one VPL near a wall into
 * its neighbours' light instead of a spot (one share left the spots, half
 * as bright). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "topo.h"

static const char fragment_shader[] =
#include "runtime/topo/topo_gather.frag.glsl.inc"
    ;

static GLuint route_buffer(const gb_topo_gates *gates)
{
    uint32_t *data = calloc((size_t)gates->route_count * 4 + 4, sizeof *data);
    if (!data)
        return 0;
    for (uint32_t i = 0; i < gates->route_count; ++i) {
        data[4 * i] = gates->routes[i].gates[0];
        data[4 * i + 1] = gates->routes[i].gates[1];
        data[4 * i + 2] = gates->routes[i].target;
    }
    GLuint buffer = gb_gl_buffer(data, (GLsizeiptr)(gates->route_count * 4 * sizeof *data));
    free(data);
    return buffer;
}

static GLuint group_buffer(const gb_topo_gates *gates)
{
    uint32_t *data = calloc((size_t)gates->group_count * 4 + 4, sizeof *data);
    if (!data)
        return 0;
    for (uint32_t i = 0; i < gates->group_count; ++i) {
        data[4 * i] = gates->groups[i].target;
        data[4 * i + 1] = gates->groups[i].first;
        data[4 * i + 2] = gates->groups[i].count;
    }
    GLuint buffer = gb_gl_buffer(data, (GLsizeiptr)(gates->group_count * 4 * sizeof *data));
    free(data);
    return buffer;
}

static GLuint vpl_buffer(const gb_vpl_set *vpls)
{
    float *data = calloc((size_t)vpls->count * 12 + 12, sizeof *data);
    if (!data)
        return 0;
    for (uint32_t i = 0; i < vpls->count; ++i) {
        memcpy(&data[12 * i], vpls->vpls[i].position, 3 * sizeof(float));
        memcpy(&data[12 * i + 4], vpls->vpls[i].normal, 3 * sizeof(float));
        memcpy(&data[12 * i + 8], vpls->vpls[i].power, 3 * sizeof(float));
    }
    GLuint buffer = gb_gl_buffer(data, (GLsizeiptr)(vpls->count * 12 * sizeof *data));
    free(data);
    return buffer;
}

static GLuint gate_buffer(const gb_segmentation *s)
{
    float *data = calloc((size_t)s->gate_count * 8 + 8, sizeof *data);
    if (!data)
        return 0;
    for (uint32_t i = 0; i < s->gate_count; ++i) {   /* Gate: disk, normal */
        memcpy(&data[8 * i], s->gates[i].centre, 3 * sizeof(float));
        data[8 * i + 3] = s->gates[i].radius;
        memcpy(&data[8 * i + 4], s->gates[i].normal, 3 * sizeof(float));
    }
    GLuint buffer = gb_gl_buffer(data, (GLsizeiptr)(s->gate_count * 8 * sizeof *data));
    free(data);
    return buffer;
}

float gb_topo_vsl_radius(const gb_scene *scene, uint32_t vpl_count, float voxel_size)
{
    double area = 0.0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        area += gb_triangle_area(scene, t);
    double radius =
        vpl_count > 0 ? sqrt(GB_TOPO_VSL_SHARE * area / (M_PI * vpl_count)) : 0.0;
    return (float)fmax(radius, (double)voxel_size);
}

gb_result gb_topo_gather_create(const gb_vpl_set *vpls, const gb_segmentation *s,
                                const gb_topo_gates *gates, float vsl_radius,
                                gb_topo_gather_pass *pass, gb_error *error)
{
    memset(pass, 0, sizeof *pass);
    gb_result result = gb_gl_program("topo IL", gb_gl_fullscreen_vertex_shader, fragment_shader,
                                     &pass->program, error);
    if (result != GB_OK)
        return result;
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    pass->vpl_buffer = vpl_buffer(vpls);
    pass->gate_buffer = gate_buffer(s);
    pass->route_buffer = route_buffer(gates);
    pass->group_buffer = group_buffer(gates);
    pass->range_buffer = gb_gl_buffer(NULL, 16);
    pass->entry_buffer = gb_gl_buffer(NULL, 16);
    if (!pass->vpl_buffer || !pass->gate_buffer || !pass->route_buffer || !pass->group_buffer)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "IL: out of memory");
    pass->vpl_count = vpls->count;
    pass->vsl_radius = vsl_radius;
    return GB_OK;
}

void gb_topo_gather_draw(const gb_topo_gather_pass *pass, const float view_to_world[16],
                         const float tan_half_fov[2], float near, int every_vpl)
{
    GLuint p = pass->program;
    glUseProgram(p);
    gb_gbuffer_set_view(p, view_to_world, tan_half_fov, near);
    glProgramUniform1f(p, glGetUniformLocation(p, "vsl_radius2"),
                       pass->vsl_radius * pass->vsl_radius);
    glProgramUniform1i(p, glGetUniformLocation(p, "vpl_count"), (GLint)pass->vpl_count);
    glProgramUniform1i(p, glGetUniformLocation(p, "every_vpl"), every_vpl);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, pass->vpl_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, pass->gate_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, pass->range_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, pass->entry_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, pass->route_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, pass->group_buffer);
    gb_gl_draw_fullscreen(pass->empty_vertex_array);
}

void gb_topo_gather_destroy(gb_topo_gather_pass *pass)
{
    if (pass->program)
        glDeleteProgram(pass->program);
    if (pass->empty_vertex_array)
        glDeleteVertexArrays(1, &pass->empty_vertex_array);
    GLuint buffers[] = {pass->vpl_buffer, pass->gate_buffer, pass->route_buffer,
                        pass->group_buffer, pass->range_buffer, pass->entry_buffer};
    for (int i = 0; i < 6; ++i)
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
    memset(pass, 0, sizeof *pass);
}
