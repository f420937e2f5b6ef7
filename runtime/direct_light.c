#include "direct_light.h"

#include <math.h>
#include <string.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "shadow_cascades.h"

static const char fragment_shader[] =
#include "runtime/direct_light.frag.glsl.inc"
    ;

/* The map as a float RGB texture: bilinear, wrapping round in u, clamped in v. */
static GLuint environment_texture(const gb_texture *map)
{
    GLuint texture;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGB32F, map->width, map->height);
    glTextureSubImage2D(texture, 0, 0, 0, map->width, map->height, GL_RGB, GL_FLOAT, map->rgb);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

gb_result gb_direct_light_create(gb_direct_light *pass, const gb_texture *environment_map,
                                 gb_error *error)
{
    memset(pass, 0, sizeof *pass);
    gb_result result = gb_gl_program("direct light", gb_gl_fullscreen_vertex_shader,
                                     fragment_shader, &pass->program, error);
    if (result != GB_OK)
        return result;
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    if (environment_map && environment_map->rgb)
        pass->environment_map = environment_texture(environment_map);
    return GB_OK;
}

static void set_uniforms(GLuint program, GLuint environment_map, const gb_direct_inputs *in)
{
    const gb_view *view = in->view;
    gb_gbuffer_set_view_of(program, view, in->gbuffer->width, in->gbuffer->height);
    glProgramUniform3fv(program, glGetUniformLocation(program, "environment"), 1,
                        in->environment);
    glProgramUniform1i(program, glGetUniformLocation(program, "has_environment_map"),
                       environment_map != 0);
    glProgramUniform1i(program, glGetUniformLocation(program, "point_count"),
                       (GLint)in->shadows->point_count);
    glProgramUniform1i(program, glGetUniformLocation(program, "plane_count"),
                       (GLint)in->shadows->plane_count);
    glProgramUniform1i(program, glGetUniformLocation(program, "shadows"), in->shadows_enabled);
    glProgramUniform1f(program, glGetUniformLocation(program, "cube_texel"),
                       2.0f / (float)in->shadows->cube_size);
    glProgramUniform1i(program, glGetUniformLocation(program, "cascade_count"),
                       in->cascades ? GB_SHADOW_CASCADES : 0);
}

void gb_direct_light_draw(gb_direct_light *pass, const gb_direct_inputs *inputs)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(pass->program);
    set_uniforms(pass->program, pass->environment_map, inputs);
    glBindTextureUnit(10, pass->environment_map);
    gb_gbuffer_bind(inputs->gbuffer);
    gb_shadow_maps_bind(inputs->shadows);
    gb_shadow_maps_bind_cascades(inputs->shadows);
    gb_gl_draw_fullscreen(pass->empty_vertex_array);
}

void gb_direct_light_destroy(gb_direct_light *pass)
{
    if (pass->program)
        glDeleteProgram(pass->program);
    if (pass->empty_vertex_array)
        glDeleteVertexArrays(1, &pass->empty_vertex_array);
    if (pass->environment_map)
        glDeleteTextures(1, &pass->environment_map);
    memset(pass, 0, sizeof *pass);
}
