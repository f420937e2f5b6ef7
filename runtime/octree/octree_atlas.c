/* octree_atlas.c — the light octree rendered into the atlas once and shown
 * through it (octree_atlas.h). */
#include "octree_atlas.h"

#include <stdlib.h>
#include <string.h>

#include "gl_util.h"
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
                                   where filled */
    GLuint corner_buffer, corner_array;
    GLsizei corner_count;
    GLuint uv_program, display_program, empty_vertex_array;
    gb_gl_target seen_uv;       /* RGBA32F: the atlas UV at each pixel (-1 for none)
                                   and the layer of the side seen */
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

/* ---- the render into the atlas ---- */

static GLuint make_atlas_texture(const gb_atlas_header *h)
{
    GLuint texture;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
    glTextureStorage3D(texture, 1, GL_RGBA32F, (GLsizei)h->width, (GLsizei)h->height, SIDES);
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

static void set_octree_uniforms(GLuint program, const gb_light_octree_header *h)
{
    glProgramUniform3fv(program, glGetUniformLocation(program, "origin"), 1, h->origin);
    glProgramUniform1f(program, glGetUniformLocation(program, "cell_size"),
                       h->size / (float)(1u << h->depth));
    glProgramUniform1i(program, glGetUniformLocation(program, "depth"), (GLint)h->depth);
}

/* The triangles drawn at their UVs, each reaching gb_atlas_reach texels
 * past its edges, the nearest triangle keeping a texel (a depth test on the
 * distance): the irradiance of each side into its layer of s->texture. */
static gb_result render_triangles(gb_octree_atlas *s, const gb_atlas_header *h,
                                  const gb_light_octree_header *octree, gb_error *error)
{
    GLuint program;
    gb_result result = gb_gl_program("octree atlas render", render_vertex_shader,
                                     render_fragment_shader, &program, error);
    if (result != GB_OK)
        return result;
    set_octree_uniforms(program, octree);
    glProgramUniform2f(program, glGetUniformLocation(program, "atlas_size"), (float)h->width,
                       (float)h->height);
    glProgramUniform1f(program, glGetUniformLocation(program, "reach"),
                       (float)gb_atlas_reach(h->padding));
    GLuint depth = gb_gl_texture_2d(GL_DEPTH_COMPONENT32F, (int)h->width, (int)h->height);
    static const float nothing_filled[4] = {0, 0, 0, 0}, farthest = 1.0f;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_CORNERS, s->corner_buffer);
    glUseProgram(program);
    glBindVertexArray(s->empty_vertex_array);
    for (int layer = 0; layer < SIDES; ++layer) {
        GLuint framebuffer = framebuffer_of(s->texture, layer);
        glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, nothing_filled);
        glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &farthest);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glProgramUniform1f(program, glGetUniformLocation(program, "side"),
                           layer == 0 ? 1.0f : -1.0f);
        glDrawArrays(GL_TRIANGLES, 0, s->corner_count);
        glDeleteFramebuffers(1, &framebuffer);
    }
    glDisable(GL_DEPTH_TEST);
    glDeleteTextures(1, &depth);
    glDeleteProgram(program);
    return GB_OK;
}

/* One full-screen pass of program per layer, reading s->texture (unit 0)
 * into a new texture, which becomes s->texture. */
static void pass_into_new_texture(gb_octree_atlas *s, const gb_atlas_header *h, GLuint program)
{
    GLuint next = make_atlas_texture(h);
    glUseProgram(program);
    glBindTextureUnit(0, s->texture);
    for (int layer = 0; layer < SIDES; ++layer) {
        GLuint framebuffer = framebuffer_of(next, layer);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glProgramUniform1i(program, glGetUniformLocation(program, "layer"), layer);
        gb_gl_draw_fullscreen(s->empty_vertex_array);
        glDeleteFramebuffers(1, &framebuffer);
    }
    glDeleteTextures(1, &s->texture);
    s->texture = next;
}

/* The rest of the gutter, past the triangles' reach: padding - 1 rounds of
 * means. */
static gb_result fill_gutter(gb_octree_atlas *s, const gb_atlas_header *h, gb_error *error)
{
    GLuint gutter;
    gb_result result = gb_gl_program("octree atlas gutter", gb_gl_fullscreen_vertex_shader,
                                     gutter_fragment_shader, &gutter, error);
    if (result != GB_OK)
        return result;
    for (uint32_t round = 1; round < h->padding; ++round)
        pass_into_new_texture(s, h, gutter);
    glDeleteProgram(gutter);
    return GB_OK;
}

static gb_result render_atlas(gb_octree_atlas *s, const gb_atlas_header *h,
                              const gb_light_octree_header *octree, gb_error *error)
{
    GLint output = 0, viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &output);
    glGetIntegerv(GL_VIEWPORT, viewport);
    s->texture = make_atlas_texture(h);
    glViewport(0, 0, (GLsizei)h->width, (GLsizei)h->height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    gb_result result = render_triangles(s, h, octree, error);
    if (result == GB_OK)
        result = fill_gutter(s, h, error);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)output);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    return result;
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
        result = render_atlas(s, &atlas->header, octree, error);
    if (result != GB_OK) {
        gb_octree_atlas_destroy(s);
        return result;
    }
    *state = s;
    return GB_OK;
}

/* The atlas UV and the side seen at each pixel; drawn again only when the
 * view or the size changed (the scene is static). */
static void draw_seen_uv(gb_octree_atlas *s, const gb_indirect_frame *frame)
{
    if (!gb_gl_target_stale(&s->seen_uv, GL_RGBA32F, frame->width, frame->height,
                            frame->view_matrix->m, frame->projection->m))
        return;
    static const float none[4] = {-1, -1, 0, 0};
    glClearNamedFramebufferfv(s->seen_uv.framebuffer, GL_COLOR, 0, none);
    gb_gl_target_begin_geometry(&s->seen_uv);
    glDisable(GL_CULL_FACE);
    glUseProgram(s->uv_program);
    gb_gl_set_view_projection(s->uv_program, frame->view_matrix->m, frame->projection->m);
    glBindVertexArray(s->corner_array);
    glDrawArrays(GL_TRIANGLES, 0, s->corner_count);
    glDisable(GL_DEPTH_TEST);
}

void gb_octree_atlas_draw(gb_octree_atlas *s, const gb_indirect_frame *frame)
{
    GLint output = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &output);
    draw_seen_uv(s, frame);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)output);
    glViewport(0, 0, frame->width, frame->height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
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
