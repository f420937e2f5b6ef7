/* topo_gather.c — IL (Noël & Biri 2014, §V.D): each fragment gathers the
 * VPLs LA assigned to its geometry cluster (G-buffer clusters.y). A VPL
 * stored with a route lights the fragment only when the fragment lies in the
 * cone from the VPL through each gate's disk of the route: the implicit
 * shadow. A VPL is stored once, with the group of routes from its cluster
 * to the fragment's: one route containing the fragment lights it.
 *
 * The geometric term G = cos(VPL) cos(x) / r^2 is bounded as in instant
 * radiosity with bounded contributions (Kollig & Keller 2004, the paper's
 * [Keller 1997] follow-up): 1/r^2 becomes 1/max(r, r_clamp)^2, r_clamp one
 * voxel of the bake, which removes the bright spots near VPLs (and the
 * energy within r_clamp of each, which the reference keeps). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "topo.h"

/* common/brdf.h's BRDF in GLSL (as direct_light.c has it). */
#define GLSL_BRDF                                                                  \
    "const float PI = 3.14159265358979323846;\n"                                   \
    "vec3 brdf_eval(vec3 Kd, vec3 Ks, float Ns, float n_dot_wo, float n_dot_wi,\n"  \
    "               float wo_dot_wi) {\n"                                          \
    "    if (n_dot_wo <= 0.0 || n_dot_wi <= 0.0)\n"                                \
    "        return vec3(0.0);\n"                                                  \
    "    float cos_mirror = 2.0 * n_dot_wo * n_dot_wi - wo_dot_wi;\n"              \
    "    float lobe = cos_mirror > 0.0 ? (Ns + 2.0) / (2.0 * PI) * pow(cos_mirror, Ns) : 0.0;\n" \
    "    return Kd / PI + Ks * lobe;\n"                                            \
    "}\n"

