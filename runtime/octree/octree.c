/* octree.c — the light octree as a GI method (octree.h). */
#include "octree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "indirect_method.h"
#include "light_octree.h"
#include "method_parameters.h"
#include "octree_atlas.h"

enum { SSBO_NODES = 0, SSBO_LEAVES = 1, SSBO_VDLS = 2 };

typedef struct octree_state {
    const gb_light_octree *octree;  /* borrowed from the bake */
    GLuint buffers[3];          /* nodes, leaves, VDLs */
    GLuint program, empty_vertex_array;
    gb_octree_atlas *atlas;     /* the display through the atlas, or NULL: the walk */
} octree_state;

static const char fragment_shader[] =
#include "runtime/octree/octree_display.frag.glsl.inc"
    ;

static void octree_destroy(void *state)
{
    octree_state *s = state;
    if (!s)
        return;
    gb_octree_atlas_destroy(s->atlas);
    glDeleteBuffers(3, s->buffers);
    if (s->empty_vertex_array)
        glDeleteVertexArrays(1, &s->empty_vertex_array);
    if (s->program)
        glDeleteProgram(s->program);
    free(s);
}

static gb_result borrow_octree(const gb_indirect_setup *setup, const gb_light_octree **octree,
                               gb_error *error)
{
    const gb_bake *bake = setup->bake;
    if (!bake)
        return gb_fail(error, GB_ERROR_IO,
                       "octree: needs a light octree (NAME.lot from cluster): give --bake DIR");
    if (!(*octree = gb_bake_light_octree(bake)))
        return gb_fail(error, GB_ERROR_IO, "octree: no usable light octree: %s",
                       gb_bake_problem(bake, GB_BAKE_LIGHT_OCTREE));
    return GB_OK;
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
    const gb_light_octree *o = s->octree;
    s->buffers[SSBO_NODES] = make_buffer(o->nodes, o->header.node_count, sizeof *o->nodes);
    s->buffers[SSBO_LEAVES] = make_buffer(o->leaves, o->header.leaf_count, sizeof *o->leaves);
    s->buffers[SSBO_VDLS] = make_buffer(o->vdls, o->header.vdl_count, sizeof *o->vdls);
}

static void bind_buffers(const octree_state *s)
{
    for (GLuint i = 0; i < 3; ++i)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, s->buffers[i]);
}

/* The atlas named by --atlas (read into *own), or the bake's when it has
 * one, or *atlas NULL: none given, or "none". */
static gb_result find_atlas(const gb_indirect_setup *setup, gb_atlas *own,
                            const gb_atlas **atlas, gb_error *error)
{
    const char *path = setup->parameters->octree.atlas;
    *atlas = NULL;
    if (path && strcmp(path, "none") == 0)
        return GB_OK;
    if (path) {
        gb_result result = gb_atlas_read(path, own, error);
        if (result == GB_OK)
            result = gb_atlas_check_scene(own, setup->scene->hash,
                                          setup->scene->triangle_count, path, error);
        *atlas = result == GB_OK ? own : NULL;
        return result;
    }
    if (!setup->bake || access(gb_bake_path(setup->bake, GB_BAKE_ATLAS), F_OK) != 0)
        return GB_OK;
    if (!(*atlas = gb_bake_atlas(setup->bake)))
        return gb_fail(error, GB_ERROR_IO, "octree: %s (bake it again, or give --atlas none)",
                       gb_bake_problem(setup->bake, GB_BAKE_ATLAS));
    return GB_OK;
}

static gb_result create_atlas_display(octree_state *s, const gb_indirect_setup *setup,
                                      gb_error *error)
{
    gb_atlas own = {0};
    const gb_atlas *atlas;
    gb_result result = find_atlas(setup, &own, &atlas, error);
    if (result == GB_OK && atlas)
        result = gb_octree_atlas_create(setup->scene, atlas, &s->octree->header, &s->atlas,
                                        error);
    gb_atlas_free(&own);
    return result;
}

static gb_result octree_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    *state = NULL;
    octree_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "octree: out of memory");
    gb_result result = borrow_octree(setup, &s->octree, error);
    if (result == GB_OK)
        result = gb_gl_program("octree", gb_gl_fullscreen_vertex_shader, fragment_shader,
                               &s->program, error);
    if (result == GB_OK) {
        upload(s);
        glCreateVertexArrays(1, &s->empty_vertex_array);
        result = create_atlas_display(s, setup, error);
    }
    if (result != GB_OK) {
        octree_destroy(s);
        return result;
    }
    *state = s;
    return GB_OK;
}

static void set_uniforms(const octree_state *s, const gb_indirect_frame *frame)
{
    GLuint p = s->program;
    const gb_view *view = frame->view;
    const gb_light_octree_header *h = &s->octree->header;
    gb_gbuffer_set_view_of(p, view, frame->width, frame->height);
    glProgramUniform2i(p, glGetUniformLocation(p, "full_size"), frame->width, frame->height);
    gb_octree_set_irradiance_uniforms(p, h);
}

/* The walk: the octree's irradiance at each pixel of the band. */
static void draw_walk(octree_state *s, const gb_indirect_frame *frame)
{
    set_uniforms(s, frame);
    bind_buffers(s);
    glUseProgram(s->program);
    gb_gbuffer_bind(frame->gbuffer);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

/* With an atlas: at part 0, slices of it until the budget is spent; the
 * walk until it is complete (another image will be better), then the
 * display through it. */
static int octree_draw(void *state, const gb_indirect_frame *frame)
{
    octree_state *s = state;
    int complete = !s->atlas || gb_octree_atlas_complete(s->atlas);
    if (!complete && frame->part == 0) {
        bind_buffers(s);
        complete = gb_octree_atlas_render(s->atlas, frame->budget_ms);
    }
    if (s->atlas && complete)
        gb_octree_atlas_draw(s->atlas, frame);
    else
        draw_walk(s, frame);
    return complete ? GB_IMAGE_FINAL : GB_IMAGE_PROVISIONAL;
}

gb_octree_atlas *gb_octree_atlas_of(void *state)
{
    return ((octree_state *)state)->atlas;
}

const gb_indirect_method gb_octree_method = {
    .create = octree_create,
    .draw = octree_draw,
    .destroy = octree_destroy,
};
