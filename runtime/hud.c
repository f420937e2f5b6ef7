/* hud.c — text over the window's image (hud.h). */
#include "hud.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* stb_easy_font's functions are static: the one hud.c does not call
 * (stb_easy_font_spacing) would warn. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

static const char vertex_shader[] =
#include "runtime/hud.vert.glsl.inc"
    ;
static const char fragment_shader[] =
#include "runtime/hud.frag.glsl.inc"
    ;

/* stb_easy_font's vertex: x, y, z as floats, then RGBA8; 4 a quad. */
enum { VERTEX_BYTES = 16, QUAD_BYTES = 4 * VERTEX_BYTES, COLOUR_OFFSET = 12 };
/* The most quads a character makes is 11 (measured over ' '..'~'): 12 a
 * character leaves room, so that the first try is enough. */
enum { QUADS_PER_CHARACTER = 12 };

/* stb_easy_font takes the colour as unsigned char *, not const. */
static unsigned char text_colour[4] = {255, 255, 255, 255};
static const unsigned char box_colour[4] = {0, 0, 0, 150};

gb_result gb_hud_create(gb_hud *hud, gb_error *error)
{
    memset(hud, 0, sizeof *hud);
    gb_result result = gb_gl_program("hud", vertex_shader, fragment_shader, &hud->program, error);
    if (result != GB_OK)
        return result;
    glCreateBuffers(1, &hud->vertex_buffer);
    glCreateBuffers(1, &hud->index_buffer);
    glCreateVertexArrays(1, &hud->vertex_array);
    GLuint array = hud->vertex_array;
    glVertexArrayVertexBuffer(array, 0, hud->vertex_buffer, 0, VERTEX_BYTES);
    glVertexArrayElementBuffer(array, hud->index_buffer);
    glEnableVertexArrayAttrib(array, 0);
    glVertexArrayAttribFormat(array, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(array, 0, 0);
    glEnableVertexArrayAttrib(array, 1);
    glVertexArrayAttribFormat(array, 1, 4, GL_UNSIGNED_BYTE, GL_TRUE, COLOUR_OFFSET);
    glVertexArrayAttribBinding(array, 1, 0);
    return GB_OK;
}

int gb_hud_scale(int height)
{
    return height / 360 > 1 ? height / 360 : 1;
}

/* ---- the text and its box ---- */

/* text into out (strlen(text) + 1 bytes), each character stb_easy_font
 * cannot draw replaced by '?'. */
static void make_printable(const char *text, char *out)
{
    for (; *text; ++text, ++out)
        *out = *text == '\n' || (*text >= ' ' && *text <= '~') ? *text : '?';
    *out = '\0';
}

/* The box around printable text of w x h font pixels (stb_easy_font_width,
 * _height), as gb_hud_box gives it. */
static void box_around(int w, int h, gb_hud_corner corner, int height, int box[4])
{
    int scale = gb_hud_scale(height);
    if (w <= 0 || h <= 0) {
        box[0] = box[1] = box[2] = box[3] = 0;
        return;
    }
    box[2] = (w + 2 * GB_HUD_PADDING) * scale;
    box[3] = (h + 2 * GB_HUD_PADDING) * scale;
    box[0] = GB_HUD_MARGIN * scale;
    box[1] = corner == GB_HUD_TOP_LEFT ? GB_HUD_MARGIN * scale
                                        : height - GB_HUD_MARGIN * scale - box[3];
}

void gb_hud_box(const char *text, gb_hud_corner corner, int height, int box[4])
{
    char *printable = text ? malloc(strlen(text) + 1) : NULL;
    int w = 0, h = 0;
    if (printable) {
        make_printable(text, printable);
        w = stb_easy_font_width(printable);
        h = stb_easy_font_height(printable);
        free(printable);
    }
    box_around(w, h, corner, height, box);
}

/* Grows *buffer to at least bytes; 0 when out of memory. */
static int reserve(char **buffer, size_t *allocated, size_t bytes)
{
    if (bytes <= *allocated)
        return 1;
    char *grown = realloc(*buffer, bytes);
    if (!grown)
        return 0;
    *buffer = grown;
    *allocated = bytes;
    return 1;
}

/* One quad of the box's colour from (x0, y0) to (x1, y1), font pixels. */
static void box_quad(char *out, float x0, float y0, float x1, float y1)
{
    const float corners[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int c = 0; c < 4; ++c, out += VERTEX_BYTES) {
        const float vertex[3] = {corners[c][0], corners[c][1], 0.0f};
        memcpy(out, vertex, sizeof vertex);
        memcpy(out + COLOUR_OFFSET, box_colour, sizeof box_colour);
    }
}

/* The box's quad, then the glyphs' of hud->text (w x h font pixels, its top
 * left corner at 0, 0) into hud->vertices: how many quads, 0 when out of
 * memory. stb_easy_font drops the quads that do not fit: it is given room
 * to spare, and more when it used nearly all of it. */
static int make_quads(gb_hud *hud, int w, int h)
{
    size_t room = (QUADS_PER_CHARACTER * strlen(hud->text) + 1) * QUAD_BYTES;
    for (;;) {
        if (!reserve(&hud->vertices, &hud->vertex_bytes, QUAD_BYTES + room))
            return 0;
        box_quad(hud->vertices, -GB_HUD_PADDING, -GB_HUD_PADDING, (float)(w + GB_HUD_PADDING),
                 (float)(h + GB_HUD_PADDING));
        int quads = stb_easy_font_print(0.0f, 0.0f, hud->text, text_colour,
                                        hud->vertices + QUAD_BYTES, (int)room);
        if ((size_t)quads * QUAD_BYTES + QUAD_BYTES <= room)
            return 1 + quads;
        room *= 2;
    }
}

/* The index buffer made to hold quads quads as two triangles each (0 1 2,
 * 0 2 3); 0 when out of memory. */
static int fit_indices(gb_hud *hud, int quads)
{
    if (quads <= hud->index_quads)
        return 1;
    GLsizei count = quads > 2 * hud->index_quads ? quads : 2 * hud->index_quads;
    uint32_t *indices = malloc((size_t)count * 6 * sizeof *indices);
    if (!indices)
        return 0;
    static const uint32_t corners[6] = {0, 1, 2, 0, 2, 3};
    for (GLsizei q = 0; q < count; ++q)
        for (int i = 0; i < 6; ++i)
            indices[6 * q + i] = 4 * (uint32_t)q + corners[i];
    glNamedBufferData(hud->index_buffer, (GLsizeiptr)count * 6 * sizeof *indices, indices,
                      GL_STATIC_DRAW);
    free(indices);
    hud->index_quads = count;
    return 1;
}

/* ---- drawing ---- */

/* Draws quads quads of hud->vertices, the text's top left corner at pixel
 * origin of the width x height framebuffer. */
static void draw_quads(const gb_hud *hud, int quads, const float origin[2], int width,
                       int height)
{
    GLuint p = hud->program;
    glNamedBufferData(hud->vertex_buffer, (GLsizeiptr)quads * QUAD_BYTES, hud->vertices,
                      GL_STREAM_DRAW);
    glProgramUniform2fv(p, glGetUniformLocation(p, "origin"), 1, origin);
    glProgramUniform1f(p, glGetUniformLocation(p, "scale"), (float)gb_hud_scale(height));
    glProgramUniform2f(p, glGetUniformLocation(p, "size"), (float)width, (float)height);
    gb_gl_state saved;
    gb_gl_state_save(&saved);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(p);
    glBindVertexArray(hud->vertex_array);
    glDrawElements(GL_TRIANGLES, 6 * quads, GL_UNSIGNED_INT, NULL);
    gb_gl_state_restore(&saved);
}

void gb_hud_draw(gb_hud *hud, const char *text, gb_hud_corner corner, int width, int height)
{
    if (!text || !reserve(&hud->text, &hud->text_bytes, strlen(text) + 1))
        return;
    make_printable(text, hud->text);
    int w = stb_easy_font_width(hud->text), h = stb_easy_font_height(hud->text), box[4];
    box_around(w, h, corner, height, box);
    if (box[2] == 0)
        return;
    int quads = make_quads(hud, w, h);
    if (quads == 0 || !fit_indices(hud, quads))
        return;
    int inset = GB_HUD_PADDING * gb_hud_scale(height);
    const float origin[2] = {(float)(box[0] + inset), (float)(box[1] + inset)};
    draw_quads(hud, quads, origin, width, height);
}

void gb_hud_destroy(gb_hud *hud)
{
    if (hud->program)
        glDeleteProgram(hud->program);
    if (hud->vertex_array)
        glDeleteVertexArrays(1, &hud->vertex_array);
    if (hud->vertex_buffer)
        glDeleteBuffers(1, &hud->vertex_buffer);
    if (hud->index_buffer)
        glDeleteBuffers(1, &hud->index_buffer);
    free(hud->vertices);
    free(hud->text);
    memset(hud, 0, sizeof *hud);
}
