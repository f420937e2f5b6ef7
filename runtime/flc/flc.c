#include "flc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gbuffer.h"
#include "gl_util.h"
#include "method_parameters.h"
#include "progress.h"

/* The seed of v_rand (per vertex, at load) and of u_rand (per frame). */
#define FLC_SEED 0x464c43u
enum {
    SSBO_TRIANGLES = 3,
    SSBO_ALBEDOS = 4,
    SSBO_VPLS = 5,
    SSBO_PATCHES = 6,
    SSBO_COMMANDS = 7,
    UNIT_SPLAT = 10,
    UNIT_ACCUMULATED = 11,
    GENERATE_GROUP = 64,
    VPL_BYTES = 64,
};

/* Pass 1 (flc_generate.glsl): the regular pipeline's compute pass; the
 * divergent pipeline's tessellation of the patches, whose geometry stage
 * makes their VPLs. */
static const char generate_shader[] =
#include "runtime/flc/flc_generate.comp.glsl.inc"
    ;
static const char tess_vertex_shader[] =
#include "runtime/flc/flc_tess.vert.glsl.inc"
    ;
static const char tess_control_shader[] =
#include "runtime/flc/flc_tess.tesc.glsl.inc"
    ;
static const char tess_evaluation_shader[] =
#include "runtime/flc/flc_tess.tese.glsl.inc"
    ;
static const char tess_geometry_shader[] =
#include "runtime/flc/flc_tess.geom.glsl.inc"
    ;

/* Pass 2: a point a VPL, a quad a side, the VPL's light at each pixel. */
static const char splat_vertex_shader[] =
#include "runtime/flc/flc_splat.vert.glsl.inc"
    ;
static const char splat_geometry_shader[] =
#include "runtime/flc/flc_splat.geom.glsl.inc"
    ;
static const char splat_fragment_shader[] =
#include "runtime/flc/flc_splat.frag.glsl.inc"
    ;

/* Plain FLC's visibility term: every VPL sees every receiver (unshadowed). */
static const char unshadowed_shader[] =
#include "runtime/flc/flc_unshadowed.frag.glsl.inc"
    ;

/* Passes 3 and 4: untile and blur into the accumulation; its mean onto the
 * output. */
static const char resolve_shader[] =
#include "runtime/flc/flc_resolve.frag.glsl.inc"
    ;
static const char composite_shader[] =
#include "runtime/flc/flc_composite.frag.glsl.inc"
    ;

typedef struct flc_state {
    const gb_scene *scene;
    gb_flc_levels levels;
    float epsilon;
    int tiling;
    uint32_t triangle_count, regular_count;   /* regular ones first, divergent ones whole */
    uint32_t patch_capacity, divergent_capacity;  /* room for the tessellation */
    GLuint generate_program, splat_program, tess_program, resolve_program, composite_program;
    GLuint triangle_buffer, albedo_buffer, vpl_buffer, empty_vertex_array;
    GLuint patch_buffer, command_buffer;
    int width, height, tile_width, tile_height;
    gb_gl_target splat, accumulated;    /* the tiled splat buffer, the accumulation */
    uint32_t samples;               /* images in the accumulation */
    gb_mat4 last_view, last_projection;
    gb_flc_visibility visibility;   /* the splatting's visibility term */
    int measuring;
    gb_flc_pass_times times;
} flc_state;

void gb_flc_scene_levels(const gb_scene *scene, const gb_flc_parameters *parameters,
                         gb_flc_levels *levels)
{
    double diagonal = 0.0;
    for (int c = 0; c < 3; ++c) {
        double side = (double)scene->bounds_max[c] - scene->bounds_min[c];
        diagonal += side * side;
    }
    double R_scene = 0.5 * sqrt(diagonal);
    double N_avg = parameters->n_avg > 0.0f ? parameters->n_avg : GB_FLC_DEFAULT_N_AVG;
    double mu = parameters->mu > 1.0f ? parameters->mu : GB_FLC_DEFAULT_MU;
    int count = parameters->levels > 0 ? parameters->levels : GB_FLC_DEFAULT_LEVELS;
    gb_flc_levels_make(GB_FLC_D_NEAR_FRACTION * R_scene, N_avg, mu, count - 1, levels);
    levels->keep_all = parameters->levels == GB_FLC_NO_DECIMATION;
}

