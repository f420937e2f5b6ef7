/* octree_atlas.c — the light octree rendered into the atlas, in slices,
 * and shown through it (octree_atlas.h). */
#include "octree_atlas.h"

#include <stdlib.h>
#include <string.h>

#include "gl_util.h"
#include "progress.h"
#include "scene_triangles.h"

enum { UNIT_ATLAS = 7, UNIT_SEEN_UV = 8, SSBO_CORNERS = 3 };

/* A triangle corner as the passes read it (the render into the atlas from
 * a storage buffer, octree_atlas_corners.glsl; the UV pass as attributes):
 * atlas UV, world position, shading normal, face normal. */
enum { CORNER_FLOATS = 11 };

/* The two sides of every triangle, a layer each: 0 the side its winding
 * faces, 1 the back. */
enum { SIDES = 2 };

struct gb_octree_atlas {
    GLuint texture;             /* RGBA32F array of SIDES layers: irradiance, alpha 1
                                   where filled (complete once every pass is done) */
    GLuint corner_buffer, corner_array;
    GLsizei corner_count;
    GLuint uv_program, display_program, empty_vertex_array;
    gb_gl_target seen_uv;       /* RGBA32F: the atlas UV at each pixel (-1 for none)
                                   and the layer of the side seen */
    /* The render into the atlas, in slices (its programs and textures
     * released when it is complete): */
    GLsizei width, height;      /* the atlas's, texels */
    uint32_t padding;
    GLuint render_program, gutter_program;
    GLuint depth;               /* the triangles' distance to each texel */
    GLuint next;                /* the texture a gutter round writes, or 0 */
    int pass;                   /* the pass under way (pass_count: complete) */
    GLsizei row;                /* its first row not yet rendered */
    /* A slice's time, fixed + rows x per_row: each slice draws every chart's
     * triangles (the fixed part), its rows only bound their fragments. Two
     * slices of different heights give both (measure_slice). */
    double seconds_per_row;     /* 0 before any slice */
    double fixed_seconds;
    int last_rows;              /* the last slice's, and its time */
    double last_seconds;
};

static const char render_vertex_shader[] =
#include "runtime/octree/octree_atlas_render.vert.glsl.inc"
    ;
static const char render_fragment_shader[] =
#include "runtime/octree/octree_atlas_render.frag.glsl.inc"
    ;
static const char gutter_fragment_shader[] =
#include "runtime/octree/octree_atlas_gutter.frag.glsl.inc"
    ;
static const char uv_vertex_shader[] =
#include "runtime/octree/octree_atlas_uv.vert.glsl.inc"
    ;
static const char uv_fragment_shader[] =
#include "runtime/octree/octree_atlas_uv.frag.glsl.inc"
    ;
static const char display_fragment_shader[] =
#include "runtime/octree/octree_atlas_display.frag.glsl.inc"
    ;

/* ---- the corners ---- */

/* Every triangle corner of the scene, CORNER_FLOATS each; NULL when out of
 * memory. */
static float *make_corners(const gb_scene *scene, const gb_atlas *atlas)
{
    float *corners = malloc((size_t)scene->triangle_count * 3 * CORNER_FLOATS * sizeof *corners);
    if (!corners)
        return NULL;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        gb_vec3 face = gb_triangle_normal(scene, t);
        for (int c = 0; c < 3; ++c) {
            float *out = corners + ((size_t)t * 3 + c) * CORNER_FLOATS;
            memcpy(out, atlas->uvs + 6 * (size_t)t + 2 * c, 2 * sizeof *out);
            gb_vec3_store(gb_triangle_corner(scene, t, c), out + 2);
            gb_vec3_store(gb_corner_normal(scene, t, c, face), out + 5);
            gb_vec3_store(face, out + 8);
        }
    }
    return corners;
}

static void attribute(GLuint array, GLuint location, GLint size, GLuint offset)
{
    glEnableVertexArrayAttrib(array, location);
    glVertexArrayAttribFormat(array, location, size, GL_FLOAT, GL_FALSE,
                              offset * sizeof(float));
    glVertexArrayAttribBinding(array, location, 0);
}