static const char fragment_shader[] =
    "#version 450 core\n"
    "struct VPL { vec4 position; vec4 normal; vec4 power; };\n"
    "layout(std430, binding = 3) readonly buffer VPLs { VPL vpls[]; };\n"
    "struct Gate { vec4 disk; vec4 normal; };\n"
    "layout(std430, binding = 4) readonly buffer Gates { Gate gates[]; };\n"
    "layout(std430, binding = 5) readonly buffer Ranges { uvec2 ranges[]; };\n"
    "layout(std430, binding = 6) readonly buffer Entries { uvec2 entries[]; };\n"
    "layout(std430, binding = 10) readonly buffer Routes { uvec4 routes[]; };\n"
    "layout(std430, binding = 11) readonly buffer Groups { uvec4 groups[]; };\n"
    "layout(binding = 1) uniform sampler2D gbuffer_normal;\n"
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(binding = 3) uniform sampler2D gbuffer_diffuse;\n"
    "layout(binding = 4) uniform sampler2D gbuffer_glossy;\n"
    "layout(binding = 5) uniform usampler2D gbuffer_clusters;\n"
    "uniform mat4 view_to_world;\n"
    "uniform vec2 tan_half_fov;\n"
    "uniform float near;\n"
    "uniform float clamp_distance2;\n"
    "uniform int vpl_count;\n"
    "uniform bool every_vpl;\n"
    "out vec4 radiance;\n"
    "const uint NO = 0xffffffffu;\n"
    GB_GLSL_OCTAHEDRAL
    GLSL_BRDF
    GB_GLSL_SURFACE
    /* The cone from p through the gate's disk; from within the disk's
     * radius, the segment to x through the disk (topo_assignment.c). */
    "bool in_gate_cone(vec3 p, uint gate, vec3 x) {\n"
    "    vec4 g = gates[gate].disk;\n"
    "    vec3 axis = g.xyz - p;\n"
    "    float d = length(axis);\n"
    "    if (d <= g.w) {\n"
    "        vec3 n = gates[gate].normal.xyz;\n"
    "        float dp = dot(p - g.xyz, n), dx = dot(x - g.xyz, n);\n"
    "        if (!(dp * dx < 0.0))\n"
    "            return false;\n"
    "        vec3 q = p + (dp / (dp - dx)) * (x - p) - g.xyz;\n"
    "        return dot(q, q) <= g.w * g.w;\n"
    "    }\n"
    "    float cos_half = d / sqrt(d * d + g.w * g.w);\n"
    "    vec3 v = x - p;\n"
    "    return dot(v, axis / d) >= cos_half * length(v);\n"
    "}\n"
    "bool in_route(vec3 p, uint route, vec3 x) {\n"
    "    uvec4 r = routes[route];\n"
    "    return in_gate_cone(p, r.x, x) && (r.y == NO || in_gate_cone(p, r.y, x));\n"
    "}\n"
    "bool in_group(vec3 p, uint group, vec3 x) {\n"
    "    uvec4 g = groups[group];\n"
    "    for (uint k = g.y; k < g.y + g.z; ++k)\n"
    "        if (in_route(p, k, x))\n"
    "            return true;\n"
    "    return false;\n"
    "}\n"
    "vec3 vpl_light(uint i, Surface s) {\n"
    "    VPL l = vpls[i];\n"
    "    vec3 to_vpl = l.position.xyz - s.position;\n"
    "    float d2 = dot(to_vpl, to_vpl);\n"
    "    if (d2 <= 0.0)\n"
    "        return vec3(0.0);\n"
    "    vec3 wi = to_vpl * inversesqrt(d2);\n"
    "    float emission = max(0.0, -dot(l.normal.xyz, wi)) / PI;\n"
    "    float n_dot_wi = dot(s.n, wi);\n"
    "    if (emission <= 0.0 || dot(s.ng, wi) <= 0.0)\n"
    "        return vec3(0.0);\n"
    "    vec3 f = brdf_eval(s.Kd, s.Ks, s.Ns, dot(s.n, s.wo), n_dot_wi, dot(s.wo, wi));\n"
    "    return f * l.power.rgb * (emission * n_dot_wi / max(d2, clamp_distance2));\n"
    "}\n"
    "void main() {\n"
    "    ivec2 pixel = ivec2(gl_FragCoord.xy);\n"
    "    float depth = texelFetch(gbuffer_depth, pixel, 0).r;\n"
    "    radiance = vec4(0.0, 0.0, 0.0, 1.0);\n"
    "    if (depth <= 0.0)\n"
    "        return;\n"
    "    Surface s = surface_at(pixel, depth);\n"
    "    uint g = texelFetch(gbuffer_clusters, pixel, 0).y;\n"
    "    vec3 L = vec3(0.0);\n"
    "    if (every_vpl || g == NO) {\n"
    "        for (int i = 0; i < vpl_count; ++i)\n"
    "            L += vpl_light(uint(i), s);\n"
    "    } else {\n"
    "        uvec2 range = ranges[g];\n"
    "        for (uint k = range.x; k < range.x + range.y; ++k) {\n"
    "            uvec2 e = entries[k];\n"
    "            if (e.y == NO || in_group(vpls[e.x].position.xyz, e.y, s.position))\n"
    "                L += vpl_light(e.x, s);\n"
    "        }\n"
    "    }\n"
    "    radiance = vec4(L, 1.0);\n"
    "}\n";

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

gb_result gb_topo_gather_create(const gb_vpl_set *vpls, const gb_segmentation *s,
                                const gb_topo_gates *gates, float clamp_distance,
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
    pass->clamp_distance = clamp_distance;
    return GB_OK;
}

void gb_topo_gather_draw(const gb_topo_gather_pass *pass, const float view_to_world[16],
                         const float tan_half_fov[2], float near, int every_vpl)
{
    GLuint p = pass->program;
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "view_to_world"), 1, GL_FALSE,
                              view_to_world);
    glProgramUniform2f(p, glGetUniformLocation(p, "tan_half_fov"), tan_half_fov[0],
                       tan_half_fov[1]);
    glProgramUniform1f(p, glGetUniformLocation(p, "near"), near);
    glProgramUniform1f(p, glGetUniformLocation(p, "clamp_distance2"),
                       pass->clamp_distance * pass->clamp_distance);
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
