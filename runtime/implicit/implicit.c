/* implicit.c — implicit visibility (Dong 2007) as a GI method of the
 * runtime (indirect_method.h).
 *
 * prepare  on the CPU, without GL (any thread): Algorithm 1 steps 1-2
 *          (elements, hierarchy), the bins, the environment in them and a
 *          first build of the links (steps 4-7), which report to the
 *          setup's progress and stop when it asks. The result is the
 *          method's state with its GL half empty.
 * create   takes prepare's result over (or runs prepare itself first when
 *          the setup has none) and makes the GL half: programs, the finer
 *          mesh on the GPU, the target.
 * draw     at part 0 of an image, on the CPU: steps 4-7 again
 *          (UpdateElements, the links in bins) while the last build took
 *          under GB_IMPLICIT_FRAME_SECONDS — gbview's scenes do not move, so
 *          above that the last links, which a rebuild would give again, are
 *          kept — then steps 8-11 (the light). That is every image when the
 *          frame has no budget (headless rendering, tests, the report:
 *          bench/implicit.sh measures this loop). In the window (a budget)
 *          the scene and its lights are static, so that loop would give
 *          each image the first one's solution: the first image computes it
 *          and later ones keep it. The elements' incident radiance E / pi
 *          (environment and bounces) on each side is uploaded as two vertex
 *          attributes and interpolated over the finer mesh's triangles (the
 *          paper's display, 4.3.1) into the method's own target with its own
 *          depth test, a fragment taking the side it shows (a back face its
 *          element's back), the scissor test off: the whole view, drawn
 *          again when the solution or the view changed. At every part, a
 *          full-screen pass adds Kd (the G-buffer's, texture included)
 *          times it onto the output, within the part's band.
 */
#include "implicit.h"

#include <stdlib.h>
#include <string.h>

#include "gl_util.h"
#include "indirect_method.h"
#include "method_parameters.h"
#include "progress.h"

enum { UNIT_INCIDENT = 10, DEFAULT_BINS = 12, DEFAULT_BOUNCES = 1 };

typedef struct implicit_state {
    const gb_scene *scene;
    gb_implicit_model model;
    gb_implicit_bins bins;
    gb_implicit_links links;
    gb_implicit_solution solution;
    float *vertex_incident;     /* model.vertex_count * 6: its element's display,
                                   front then back */
    uint32_t *shown;            /* 2 * element_count: the element shown for each
                                   side (implicit_hidden.h), made once: gbview's
                                   scenes do not move */
    float *environment;         /* bins.count * 3 from the scene's map, or NULL */
    int bounces;
    int paper_rules;            /* the links by 4.2.2's rules alone (--paper-rules) */
    gb_progress_callback progress;  /* the setup's (gb_indirect_setup): the first
                                   links report to it, later ones not */
    void *progress_user;
    double build_seconds;       /* the last Update + links */
    gb_implicit_step_times times;
    /* The GL half, which create makes. */
    GLuint position_buffer, incident_buffer, index_buffer, vertex_array;
    GLuint mesh_program, compose_program, empty_vertex_array;
    gb_gl_target incident;      /* RGBA32F incident radiance, with its depth */
} implicit_state;

static const char mesh_vertex_shader[] =
#include "runtime/implicit/implicit_mesh.vert.glsl.inc"
    ;

static const char mesh_fragment_shader[] =
#include "runtime/implicit/implicit_mesh.frag.glsl.inc"
    ;

static const char compose_fragment_shader[] =
#include "runtime/implicit/implicit_compose.frag.glsl.inc"
    ;

