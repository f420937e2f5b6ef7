/* scene_builder.h — small scenes built in memory for the reference renderer's
 * tests: quads, axis-aligned boxes seen from inside or outside, the Cornell
 * box from its published measurements (scenes/cornell/cornell.obj), lights
 * and cameras. Every array is malloc'ed so gb_scene_free releases it; call
 * gb_scene_finish (through scene_done) once the scene is complete.
 */
#ifndef GB_SCENE_BUILDER_H
#define GB_SCENE_BUILDER_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "vec3.h"

static inline void *builder_grow(void *array, size_t count, size_t size)
{
    void *grown = realloc(array, count * size);
    if (!grown) {
        fprintf(stderr, "scene_builder: out of memory\n");
        exit(2);
    }
    return grown;
}

static inline uint32_t add_material(gb_scene *scene, const float Kd[3], const float Ks[3], float Ns,
                                    const float Ke[3])
{
    scene->materials = builder_grow(scene->materials, scene->material_count + 1,
                                    sizeof *scene->materials);
    gb_material *m = &scene->materials[scene->material_count];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "material%u", scene->material_count);
    for (int k = 0; k < 3; ++k) {
        m->Kd[k] = Kd ? Kd[k] : 0.0f;
        m->Ks[k] = Ks ? Ks[k] : 0.0f;
        m->Ke[k] = Ke ? Ke[k] : 0.0f;
    }
    m->Ns = Ns;
    return scene->material_count++;
}

static inline uint32_t add_grey(gb_scene *scene, float albedo, float emission)
{
    const float Kd[3] = {albedo, albedo, albedo}, Ke[3] = {emission, emission, emission};
    return add_material(scene, Kd, NULL, 0.0f, Ke);
}

static inline void add_triangle(gb_scene *scene, uint32_t a, uint32_t b, uint32_t c,
                                uint32_t material)
{
    uint32_t t = scene->triangle_count++;
    scene->indices = builder_grow(scene->indices, 3 * (size_t)scene->triangle_count,
                                  sizeof *scene->indices);
    scene->triangle_material = builder_grow(scene->triangle_material, scene->triangle_count,
                                            sizeof *scene->triangle_material);
    scene->indices[3 * t] = a;
    scene->indices[3 * t + 1] = b;
    scene->indices[3 * t + 2] = c;
    scene->triangle_material[t] = material;
}

/* Quad p0 p1 p2 p3 (in order around it); its front is the side of
 * cross(p1 - p0, p2 - p0). */
static inline void add_quad(gb_scene *scene, const float p[4][3], uint32_t material)
{
    uint32_t first = scene->vertex_count;
    scene->vertex_count += 4;
    scene->positions = builder_grow(scene->positions, 3 * (size_t)scene->vertex_count,
                                    sizeof *scene->positions);
    memcpy(&scene->positions[3 * (size_t)first], p, 12 * sizeof(float));
    add_triangle(scene, first, first + 1, first + 2, material);
    add_triangle(scene, first, first + 2, first + 3, material);
}

/* The same quad with its front toward `toward` (a point). */
static inline void add_quad_facing(gb_scene *scene, const float p[4][3], const float toward[3],
                                   uint32_t material)
{
    gb_vec3 o = gb_vec3_load(p[0]), e1 = gb_vec3_sub(gb_vec3_load(p[1]), o),
            e2 = gb_vec3_sub(gb_vec3_load(p[2]), o);
    if (gb_vec3_dot(gb_vec3_cross(e1, e2), gb_vec3_sub(gb_vec3_load(toward), o)) >= 0.0f) {
        add_quad(scene, p, material);
        return;
    }
    const float reversed[4][3] = {{p[3][0], p[3][1], p[3][2]}, {p[2][0], p[2][1], p[2][2]},
                                  {p[1][0], p[1][1], p[1][2]}, {p[0][0], p[0][1], p[0][2]}};
    add_quad(scene, reversed, material);
}

