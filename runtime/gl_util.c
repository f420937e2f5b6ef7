#include "gl_util.h"

#include <stdio.h>
#include <string.h>

static void GLAPIENTRY collect_message(GLenum source, GLenum type, GLuint id, GLenum severity,
                                       GLsizei length, const GLchar *message,
                                       const void *user)
{
    (void)source, (void)id, (void)length;
    if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH)
        return;
    gb_gl_errors *errors = (gb_gl_errors *)user;
    if (errors->count++ == 0)
        snprintf(errors->first, sizeof errors->first, "%s", message);
}

void gb_gl_errors_install(gb_gl_errors *errors)
{
    errors->count = 0;
    errors->first[0] = '\0';
    glEnable(GL_DEBUG_OUTPUT);
#ifndef NDEBUG
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
#endif
    glDebugMessageCallback(collect_message, errors);
}

static const char *error_name(GLenum code)
{
    switch (code) {
    case GL_INVALID_ENUM: return "invalid enum";
    case GL_INVALID_VALUE: return "invalid value";
    case GL_INVALID_OPERATION: return "invalid operation";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "invalid framebuffer operation";
    case GL_OUT_OF_MEMORY: return "out of memory";
    default: return "error";
    }
}

/* Clears glGetError's flags; counts them only when the callback saw
 * nothing (each error reaches both). */
static void drain_get_error(gb_gl_errors *errors)
{
    int seen_by_callback = errors->count > 0;
    for (GLenum code; (code = glGetError()) != GL_NO_ERROR;)
        if (!seen_by_callback && errors->count++ == 0)
            snprintf(errors->first, sizeof errors->first, "%s (0x%04x)", error_name(code),
                     code);
}

gb_result gb_gl_check(gb_gl_errors *errors, const char *where, gb_error *error)
{
    drain_get_error(errors);
    if (errors->count == 0)
        return GB_OK;
    unsigned more = errors->count - 1;
    errors->count = 0;
    if (more)
        return gb_fail(error, GB_ERROR_INVALID, "OpenGL: %s: %s (and %u more)", where,
                       errors->first, more);
    return gb_fail(error, GB_ERROR_INVALID, "OpenGL: %s: %s", where, errors->first);
}

gb_result gb_gl_require_45(gb_error *error)
{
    int version = epoxy_gl_version();
    if (version < 45)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "OpenGL 4.5 core is needed, the driver gives %d.%d (%s)", version / 10,
                       version % 10, (const char *)glGetString(GL_RENDERER));
    return GB_OK;
}

static const char *stage_name(GLenum type)
{
    switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_TESS_CONTROL_SHADER: return "tessellation control";
    case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    default: return "unknown";
    }
}

/* Compiles one stage and attaches it to program. */
static gb_result attach_stage(const char *name, const gb_gl_stage *stage, GLuint program,
                              gb_error *error)
{
    GLsizei part_count = 0;
    while (stage->parts[part_count])
        ++part_count;
    GLuint shader = glCreateShader(stage->type);
    glShaderSource(shader, part_count, stage->parts, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    char log[1024] = "";
    if (!ok)
        glGetShaderInfoLog(shader, sizeof log, NULL, log);
    else
        glAttachShader(program, shader);
    glDeleteShader(shader);
    return ok ? GB_OK
              : gb_fail(error, GB_ERROR_INVALID, "shader %s (%s): %s", name,
                        stage_name(stage->type), log);
}

gb_result gb_gl_program_stages(const char *name, const gb_gl_stage *stages, int count,
                               GLuint *program, gb_error *error)
{
    *program = glCreateProgram();
    gb_result result = GB_OK;
    for (int i = 0; i < count && result == GB_OK; ++i)
        result = attach_stage(name, &stages[i], *program, error);
    if (result == GB_OK) {
        glLinkProgram(*program);
        GLint ok = GL_FALSE;
        glGetProgramiv(*program, GL_LINK_STATUS, &ok);
        char log[1024] = "";
        if (!ok) {
            glGetProgramInfoLog(*program, sizeof log, NULL, log);
            result = gb_fail(error, GB_ERROR_INVALID, "program %s: %s", name, log);
        }
    }
    if (result != GB_OK) {
        glDeleteProgram(*program);
        *program = 0;
    }
    return result;
}

gb_result gb_gl_program(const char *name, const char *vertex, const char *fragment,
                        GLuint *program, gb_error *error)
{
    const char *vertex_parts[] = {vertex, NULL}, *fragment_parts[] = {fragment, NULL};
    const gb_gl_stage stages[] = {{GL_VERTEX_SHADER, vertex_parts},
                                  {GL_FRAGMENT_SHADER, fragment_parts}};
    return gb_gl_program_stages(name, stages, 2, program, error);
}

gb_result gb_gl_compute_program(const char *name, const char *source, GLuint *program,
                                gb_error *error)
{
    const char *parts[] = {source, NULL};
    const gb_gl_stage stage = {GL_COMPUTE_SHADER, parts};
    return gb_gl_program_stages(name, &stage, 1, program, error);
}

GLuint gb_gl_buffer(const void *data, GLsizeiptr size)
{
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, size > 0 ? size : 16, size > 0 ? data : NULL, GL_DYNAMIC_DRAW);
    return buffer;
}

