/* implicit_elements.c — CreateSurfels (Dong 2007, 4.1): oriented discs at
 * the vertices, their area one third of the triangles around them. The
 * vertices are those of a finer mesh (implicit.h): each triangle cut into
 * n x n, the corners welded within a segment by position (quantised to
 * 1/64 of the element size). The vertices of a segment in one cell of a
 * grid (GB_IMPLICIT_ELEMENT_CELL element sizes in the runtime) make one
 * element, so that a finely tessellated scene gets no more elements than
 * its size needs; a coarse one, cut to the element size, keeps one element
 * a vertex; a segment regrouped from small ones is one element
 * (implicit_small_segments.h). Also the model's create and free. */
#include "implicit_elements.h"
#include "implicit_closed_parts.h"
#include "implicit_hierarchy.h"
#include "implicit_small_segments.h"
#include "implicit_update.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct corner {
    uint32_t segment;
    int64_t q[3];               /* quantised position */
    float position[3];
    uint32_t slot;              /* index before sorting */
} corner;

static int compare_corners(const void *x, const void *y)
{
    const corner *p = x, *q = y;
    if (p->segment != q->segment)
        return p->segment < q->segment ? -1 : 1;
    for (int k = 0; k < 3; ++k)
        if (p->q[k] != q->q[k])
            return p->q[k] < q->q[k] ? -1 : 1;
    return p->slot < q->slot ? -1 : p->slot > q->slot;
}

static const float *vertex(const gb_scene *scene, uint32_t t, int k)
{
    return &scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + k]];
}

/* n: the triangle's cuts a side so that no edge exceeds the element size. */
static uint32_t cuts(const gb_scene *scene, uint32_t t, float size)
{
    float longest = 0.0f;
    for (int k = 0; k < 3; ++k) {
        const float *a = vertex(scene, t, k), *b = vertex(scene, t, (k + 1) % 3);
        float d = sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
        longest = fmaxf(longest, d);
    }
    float n = ceilf(longest / size);
    return n < 1.0f ? 1u : n > 128.0f ? 128u : (uint32_t)n;
}

static size_t corner_index(uint32_t n, uint32_t i, uint32_t j)
{
    return (size_t)i * (n + 1) - (size_t)i * (i - 1) / 2 + j;
}

static void set_corner(corner *x, uint32_t segment, uint32_t slot, const double p[3],
                       float quantum)
{
    x->segment = segment;
    x->slot = slot;
    for (int k = 0; k < 3; ++k) {
        x->position[k] = (float)p[k];
        x->q[k] = llround(p[k] / quantum);
    }
}

static void fill_corners(const gb_scene *scene, const gb_implicit_model *model, uint32_t t,
                         uint32_t n, float quantum, corner *out, size_t base)
{
    const float *a = vertex(scene, t, 0), *b = vertex(scene, t, 1), *c = vertex(scene, t, 2);
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; i + j <= n; ++j) {
            double p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = a[k] + ((double)b[k] - a[k]) * i / n + ((double)c[k] - a[k]) * j / n;
            size_t slot = base + corner_index(n, i, j);
            set_corner(&out[slot], model->triangle_segment[t], (uint32_t)slot, p, quantum);
        }
}

/* The finer mesh's triangles, by the corners' vertices. */
static void emit_triangles(const gb_scene *scene, gb_implicit_model *model,
                           const uint32_t *vertex_of, const size_t *base)
{
    uint32_t out = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        uint32_t n = cuts(scene, t, model->element_size);
        const uint32_t *of = vertex_of + base[t];
        for (uint32_t i = 0; i < n; ++i)
            for (uint32_t j = 0; i + j < n; ++j) {
                uint32_t up[3] = {of[corner_index(n, i, j)], of[corner_index(n, i + 1, j)],
                                  of[corner_index(n, i, j + 1)]};
                memcpy(&model->triangles[3 * (size_t)out++], up, sizeof up);
                if (i + j + 1 < n) {
                    uint32_t down[3] = {of[corner_index(n, i + 1, j)],
                                        of[corner_index(n, i + 1, j + 1)],
                                        of[corner_index(n, i, j + 1)]};
                    memcpy(&model->triangles[3 * (size_t)out++], down, sizeof down);
                }
            }
    }
}

static int same_place(const corner *a, const corner *b)
{
    return a->segment == b->segment && a->q[0] == b->q[0] && a->q[1] == b->q[1] &&
           a->q[2] == b->q[2];
}

/* Sorts the corners and numbers them by place: group_of[slot] is the
 * group of each, in sorted order. first, when not NULL, gets the first
 * corner of each group. Returns the groups. */
static uint32_t group_by_place(corner *corners, size_t count, uint32_t *group_of,
                               corner *first)
{
    qsort(corners, count, sizeof *corners, compare_corners);
    uint32_t groups = 0;
    for (size_t i = 0; i < count; ++i) {
        if (i == 0 || !same_place(&corners[i], &corners[i - 1])) {
            if (first)
                first[groups] = corners[i];
            ++groups;
        }
        group_of[corners[i].slot] = groups - 1;
    }
    return groups;
}

/* The vertices (welded, vertex_count of them) into elements: those of a
 * segment in one grid cell, numbered segment by segment. welded is then
 * overwritten with each element's first vertex; scratch holds vertex_count. */