/* "#version 450 core" and the constants the GLSL shares with
 * flc_decimation.h, into text: the first part of the stages that start
 * without it. */
static const char *flc_prelude(char *text, size_t size)
{
    snprintf(text, size,
             "#version 450 core\n#define MAX_SUBDIVISION %uu\n#define MAX_TESS_LEVEL %uu\n"
             "#define TESS_GRID %u.0\n", (unsigned)GB_FLC_MAX_SUBDIVISION,
             (unsigned)GB_FLC_MAX_TESS_LEVEL, (unsigned)GB_FLC_TESS_GRID);
    return text;
}

static gb_result build_programs(flc_state *s, gb_error *error)
{
    char prelude[256];
    const char *pre = flc_prelude(prelude, sizeof prelude);
    const char *generate[] = {pre, generate_shader, NULL};
    const char *splat_vertex[] = {splat_vertex_shader, NULL};
    const char *splat_geometry[] = {splat_geometry_shader, NULL};
    const char *splat_fragment[] = {"#version 450 core\n", s->visibility.glsl,
                                    splat_fragment_shader, NULL};
    const char *tess_vertex[] = {tess_vertex_shader, NULL};
    const char *tess_control[] = {tess_control_shader, NULL};
    const char *tess_evaluation[] = {pre, tess_evaluation_shader, NULL};
    const char *tess_geometry[] = {pre, tess_geometry_shader, NULL};
    const gb_gl_stage generation[] = {{GL_COMPUTE_SHADER, generate}};
    const gb_gl_stage splatting[] = {{GL_VERTEX_SHADER, splat_vertex},
                                     {GL_GEOMETRY_SHADER, splat_geometry},
                                     {GL_FRAGMENT_SHADER, splat_fragment}};
    const gb_gl_stage tessellation[] = {{GL_VERTEX_SHADER, tess_vertex},
                                        {GL_TESS_CONTROL_SHADER, tess_control},
                                        {GL_TESS_EVALUATION_SHADER, tess_evaluation},
                                        {GL_GEOMETRY_SHADER, tess_geometry}};
    gb_result result = gb_gl_program_stages("flc VPL generation", generation, 1,
                                            &s->generate_program, error);
    if (result == GB_OK)
        result = gb_gl_program_stages("flc splatting", splatting, 3, &s->splat_program, error);
    if (result == GB_OK)
        result = gb_gl_program_stages("flc divergent tessellation", tessellation, 4,
                                      &s->tess_program, error);
    if (result == GB_OK)
        result = gb_gl_program("flc untile and blur", gb_gl_fullscreen_vertex_shader,
                               resolve_shader, &s->resolve_program, error);
    if (result == GB_OK)
        result = gb_gl_program("flc composite", gb_gl_fullscreen_vertex_shader,
                               composite_shader, &s->composite_program, error);
    return result;
}

/* rho of every material: Kd, times its texture's mean when it has one. */
static GLuint make_albedo_buffer(const gb_scene *scene)
{
    size_t count = scene->material_count ? scene->material_count : 1;
    float *albedo = calloc(4 * count, sizeof *albedo);
    for (uint32_t m = 0; albedo && m < scene->material_count; ++m) {
        const gb_material *material = &scene->materials[m];
        const gb_texture *texture = &material->texture;
        size_t pixels = (size_t)texture->width * (size_t)texture->height;
        for (int c = 0; c < 3; ++c) {
            double mean = 1.0;
            if (pixels && texture->rgb) {
                mean = 0.0;
                for (size_t i = 0; i < pixels; ++i)
                    mean += texture->rgb[3 * i + c];
                mean /= (double)pixels;
            }
            albedo[4 * m + c] = (float)(material->Kd[c] * mean);
        }
    }
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, (GLsizeiptr)(4 * count * sizeof(float)), albedo, 0);
    free(albedo);
    return buffer;
}

