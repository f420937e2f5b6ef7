#include "shadow_maps.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

#include "area_lights.h"
#include "light_frame.h"
#include "mat4.h"
#include "scene_triangles.h"
#include "shadow_cascades.h"

enum { POINT_FLOATS = 12, PLANE_FLOATS = 32, CASCADE_FLOATS = 20 };

static const char cube_vertex_shader[] =
#include "runtime/shadow_maps_cube.vert.glsl.inc"
    ;

static const char cube_fragment_shader[] =
#include "runtime/shadow_maps_cube.frag.glsl.inc"
    ;

static const char plane_vertex_shader[] =
#include "runtime/shadow_maps_plane.vert.glsl.inc"
    ;

static const char plane_fragment_shader[] =
#include "runtime/shadow_maps_plane.frag.glsl.inc"
    ;

/* The faces of a cube map as OpenGL samples them: forward and up of each. */
static const float cube_faces[6][2][3] = {
    {{1, 0, 0}, {0, -1, 0}}, {{-1, 0, 0}, {0, -1, 0}}, {{0, 1, 0}, {0, 0, 1}},
    {{0, -1, 0}, {0, 0, -1}}, {{0, 0, 1}, {0, -1, 0}}, {{0, 0, -1}, {0, -1, 0}},
};

static float scene_diagonal(const gb_scene *scene)
{
    return gb_vec3_length(gb_vec3_sub(gb_scene_bounds_corner(scene, 7), gb_scene_bounds_corner(scene, 0)));
}

/* The distance from p to the farthest corner of the bounds, a little more. */
static float range_from(const gb_scene *scene, gb_vec3 p)
{
    float range = 0.0f;
    for (int k = 0; k < 8; ++k)
        range = fmaxf(range, gb_vec3_length(gb_vec3_sub(gb_scene_bounds_corner(scene, k), p)));
    return 1.01f * range + 1e-3f * scene_diagonal(scene) + 1e-20f;
}

static void put3(float *out, const float *v)
{
    out[0] = v[0], out[1] = v[1], out[2] = v[2];
}

/* normal: an area light's emitter's, NULL for a point light; area: the
 * emitter's (area_lights.h). */
static void put_point(const gb_scene *scene, const float position[3], const float intensity[3],
                      const float *normal, float area, float *out)
{
    put3(out, position);
    out[3] = range_from(scene, gb_vec3_load(position));
    put3(out + 4, intensity);
    out[7] = normal ? 1.0f : 0.0f;
    if (normal)
        put3(out + 8, normal);
    out[11] = area / 3.14159265358979f;
}

/* Orthographic over the scene's bounds seen along direction. */
static gb_mat4 directional_matrix(const gb_scene *scene, gb_vec3 direction, int size,
                                  float *texel)
{
    float diagonal = scene_diagonal(scene);
    gb_vec3 centre =
        gb_vec3_scale(gb_vec3_add(gb_scene_bounds_corner(scene, 0), gb_scene_bounds_corner(scene, 7)), 0.5f);
    gb_vec3 forward = gb_vec3_normalize(direction);
    gb_light_frame f = gb_light_frame_make(gb_vec3_sub(centre, gb_vec3_scale(forward, diagonal)),
                               forward, gb_light_up_hint(forward));
    gb_mat4 view = gb_light_frame_view(&f);
    gb_vec3 low = {INFINITY, INFINITY, INFINITY}, high = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 8; ++k) {
        gb_vec3 p = gb_mat4_transform_point(&view, gb_scene_bounds_corner(scene, k));
        low = gb_vec3_make(fminf(low.x, p.x), fminf(low.y, p.y), fminf(low.z, p.z));
        high = gb_vec3_make(fmaxf(high.x, p.x), fmaxf(high.y, p.y), fmaxf(high.z, p.z));
    }
    float margin = 1e-3f * diagonal + 1e-20f;
    gb_mat4 projection = gb_mat4_orthographic(low.x - margin, high.x + margin, low.y - margin,
                                              high.y + margin, -high.z - margin,
                                              -low.z + margin);
    *texel = fmaxf(high.x - low.x, high.y - low.y) / (float)size;
    return gb_mat4_multiply(&projection, &view);
}