static gb_result upload_corners(gb_octree_atlas *s, const gb_scene *scene,
                                const gb_atlas *atlas, gb_error *error)
{
    float *corners = make_corners(scene, atlas);
    if (!corners)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree atlas: out of memory");
    s->corner_count = (GLsizei)(3 * scene->triangle_count);
    glCreateBuffers(1, &s->corner_buffer);
    glNamedBufferStorage(s->corner_buffer,
                         (GLsizeiptr)s->corner_count * CORNER_FLOATS * sizeof *corners,
                         corners, 0);
    free(corners);
    glCreateVertexArrays(1, &s->corner_array);
    glVertexArrayVertexBuffer(s->corner_array, 0, s->corner_buffer, 0,
                              CORNER_FLOATS * sizeof(float));
    attribute(s->corner_array, 0, 2, 0);    /* the UV pass's: UV, position, face normal */
    attribute(s->corner_array, 1, 3, 2);
    attribute(s->corner_array, 3, 3, 8);
    return GB_OK;
}

/* ---- the render into the atlas, in slices ---- */

/* The render is a sequence of passes, each over the whole atlas, one
 * layer each: the triangles into layer 0, then layer 1 (round 0); then
 * each gutter round r = 1 .. padding - 1 reads the texture the round before
 * wrote and writes both layers of a new one. A pass is cut into bands of
 * rows, the slices, each drawn with the scissor on its rows: a texel's
 * value depends on the fragments that reach it and on their order alone,
 * which the scissor leaves as they are, so the atlas is the same bytes
 * whatever the slices. */
static int pass_count(const gb_octree_atlas *s)
{
    return SIDES * (s->padding > 1 ? (int)s->padding : 1);
}

static GLuint make_atlas_texture(const gb_octree_atlas *s)
{
    GLuint texture;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
    glTextureStorage3D(texture, 1, GL_RGBA32F, s->width, s->height, SIDES);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

/* A framebuffer drawing into one layer of an atlas texture. */
static GLuint framebuffer_of(GLuint texture, int layer)
{
    GLuint framebuffer;
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTextureLayer(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0, layer);
    return framebuffer;
}

void gb_octree_set_irradiance_uniforms(GLuint program, const gb_light_octree_header *h)
{
    glProgramUniform3fv(program, glGetUniformLocation(program, "origin"), 1, h->origin);
    glProgramUniform1f(program, glGetUniformLocation(program, "cell_size"),
                       h->size / (float)(1u << h->depth));
    glProgramUniform1i(program, glGetUniformLocation(program, "depth"), (GLint)h->depth);
    glProgramUniform1i(program, glGetUniformLocation(program, "surface_interpolation"),
                       h->interpolation == GB_LIGHT_OCTREE_SURFACE);
}

/* The programs and the depth texture the render needs, kept until it is
 * complete. */
static gb_result prepare_render(gb_octree_atlas *s, const gb_atlas_header *h,
                                const gb_light_octree_header *octree, gb_error *error)
{
    s->width = (GLsizei)h->width;
    s->height = (GLsizei)h->height;
    s->padding = h->padding;
    gb_result result = gb_gl_program("octree atlas render", render_vertex_shader,
                                     render_fragment_shader, &s->render_program, error);
    if (result == GB_OK)
        result = gb_gl_program("octree atlas gutter", gb_gl_fullscreen_vertex_shader,
                               gutter_fragment_shader, &s->gutter_program, error);
    if (result != GB_OK)
        return result;
    GLuint p = s->render_program;
    gb_octree_set_irradiance_uniforms(p, octree);
    glProgramUniform2f(p, glGetUniformLocation(p, "atlas_size"), (float)h->width,
                       (float)h->height);
    glProgramUniform1f(p, glGetUniformLocation(p, "reach"), (float)gb_atlas_reach(h->padding));
    s->texture = make_atlas_texture(s);
    s->depth = gb_gl_texture_2d(GL_DEPTH_COMPONENT32F, s->width, s->height);
    return GB_OK;
}

/* What only the render needs, once it is complete. */
static void release_render(gb_octree_atlas *s)
{
    if (s->render_program)
        glDeleteProgram(s->render_program);
    if (s->gutter_program)
        glDeleteProgram(s->gutter_program);
    GLuint textures[2] = {s->depth, s->next};
    glDeleteTextures(2, textures);
    s->render_program = s->gutter_program = s->depth = s->next = 0;
}

/* The triangles drawn at their UVs into the scissor's rows of layer,
 * each reaching gb_atlas_reach texels past its edges, the nearest triangle
 * keeping a texel (a depth test on the distance): the irradiance of the
 * layer's side. The rows are cleared first (the clears obey the scissor). */
static void triangles_slice(gb_octree_atlas *s, int layer)
{
    static const float nothing_filled[4] = {0, 0, 0, 0}, farthest = 1.0f;
    GLuint framebuffer = framebuffer_of(s->texture, layer);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, s->depth, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, nothing_filled);
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &farthest);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_CORNERS, s->corner_buffer);
    glUseProgram(s->render_program);
    glProgramUniform1f(s->render_program, glGetUniformLocation(s->render_program, "side"),
                       layer == 0 ? 1.0f : -1.0f);
    glBindVertexArray(s->empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, s->corner_count);
    glDisable(GL_DEPTH_TEST);
    glDeleteFramebuffers(1, &framebuffer);
}