static gb_result make_buffers(flc_state *s, uint64_t seed, gb_error *error)
{
    gb_flc_triangles triangles;
    gb_result result = gb_flc_triangles_build_whole(s->scene, &s->levels, seed, &triangles,
                                                    error);
    if (result != GB_OK)
        return result;
    if (triangles.count + triangles.tessellated_bound > GB_FLC_MAX_TRIANGLES) {
        gb_flc_triangles_free(&triangles);
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "flc: room for %llu VPLs of divergent triangles (at most %u): "
                       "lower N_avg", (unsigned long long)triangles.tessellated_bound,
                       GB_FLC_MAX_TRIANGLES);
    }
    s->triangle_count = triangles.count;
    s->regular_count = triangles.regular_count;
    s->patch_capacity = (uint32_t)triangles.patch_bound;
    s->divergent_capacity = (uint32_t)triangles.tessellated_bound;
    s->times.regular_triangles = triangles.regular_count;
    s->times.divergent_triangles = triangles.divergent_count;
    size_t count = triangles.count ? triangles.count : 1;
    glCreateBuffers(1, &s->triangle_buffer);
    glNamedBufferStorage(s->triangle_buffer, (GLsizeiptr)(count * sizeof *triangles.items),
                         triangles.count ? triangles.items : NULL, 0);
    gb_flc_triangles_free(&triangles);
    glCreateBuffers(1, &s->vpl_buffer);
    glNamedBufferStorage(s->vpl_buffer,
                         (GLsizeiptr)((count + s->divergent_capacity) * VPL_BYTES), NULL, 0);
    glCreateBuffers(1, &s->patch_buffer);
    glNamedBufferStorage(s->patch_buffer,
                         (GLsizeiptr)((s->patch_capacity + 1) * 4 * sizeof(uint32_t)), NULL, 0);
    glCreateBuffers(1, &s->command_buffer);
    glNamedBufferStorage(s->command_buffer, 8 * sizeof(uint32_t), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    s->albedo_buffer = make_albedo_buffer(s->scene);
    glCreateVertexArrays(1, &s->empty_vertex_array);
    return GB_OK;
}

/* The tiled splat buffer (4^tiling tiles of ceil(size / 2^tiling)) and the
 * accumulation, for a frame of width x height. */
static void prepare_targets(flc_state *s, int width, int height)
{
    if (width == s->width && height == s->height)
        return;
    int scale = 1 << s->tiling;
    s->width = width;
    s->height = height;
    s->tile_width = (width + scale - 1) / scale;
    s->tile_height = (height + scale - 1) / scale;
    gb_gl_target_resize(&s->splat, GL_RGBA32F, s->tile_width * scale, s->tile_height * scale);
    gb_gl_target_resize(&s->accumulated, GL_RGBA32F, width, height);
    s->samples = 0;
}

void gb_flc_destroy(void *state)
{
    flc_state *s = state;
    if (!s)
        return;
    gb_gl_target_release(&s->splat);
    gb_gl_target_release(&s->accumulated);
    GLuint programs[] = {s->generate_program, s->splat_program, s->tess_program,
                         s->resolve_program, s->composite_program};
    for (int i = 0; i < 5; ++i)
        if (programs[i])
            glDeleteProgram(programs[i]);
    GLuint buffers[] = {s->triangle_buffer, s->albedo_buffer, s->vpl_buffer, s->patch_buffer,
                        s->command_buffer};
    for (int i = 0; i < 5; ++i)
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
    if (s->empty_vertex_array)
        glDeleteVertexArrays(1, &s->empty_vertex_array);
    free(s);
}

static float default_epsilon(const gb_flc_levels *levels)
{
    return GB_FLC_EPSILON_FRACTION / GB_FLC_D_NEAR_FRACTION * levels->D_near;
}

gb_result gb_flc_create(const gb_indirect_setup *setup, const gb_flc_visibility *visibility,
                        void **state, gb_error *error)
{
    const gb_flc_parameters *parameters = &setup->parameters->flc;
    if (parameters->tiling < 0 || parameters->tiling > GB_FLC_MAX_TILING)
        return gb_fail(error, GB_ERROR_ARGUMENT, "flc: tiling %d is not in 0..%d",
                       parameters->tiling, GB_FLC_MAX_TILING);
    if (parameters->levels > GB_FLC_MAX_LEVELS ||
        (parameters->levels < 0 && parameters->levels != GB_FLC_NO_DECIMATION))
        return gb_fail(error, GB_ERROR_ARGUMENT, "flc: %d levels: at most %d",
                       parameters->levels, GB_FLC_MAX_LEVELS);
    flc_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc: out of memory");
    s->scene = setup->scene;
    s->visibility.glsl = unshadowed_shader;
    if (visibility)
        s->visibility = *visibility;
    s->tiling = parameters->tiling;
    gb_flc_scene_levels(setup->scene, parameters, &s->levels);
    s->epsilon = parameters->epsilon > 0.0f ? parameters->epsilon
                                                : default_epsilon(&s->levels);
    gb_result result = build_programs(s, error);
    if (result == GB_OK)
        result = make_buffers(s, FLC_SEED, error);
    if (result != GB_OK) {
        gb_flc_destroy(s);
        return result;
    }
    prepare_targets(s, setup->width, setup->height);
    *state = s;
    return GB_OK;
}

