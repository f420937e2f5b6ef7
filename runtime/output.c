#include "output.h"

#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

static const char present_shader[] =
#include "runtime/output_present.frag.glsl.inc"
    ;

static gb_result make_target(gb_output *output, int width, int height, gb_error *error)
{
    output->width = width;
    output->height = height;
    output->radiance = gb_gl_texture_2d(GL_RGBA32F, width, height);
    glNamedFramebufferTexture(output->framebuffer, GL_COLOR_ATTACHMENT0, output->radiance, 0);
    glNamedFramebufferDrawBuffer(output->framebuffer, GL_COLOR_ATTACHMENT0);
    glNamedFramebufferReadBuffer(output->framebuffer, GL_COLOR_ATTACHMENT0);
    GLenum status = glCheckNamedFramebufferStatus(output->framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "output %dx%d: framebuffer incomplete (0x%04x)",
                       width, height, status);
    return GB_OK;
}

gb_result gb_output_create(int width, int height, gb_output *output, gb_error *error)
{
    memset(output, 0, sizeof *output);
    glCreateFramebuffers(1, &output->framebuffer);
    glCreateVertexArrays(1, &output->empty_vertex_array);
    gb_result result = make_target(output, width, height, error);
    if (result == GB_OK)
        result = gb_gl_program("present", gb_gl_fullscreen_vertex_shader, present_shader,
                               &output->present_program, error);
    if (result != GB_OK)
        gb_output_destroy(output);
    return result;
}

gb_result gb_output_resize(gb_output *output, int width, int height, gb_error *error)
{
    if (width == output->width && height == output->height)
        return GB_OK;
    glDeleteTextures(1, &output->radiance);
    return make_target(output, width, height, error);
}

void gb_output_bind(const gb_output *output)
{
    glBindFramebuffer(GL_FRAMEBUFFER, output->framebuffer);
    glViewport(0, 0, output->width, output->height);
}

void gb_output_clear(const gb_output *output)
{
    static const float black[4] = {0, 0, 0, 1};
    glClearNamedFramebufferfv(output->framebuffer, GL_COLOR, 0, black);
}

/* OpenGL's row 0 is the bottom: rows are flipped into the image. */
gb_result gb_output_read(const gb_output *output, gb_image *image, gb_error *error)
{
    gb_result result = gb_image_allocate(image, output->width, output->height, 3, error);
    if (result != GB_OK)
        return result;
    size_t row = 3 * (size_t)output->width;
    float *rows = malloc(row * (size_t)output->height * sizeof *rows);
    if (!rows) {
        gb_image_free(image);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "output: out of memory");
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, output->framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, output->width, output->height, GL_RGB, GL_FLOAT, rows);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    for (int y = 0; y < output->height; ++y)
        memcpy(&image->pixels[(size_t)y * row], &rows[(size_t)(output->height - 1 - y) * row],
               row * sizeof *rows);
    free(rows);
    return GB_OK;
}

void gb_output_present(const gb_output *output, int width, int height)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(output->present_program);
    glProgramUniform2f(output->present_program,
                       glGetUniformLocation(output->present_program, "scale"),
                       (float)output->width / (float)(width > 0 ? width : 1),
                       (float)output->height / (float)(height > 0 ? height : 1));
    glBindTextureUnit(0, output->radiance);
    gb_gl_draw_fullscreen(output->empty_vertex_array);
}

void gb_output_destroy(gb_output *output)
{
    if (output->radiance)
        glDeleteTextures(1, &output->radiance);
    if (output->framebuffer)
        glDeleteFramebuffers(1, &output->framebuffer);
    if (output->present_program)
        glDeleteProgram(output->present_program);
    if (output->empty_vertex_array)
        glDeleteVertexArrays(1, &output->empty_vertex_array);
    memset(output, 0, sizeof *output);
}