/* Perspective over the spot's cone. */
static gb_mat4 spot_matrix(const gb_scene *scene, const gb_light *light, int size, float *texel)
{
    gb_vec3 position = gb_vec3_load(light->position);
    gb_vec3 forward = gb_vec3_normalize(gb_vec3_load(light->direction));
    gb_light_frame f = gb_light_frame_make(position, forward, gb_light_up_hint(forward));
    gb_mat4 view = gb_light_frame_view(&f);
    float fov = fminf(2.0f * fmaxf(light->cone_angle, light->falloff_angle) + 2.0f, 170.0f);
    float range = range_from(scene, position);
    gb_mat4 projection = gb_mat4_perspective(fov, 1.0f, 1e-4f * range, range);
    *texel = 2.0f * tanf(0.5f * fov * 3.14159265358979f / 180.0f) / (float)size;
    return gb_mat4_multiply(&projection, &view);
}

/* cascade: the light's first cascade, or -1. */
static void put_plane(const gb_scene *scene, const gb_light *light, int size, int cascade,
                      float *out)
{
    float texel = 0.0f;
    gb_mat4 matrix = light->type == GB_LIGHT_DIRECTIONAL
                         ? directional_matrix(scene, gb_vec3_load(light->direction), size, &texel)
                         : spot_matrix(scene, light, size, &texel);
    memcpy(out, matrix.m, sizeof matrix.m);
    put3(out + 16, light->position);
    out[19] = light->type == GB_LIGHT_DIRECTIONAL ? 1.0f : 0.0f;
    gb_vec3 direction = gb_vec3_normalize(gb_vec3_load(light->direction));
    out[20] = direction.x, out[21] = direction.y, out[22] = direction.z;
    out[23] = texel;
    put3(out + 24, light->intensity);
    out[28] = light->cone_angle;
    out[29] = light->falloff_angle;
    out[30] = (float)cascade;
}

/* Whether light i of the scene gets cascades: a directional light of the
 * scene's own, when the options allow them. */
static int has_cascades(const gb_scene *scene, const gb_shadow_options *options, uint32_t i)
{
    return !(options && options->cascade_size < 0) &&
           scene->lights[i].type == GB_LIGHT_DIRECTIONAL &&
           i < gb_scene_own_light_count(scene);
}

/* How far an area light's emitter sits off its triangle, toward its front:
 * 1e-5 of the scene's diagonal, and at least 8 float ulps of its coordinates
 * (2^-20 of their magnitude). Without that floor the lift rounds away far
 * from the origin and the emitter's own triangle shadows the room: the
 * Cornell box moved by 1e6 mm gave relative MSE 0.0075 against the unmoved
 * box (with the floor: 1.1e-5). */
static float emitter_lift(const gb_scene *scene, const float position[3])
{
    float magnitude = fmaxf(fabsf(position[0]), fmaxf(fabsf(position[1]), fabsf(position[2])));
    return fmaxf(1e-5f * scene_diagonal(scene), 0x1p-20f * magnitude);
}

