/* implicit_steps.c — Table 1 of Dong et al. 2007 on this machine: ms per
 * step of implicit visibility (runtime/implicit/implicit.h) run on the CPU as the
 * paper runs it, every step every frame: UpdateElements, CreateHierarchical-
 * Links, Refine + PushdownLinks (with the per-element link lists), and the
 * illumination (direct light through the links and the empty bins, then
 * ComputeIlluminateLeafNodes + PullupEnergy a bounce). The model is made
 * here: a bumpy sphere (the paper's "monster") standing on a square ground
 * plane, lit by a constant environment, deformed a little each frame (a
 * wave of its radius) so that the links really change. Its element size is
 * the longest edge, so that the elements are the vertices (as in the paper;
 * vertices on a segment's border are one element in each segment).
 *
 *   implicit_steps table VERTICES FRAMES BOUNCES BINS...
 *       one line per bin count: bins vertices elements, then the CPU ms
 *       (process CPU time, both threads count) of update create refine
 *       illuminate and the frame, and the frame's wall ms; means over the
 *       frames, after one that is not counted (see run); then the CPU ms
 *       of steps 1-2 (elements and hierarchy, once)
 *   implicit_steps scale BINS FRAMES VERTICES...
 *       one line per model size, the same columns
 *   implicit_steps runtime-scale BINS FRAMES VERTICES...
 *       the same models at the runtime's element size and cell
 *   implicit_steps scene FILE FRAMES BOUNCES BINS...
 *       a scene file's model at the runtime's element size and cell (the
 *       others keep one element a vertex), the same columns
 *
 * The gathering runs on 2 threads (implicit_bounce.c), the rest on one
 * (CreateHierarchicalLinks on IMPLICIT_LINK_THREADS, default 1: the
 * paper's one CPU; IMPLICIT_PAPER_RULES=1: the paper's rules alone, see
 * paper_rules below): on a loaded machine the CPU times are the steadier
 * figures; on an idle 2-core one the gathering's wall time is about half
 * its CPU time. The last column is CreateHierarchicalLinks' wall ms.
 * The seconds of the whole run go to stderr.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../runtime/implicit/implicit.h"
#include "progress.h"

typedef struct grower {
    gb_scene *scene;
    uint32_t vertex_capacity, triangle_capacity;
} grower;

static void *grow(void *array, size_t count, size_t size)
{
    void *grown = realloc(array, count * size + 1);
    if (!grown) {
        fprintf(stderr, "implicit_steps: out of memory\n");
        exit(1);
    }
    return grown;
}

static uint32_t add_vertex(grower *g, float x, float y, float z)
{
    gb_scene *s = g->scene;
    if (s->vertex_count == g->vertex_capacity) {
        g->vertex_capacity = 2 * g->vertex_capacity + 64;
        s->positions = grow(s->positions, 3 * (size_t)g->vertex_capacity, sizeof(float));
    }
    float *p = &s->positions[3 * (size_t)s->vertex_count];
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return s->vertex_count++;
}

static void add_face(grower *g, uint32_t a, uint32_t b, uint32_t c, uint32_t material)
{
    gb_scene *s = g->scene;
    if (s->triangle_count == g->triangle_capacity) {
        g->triangle_capacity = 2 * g->triangle_capacity + 64;
        s->indices = grow(s->indices, 3 * (size_t)g->triangle_capacity, sizeof(uint32_t));
        s->triangle_material =
            grow(s->triangle_material, g->triangle_capacity, sizeof(uint32_t));
    }
    uint32_t *t = &s->indices[3 * (size_t)s->triangle_count];
    t[0] = a;
    t[1] = b;
    t[2] = c;
    s->triangle_material[s->triangle_count++] = material;
}

/* The bumpy sphere's radius at polar angle theta, azimuth phi. */
static float radius(double theta, double phi)
{
    return (float)(0.5 * (1.0 + 0.15 * sin(3.0 * theta) * cos(4.0 * phi) +
                          0.08 * sin(5.0 * phi + 1.0) * sin(theta)));
}

/* rows x 2 rows lat-long grid plus two poles, centre (0, 0.55, 0), y up. */
static void add_blob(grower *g, int rows, uint32_t material)
{
    int columns = 2 * rows;
    uint32_t top = add_vertex(g, 0.0f, 0.55f + radius(0.0, 0.0), 0.0f), first = top + 1;
    for (int i = 1; i <= rows; ++i)
        for (int j = 0; j < columns; ++j) {
            double theta = M_PI * i / (rows + 1), phi = 2.0 * M_PI * j / columns;
            float r = radius(theta, phi);
            add_vertex(g, r * (float)(sin(theta) * cos(phi)), 0.55f + r * (float)cos(theta),
                       r * (float)(sin(theta) * sin(phi)));
        }
    uint32_t bottom = add_vertex(g, 0.0f, 0.55f - radius(M_PI, 0.0), 0.0f);
    for (int j = 0; j < columns; ++j) {
        uint32_t a = first + (uint32_t)j, b = first + (uint32_t)((j + 1) % columns);
        add_face(g, top, b, a, material);
        uint32_t c = first + (uint32_t)((rows - 1) * columns + j);
        uint32_t d = first + (uint32_t)((rows - 1) * columns + (j + 1) % columns);
        add_face(g, bottom, c, d, material);
    }
    for (int i = 0; i + 1 < rows; ++i)
        for (int j = 0; j < columns; ++j) {
            uint32_t a = first + (uint32_t)(i * columns + j);
            uint32_t b = first + (uint32_t)(i * columns + (j + 1) % columns);
            add_face(g, a, b, b + (uint32_t)columns, material);
            add_face(g, a, b + (uint32_t)columns, a + (uint32_t)columns, material);
        }
}