static void make_mesh(implicit_state *s)
{
    const gb_implicit_model *m = &s->model;
    glCreateBuffers(1, &s->position_buffer);
    glNamedBufferStorage(s->position_buffer, 3 * (GLsizeiptr)m->vertex_count * sizeof(float),
                         m->vertices, 0);
    glCreateBuffers(1, &s->incident_buffer);
    glNamedBufferStorage(s->incident_buffer, 6 * (GLsizeiptr)m->vertex_count * sizeof(float),
                         NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateBuffers(1, &s->index_buffer);
    glNamedBufferStorage(s->index_buffer, 3 * (GLsizeiptr)m->triangle_count * sizeof(uint32_t),
                         m->triangles, 0);
    glCreateVertexArrays(1, &s->vertex_array);
    glVertexArrayVertexBuffer(s->vertex_array, 0, s->position_buffer, 0, 3 * sizeof(float));
    glVertexArrayVertexBuffer(s->vertex_array, 1, s->incident_buffer, 0, 6 * sizeof(float));
    /* attributes: 0 position, 1 the front's incident radiance, 2 the back's */
    for (GLuint i = 0; i < 3; ++i) {
        glEnableVertexArrayAttrib(s->vertex_array, i);
        glVertexArrayAttribFormat(s->vertex_array, i, 3, GL_FLOAT, GL_FALSE,
                                  i == 2 ? 3 * sizeof(float) : 0);
        glVertexArrayAttribBinding(s->vertex_array, i, i == 0 ? 0 : 1);
    }
    glVertexArrayElementBuffer(s->vertex_array, s->index_buffer);
}

/* prepare's half: what the CPU holds. */
static void implicit_discard(void *prepared)
{
    implicit_state *s = prepared;
    if (!s)
        return;
    gb_implicit_solution_free(&s->solution);
    free(s->vertex_incident);
    free(s->shown);
    gb_implicit_links_free(&s->links);
    free(s->environment);
    gb_implicit_bins_free(&s->bins);
    gb_implicit_model_free(&s->model);
    free(s);
}

static void implicit_destroy(void *state)
{
    implicit_state *s = state;
    if (!s)
        return;
    GLuint buffers[3] = {s->position_buffer, s->incident_buffer, s->index_buffer};
    glDeleteBuffers(3, buffers);
    GLuint arrays[2] = {s->vertex_array, s->empty_vertex_array};
    glDeleteVertexArrays(2, arrays);
    if (s->mesh_program)
        glDeleteProgram(s->mesh_program);
    if (s->compose_program)
        glDeleteProgram(s->compose_program);
    gb_gl_target_release(&s->incident);
    implicit_discard(s);
}

static gb_result check_parameters(const gb_implicit_parameters *p, int *bins, int *bounces,
                                  gb_error *error)
{
    *bins = p && p->bins ? p->bins : DEFAULT_BINS;
    *bounces = p && p->bounces ? p->bounces : DEFAULT_BOUNCES;
    if (*bins < 1 || *bins > 64)
        return gb_fail(error, GB_ERROR_ARGUMENT, "implicit: bins %d is not in 1..64", *bins);
    if (*bounces < 1 || *bounces > 8)
        return gb_fail(error, GB_ERROR_ARGUMENT, "implicit: bounces %d is not in 1..8", *bounces);
    return GB_OK;
}

/* Steps 4-7: UpdateElements, then the links, which replace the old ones
 * only when made. */
static gb_result rebuild_links(implicit_state *s, gb_error *error)
{
    gb_implicit_link_options options = {.hierarchical = 1, .lights = s->scene,
                                        .environment = s->environment,
                                        .paper_rules = s->paper_rules,
                                        .progress = s->progress,
                                        .progress_user = s->progress_user};
    gb_implicit_links links;
    double start = gb_seconds();
    gb_result result = gb_implicit_update_elements(&s->model, error);
    double updated = gb_seconds();
    if (result == GB_OK)
        result = gb_implicit_create_links(&s->model, &s->bins, &options, &links, NULL, error);
    s->progress = NULL;
    if (result != GB_OK)
        return result;
    gb_implicit_links_free(&s->links);
    s->links = links;
    s->build_seconds = gb_seconds() - start;
    s->times.update_ms += 1e3 * (updated - start);
    s->times.create_ms += 1e3 * links.wall.create;
    s->times.refine_ms += 1e3 * (links.wall.refine + links.wall.compact);
    return GB_OK;
}

/* The scene's environment map, if loaded, averaged over each bin (4.4). */
static gb_result make_environment(implicit_state *s, gb_error *error)
{
    if (!s->scene->environment_texture.rgb)
        return GB_OK;
    s->environment = malloc(3 * (size_t)s->bins.count * sizeof *s->environment);
    if (!s->environment)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    return gb_implicit_environment_bins(&s->bins, &s->scene->environment_texture, 1.0f,
                                        s->environment, error);
}

static gb_result build(implicit_state *s, int bins, gb_error *error)
{
    gb_result result =
        gb_implicit_model_create(s->scene, 0.0f, GB_IMPLICIT_ELEMENT_CELL, &s->model, error);
    if (result == GB_OK) {
        s->shown = malloc(2 * (size_t)s->model.element_count * sizeof *s->shown + 1);
        result = s->shown ? gb_implicit_shown_elements(&s->model, s->shown, NULL, NULL, error)
                          : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    if (result == GB_OK)
        result = gb_implicit_bins_create(bins, &s->bins, error);
    if (result == GB_OK)
        result = make_environment(s, error);
    if (result == GB_OK)
        result = rebuild_links(s, error);
    if (result == GB_OK)
        result = gb_implicit_solution_create(&s->model, &s->solution, error);
    if (result == GB_OK) {
        s->vertex_incident = malloc(6 * (size_t)s->model.vertex_count * sizeof(float) + 1);
        if (!s->vertex_incident)
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    return result;
}

void gb_implicit_times(const void *method_state, gb_implicit_step_times *times)
{
    const implicit_state *s = method_state;
    memset(times, 0, sizeof *times);
    if (s)
        *times = s->times;
}

/* create's CPU half (the file's top comment): no GL call. */
static gb_result implicit_prepare(const gb_indirect_setup *setup, void **prepared,
                                  gb_error *error)
{
    *prepared = NULL;
    int bins, bounces;
    gb_result result = check_parameters(setup->parameters ? &setup->parameters->implicit : NULL, &bins, &bounces, error);
    if (result != GB_OK)
        return result;
    implicit_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    s->scene = setup->scene;
    s->bounces = bounces;
    s->paper_rules = setup->parameters && setup->parameters->implicit.paper_rules;
    s->progress = setup->progress;
    s->progress_user = setup->progress_user;
    result = build(s, bins, error);
    if (result != GB_OK) {
        implicit_discard(s);
        return result;
    }
    *prepared = s;
    return GB_OK;
}

/* Takes setup->prepared over (freed here also when this fails). */
static gb_result implicit_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    *state = NULL;
    implicit_state *s = setup->prepared;
    gb_result result = s ? GB_OK : implicit_prepare(setup, (void **)&s, error);
    if (result != GB_OK)
        return result;
    result = gb_gl_program("implicit mesh", mesh_vertex_shader, mesh_fragment_shader,
                           &s->mesh_program, error);
    if (result == GB_OK)
        result = gb_gl_program("implicit compose", gb_gl_fullscreen_vertex_shader,
                               compose_fragment_shader, &s->compose_program, error);
    if (result != GB_OK) {
        implicit_destroy(s);
        return result;
    }
    make_mesh(s);
    glCreateVertexArrays(1, &s->empty_vertex_array);
    gb_gl_target_resize(&s->incident, GL_RGBA32F, setup->width, setup->height);
    *state = s;
    return GB_OK;
}

/* Each vertex's element's display, front and back, to the GPU; an element
 * of a closed part shows its front on both (gb_implicit_node_two_sided), a
 * hidden side that of the element shown in its place (implicit_hidden.h:
 * the ceiling's elements under the Cornell box's light, which would darken
 * the finer triangles reaching out from under it). */
static void upload_incident(implicit_state *s)
{
    const gb_implicit_model *m = &s->model;
    const float *display = s->solution.display;
    for (uint32_t v = 0; v < m->vertex_count; ++v) {
        size_t e = m->vertex_element[v];
        int back = gb_implicit_node_two_sided(m, &m->nodes[e]) ? GB_IMPLICIT_BACK
                                                                : GB_IMPLICIT_FRONT;
        for (int side = 0; side < GB_IMPLICIT_SIDES; ++side) {
            size_t r = (side ? back : side) * (size_t)m->element_count;
            memcpy(&s->vertex_incident[6 * (size_t)v + 3 * side],
                   &display[3 * (r + s->shown[r + e])], 3 * sizeof(float));
        }
    }
    glNamedBufferSubData(s->incident_buffer, 0, 6 * (GLsizeiptr)m->vertex_count * sizeof(float),
                         s->vertex_incident);
}

/* The finer mesh, its incident radiance interpolated, into the own target
 * (of the frame's size already). */
static void draw_incident(implicit_state *s, const gb_indirect_frame *frame)
{
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->incident.framebuffer, GL_COLOR, 0, zero);
    gb_gl_target_begin_geometry(&s->incident);
    glUseProgram(s->mesh_program);
    gb_gl_set_view_projection(s->mesh_program, frame->view_matrix->m, frame->projection->m);
    glBindVertexArray(s->vertex_array);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * s->model.triangle_count), GL_UNSIGNED_INT, NULL);
    glDisable(GL_DEPTH_TEST);
}