static gb_result fill_lights(const gb_scene *scene, const gb_shadow_options *options,
                             gb_shadow_maps *maps, gb_error *error)
{
    gb_point_emitter *emitters = NULL;
    uint32_t emitter_count = 0;
    int samples = options && options->area_samples ? options->area_samples
                                                   : GB_DEFAULT_AREA_SAMPLES;
    gb_result result = gb_area_light_sample(scene, samples > 0 ? (uint32_t)samples : 0,
                                            &emitters, &emitter_count, error);
    if (result != GB_OK)
        return result;
    uint32_t points = emitter_count, planes = 0;
    for (uint32_t i = 0; i < scene->light_count; ++i)
        scene->lights[i].type == GB_LIGHT_POINT ? ++points : ++planes;
    maps->point_data = calloc((size_t)points * POINT_FLOATS + 1, sizeof(float));
    maps->plane_data = calloc((size_t)planes * PLANE_FLOATS + 1, sizeof(float));
    maps->cascade_data =
        calloc((size_t)planes * GB_SHADOW_CASCADES * CASCADE_FLOATS + 1, sizeof(float));
    if (!maps->point_data || !maps->plane_data || !maps->cascade_data) {
        free(emitters);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "shadow maps: out of memory");
    }
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        const gb_light *light = &scene->lights[i];
        if (light->type == GB_LIGHT_POINT)
            put_point(scene, light->position, light->intensity, NULL, 0.0f,
                      &maps->point_data[POINT_FLOATS * maps->point_count++]);
        else
            put_plane(scene, light, maps->plane_size,
                      has_cascades(scene, options, i) ? (int)maps->cascaded_count++ : -1,
                      &maps->plane_data[PLANE_FLOATS * maps->plane_count++]);
    }
    for (uint32_t i = 0; i < emitter_count; ++i) {
        const gb_point_emitter *e = &emitters[i];
        float p[3], lift = emitter_lift(scene, e->position);
        for (int c = 0; c < 3; ++c)
            p[c] = e->position[c] + lift * e->normal[c];
        put_point(scene, p, e->intensity, e->normal, e->area,
                  &maps->point_data[POINT_FLOATS * maps->point_count++]);
    }
    free(emitters);
    return GB_OK;
}

static GLuint make_buffer(const float *data, size_t floats)
{
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    /* an empty list still gets a (zeroed) buffer to bind */
    glNamedBufferStorage(buffer, (GLsizeiptr)((floats ? floats : 4) * sizeof(float)),
                         floats ? data : NULL, 0);
    return buffer;
}

static GLuint make_depth_array(GLenum target, int size, int layers, GLenum compare)
{
    GLuint texture;
    glCreateTextures(target, 1, &texture);
    glTextureStorage3D(texture, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(texture, GL_TEXTURE_COMPARE_FUNC, compare);
    return texture;
}

static gb_result make_gpu_objects(gb_shadow_maps *maps, gb_error *error)
{
    maps->point_buffer = make_buffer(maps->point_data, (size_t)maps->point_count * POINT_FLOATS);
    maps->plane_buffer = make_buffer(maps->plane_data, (size_t)maps->plane_count * PLANE_FLOATS);
    /* An empty light list still gets one layer: samplers need a texture. */
    int cubes = maps->point_count ? (int)maps->point_count : 1;
    int planes = maps->plane_count ? (int)maps->plane_count : 1;
    maps->cube_array = make_depth_array(GL_TEXTURE_CUBE_MAP_ARRAY, maps->cube_size, 6 * cubes,
                                        GL_LEQUAL);
    maps->plane_array = make_depth_array(GL_TEXTURE_2D_ARRAY, maps->plane_size, planes,
                                         GL_GEQUAL);
    int cascades = GB_SHADOW_CASCADES * (maps->cascaded_count ? (int)maps->cascaded_count : 1);
    maps->cascade_array = make_depth_array(GL_TEXTURE_2D_ARRAY,
                                           maps->cascaded_count ? maps->cascade_size : 1,
                                           cascades, GL_GEQUAL);
    glCreateBuffers(1, &maps->cascade_buffer);
    glNamedBufferStorage(maps->cascade_buffer,
                         (GLsizeiptr)(cascades * CASCADE_FLOATS * sizeof(float)), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    glCreateFramebuffers(1, &maps->framebuffer);
    glNamedFramebufferDrawBuffer(maps->framebuffer, GL_NONE);
    glNamedFramebufferReadBuffer(maps->framebuffer, GL_NONE);
    gb_result result = gb_gl_program("cube shadow map", cube_vertex_shader,
                                     cube_fragment_shader, &maps->cube_program, error);
    if (result == GB_OK)
        result = gb_gl_program("2-D shadow map", plane_vertex_shader, plane_fragment_shader,
                               &maps->plane_program, error);
    return result;
}

gb_result gb_shadow_maps_create(const gb_scene *scene, const gb_shadow_options *options,
                                gb_shadow_maps *maps, gb_error *error)
{
    memset(maps, 0, sizeof *maps);
    int size = options && options->size > 0 ? options->size : GB_DEFAULT_SHADOW_SIZE;
    maps->plane_size = size;
    maps->cube_size = size / 2 > 16 ? size / 2 : 16;
    maps->cascade_size = options && options->cascade_size > 0 ? options->cascade_size
                                                               : GB_DEFAULT_CASCADE_SIZE;
    gb_result result = fill_lights(scene, options, maps, error);
    if (result == GB_OK)
        result = make_gpu_objects(maps, error);
    if (result != GB_OK)
        gb_shadow_maps_destroy(maps);
    return result;
}

static void set_matrix(GLuint program, const char *name, const gb_mat4 *m)
{
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, name), 1, GL_FALSE, m->m);
}