GLuint gb_gl_texture_2d(GLenum internal_format, int width, int height)
{
    GLuint texture;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, internal_format, width, height);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

int gb_gl_target_resize(gb_gl_target *target, GLenum color_format, int width, int height)
{
    if (target->framebuffer && target->width == width && target->height == height)
        return 0;
    gb_gl_target_release(target);
    target->width = width;
    target->height = height;
    target->color = gb_gl_texture_2d(color_format, width, height);
    target->depth = gb_gl_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &target->framebuffer);
    glNamedFramebufferTexture(target->framebuffer, GL_COLOR_ATTACHMENT0, target->color, 0);
    glNamedFramebufferTexture(target->framebuffer, GL_DEPTH_ATTACHMENT, target->depth, 0);
    return 1;
}

int gb_gl_target_stale(gb_gl_target *target, GLenum color_format, int width, int height,
                       const float view[16], const float projection[16])
{
    int made = gb_gl_target_resize(target, color_format, width, height);
    if (!made && target->drawn && !memcmp(target->view, view, sizeof target->view) &&
        !memcmp(target->projection, projection, sizeof target->projection))
        return 0;
    target->drawn = 1;
    memcpy(target->view, view, sizeof target->view);
    memcpy(target->projection, projection, sizeof target->projection);
    return 1;
}

void gb_gl_target_release(gb_gl_target *target)
{
    if (target->framebuffer)
        glDeleteFramebuffers(1, &target->framebuffer);
    GLuint textures[2] = {target->color, target->depth};
    glDeleteTextures(2, textures);
    memset(target, 0, sizeof *target);
}

void gb_gl_target_begin_geometry(const gb_gl_target *target)
{
    const float far = 0.0f;
    glClearNamedFramebufferfv(target->framebuffer, GL_DEPTH, 0, &far);
    glBindFramebuffer(GL_FRAMEBUFFER, target->framebuffer);
    glViewport(0, 0, target->width, target->height);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
}

void gb_gl_set_view_projection(GLuint program, const float view[16], const float projection[16])
{
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view"), 1, GL_FALSE, view);
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "projection"), 1, GL_FALSE,
                              projection);
}

void gb_gl_state_save(gb_gl_state *s)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_framebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_framebuffer);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_SCISSOR_BOX, s->scissor_box);
    s->scissor_test = glIsEnabled(GL_SCISSOR_TEST);
    s->blend = glIsEnabled(GL_BLEND);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_functions[0]);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_functions[1]);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_functions[2]);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_functions[3]);
    s->depth_test = glIsEnabled(GL_DEPTH_TEST);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_function);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    s->cull_face = glIsEnabled(GL_CULL_FACE);
}

static void set_enabled(GLenum capability, GLboolean enabled)
{
    if (enabled)
        glEnable(capability);
    else
        glDisable(capability);
}

void gb_gl_state_restore(const gb_gl_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_framebuffer);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_framebuffer);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glScissor(s->scissor_box[0], s->scissor_box[1], s->scissor_box[2], s->scissor_box[3]);
    set_enabled(GL_SCISSOR_TEST, s->scissor_test);
    set_enabled(GL_BLEND, s->blend);
    glBlendFuncSeparate((GLenum)s->blend_functions[0], (GLenum)s->blend_functions[1],
                        (GLenum)s->blend_functions[2], (GLenum)s->blend_functions[3]);
    set_enabled(GL_DEPTH_TEST, s->depth_test);
    glDepthFunc((GLenum)s->depth_function);
    glDepthMask(s->depth_mask);
    set_enabled(GL_CULL_FACE, s->cull_face);
}

const char gb_gl_fullscreen_vertex_shader[] =
#include "runtime/fullscreen.vert.glsl.inc"
    ;

void gb_gl_draw_fullscreen(GLuint empty_vertex_array)
{
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}
