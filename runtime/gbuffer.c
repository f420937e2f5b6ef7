#include "gbuffer.h"

#include <string.h>

#include "gl_util.h"

static const char vertex_shader[] =
    "#version 450 core\n"
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in vec3 normal;\n"
    "layout(location = 2) in vec3 face_normal;\n"
    "layout(location = 3) in vec2 texcoord;\n"
    "layout(location = 4) in uint material;\n"
    "uniform mat4 view;\n"
    "uniform mat4 projection;\n"
    "out vec3 v_normal;\n"
    "flat out vec3 v_face_normal;\n"
    "out vec2 v_texcoord;\n"
    "flat out uint v_material;\n"
    "void main() {\n"
    "    v_normal = mat3(view) * normal;\n"
    "    v_face_normal = mat3(view) * face_normal;\n"
    "    v_texcoord = texcoord;\n"
    "    v_material = material;\n"
    "    gl_Position = projection * (view * vec4(position, 1.0));\n"
    "}\n";

/* Sides as in common/brdf.h: the geometric normal turned toward the viewer
 * (the front face is cross(v1 - v0, v2 - v0), counter-clockwise on screen),
 * the shading normal turned to its side; only the front face emits. */
static const char fragment_shader[] =
    "#version 450 core\n"
    "struct Material { vec4 Kd_textured; vec4 Ks_Ns; vec4 Ke; };\n"
    "layout(std430, binding = 0) readonly buffer Materials { Material materials[]; };\n"
    "layout(binding = 0) uniform sampler2D diffuse_texture;\n"
    "in vec3 v_normal;\n"
    "flat in vec3 v_face_normal;\n"
    "in vec2 v_texcoord;\n"
    "flat in uint v_material;\n"
    "layout(location = 0) out vec4 out_normal;\n"
    "layout(location = 1) out vec4 out_diffuse;\n"
    "layout(location = 2) out vec4 out_glossy;\n"
    "layout(location = 3) out uvec2 out_clusters;\n"
    "layout(location = 4) out vec4 out_emission;\n"
    GB_GLSL_OCTAHEDRAL
    "void main() {\n"
    "    Material m = materials[v_material];\n"
    "    vec3 ng = normalize(gl_FrontFacing ? v_face_normal : -v_face_normal);\n"
    "    vec3 n = normalize(v_normal);\n"
    "    if (!(dot(n, n) > 0.0))\n"
    "        n = ng;\n"
    "    if (dot(n, ng) < 0.0)\n"
    "        n = -n;\n"
    "    vec3 texel = m.Kd_textured.w > 0.5 ? texture(diffuse_texture, v_texcoord).rgb\n"
    "                                       : vec3(1.0);\n"
    "    out_normal = vec4(oct_encode(n), oct_encode(ng));\n"
    "    out_diffuse = vec4(m.Kd_textured.rgb * texel, 1.0);\n"
    "    out_glossy = m.Ks_Ns;\n"
    "    out_clusters = uvec2(0xffffffffu);\n"
    "    out_emission = vec4(gl_FrontFacing ? m.Ke.rgb : vec3(0.0), 1.0);\n"
    "}\n";

static void delete_textures(gb_gbuffer *g)
{
    GLuint *names[] = {&g->normal, &g->depth, &g->diffuse, &g->glossy, &g->clusters,
                       &g->emission};
    for (size_t i = 0; i < sizeof names / sizeof *names; ++i)
        if (*names[i]) {
            glDeleteTextures(1, names[i]);
            *names[i] = 0;
        }
}