static void cluster_vertices(corner *welded, corner *scratch, gb_implicit_model *model)
{
    for (uint32_t v = 0; v < model->vertex_count; ++v) {
        double p[3] = {welded[v].position[0], welded[v].position[1], welded[v].position[2]};
        memcpy(&model->vertices[3 * (size_t)v], welded[v].position, sizeof welded[v].position);
        if (model->segment_regrouped && model->segment_regrouped[welded[v].segment]) {
            scratch[v] = welded[v];     /* the whole segment one place */
            scratch[v].q[0] = scratch[v].q[1] = scratch[v].q[2] = 0;
            scratch[v].slot = v;
        } else if (model->element_cell > 0.0f)
            set_corner(&scratch[v], welded[v].segment, v, p, model->element_cell);
        else {      /* a place of its own */
            scratch[v] = welded[v];
            scratch[v].q[0] = v;
            scratch[v].q[1] = scratch[v].q[2] = 0;
            scratch[v].slot = v;
        }
    }
    model->element_count =
        group_by_place(scratch, model->vertex_count, model->vertex_element, welded);
    for (uint32_t e = 0; e < model->element_count; ++e) {
        gb_implicit_node *node = &model->nodes[e];
        memset(node, 0, sizeof *node);
        memcpy(node->position, welded[e].position, sizeof node->position);
        node->segment = welded[e].segment;
    }
}

/* Each element's diffuse reflectance and emission: its segment's material's. */
static void set_materials(const gb_scene *scene, gb_implicit_model *model,
                          const uint32_t *segment_material)
{
    for (uint32_t e = 0; e < model->element_count; ++e) {
        const gb_material *m = &scene->materials[segment_material[model->nodes[e].segment]];
        memcpy(&model->Kd[3 * (size_t)e], m->Kd, 3 * sizeof(float));
        memcpy(&model->Le[3 * (size_t)e], m->Ke, 3 * sizeof(float));
    }
}

static float default_element_size(const gb_scene *scene)
{
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k)
        d2 += (scene->bounds_max[k] - scene->bounds_min[k]) *
              (scene->bounds_max[k] - scene->bounds_min[k]);
    float size = sqrtf(d2) / GB_IMPLICIT_ELEMENTS_PER_DIAGONAL;
    return size > 0.0f ? size : 1.0f;
}

gb_result gb_implicit_create_surfels(const gb_scene *scene, gb_implicit_model *model,
                                     gb_error *error)
{
    size_t *base = malloc(((size_t)scene->triangle_count + 1) * sizeof *base);
    uint32_t *segment_material = malloc(((size_t)model->segment_count + 1) * sizeof(uint32_t));
    if (!base || !segment_material) {
        free(base);
        free(segment_material);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    size_t count = 0, triangles = 0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        uint32_t n = cuts(scene, t, model->element_size);
        base[t] = count;
        count += (size_t)(n + 1) * (n + 2) / 2;
        triangles += (size_t)n * n;
        segment_material[model->triangle_segment[t]] = scene->triangle_material[t];
    }
    corner *corners = malloc(count * sizeof *corners + 1);
    corner *welded = malloc(count * sizeof *welded + 1);
    uint32_t *vertex_of = malloc(count * sizeof *vertex_of + 1);
    model->nodes = malloc(count * sizeof *model->nodes + 1);
    model->triangles = malloc(3 * triangles * sizeof *model->triangles + 1);
    model->vertices = malloc(3 * count * sizeof *model->vertices + 1);
    model->vertex_element = malloc(count * sizeof *model->vertex_element + 1);
    gb_result result = GB_OK;
    if (!corners || !welded || !vertex_of || !model->nodes || !model->triangles ||
        !model->vertices || !model->vertex_element || count > UINT32_MAX / 4)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    if (result == GB_OK) {
        for (uint32_t t = 0; t < scene->triangle_count; ++t)
            fill_corners(scene, model, t, cuts(scene, t, model->element_size),
                         model->element_size / 64.0f, corners, base[t]);
        model->vertex_count = group_by_place(corners, count, vertex_of, welded);
        cluster_vertices(welded, corners, model);
        model->triangle_count = (uint32_t)triangles;
        model->Kd = malloc(3 * (size_t)model->element_count * sizeof(float) + 1);
        model->Le = malloc(3 * (size_t)model->element_count * sizeof(float) + 1);
        if (!model->Kd || !model->Le)
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    if (result == GB_OK) {
        emit_triangles(scene, model, vertex_of, base);
        result = gb_implicit_update_leaves(model, error);
    }
    if (result == GB_OK)
        set_materials(scene, model, segment_material);
    free(corners);
    free(welded);
    free(vertex_of);
    free(base);
    free(segment_material);
    return result;
}

gb_result gb_implicit_model_create(const gb_scene *scene, float element_size, float element_cell,
                                   gb_implicit_model *model, gb_error *error)
{
    memset(model, 0, sizeof *model);
    if (scene->triangle_count == 0)
        return gb_fail(error, GB_ERROR_INVALID, "implicit: the scene has no triangle");
    model->element_size = element_size > 0.0f ? element_size : default_element_size(scene);
    model->element_cell = element_cell > 0.0f ? element_cell * model->element_size : 0.0f;
    gb_result result = gb_implicit_segment_faces(scene, model, error);
    if (result == GB_OK && model->element_cell > 0.0f)
        result = gb_implicit_merge_small_segments(
            scene, model, model->element_cell * model->element_cell, model->element_cell, error);
    if (result == GB_OK)
        result = gb_implicit_open_segments(scene, model, error);
    if (result == GB_OK)
        result = gb_implicit_create_surfels(scene, model, error);
    if (result == GB_OK)
        result = gb_implicit_create_geometric_hierarchy(model, error);
    if (result != GB_OK)
        gb_implicit_model_free(model);
    return result;
}

void gb_implicit_model_free(gb_implicit_model *model)
{
    free(model->triangle_segment);
    free(model->segment_open);
    free(model->segment_regrouped);
    free(model->nodes);
    free(model->children);
    free(model->roots);
    free(model->Kd);
    free(model->Le);
    free(model->triangles);
    free(model->vertices);
    free(model->vertex_element);
    memset(model, 0, sizeof *model);
}