static void draw_cube(gb_shadow_maps *maps, const gb_gpu_scene *scene, uint32_t light)
{
    const float *data = &maps->point_data[POINT_FLOATS * light];
    gb_vec3 position = gb_vec3_load(data);
    float range = data[3];
    gb_mat4 projection = gb_mat4_perspective(90.0f, 1.0f, 1e-4f * range, range);
    GLuint program = maps->cube_program;
    glProgramUniform3f(program, glGetUniformLocation(program, "light_position"), position.x,
                       position.y, position.z);
    glProgramUniform1f(program, glGetUniformLocation(program, "range"), range);
    for (int face = 0; face < 6; ++face) {
        gb_light_frame f = gb_light_frame_make(position, gb_vec3_load(cube_faces[face][0]),
                                   gb_vec3_load(cube_faces[face][1]));
        gb_mat4 view = gb_light_frame_view(&f);
        gb_mat4 view_projection = gb_mat4_multiply(&projection, &view);
        set_matrix(program, "view_projection", &view_projection);
        glNamedFramebufferTextureLayer(maps->framebuffer, GL_DEPTH_ATTACHMENT,
                                       maps->cube_array, 0, (GLint)(6 * light + face));
        static const float far = 1.0f;
        glClearNamedFramebufferfv(maps->framebuffer, GL_DEPTH, 0, &far);
        gb_gpu_scene_draw(scene, 0);
    }
}

/* Draws the scene through matrix (16 floats) into layer of array. */
static void draw_plane(gb_shadow_maps *maps, const gb_gpu_scene *scene, const float *matrix,
                       GLuint array, uint32_t layer)
{
    gb_mat4 m;
    memcpy(m.m, matrix, sizeof m.m);
    set_matrix(maps->plane_program, "view_projection", &m);
    glNamedFramebufferTextureLayer(maps->framebuffer, GL_DEPTH_ATTACHMENT, array, 0,
                                   (GLint)layer);
    static const float far = 0.0f;   /* reversed depth */
    glClearNamedFramebufferfv(maps->framebuffer, GL_DEPTH, 0, &far);
    gb_gpu_scene_draw(scene, 0);
}

/* The state every 2-D map is drawn in, at size x size. */
static void begin_planes(const gb_shadow_maps *maps, int size)
{
    glBindFramebuffer(GL_FRAMEBUFFER, maps->framebuffer);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glViewport(0, 0, size, size);
    glDepthFunc(GL_GREATER);
    glUseProgram(maps->plane_program);
}

static void end_maps(void)
{
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void gb_shadow_maps_draw(gb_shadow_maps *maps, const gb_gpu_scene *scene)
{
    if (maps->drawn)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, maps->framebuffer);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glViewport(0, 0, maps->cube_size, maps->cube_size);
    glDepthFunc(GL_LESS);
    glUseProgram(maps->cube_program);
    for (uint32_t i = 0; i < maps->point_count; ++i)
        draw_cube(maps, scene, i);
    begin_planes(maps, maps->plane_size);
    for (uint32_t i = 0; i < maps->plane_count; ++i)
        draw_plane(maps, scene, &maps->plane_data[PLANE_FLOATS * i], maps->plane_array, i);
    end_maps();
    maps->drawn = 1;
}

