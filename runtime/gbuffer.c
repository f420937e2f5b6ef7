#include "gbuffer.h"

#include <math.h>
#include <string.h>

#include "gl_util.h"

static const char vertex_shader[] =
#include "runtime/gbuffer.vert.glsl.inc"
    ;

static const char fragment_shader[] =
#include "runtime/gbuffer.frag.glsl.inc"
    ;

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
    gb_gl_set_view_projection(gbuffer->program, view->m, projection->m);
    gb_gpu_scene_draw(scene, 1);
    glDisable(GL_DEPTH_TEST);
}

void gb_gbuffer_set_view(GLuint program, const float view_to_world[16],
                         const float tan_half_fov[2], float near)
{
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view_to_world"), 1,
                              GL_FALSE, view_to_world);
    glProgramUniform2f(program, glGetUniformLocation(program, "tan_half_fov"), tan_half_fov[0],
                       tan_half_fov[1]);
    glProgramUniform1f(program, glGetUniformLocation(program, "near"), near);
}

void gb_gbuffer_set_view_of(GLuint program, const gb_view *view, int width, int height)
{
    gb_mat4 view_to_world = gb_view_inverse_matrix(view);
    float tan_y = tanf(0.5f * view->fov_y * 3.14159265358979f / 180.0f);
    float aspect = (float)width / (float)height;
    float tan_half_fov[2] = {tan_y * aspect, tan_y};
    gb_gbuffer_set_view(program, view_to_world.m, tan_half_fov, view->near);
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
