/* implicit_update.c — UpdateElements (Dong 2007, 4.2.1; step 4 of
 * Algorithm 1): every node's position, normal, area and box again from the
 * finer mesh's vertices (model->vertices, which the caller moves when the
 * model deforms); the hierarchy itself is untouched. The leaves first, from
 * the finer triangles around each element, then the internal nodes bottom
 * up (each comes after its children) from their children, like refitting a
 * bounding volume hierarchy. gb_implicit_create_surfels uses the leaves'
 * part once at the start. */
#include "implicit_update.h"
#include "implicit_hierarchy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Adds a third of the finer triangle (v0, v1, v2)'s area, its area-weighted
 * normal and the centroid of the corner's third, (22 a + 7 b + 7 c) / 36, to
 * each corner's element. sums: normal xyz, centroid xyz times area. */
static void add_triangle(gb_implicit_model *model, const uint32_t v[3], double *sums)
{
    const float *p[3];
    uint32_t e[3];
    for (int k = 0; k < 3; ++k) {
        p[k] = &model->vertices[3 * (size_t)v[k]];
        e[k] = model->vertex_element[v[k]];
    }
    double n[3];
    gb_implicit_triangle_cross(p[0], p[1], p[2], n);
    double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) {
        model->nodes[e[k]].area += (float)(area / 3.0);
        double *sum = &sums[6 * (size_t)e[k]];
        for (int c = 0; c < 3; ++c) {
            sum[c] += 0.5 * n[c];
            double centroid = (22.0 * p[k][c] + 7.0 * p[(k + 1) % 3][c] +
                               7.0 * p[(k + 2) % 3][c]) / 36.0;
            sum[3 + c] += area / 3.0 * centroid;
        }
    }
}

/* An element of no area (its triangles all degenerate) keeps its position
 * (at first, its first vertex) and gets the zero normal: it sends and
 * receives nothing. */
static void finish_leaf(gb_implicit_model *model, uint32_t e, const double *sum)
{
    gb_implicit_node *node = &model->nodes[e];
    double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    for (int k = 0; k < 3; ++k) {
        node->normal[k] = length > 0.0 ? (float)(sum[k] / length) : 0.0f;
        node->position[k] = node->area > 0.0f ? (float)(sum[3 + k] / node->area)
                                              : node->position[k];
        node->box_min[k] = node->box_max[k] = node->position[k];
    }
}

gb_result gb_implicit_update_leaves(gb_implicit_model *model, gb_error *error)
{
    double *sums = calloc(6 * (size_t)model->element_count + 1, sizeof *sums);
    if (!sums)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    for (uint32_t e = 0; e < model->element_count; ++e)
        model->nodes[e].area = 0.0f;
    for (uint32_t t = 0; t < model->triangle_count; ++t)
        add_triangle(model, &model->triangles[3 * (size_t)t], sums);
    for (uint32_t e = 0; e < model->element_count; ++e)
        finish_leaf(model, e, &sums[6 * (size_t)e]);
    free(sums);
    return GB_OK;
}

gb_result gb_implicit_update_elements(gb_implicit_model *model, gb_error *error)
{
    gb_result result = gb_implicit_update_leaves(model, error);
    if (result != GB_OK)
        return result;
    for (uint32_t i = model->element_count; i < model->node_count; ++i)
        gb_implicit_summarise(model, &model->nodes[i]);
    return GB_OK;
}
