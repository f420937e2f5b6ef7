/* flc_iv.c — Forward Light Cuts with implicit visibility as a GI method of
 * the runtime (flc_iv.h says what it computes).
 *
 * prepare  on the CPU, without GL (any thread): the implicit model, its
 *          links with the depth maps (reporting to the setup's progress,
 *          stopping when it asks), packed dense for the GPU.
 * create   takes prepare's result over (or runs prepare first when the
 *          setup has none): the depth maps and the finer mesh to the GPU,
 *          the element-id program, FLC's state with this visibility term.
 * draw     at part 0, the element ids of the view into the method's own
 *          target (scissor test off: the whole view), then FLC's draw,
 *          which cuts its image by VPLs (flc.h).
 */
#include "flc_iv.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flc/flc.h"
#include "gl_util.h"
#include "implicit/implicit.h"
#include "method_parameters.h"

enum {
    SSBO_DEPTHS = 11,
    SSBO_CENTRES = 12,
    UNIT_ELEMENT_IDS = 12,
    DEFAULT_BINS = 12,
    NO_ELEMENT = 0xffffffffu,
};

static const char elements_vertex_shader[] =
#include "runtime/flc_iv/flc_iv_elements.vert.glsl.inc"
    ;

static const char elements_geometry_shader[] =
#include "runtime/flc_iv/flc_iv_elements.geom.glsl.inc"
    ;

static const char elements_fragment_shader[] =
#include "runtime/flc_iv/flc_iv_elements.frag.glsl.inc"
    ;

static const char visibility_shader[] =
#include "runtime/flc_iv/flc_iv_visibility.frag.glsl.inc"
    ;

typedef struct flc_iv_state {
    void *flc;
    gb_implicit_model model;
    gb_implicit_bins bins;
    gb_implicit_links links;
    int bin_filter;
    float depth_unit;           /* metres (scene units) of one step of depth */
    uint16_t *depths;           /* prepare's dense depth maps (element_count x
                                   bins.count, rounded up to pairs) and */
    float *centres;             /* the elements' centres (4 floats each), until
                                   create uploads them */
    uint32_t *vertex_shown;     /* the finer mesh's vertex_count x 2: the element
                                   shown on the front and on the back of each
                                   vertex's (implicit_hidden.h), until uploaded */
    /* The GL half, which create makes. */
    GLuint depths_buffer, centres_buffer;
    GLuint position_buffer, element_buffer, index_buffer, vertex_array, elements_program;
    gb_gl_target element_ids;   /* RGBA32UI, with its depth: the three elements
                                   of the triangle seen, the weights of the
                                   last two (flc_iv_elements.frag.glsl) */
} flc_iv_state;

/* prepare's half: what the CPU holds. */
static void flc_iv_discard(void *prepared)
{
    flc_iv_state *s = prepared;
    if (!s)
        return;
    free(s->depths);
    free(s->centres);
    free(s->vertex_shown);
    gb_implicit_links_free(&s->links);
    gb_implicit_bins_free(&s->bins);
    gb_implicit_model_free(&s->model);
    free(s);
}

static void flc_iv_destroy(void *state)
{
    flc_iv_state *s = state;
    if (!s)
        return;
    gb_flc_destroy(s->flc);
    GLuint buffers[] = {s->depths_buffer, s->centres_buffer, s->position_buffer,
                        s->element_buffer, s->index_buffer};
    glDeleteBuffers(5, buffers);
    glDeleteVertexArrays(1, &s->vertex_array);
    if (s->elements_program)
        glDeleteProgram(s->elements_program);
    gb_gl_target_release(&s->element_ids);
    flc_iv_discard(s);
}

/* Steps 1-7 of implicit visibility, with the depth maps, no light; the
 * links report to the setup's progress. */
static gb_result build_depth_maps(flc_iv_state *s, const gb_indirect_setup *setup, int bins,
                                  gb_error *error)
{
    gb_result result =
        gb_implicit_model_create(setup->scene, 0.0f, GB_IMPLICIT_ELEMENT_CELL, &s->model, error);
    if (result == GB_OK)
        result = gb_implicit_bins_create(bins, &s->bins, error);
    gb_implicit_link_options options = {.hierarchical = 1, .depths = 1,
                                        .progress = setup->progress,
                                        .progress_user = setup->progress_user};
    if (result == GB_OK)
        result = gb_implicit_create_links(&s->model, &s->bins, &options, &s->links, NULL, error);
    return result;
}

static float scene_diagonal(const gb_scene *scene)
{
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
        double side = (double)scene->bounds_max[k] - scene->bounds_min[k];
        sum += side * side;
    }
    return (float)sqrt(sum);
}

/* The number of 16-bit depths of the dense maps: one a bin and element,
 * rounded up to a whole number of 32-bit words. */
static size_t depth_count(const flc_iv_state *s)
{
    return ((size_t)s->model.element_count * s->bins.count + 1) / 2 * 2;
}

/* The depth maps, dense, 16 bits a bin and element (flc_iv.h), two a word,
 * and the elements' centres; the links are then freed. */