static void set_int(GLuint program, const char *name, int value)
{
    glProgramUniform1i(program, glGetUniformLocation(program, name), value);
}

static void set_float(GLuint program, const char *name, float value)
{
    glProgramUniform1f(program, glGetUniformLocation(program, name), value);
}

static void set_size(GLuint program, const char *name, int x, int y)
{
    glProgramUniform2i(program, glGetUniformLocation(program, name), x, y);
}

static void set_levels(GLuint program, const gb_flc_levels *levels)
{
    set_int(program, "N", levels->N);
    glProgramUniform1fv(program, glGetUniformLocation(program, "D"), levels->N + 2, levels->D);
}

static void set_tiles(GLuint program, const flc_state *s)
{
    set_size(program, "full_size", s->width, s->height);
    set_size(program, "tile_size", s->tile_width, s->tile_height);
    set_int(program, "scale", 1 << s->tiling);
}

/* Pass 1's uniforms and bindings in program (the compute pass or the
 * tessellation's geometry shader). */
static void prepare_generation(flc_state *s, GLuint program, const gb_indirect_frame *frame)
{
    uint32_t u_rand = gb_flc_hash(frame->frame_index * 0x9e3779b9u ^ gb_flc_hash(FLC_SEED));
    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "u_rand"), u_rand);
    glProgramUniform1ui(program, glGetUniformLocation(program, "tiles"),
                        1u << (2 * s->tiling));
    glProgramUniform1fv(program, glGetUniformLocation(program, "S_bar"), s->levels.N + 1,
                        s->levels.S_bar);
    glProgramUniform1fv(program, glGetUniformLocation(program, "S"), s->levels.N + 1,
                        s->levels.S);
    set_int(program, "keep_all", s->levels.keep_all);
    set_levels(program, &s->levels);
    set_int(program, "point_count", (int)frame->shadows->point_count);
    set_int(program, "plane_count", (int)frame->shadows->plane_count);
    set_float(program, "cube_texel", 2.0f / (float)frame->shadows->cube_size);
    set_int(program, "shadows", frame->shadows->drawn);   /* not drawn with --no-shadows */
    gb_shadow_maps_bind(frame->shadows);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_TRIANGLES, s->triangle_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_ALBEDOS, s->albedo_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_PATCHES, s->patch_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_COMMANDS, s->command_buffer);
    glProgramUniform1ui(program, glGetUniformLocation(program, "patch_capacity"),
                        s->patch_capacity);
}

/* Pass 1 over the VPL triangles [first, first + count), in dispatches of at
 * most the 65 535 groups every GL 4.3 gives (4.2 M triangles a dispatch). */