static int same_view(const gb_shadow_maps *maps, const gb_view *view, int width, int height)
{
    return maps->fitted_width == width && maps->fitted_height == height &&
           !memcmp(&maps->fitted_view, view, sizeof *view);
}

void gb_shadow_maps_fit_view(gb_shadow_maps *maps, const gb_scene *scene,
                             const gb_gpu_scene *gpu_scene, const gb_view *view, int width,
                             int height)
{
    if (!maps->cascaded_count || same_view(maps, view, width, height))
        return;
    float splits[GB_SHADOW_CASCADES + 1];
    gb_cascade_splits(view->near, gb_cascade_view_far(view, scene), GB_SHADOW_CASCADES,
                      GB_CASCADE_LOG_SHARE, splits);
    for (uint32_t i = 0; i < maps->plane_count; ++i) {
        const float *plane = &maps->plane_data[PLANE_FLOATS * i];
        if (plane[30] < 0.0f)
            continue;
        for (int c = 0; c < GB_SHADOW_CASCADES; ++c) {
            gb_cascade k = gb_cascade_fit(view, (float)width / (float)height, splits[c],
                                          splits[c + 1], gb_vec3_load(plane + 20), scene,
                                          maps->cascade_size);
            float *out = &maps->cascade_data[CASCADE_FLOATS *
                                             ((size_t)plane[30] * GB_SHADOW_CASCADES + c)];
            memcpy(out, k.world_to_clip.m, sizeof k.world_to_clip.m);
            out[16] = k.far, out[17] = k.texel, out[18] = 1.0f / k.depth_range;
        }
    }
    uint32_t layers = maps->cascaded_count * GB_SHADOW_CASCADES;
    glNamedBufferSubData(maps->cascade_buffer, 0,
                         (GLsizeiptr)(layers * CASCADE_FLOATS * sizeof(float)),
                         maps->cascade_data);
    begin_planes(maps, maps->cascade_size);
    for (uint32_t layer = 0; layer < layers; ++layer)
        draw_plane(maps, gpu_scene, &maps->cascade_data[CASCADE_FLOATS * layer],
                   maps->cascade_array, layer);
    end_maps();
    maps->fitted_view = *view;
    maps->fitted_width = width, maps->fitted_height = height;
}

void gb_shadow_maps_bind(const gb_shadow_maps *maps)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GB_SSBO_POINT_LIGHTS, maps->point_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GB_SSBO_PLANE_LIGHTS, maps->plane_buffer);
    glBindTextureUnit(GB_UNIT_SHADOW_CUBES, maps->cube_array);
    glBindTextureUnit(GB_UNIT_SHADOW_PLANES, maps->plane_array);
}

void gb_shadow_maps_bind_cascades(const gb_shadow_maps *maps)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GB_SSBO_SHADOW_CASCADES, maps->cascade_buffer);
    glBindTextureUnit(GB_UNIT_SHADOW_CASCADES, maps->cascade_array);
}

void gb_shadow_maps_destroy(gb_shadow_maps *maps)
{
    GLuint buffers[] = {maps->point_buffer, maps->plane_buffer, maps->cascade_buffer};
    GLuint textures[] = {maps->cube_array, maps->plane_array, maps->cascade_array};
    for (int i = 0; i < 3; ++i) {
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
        if (textures[i])
            glDeleteTextures(1, &textures[i]);
    }
    if (maps->framebuffer)
        glDeleteFramebuffers(1, &maps->framebuffer);
    if (maps->cube_program)
        glDeleteProgram(maps->cube_program);
    if (maps->plane_program)
        glDeleteProgram(maps->plane_program);
    free(maps->point_data);
    free(maps->plane_data);
    free(maps->cascade_data);
    memset(maps, 0, sizeof *maps);
}