/* side x side vertices over [-2, 2]^2 at y = 0, facing +y. */
static void add_ground(grower *g, int side, uint32_t material)
{
    uint32_t first = g->scene->vertex_count;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            add_vertex(g, -2.0f + 4.0f * j / (side - 1), 0.0f, -2.0f + 4.0f * i / (side - 1));
    for (int i = 0; i + 1 < side; ++i)
        for (int j = 0; j + 1 < side; ++j) {
            uint32_t a = first + (uint32_t)(i * side + j);
            add_face(g, a, a + (uint32_t)side, a + 1, material);
            add_face(g, a + 1, a + (uint32_t)side, a + (uint32_t)side + 1, material);
        }
}

static uint32_t add_diffuse(gb_scene *s, float r, float g, float b)
{
    s->materials = grow(s->materials, s->material_count + 1, sizeof *s->materials);
    gb_material *m = &s->materials[s->material_count];
    gb_material_set_default(m, s->material_count ? "blob" : "ground");
    m->Kd[0] = r;
    m->Kd[1] = g;
    m->Kd[2] = b;
    return s->material_count++;
}

/* About `vertices` vertices: three quarters on the blob, a quarter on the
 * ground; lit by a white environment. */
static void make_model(int vertices, gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    grower g = {.scene = scene};
    uint32_t ground = add_diffuse(scene, 0.5f, 0.5f, 0.5f);
    uint32_t blob = add_diffuse(scene, 0.7f, 0.45f, 0.3f);
    int rows = (int)lround(sqrt(0.75 * vertices / 2.0)), side = (int)lround(sqrt(0.25 * vertices));
    add_blob(&g, rows < 2 ? 2 : rows, blob);
    add_ground(&g, side < 2 ? 2 : side, ground);
    scene->environment[0] = scene->environment[1] = scene->environment[2] = 1.0f;
    gb_error error;
    if (gb_scene_finish(scene, &error) != GB_OK) {
        fprintf(stderr, "implicit_steps: %s\n", error.message);
        exit(1);
    }
}

static float longest_edge(const gb_scene *scene)
{
    float longest = 0.0f;
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        for (int k = 0; k < 3; ++k) {
            const float *a = &scene->positions[3 * (size_t)scene->indices[3 * t + k]];
            const float *b = &scene->positions[3 * (size_t)scene->indices[3 * t + (k + 1) % 3]];
            float d = sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
            longest = fmaxf(longest, d);
        }
    return longest * 1.001f;
}

/* Frame f's deformation: the blob's vertices (y > 0.01) breathe, a wave of
 * 2 % of their height round the vertical axis. */
static void deform(gb_implicit_model *m, const float *rest, int frame)
{
    for (uint32_t v = 0; v < m->vertex_count; ++v) {
        const float *p = &rest[3 * (size_t)v];
        float *q = &m->vertices[3 * (size_t)v];
        float s = p[1] > 0.01f ? 1.0f + 0.02f * sinf(0.7f * (float)frame + 3.0f * p[0]) : 1.0f;
        q[0] = p[0] * s;
        q[1] = p[1];
        q[2] = p[2] * s;
    }
}

/* CPU seconds of each step and of the frame, and the frame's wall seconds. */
typedef struct step_times {
    double update, create, refine, illuminate, total, wall, create_wall;
} step_times;

static int link_threads(void)
{
    const char *text = getenv("IMPLICIT_LINK_THREADS");
    return text && atoi(text) > 0 ? atoi(text) : 1;
}

/* IMPLICIT_PAPER_RULES=1: the links by 4.2.2's rules alone
 * (gb_implicit_link_options.paper_rules), to measure what the runtime's
 * additions cost. */
static int paper_rules(void)
{
    const char *text = getenv("IMPLICIT_PAPER_RULES");
    return text && atoi(text) == 1;
}