/* Steps 4-11 on the CPU, their display to the GPU. The create made the
 * first image's links; a failed rebuild keeps the last. */
static void solve(implicit_state *s)
{
    gb_error error;
    if (s->times.frames > 0 && s->build_seconds < GB_IMPLICIT_FRAME_SECONDS &&
        rebuild_links(s, &error) == GB_OK)
        ++s->times.rebuilds;
    double start = gb_seconds();
    gb_implicit_illuminate(s->scene, &s->model, &s->links, s->bounces, &s->solution);
    s->times.illuminate_ms += 1e3 * (gb_seconds() - start);
    ++s->times.frames;
    upload_incident(s);
}

/* Part 0's work: the solution (every image without a budget, the first
 * one's kept with one: the top comment), and the incident target, which
 * covers the whole view, so drawn with the scissor test off. */
static void draw_view(implicit_state *s, const gb_indirect_frame *frame)
{
    int solved = frame->budget_ms <= 0.0 || s->times.frames == 0;
    if (solved)
        solve(s);
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    if (gb_gl_target_stale(&s->incident, GL_RGBA32F, frame->width, frame->height,
                           frame->view_matrix->m, frame->projection->m) ||
        solved)
        draw_incident(s, frame);
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
}

static int implicit_draw(void *state, const gb_indirect_frame *frame)
{
    implicit_state *s = state;
    GLint output = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &output);
    if (frame->part == 0)
        draw_view(s, frame);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)output);
    glViewport(0, 0, frame->width, frame->height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(s->compose_program);
    gb_gbuffer_bind(frame->gbuffer);
    glBindTextureUnit(UNIT_INCIDENT, s->incident.color);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
    return 0;
}

const gb_indirect_method gb_implicit_method = {
    .create = implicit_create,
    .draw = implicit_draw,
    .destroy = implicit_destroy,
    .prepare = implicit_prepare,
    .discard = implicit_discard,
};