static void generate_vpls(flc_state *s, uint32_t first, uint32_t count)
{
    const uint32_t most = 65535u * GENERATE_GROUP;
    GLuint program = s->generate_program;
    glUseProgram(program);
    for (uint32_t done = 0; done < count; done += most) {
        uint32_t n = count - done < most ? count - done : most;
        glProgramUniform1ui(program, glGetUniformLocation(program, "first"), first + done);
        glProgramUniform1ui(program, glGetUniformLocation(program, "triangle_count"), n);
        glDispatchCompute((n + GENERATE_GROUP - 1) / GENERATE_GROUP, 1, 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

static void set_splat_uniforms(const flc_state *s, const gb_indirect_frame *frame)
{
    GLuint program = s->splat_program;
    const gb_view *view = frame->view;
    gb_mat4 view_projection = gb_mat4_multiply(frame->projection, frame->view_matrix);
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view_projection"), 1,
                              GL_FALSE, view_projection.m);
    gb_gbuffer_set_view_of(program, view, frame->width, frame->height);
    set_size(program, "splat_size", s->tile_width << s->tiling, s->tile_height << s->tiling);
    set_tiles(program, s);
    set_levels(program, &s->levels);
    glProgramUniform1fv(program, glGetUniformLocation(program, "S"), s->levels.N + 1,
                        s->levels.S);
    set_float(program, "epsilon", s->epsilon);
    set_float(program, "tile_weight", (float)(1 << (2 * s->tiling)));
    set_int(program, "vpl_count", (int)(s->triangle_count + s->divergent_capacity));
}

/* Pass 2's target, uniforms and bindings. */
static void prepare_splatting(flc_state *s, const gb_indirect_frame *frame)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat.framebuffer);
    glViewport(0, 0, s->tile_width << s->tiling, s->tile_height << s->tiling);
    glUseProgram(s->splat_program);
    set_splat_uniforms(s, frame);
    if (s->visibility.bind)
        s->visibility.bind(s->visibility.context, s->splat_program);
    gb_gbuffer_bind(frame->gbuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glBindVertexArray(s->empty_vertex_array);
}

/* Pass 2 of the VPLs of [first, first + count). */
static void splat_vpls(flc_state *s, uint32_t first, uint32_t count)
{
    glUseProgram(s->splat_program);
    glBindVertexArray(s->empty_vertex_array);
    glDrawArrays(GL_POINTS, (GLint)first, (GLsizei)count);
}

/* The regular pipeline's VPL generation, over every regular triangle. */
static void generate_regular(flc_state *s, const gb_indirect_frame *frame)
{
    if (!s->regular_count)
        return;
    prepare_generation(s, s->generate_program, frame);
    generate_vpls(s, 0, s->regular_count);
}

/* The regular pipeline's splatting, of part's share of its VPLs: the
 * ranges of the parts follow each other, so that blending, in primitive
 * order, adds them as one draw would. */
static void splat_regular(flc_state *s, const gb_indirect_frame *frame)
{
    uint64_t R = s->regular_count;
    uint32_t first = (uint32_t)(R * (uint64_t)frame->part / (uint64_t)frame->parts);
    uint32_t end = (uint32_t)(R * (uint64_t)(frame->part + 1) / (uint64_t)frame->parts);
    if (first == end)
        return;
    prepare_splatting(s, frame);
    splat_vpls(s, first, end - first);
}

/* The divergent pipeline: the compute pass appends the divergent triangles'
 * cells to the divergent buffer and counts them in the first indirect draw,
 * which tessellates them and appends their VPLs after the regular ones,
 * counting them in the second indirect draw, the splatting. No CPU wait. */
static void run_divergent(flc_state *s, const gb_indirect_frame *frame)
{
    uint32_t divergent = s->triangle_count - s->regular_count;
    if (!divergent)
        return;
    const uint32_t commands[8] = {0, 1, 0, 0, 0, 1, s->triangle_count, 0};
    glNamedBufferSubData(s->command_buffer, 0, sizeof commands, commands);
    prepare_generation(s, s->generate_program, frame);
    generate_vpls(s, s->regular_count, divergent);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    GLuint program = s->tess_program;
    glUseProgram(program);
    prepare_generation(s, program, frame);
    glProgramUniform1ui(program, glGetUniformLocation(program, "divergent_first"),
                        s->triangle_count);
    glProgramUniform1ui(program, glGetUniformLocation(program, "divergent_capacity"),
                        s->divergent_capacity);
    glBindVertexArray(s->empty_vertex_array);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->command_buffer);
    glPatchParameteri(GL_PATCH_VERTICES, 3);
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArraysIndirect(GL_PATCHES, (const void *)0);
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    prepare_splatting(s, frame);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->command_buffer);
    glDrawArraysIndirect(GL_POINTS, (const void *)(4 * sizeof(uint32_t)));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

/* The wall-clock ms since *start, after glFinish when measuring; restarts *start. */
static double lap(const flc_state *s, double *start)
{
    if (!s->measuring)
        return 0.0;
    glFinish();
    double now = gb_seconds(), ms = 1e3 * (now - *start);
    *start = now;
    return ms;
}