static gb_result run(const gb_scene *scene, float element_size, float element_cell, int bins_n,
                     int frames, int bounces, int deforming, gb_error *error)
{
    gb_implicit_model m;
    gb_implicit_bins bins;
    double prepare = gb_cpu_seconds();
    gb_result result = gb_implicit_model_create(scene, element_size, element_cell, &m, error);
    if (result != GB_OK)
        return result;
    prepare = gb_cpu_seconds() - prepare;
    result = gb_implicit_bins_create(bins_n, &bins, error);
    gb_implicit_solution solution;
    if (result == GB_OK)
        result = gb_implicit_solution_create(&m, &solution, error);
    float *rest = malloc(3 * (size_t)m.vertex_count * sizeof *rest + 1);
    if (rest)
        memcpy(rest, m.vertices, 3 * (size_t)m.vertex_count * sizeof *rest);
    else if (result == GB_OK)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit_steps: out of memory");
    step_times sum = {0};
    gb_implicit_link_options options = {.hierarchical = 1, .lights = scene,
                                        .thread_count = link_threads(),
                                        .paper_rules = paper_rules()};
    /* An animation (deforming) starts with a frame that is not counted: the
     * first build of the links at a bin count pays the page faults of its
     * slot array, once, as the paper's per-frame figures of a running
     * animation do not. */
    for (int f = deforming ? -1 : 0; f < frames && result == GB_OK; ++f) {
        if (deforming)
            deform(&m, rest, f);
        gb_implicit_links links;
        double wall = gb_seconds(), t0 = gb_cpu_seconds();
        result = gb_implicit_update_elements(&m, error);
        double t1 = gb_cpu_seconds();
        if (result == GB_OK)
            result = gb_implicit_create_links(&m, &bins, &options, &links, NULL, error);
        if (result != GB_OK)
            break;
        double t2 = gb_cpu_seconds();
        gb_implicit_illuminate(scene, &m, &links, bounces, &solution);
        double t3 = gb_cpu_seconds();
        if (f >= 0) {
            sum.wall += gb_seconds() - wall;
            sum.update += t1 - t0;
            sum.create += links.cpu.create;
            sum.create_wall += links.wall.create;
            sum.refine += links.cpu.refine + links.cpu.compact;
            sum.illuminate += t3 - t2;
            sum.total += t3 - t0;
        }
        gb_implicit_links_free(&links);
    }
    if (result == GB_OK) {
        double k = 1e3 / frames;
        printf("%3d %8u %8u %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f\n", bins_n,
               scene->vertex_count, m.element_count, k * sum.update, k * sum.create,
               k * sum.refine, k * sum.illuminate, k * sum.total, k * sum.wall,
               1e3 * prepare, k * sum.create_wall);
        fflush(stdout);
    }
    free(rest);
    gb_implicit_solution_free(&solution);
    gb_implicit_bins_free(&bins);
    gb_implicit_model_free(&m);
    return result;
}

static void header(void)
{
    printf("bins vertices elements update_ms create_ms refine_ms illum_ms total_ms wall_ms "
           "prepare_ms create_wall_ms\n");
}

static int usage(void)
{
    fprintf(stderr, "usage: implicit_steps table VERTICES FRAMES BOUNCES BINS...\n"
                    "       implicit_steps scale BINS FRAMES VERTICES...\n"
                    "       implicit_steps runtime-scale BINS FRAMES VERTICES...\n"
                    "       implicit_steps scene FILE FRAMES BOUNCES BINS...\n");
    return 2;
}

int main(int argc, char **argv)
{
    if (argc < 5)
        return usage();
    gb_error error;
    gb_result result = GB_OK;
    gb_scene scene;
    double cpu = gb_cpu_seconds();
    double wall = gb_seconds();
    header();
    if (strcmp(argv[1], "table") == 0) {
        make_model(atoi(argv[2]), &scene);
        for (int i = 5; i < argc && result == GB_OK; ++i)
            result = run(&scene, longest_edge(&scene), 0.0f, atoi(argv[i]), atoi(argv[3]),
                         atoi(argv[4]), 1, &error);
        gb_scene_free(&scene);
    } else if (strcmp(argv[1], "scale") == 0 || strcmp(argv[1], "runtime-scale") == 0) {
        int runtime = strcmp(argv[1], "runtime-scale") == 0;
        for (int i = 4; i < argc && result == GB_OK; ++i) {
            make_model(atoi(argv[i]), &scene);
            result = run(&scene, runtime ? 0.0f : longest_edge(&scene),
                         runtime ? GB_IMPLICIT_ELEMENT_CELL : 0.0f, atoi(argv[2]), atoi(argv[3]),
                         1, 1, &error);
            gb_scene_free(&scene);
        }
    } else if (strcmp(argv[1], "scene") == 0) {
        result = gb_scene_load(argv[2], NULL, &scene, &error);
        for (int i = 5; i < argc && result == GB_OK; ++i)
            result = run(&scene, 0.0f, GB_IMPLICIT_ELEMENT_CELL, atoi(argv[i]), atoi(argv[3]),
                         atoi(argv[4]), 0, &error);
        gb_scene_free(&scene);
    } else {
        return usage();
    }
    if (result != GB_OK) {
        fprintf(stderr, "implicit_steps: %s\n", error.message);
        return 1;
    }
    fprintf(stderr, "implicit_steps: %.1f s wall, %.1f s CPU\n", gb_seconds() - wall,
            gb_cpu_seconds() - cpu);
    return 0;
}