static gb_result pack_depth_maps(flc_iv_state *s, const gb_scene *scene, gb_error *error)
{
    uint32_t elements = s->model.element_count, bins = s->bins.count;
    s->depths = malloc((depth_count(s) + 1) * sizeof *s->depths);
    s->centres = malloc(4 * (size_t)elements * sizeof *s->centres + 1);
    if (!s->depths || !s->centres)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc-iv: out of memory");
    float diagonal = scene_diagonal(scene);
    s->depth_unit = (diagonal > 0.0f ? diagonal : 1.0f) / GB_FLC_IV_DEPTH_FAR;
    memset(s->depths, 0xff, (depth_count(s) + 1) * sizeof *s->depths);
    for (uint32_t e = 0; e < elements; ++e) {
        for (uint32_t i = s->links.depth_first[e]; i < s->links.depth_first[e + 1]; ++i) {
            /* Rounded up: a depth never comes nearer than the link. */
            float steps = ceilf(s->links.depth[i] / s->depth_unit);
            s->depths[(size_t)e * bins + s->links.depth_bin[i]] =
                (uint16_t)(steps < GB_FLC_IV_DEPTH_FAR ? steps : GB_FLC_IV_DEPTH_FAR);
        }
        memcpy(&s->centres[4 * (size_t)e], s->model.nodes[e].position, 3 * sizeof(float));
        s->centres[4 * (size_t)e + 3] = 0.0f;
    }
    gb_implicit_links_free(&s->links);
    return GB_OK;
}

/* Each vertex's element as shown on each side (implicit_hidden.h): a
 * hidden side, whose depth map hides every VPL (the ceiling's elements
 * under the Cornell box's light, 0.5 mm deep a bin), takes the nearest
 * element of its surface that is seen, so that the finer triangles
 * reaching out from under the light are not black. */
static gb_result vertex_elements(flc_iv_state *s, gb_error *error)
{
    const gb_implicit_model *m = &s->model;
    uint32_t *shown = malloc(2 * (size_t)m->element_count * sizeof *shown + 1);
    s->vertex_shown = malloc(2 * (size_t)m->vertex_count * sizeof *s->vertex_shown + 1);
    gb_result result = shown && s->vertex_shown
                           ? gb_implicit_shown_elements(m, shown, NULL, NULL, error)
                           : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc-iv: out of memory");
    for (uint32_t v = 0; result == GB_OK && v < m->vertex_count; ++v)
        for (int side = 0; side < GB_IMPLICIT_SIDES; ++side) {
            size_t r = (size_t)side * m->element_count;
            s->vertex_shown[2 * (size_t)v + side] = shown[r + m->vertex_element[v]];
        }
    free(shown);
    return result;
}

/* The packed maps to the GPU; the CPU's copies freed. */
static void upload_depth_maps(flc_iv_state *s)
{
    s->depths_buffer = gb_gl_buffer(s->depths, (GLsizeiptr)(depth_count(s) * sizeof *s->depths));
    s->centres_buffer =
        gb_gl_buffer(s->centres, 4 * (GLsizeiptr)s->model.element_count * sizeof *s->centres);
    free(s->depths);
    free(s->centres);
    s->depths = NULL;
    s->centres = NULL;
}

/* The finer mesh with each vertex's element, for the element-id pass. */
static void upload_mesh(flc_iv_state *s)
{
    const gb_implicit_model *m = &s->model;
    glCreateBuffers(1, &s->position_buffer);
    glNamedBufferStorage(s->position_buffer, 3 * (GLsizeiptr)m->vertex_count * sizeof(float),
                         m->vertices, 0);
    glCreateBuffers(1, &s->element_buffer);
    glNamedBufferStorage(s->element_buffer, 2 * (GLsizeiptr)m->vertex_count * sizeof(uint32_t),
                         s->vertex_shown, 0);
    free(s->vertex_shown);
    s->vertex_shown = NULL;
    glCreateBuffers(1, &s->index_buffer);
    glNamedBufferStorage(s->index_buffer, 3 * (GLsizeiptr)m->triangle_count * sizeof(uint32_t),
                         m->triangles, 0);
    glCreateVertexArrays(1, &s->vertex_array);
    glVertexArrayVertexBuffer(s->vertex_array, 0, s->position_buffer, 0, 3 * sizeof(float));
    glEnableVertexArrayAttrib(s->vertex_array, 0);
    glVertexArrayAttribFormat(s->vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(s->vertex_array, 0, 0);
    /* attributes 1 and 2: the element shown on the front, on the back */
    glVertexArrayVertexBuffer(s->vertex_array, 1, s->element_buffer, 0, 2 * sizeof(uint32_t));
    for (GLuint i = 1; i < 3; ++i) {
        glEnableVertexArrayAttrib(s->vertex_array, i);
        glVertexArrayAttribIFormat(s->vertex_array, i, 1, GL_UNSIGNED_INT,
                                   (i - 1) * sizeof(uint32_t));
        glVertexArrayAttribBinding(s->vertex_array, i, 1);
    }
    glVertexArrayElementBuffer(s->vertex_array, s->index_buffer);
}

/* FLC's visibility hook (flc.h): the depth maps and the element ids. */
static void bind_visibility(void *context, GLuint program)
{
    const flc_iv_state *s = context;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_DEPTHS, s->depths_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_CENTRES, s->centres_buffer);
    glBindTextureUnit(UNIT_ELEMENT_IDS, s->element_ids.color);
    glProgramUniform1i(program, glGetUniformLocation(program, "bins_n"), s->bins.n);
    glProgramUniform1i(program, glGetUniformLocation(program, "bin_filter"), s->bin_filter);
    glProgramUniform1f(program, glGetUniformLocation(program, "bias_bin"),
                       GB_FLC_IV_BIAS_BIN / (float)s->bins.n);
    glProgramUniform1f(program, glGetUniformLocation(program, "bias_element"),
                       GB_FLC_IV_BIAS_ELEMENT * s->model.element_size);
    glProgramUniform1f(program, glGetUniformLocation(program, "depth_unit"), s->depth_unit);
}