/* Pass 3. */
static void resolve(flc_state *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulated.framebuffer);
    glViewport(0, 0, s->width, s->height);
    glUseProgram(s->resolve_program);
    set_tiles(s->resolve_program, s);
    glBindTextureUnit(UNIT_SPLAT, s->splat.color);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

static void bind_output(const flc_state *s, GLuint target)
{
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(0, 0, s->width, s->height);
}

/* Pass 4, into the framebuffer that was bound. */
static void composite(flc_state *s, GLuint target)
{
    bind_output(s, target);
    glUseProgram(s->composite_program);
    set_float(s->composite_program, "inverse_count", 1.0f / (float)s->samples);
    glBindTextureUnit(UNIT_ACCUMULATED, s->accumulated.color);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

/* Starts the accumulation again when the view moved. */
static void restart_if_moved(flc_state *s, const gb_indirect_frame *frame)
{
    if (s->samples && !memcmp(&s->last_view, frame->view_matrix, sizeof s->last_view) &&
        !memcmp(&s->last_projection, frame->projection, sizeof s->last_projection))
        return;
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->accumulated.framebuffer, GL_COLOR, 0, zero);
    s->samples = 0;
    s->last_view = *frame->view_matrix;
    s->last_projection = *frame->projection;
}

/* Part 0: the targets, the accumulation restarted if the view moved, the
 * splat target cleared and the regular VPLs generated. */
static void begin_sample(flc_state *s, const gb_indirect_frame *frame)
{
    prepare_targets(s, frame->width, frame->height);
    restart_if_moved(s, frame);
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->splat.framebuffer, GL_COLOR, 0, zero);
    generate_regular(s, frame);
}

/* The last part: the divergent pipeline, then the sample into the
 * accumulation and the mean onto target; the times of a sample when
 * measuring (start: the lap's). */
static void end_sample(flc_state *s, const gb_indirect_frame *frame, GLuint target,
                       double *start)
{
    run_divergent(s, frame);
    double divergent = lap(s, start);
    resolve(s);
    ++s->samples;
    composite(s, target);
    if (!s->measuring)
        return;
    s->times.divergent_ms += divergent;
    s->times.resolve_ms += lap(s, start);
    s->times.frames++;
    uint32_t made = 0;
    if (s->triangle_count > s->regular_count)
        glGetNamedBufferSubData(s->command_buffer, 4 * sizeof(uint32_t), sizeof made, &made);
    s->times.divergent_vpls += made;
}

/* One image is one sample, cut by VPLs: part k of n splats the regular
 * VPLs [k R / n, (k + 1) R / n); part 0 begins the sample, the last part
 * ends it. The scissor test is off for all of it: the splat target is the
 * whole view, and so is the composite, at the last part, when every band of
 * the output has its direct light. */
int gb_flc_draw(void *state, const gb_indirect_frame *frame)
{
    flc_state *s = state;
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    double start = 0.0;
    lap(s, &start);
    double cpu_start = s->measuring ? 1e3 * gb_cpu_seconds() : 0.0;
    if (frame->part == 0)
        begin_sample(s, frame);
    splat_regular(s, frame);
    s->times.regular_ms += lap(s, &start);
    int last = frame->part + 1 >= frame->parts;
    if (last)
        end_sample(s, frame, (GLuint)target, &start);
    else
        bind_output(s, (GLuint)target);
    if (s->measuring)
        s->times.cpu_ms += 1e3 * gb_cpu_seconds() - cpu_start;
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
    /* The samples once this image's is in: refine until the cap. */
    return s->samples + !last < GB_FLC_CONVERGED_SAMPLES ? GB_IMAGE_REFINABLE : GB_IMAGE_FINAL;
}

void gb_flc_measure(void *state, int on)
{
    flc_state *s = state;
    if (s)
        s->measuring = on;
}

void gb_flc_times(const void *state, gb_flc_pass_times *times)
{
    const flc_state *s = state;
    memset(times, 0, sizeof *times);
    if (s)
        *times = s->times;
}

static gb_result flc_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    return gb_flc_create(setup, NULL, state, error);
}

const gb_indirect_method gb_flc_method = {
    .create = flc_create,
    .draw = gb_flc_draw,
    .destroy = gb_flc_destroy,
};