/* One round of the gutter, past the triangles' reach, in the scissor's rows
 * of layer: s->texture read, s->next (made at the round's first slice)
 * written; every unfilled texel the mean of its filled neighbours. */
static void gutter_slice(gb_octree_atlas *s, int layer)
{
    if (!s->next)
        s->next = make_atlas_texture(s);
    GLuint framebuffer = framebuffer_of(s->next, layer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glUseProgram(s->gutter_program);
    glBindTextureUnit(0, s->texture);
    glProgramUniform1i(s->gutter_program, glGetUniformLocation(s->gutter_program, "layer"),
                       layer);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
    glDeleteFramebuffers(1, &framebuffer);
}

/* Rows s->row .. s->row + rows - 1 of the current pass; then on to the next
 * pass when that was its last row (a gutter round's texture becomes the
 * atlas after its last layer). */
static void render_slice(gb_octree_atlas *s, int rows)
{
    int layer = s->pass % SIDES, round = s->pass / SIDES;
    glScissor(0, s->row, s->width, rows);
    if (round == 0)
        triangles_slice(s, layer);
    else
        gutter_slice(s, layer);
    s->row += rows;
    if (s->row < s->height)
        return;
    s->row = 0;
    s->pass++;
    if (round > 0 && layer == SIDES - 1) {
        glDeleteTextures(1, &s->texture);
        s->texture = s->next;
        s->next = 0;
    }
}

/* The rows of the first slice timed. */
enum { FIRST_SLICE_ROWS = 16 };

/* A slice with a budget is at most this share of the atlas's rows: each
 * pass is cut into that many slices at least, whatever the clock says. */
enum { SLICES_A_PASS = 8 };

/* The rows of the next slice: the rest of the pass without a budget; else
 * as many as the budget left allows after the slice's fixed part, and never
 * fewer than make its rows cost as much as that part (a thinner slice would
 * spend more on the part than on the rows); at most 1/SLICES_A_PASS of the
 * atlas, at least one row; FIRST_SLICE_ROWS before any slice was timed. */
static int slice_rows(const gb_octree_atlas *s, double budget_ms, double spent_seconds)
{
    int left = s->height - s->row;
    if (budget_ms <= 0.0)
        return left;
    double rows = FIRST_SLICE_ROWS;
    if (s->seconds_per_row > 0.0) {
        double fits = (1e-3 * budget_ms - spent_seconds - s->fixed_seconds) / s->seconds_per_row;
        double balanced = s->fixed_seconds / s->seconds_per_row;
        rows = fits > balanced ? fits : balanced;
    }
    double most = (double)s->height / SLICES_A_PASS;
    rows = rows < most ? rows : most;
    return rows < 1.0 ? 1 : rows >= left ? left : (int)rows;
}

/* Updates the model of a slice's time with one that took seconds. */
static void measure_slice(gb_octree_atlas *s, int rows, double seconds)
{
    if (s->last_rows > 0 && rows != s->last_rows) {
        double per_row = (seconds - s->last_seconds) / (double)(rows - s->last_rows);
        if (per_row > 0.0) {
            s->seconds_per_row = per_row;
            s->fixed_seconds = seconds > rows * per_row ? seconds - rows * per_row : 0.0;
        }
    } else if (s->seconds_per_row <= 0.0) {
        s->seconds_per_row = seconds / rows;
    }
    s->last_rows = rows;
    s->last_seconds = seconds;
}

int gb_octree_atlas_complete(const gb_octree_atlas *s)
{
    return s->pass == pass_count(s);
}

int gb_octree_atlas_render(gb_octree_atlas *s, double budget_ms)
{
    if (gb_octree_atlas_complete(s))
        return 1;
    gb_gl_state saved;
    gb_gl_state_save(&saved);
    glViewport(0, 0, s->width, s->height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_SCISSOR_TEST);
    double start = gb_seconds();
    do {
        double slice_start = gb_seconds();
        int rows = slice_rows(s, budget_ms, slice_start - start);
        render_slice(s, rows);
        if (budget_ms > 0.0) {
            glFinish();
            measure_slice(s, rows, gb_seconds() - slice_start);
        }
    } while (!gb_octree_atlas_complete(s) &&
             (budget_ms <= 0.0 || 1e3 * (gb_seconds() - start) < budget_ms));
    if (gb_octree_atlas_complete(s))
        release_render(s);
    gb_gl_state_restore(&saved);
    return gb_octree_atlas_complete(s);
}

GLuint gb_octree_atlas_texture(const gb_octree_atlas *s)
{
    return s->texture;
}

/* ---- create, draw, destroy ---- */

gb_result gb_octree_atlas_create(const gb_scene *scene, const gb_atlas *atlas,
                                 const gb_light_octree_header *octree,
                                 gb_octree_atlas **state, gb_error *error)
{
    *state = NULL;
    gb_octree_atlas *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree atlas: out of memory");
    glCreateVertexArrays(1, &s->empty_vertex_array);
    gb_result result = upload_corners(s, scene, atlas, error);
    if (result == GB_OK)
        result = gb_gl_program("octree atlas uv", uv_vertex_shader, uv_fragment_shader,
                               &s->uv_program, error);
    if (result == GB_OK)
        result = gb_gl_program("octree atlas display", gb_gl_fullscreen_vertex_shader,
                               display_fragment_shader, &s->display_program, error);
    if (result == GB_OK)
        result = prepare_render(s, &atlas->header, octree, error);
    if (result != GB_OK) {
        gb_octree_atlas_destroy(s);
        return result;
    }
    *state = s;
    return GB_OK;
}

/* The atlas UV and the side seen at each pixel, over the whole view (the
 * scissor off); drawn again only when the view or the size changed (the
 * scene is static). Leaves the caller's state as it was. */
static void draw_seen_uv(gb_octree_atlas *s, const gb_indirect_frame *frame)
{
    if (!gb_gl_target_stale(&s->seen_uv, GL_RGBA32F, frame->width, frame->height,
                            frame->view_matrix->m, frame->projection->m))
        return;
    gb_gl_state saved;
    gb_gl_state_save(&saved);
    glDisable(GL_SCISSOR_TEST);
    static const float none[4] = {-1, -1, 0, 0};
    glClearNamedFramebufferfv(s->seen_uv.framebuffer, GL_COLOR, 0, none);
    gb_gl_target_begin_geometry(&s->seen_uv);
    glDisable(GL_CULL_FACE);
    glUseProgram(s->uv_program);
    gb_gl_set_view_projection(s->uv_program, frame->view_matrix->m, frame->projection->m);
    glBindVertexArray(s->corner_array);
    glDrawArrays(GL_TRIANGLES, 0, s->corner_count);
    gb_gl_state_restore(&saved);
}

void gb_octree_atlas_draw(gb_octree_atlas *s, const gb_indirect_frame *frame)
{
    draw_seen_uv(s, frame);
    glUseProgram(s->display_program);
    gb_gbuffer_bind(frame->gbuffer);
    glBindTextureUnit(UNIT_ATLAS, s->texture);
    glBindTextureUnit(UNIT_SEEN_UV, s->seen_uv.color);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

void gb_octree_atlas_destroy(gb_octree_atlas *s)
{
    if (!s)
        return;
    release_render(s);
    glDeleteTextures(1, &s->texture);
    glDeleteBuffers(1, &s->corner_buffer);
    GLuint arrays[2] = {s->corner_array, s->empty_vertex_array};
    glDeleteVertexArrays(2, arrays);
    if (s->uv_program)
        glDeleteProgram(s->uv_program);
    if (s->display_program)
        glDeleteProgram(s->display_program);
    gb_gl_target_release(&s->seen_uv);
    free(s);
}