/* create's CPU half (the file's top comment): no GL call. */
static gb_result flc_iv_prepare(const gb_indirect_setup *setup, void **prepared,
                                gb_error *error)
{
    *prepared = NULL;
    const gb_method_parameters *p = setup->parameters;
    int bins = p->implicit.bins ? p->implicit.bins : DEFAULT_BINS;
    if (bins < 1 || bins > 64)
        return gb_fail(error, GB_ERROR_ARGUMENT, "flc-iv: bins %d is not in 1..64", bins);
    flc_iv_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc-iv: out of memory");
    s->bin_filter = p->flc_iv.bin_filter;
    gb_result result = build_depth_maps(s, setup, bins, error);
    if (result == GB_OK)
        result = pack_depth_maps(s, setup->scene, error);
    if (result == GB_OK)
        result = vertex_elements(s, error);
    if (result != GB_OK) {
        flc_iv_discard(s);
        return result;
    }
    *prepared = s;
    return GB_OK;
}

/* Takes setup->prepared over (freed here also when this fails). */
static gb_result flc_iv_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    *state = NULL;
    flc_iv_state *s = setup->prepared;
    gb_result result = s ? GB_OK : flc_iv_prepare(setup, (void **)&s, error);
    if (result != GB_OK)
        return result;
    upload_depth_maps(s);
    const char *vertex[] = {elements_vertex_shader, NULL};
    const char *geometry[] = {elements_geometry_shader, NULL};
    const char *fragment[] = {elements_fragment_shader, NULL};
    const gb_gl_stage stages[] = {{GL_VERTEX_SHADER, vertex},
                                  {GL_GEOMETRY_SHADER, geometry},
                                  {GL_FRAGMENT_SHADER, fragment}};
    result = gb_gl_program_stages("flc-iv element ids", stages, 3, &s->elements_program, error);
    gb_flc_visibility visibility = {visibility_shader, bind_visibility, s};
    if (result == GB_OK)
        result = gb_flc_create(setup, &visibility, &s->flc, error);
    if (result != GB_OK) {
        flc_iv_destroy(s);
        return result;
    }
    upload_mesh(s);
    *state = s;
    return GB_OK;
}

/* The elements seen at each pixel, NO_ELEMENT where none is; drawn again
 * only when the view or the size changed (the scene is static). */
static void draw_element_ids(flc_iv_state *s, const gb_indirect_frame *frame)
{
    if (!gb_gl_target_stale(&s->element_ids, GL_RGBA32UI, frame->width, frame->height,
                            frame->view_matrix->m, frame->projection->m))
        return;
    const GLuint none[4] = {NO_ELEMENT, NO_ELEMENT, NO_ELEMENT, 0};
    glClearNamedFramebufferuiv(s->element_ids.framebuffer, GL_COLOR, 0, none);
    gb_gl_target_begin_geometry(&s->element_ids);
    glUseProgram(s->elements_program);
    gb_gl_set_view_projection(s->elements_program, frame->view_matrix->m, frame->projection->m);
    glBindVertexArray(s->vertex_array);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * s->model.triangle_count), GL_UNSIGNED_INT, NULL);
    glDisable(GL_DEPTH_TEST);
}

static int flc_iv_draw(void *state, const gb_indirect_frame *frame)
{
    flc_iv_state *s = state;
    if (frame->part == 0) {
        GLint output = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &output);
        GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
        glDisable(GL_SCISSOR_TEST);
        draw_element_ids(s, frame);
        if (scissor)
            glEnable(GL_SCISSOR_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)output);
        glViewport(0, 0, frame->width, frame->height);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
    }
    return gb_flc_draw(s->flc, frame);
}

const gb_indirect_method gb_flc_iv_method = {
    .create = flc_iv_create,
    .draw = flc_iv_draw,
    .destroy = flc_iv_destroy,
    .prepare = flc_iv_prepare,
    .discard = flc_iv_discard,
};