static gb_result make_textures(gb_gbuffer *g, int width, int height, gb_error *error)
{
    g->width = width;
    g->height = height;
    g->normal = gb_gl_texture_2d(GL_RGBA32F, width, height);
    g->depth = gb_gl_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    g->diffuse = gb_gl_texture_2d(GL_RGBA16F, width, height);
    g->glossy = gb_gl_texture_2d(GL_RGBA16F, width, height);
    g->clusters = gb_gl_texture_2d(GL_RG32UI, width, height);
    g->emission = gb_gl_texture_2d(GL_RGBA16F, width, height);
    GLuint colour[] = {g->normal, g->diffuse, g->glossy, g->clusters, g->emission};
    GLenum buffers[5];
    for (int i = 0; i < 5; ++i) {
        glNamedFramebufferTexture(g->framebuffer, GL_COLOR_ATTACHMENT0 + i, colour[i], 0);
        buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferTexture(g->framebuffer, GL_DEPTH_ATTACHMENT, g->depth, 0);
    glNamedFramebufferDrawBuffers(g->framebuffer, 5, buffers);
    GLenum status = glCheckNamedFramebufferStatus(g->framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "G-buffer %dx%d: framebuffer incomplete (0x%04x)", width, height, status);
    return GB_OK;
}

gb_result gb_gbuffer_create(int width, int height, gb_gbuffer *gbuffer, gb_error *error)
{
    memset(gbuffer, 0, sizeof *gbuffer);
    glCreateFramebuffers(1, &gbuffer->framebuffer);
    gb_result result = make_textures(gbuffer, width, height, error);
    if (result == GB_OK)
        result = gb_gl_program("geometry pass", vertex_shader, fragment_shader,
                               &gbuffer->program, error);
    if (result != GB_OK)
        gb_gbuffer_destroy(gbuffer);
    return result;
}

gb_result gb_gbuffer_resize(gb_gbuffer *gbuffer, int width, int height, gb_error *error)
{
    if (width == gbuffer->width && height == gbuffer->height)
        return GB_OK;
    delete_textures(gbuffer);
    return make_textures(gbuffer, width, height, error);
}

static void clear(const gb_gbuffer *g)
{
    static const float zero[4] = {0, 0, 0, 0};
    static const GLuint no_cluster[4] = {GB_NO_CLUSTER, GB_NO_CLUSTER, 0, 0};
    for (int i = 0; i < 5; ++i)
        if (i == 3)
            glClearNamedFramebufferuiv(g->framebuffer, GL_COLOR, i, no_cluster);
        else
            glClearNamedFramebufferfv(g->framebuffer, GL_COLOR, i, zero);
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(g->framebuffer, GL_DEPTH, 0, zero); /* reversed: 0 is far */
}

void gb_gbuffer_draw(gb_gbuffer *gbuffer, const gb_gpu_scene *scene, const gb_mat4 *view,
                     const gb_mat4 *projection)
{
    glBindFramebuffer(GL_FRAMEBUFFER, gbuffer->framebuffer);
    glViewport(0, 0, gbuffer->width, gbuffer->height);
    clear(gbuffer);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);    /* reversed depth */
    glDisable(GL_CULL_FACE);    /* surfaces reflect on both sides */
    glDisable(GL_BLEND);
    glUseProgram(gbuffer->program);
    glProgramUniformMatrix4fv(gbuffer->program, glGetUniformLocation(gbuffer->program, "view"),
                              1, GL_FALSE, view->m);
    glProgramUniformMatrix4fv(gbuffer->program,
                              glGetUniformLocation(gbuffer->program, "projection"), 1, GL_FALSE,
                              projection->m);
    gb_gpu_scene_draw(scene, 1);
    glDisable(GL_DEPTH_TEST);
}

void gb_gbuffer_bind(const gb_gbuffer *gbuffer)
{
    glBindTextureUnit(GB_UNIT_GBUFFER_NORMAL, gbuffer->normal);
    glBindTextureUnit(GB_UNIT_GBUFFER_DEPTH, gbuffer->depth);
    glBindTextureUnit(GB_UNIT_GBUFFER_DIFFUSE, gbuffer->diffuse);
    glBindTextureUnit(GB_UNIT_GBUFFER_GLOSSY, gbuffer->glossy);
    glBindTextureUnit(GB_UNIT_GBUFFER_CLUSTERS, gbuffer->clusters);
    glBindTextureUnit(GB_UNIT_GBUFFER_EMISSION, gbuffer->emission);
}

void gb_gbuffer_destroy(gb_gbuffer *gbuffer)
{
    delete_textures(gbuffer);
    if (gbuffer->framebuffer)
        glDeleteFramebuffers(1, &gbuffer->framebuffer);
    if (gbuffer->program)
        glDeleteProgram(gbuffer->program);
    memset(gbuffer, 0, sizeof *gbuffer);
}
