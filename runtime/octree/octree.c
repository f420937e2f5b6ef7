/* octree.c — the light octree as a GI method (octree.h). */
#include "octree.h"

#include <math.h>
#include <stdlib.h>

#include "gl_util.h"
#include "indirect_method.h"
#include "light_octree.h"

enum { SSBO_NODES = 0, SSBO_LEAVES = 1, SSBO_VDLS = 2 };

typedef struct octree_state {
    gb_light_octree octree;
    GLuint buffers[3];          /* nodes, leaves, VDLs */
    GLuint program, empty_vertex_array;
} octree_state;

static const char fragment_shader[] =
    "#version 450 core\n"
    "layout(std430, binding = 0) readonly buffer Nodes { uint nodes[]; };\n"
    "layout(std430, binding = 1) readonly buffer Leaves { uint leaves[]; };\n"
    "layout(std430, binding = 2) readonly buffer Vdls { uint vdls[]; };\n"
    "layout(binding = 1) uniform sampler2D gbuffer_normal;\n"
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(binding = 3) uniform sampler2D gbuffer_diffuse;\n"
    "uniform mat4 view_to_world;\n"
    "uniform vec2 tan_half_fov;\n"
    "uniform float near;\n"
    "uniform ivec2 full_size;\n"
    "uniform vec3 origin;\n"
    "uniform float cell_size;\n"
    "uniform int depth;\n"
    "out vec4 radiance;\n"
    "const uint NONE = 0xffffffffu;\n"
    "const float PI = 3.14159265358979;\n"
    "const float MIN_COS = 0.25;\n"
    "const float MIN_WEIGHT = 1e-6;\n"
    GB_GLSL_OCTAHEDRAL
    GB_GLSL_WORLD_POSITION
    /* gb_light_octree_find_leaf: depth node fetches from the root. */
    "uint find_leaf(ivec3 cell) {\n"
    "    if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(1 << depth))))\n"
    "        return NONE;\n"
    "    uint node = 0u;\n"
    "    for (int level = 0; level < depth; ++level) {\n"
    "        ivec3 bit = (cell >> (depth - 1 - level)) & 1;\n"
    "        node = nodes[8u * node + uint(bit.x | bit.y << 1 | bit.z << 2)];\n"
    "        if (node == NONE)\n"
    "            return NONE;\n"
    "    }\n"
    "    return node;\n"
    "}\n"
    GB_GLSL_VDL_DIRECTION
    /* Sum of the leaf's VDLs, E max(0, n.w) / max(|nl.w|, MIN_COS) (octree.h);
     * false for no leaf or no VDL. */
    "bool leaf_light(uint leaf, vec3 n, vec3 ng, out vec3 sum) {\n"
    "    sum = vec3(0.0);\n"
    "    if (leaf == NONE || leaves[8u * leaf + 4u] == 0u)\n"
    "        return false;\n"
    "    uint first = leaves[8u * leaf + 3u], end = first + leaves[8u * leaf + 4u];\n"
    "    vec3 nl = uintBitsToFloat(uvec3(leaves[8u * leaf], leaves[8u * leaf + 1u],\n"
    "                                    leaves[8u * leaf + 2u]));\n"
    "    for (uint i = first; i < end; ++i) {\n"
    "        vec3 w = vdl_direction(vdls[4u * i + 3u]);\n"
    "        float c = dot(n, w) / max(abs(dot(nl, w)), MIN_COS);\n"
    "        if (c > 0.0 && dot(ng, w) > 0.0)\n"
    "            sum += uintBitsToFloat(uvec3(vdls[4u * i], vdls[4u * i + 1u],\n"
    "                                         vdls[4u * i + 2u])) * c;\n"
    "    }\n"
    "    return true;\n"
    "}\n"
    /* Trilinear between the 8 leaf centres around x, renormalised over the
     * neighbours that have VDLs. Each weight is at least MIN_WEIGHT: at a
     * leaf centre the weights of the other 7 vanish, and when that leaf has
     * no VDLs the pixel would be black (tests/unit/test_octree_display.c);
     * there the floor makes it the mean of the others, and elsewhere it
     * changes the result by under 10^-5. */
    "vec3 interpolate(vec3 x, vec3 n, vec3 ng) {\n"
    "    vec3 g = (x - origin) / cell_size - 0.5;\n"
    "    vec3 base = floor(g), f = g - base;\n"
    "    vec3 total = vec3(0.0);\n"
    "    float weight = 0.0;\n"
    "    for (int c = 0; c < 8; ++c) {\n"
    "        ivec3 o = ivec3(c & 1, (c >> 1) & 1, c >> 2);\n"
    "        vec3 t = mix(1.0 - f, f, vec3(o));\n"
    "        float w = max(t.x * t.y * t.z, MIN_WEIGHT);\n"
    "        vec3 sum;\n"
    "        if (leaf_light(find_leaf(ivec3(base) + o), n, ng, sum)) {\n"
    "            total += w * sum;\n"
    "            weight += w;\n"
    "        }\n"
    "    }\n"
    "    return weight > 0.0 ? total / weight : vec3(0.0);\n"
    "}\n"
    "void main() {\n"
    "    ivec2 pixel = ivec2(gl_FragCoord.xy);\n"
    "    float d = texelFetch(gbuffer_depth, pixel, 0).r;\n"
    "    if (d <= 0.0) {\n"
    "        radiance = vec4(0.0);\n"
    "        return;\n"
    "    }\n"
    "    vec3 x = world_position(pixel, full_size, d);\n"
    "    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);\n"
    "    mat3 rotation = mat3(view_to_world);\n"
    "    vec3 n = normalize(rotation * oct_decode(normals.xy));\n"
    "    vec3 ng = normalize(rotation * oct_decode(normals.zw));\n"
    "    vec3 Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;\n"
    "    radiance = vec4(Kd / PI * interpolate(x, n, ng), 0.0);\n"
    "}\n";