/* The six faces of the box lo..hi, fronts inward (a room) or outward. */
static inline void add_box(gb_scene *scene, const float lo[3], const float hi[3], int inward,
                           uint32_t material)
{
    float centre[3], outside[3];
    for (int k = 0; k < 3; ++k)
        centre[k] = 0.5f * (lo[k] + hi[k]);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            float p[4][3];
            for (int i = 0; i < 4; ++i) {
                p[i][axis] = side ? hi[axis] : lo[axis];
                p[i][u] = (i == 1 || i == 2) ? hi[u] : lo[u];
                p[i][v] = (i >= 2) ? hi[v] : lo[v];
            }
            memcpy(outside, centre, sizeof outside);
            outside[axis] = side ? hi[axis] + 1.0f : lo[axis] - 1.0f;
            add_quad_facing(scene, p, inward ? centre : outside, material);
        }
}

static inline void add_point_light(gb_scene *scene, gb_light_type type, const float position[3],
                                   const float direction[3], const float intensity[3])
{
    scene->lights = builder_grow(scene->lights, scene->light_count + 1, sizeof *scene->lights);
    gb_light *light = &scene->lights[scene->light_count++];
    memset(light, 0, sizeof *light);
    light->type = type;
    for (int k = 0; k < 3; ++k) {
        light->position[k] = position ? position[k] : 0.0f;
        light->direction[k] = direction ? direction[k] : 0.0f;
        light->intensity[k] = intensity[k];
    }
}

/* A camera with up +y (or +z when looking along y). */
static inline void set_camera(gb_scene *scene, const float position[3], const float target[3],
                              float fov_y, int width, int height)
{
    free(scene->cameras);
    scene->cameras = builder_grow(NULL, 1, sizeof *scene->cameras);
    scene->camera_count = 1;
    gb_camera *camera = &scene->cameras[0];
    memset(camera, 0, sizeof *camera);
    memcpy(camera->position, position, sizeof camera->position);
    memcpy(camera->target, target, sizeof camera->target);
    float dx = target[0] - position[0], dz = target[2] - position[2];
    camera->up[dx == 0.0f && dz == 0.0f ? 2 : 1] = 1.0f;
    camera->fov_y = fov_y;
    camera->width = width;
    camera->height = height;
}

static inline void scene_done(gb_scene *scene)
{
    gb_error error;
    if (gb_scene_finish(scene, &error) != GB_OK) {
        fprintf(stderr, "scene_builder: %s\n", error.message);
        exit(2);
    }
}

/* The Cornell box of scenes/cornell (millimetres, light 0.5 mm below the
 * ceiling), its published camera at width x height. */
static inline void build_cornell_box(gb_scene *scene, int width, int height)
{
    static const float quads[16][4][3] = {
        {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}},
        {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}},
        {{343, 548.3f, 227}, {343, 548.3f, 332}, {213, 548.3f, 332}, {213, 548.3f, 227}},
        {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}},
        {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}},
        {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}},
        {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
        {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
        {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
        {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
        {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}},
        {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
        {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
        {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
        {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
        {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}},
    };
    static const float white[3] = {0.725f, 0.71f, 0.68f}, red[3] = {0.63f, 0.065f, 0.05f},
                       green[3] = {0.14f, 0.45f, 0.091f}, light_kd[3] = {0.78f, 0.78f, 0.78f},
                       light_ke[3] = {17, 12, 4};
    memset(scene, 0, sizeof *scene);
    uint32_t m_white = add_material(scene, white, NULL, 0, NULL);
    uint32_t m_red = add_material(scene, red, NULL, 0, NULL);
    uint32_t m_green = add_material(scene, green, NULL, 0, NULL);
    uint32_t m_light = add_material(scene, light_kd, NULL, 0, light_ke);
    const uint32_t material[16] = {m_white, m_white, m_light, m_white, m_green, m_red,
                                   m_white, m_white, m_white, m_white, m_white,
                                   m_white, m_white, m_white, m_white, m_white};
    for (int i = 0; i < 16; ++i)
        add_quad(scene, quads[i], material[i]);
    const float eye[3] = {278, 273, -800}, target[3] = {278, 273, 0};
    set_camera(scene, eye, target, 39.3077f, width, height);
    scene_done(scene);
}

#endif
