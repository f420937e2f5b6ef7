/* implicit_small_segments.c — the segments of a finely detailed scene
 * (implicit_small_segments.h). Segments are grown within 30 degrees of
 * normal (implicit_hierarchy.c), so a curved or detailed surface (a
 * column's fluting, a plant's leaves, a carved frame) breaks into many
 * segments, each smaller than an element, and each got an element of
 * its own at least (Sponza: 41 591 elements). Such a piece is below what
 * the bins can tell apart, so its triangles are regrouped by material and
 * place, and the pieces in one cell make one segment and one element
 * (Sponza: 16 238 elements; bench/implicit_large.sh in docs/figures.md gives
 * the links' time and the error against the reference). One element, not
 * one a cell its vertices reach: a group's triangles are placed by
 * centroid, and their corners reach into the next cells, which made
 * slivers (20 556 elements on Sponza). */
#include "implicit_small_segments.h"

#include <math.h>
#include <stdlib.h>

typedef struct placed_triangle {
    uint32_t material;
    int64_t cell[3];
    uint32_t triangle;
} placed_triangle;

/* By group (material, then cell): 0 for two triangles of one group. */
static int compare_groups(const placed_triangle *p, const placed_triangle *q)
{
    if (p->material != q->material)
        return p->material < q->material ? -1 : 1;
    for (int k = 0; k < 3; ++k)
        if (p->cell[k] != q->cell[k])
            return p->cell[k] < q->cell[k] ? -1 : 1;
    return 0;
}

/* By group, then triangle (qsort's order is then unique). */
static int compare_placed(const void *x, const void *y)
{
    const placed_triangle *p = x, *q = y;
    int by_group = compare_groups(p, q);
    if (by_group)
        return by_group;
    return p->triangle < q->triangle ? -1 : p->triangle > q->triangle;
}

/* The triangle's material and the cell of its centroid, on the grid of the
 * elements' cells (implicit_elements.c: cell k holds the points that round
 * to k cells). */
static placed_triangle place(const gb_scene *scene, uint32_t t, float cell)
{
    placed_triangle placed = {scene->triangle_material[t], {0, 0, 0}, t};
    for (int k = 0; k < 3; ++k) {
        double centroid = 0.0;
        for (int c = 0; c < 3; ++c)
            centroid += scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + c] + k];
        placed.cell[k] = llround(centroid / 3.0 / cell);
    }
    return placed;
}

/* The new segment of every triangle: the groups of the small ones first
 * take ids from segment_count up, then all ids are made consecutive in
 * order of first triangle, and the groups' marked in segment_regrouped. */
static void renumber(gb_implicit_model *model, uint32_t triangle_count, uint32_t id_count,
                     uint32_t *new_id)
{
    uint32_t first_group = model->segment_count;
    for (uint32_t i = 0; i < id_count; ++i)
        new_id[i] = GB_IMPLICIT_NO_NODE;
    uint32_t next = 0;
    for (uint32_t t = 0; t < triangle_count; ++t) {
        uint32_t old = model->triangle_segment[t], *id = &new_id[old];
        if (*id == GB_IMPLICIT_NO_NODE) {
            model->segment_regrouped[next] = old >= first_group;
            *id = next++;
        }
        model->triangle_segment[t] = *id;
    }
    model->segment_count = next;
}

gb_result gb_implicit_merge_small_segments(const gb_scene *scene, gb_implicit_model *model,
                                           float smallest_area, float cell, gb_error *error)
{
    uint32_t n = scene->triangle_count;
    double *area = calloc((size_t)model->segment_count + 1, sizeof *area);
    placed_triangle *small = malloc((size_t)n * sizeof *small + 1);
    uint32_t *new_id = malloc(((size_t)model->segment_count + n + 1) * sizeof *new_id);
    free(model->segment_regrouped);
    model->segment_regrouped = malloc((size_t)model->segment_count + n + 1);
    if (!area || !small || !new_id || !model->segment_regrouped) {
        free(area);
        free(small);
        free(new_id);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    for (uint32_t t = 0; t < n; ++t)
        area[model->triangle_segment[t]] += gb_triangle_area(scene, t);
    size_t count = 0;
    for (uint32_t t = 0; t < n; ++t)
        if (area[model->triangle_segment[t]] < smallest_area)
            small[count++] = place(scene, t, cell);
    qsort(small, count, sizeof *small, compare_placed);
    uint32_t id = model->segment_count;
    for (size_t i = 0; i < count; ++i) {
        if (i > 0 && compare_groups(&small[i], &small[i - 1]) != 0)
            ++id;
        model->triangle_segment[small[i].triangle] = id;
    }
    renumber(model, n, id + 1, new_id);
    free(area);
    free(small);
    free(new_id);
    return GB_OK;
}