static void octree_destroy(void *state)
{
    octree_state *s = state;
    if (!s)
        return;
    glDeleteBuffers(3, s->buffers);
    if (s->empty_vertex_array)
        glDeleteVertexArrays(1, &s->empty_vertex_array);
    if (s->program)
        glDeleteProgram(s->program);
    gb_light_octree_free(&s->octree);
    free(s);
}

static gb_result read_octree(const gb_indirect_setup *setup, gb_light_octree *octree,
                             gb_error *error)
{
    const gb_bake_files *bake = setup->bake;
    if (!bake)
        return gb_fail(error, GB_ERROR_IO,
                       "octree: needs a light octree (NAME.lot from cluster): give --bake DIR");
    if (!bake->usable[GB_BAKE_LIGHT_OCTREE])
        return gb_fail(error, GB_ERROR_IO, "octree: no usable light octree: %s",
                       bake->has_problem[GB_BAKE_LIGHT_OCTREE]
                           ? bake->problems[GB_BAKE_LIGHT_OCTREE].message
                           : bake->paths[GB_BAKE_LIGHT_OCTREE]);
    gb_result result = gb_light_octree_read(bake->paths[GB_BAKE_LIGHT_OCTREE], octree, error);
    if (result == GB_OK)
        result = gb_light_octree_check_scene(octree, setup->scene->hash,
                                             bake->paths[GB_BAKE_LIGHT_OCTREE], error);
    return result;
}

/* A buffer of count * size bytes (at least 16: GL refuses empty storage). */
static GLuint make_buffer(const void *data, size_t count, size_t size)
{
    GLuint buffer;
    size_t bytes = count * size;
    glCreateBuffers(1, &buffer);
    if (bytes == 0) {
        static const uint32_t zero[4] = {0, 0, 0, 0};
        glNamedBufferStorage(buffer, sizeof zero, zero, 0);
    } else {
        glNamedBufferStorage(buffer, (GLsizeiptr)bytes, data, 0);
    }
    return buffer;
}

static void upload(octree_state *s)
{
    const gb_light_octree *o = &s->octree;
    s->buffers[SSBO_NODES] = make_buffer(o->nodes, o->header.node_count, sizeof *o->nodes);
    s->buffers[SSBO_LEAVES] = make_buffer(o->leaves, o->header.leaf_count, sizeof *o->leaves);
    s->buffers[SSBO_VDLS] = make_buffer(o->vdls, o->header.vdl_count, sizeof *o->vdls);
}

static gb_result octree_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    *state = NULL;
    octree_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree: out of memory");
    gb_result result = read_octree(setup, &s->octree, error);
    if (result == GB_OK)
        result = gb_gl_program("octree", gb_gl_fullscreen_vertex_shader, fragment_shader,
                               &s->program, error);
    if (result != GB_OK) {
        octree_destroy(s);
        return result;
    }
    upload(s);
    glCreateVertexArrays(1, &s->empty_vertex_array);
    *state = s;
    return GB_OK;
}

static void set_uniforms(const octree_state *s, const gb_indirect_frame *frame)
{
    GLuint p = s->program;
    const gb_view *view = frame->view;
    const gb_light_octree_header *h = &s->octree.header;
    gb_mat4 view_to_world = gb_view_inverse_matrix(view);
    float tan_y = tanf(0.5f * view->fov_y * 3.14159265358979f / 180.0f);
    float aspect = (float)frame->width / (float)frame->height;
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "view_to_world"), 1, GL_FALSE,
                              view_to_world.m);
    glProgramUniform2f(p, glGetUniformLocation(p, "tan_half_fov"), tan_y * aspect, tan_y);
    glProgramUniform1f(p, glGetUniformLocation(p, "near"), view->near);
    glProgramUniform2i(p, glGetUniformLocation(p, "full_size"), frame->width, frame->height);
    glProgramUniform3fv(p, glGetUniformLocation(p, "origin"), 1, h->origin);
    glProgramUniform1f(p, glGetUniformLocation(p, "cell_size"),
                       h->size / (float)(1u << h->depth));
    glProgramUniform1i(p, glGetUniformLocation(p, "depth"), (GLint)h->depth);
}

static void octree_draw(void *state, const gb_indirect_frame *frame)
{
    octree_state *s = state;
    set_uniforms(s, frame);
    for (GLuint i = 0; i < 3; ++i)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, s->buffers[i]);
    glUseProgram(s->program);
    gb_gbuffer_bind(frame->gbuffer);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

const gb_indirect_method gb_octree_method = {
    .create = octree_create,
    .draw = octree_draw,
    .destroy = octree_destroy,
};
