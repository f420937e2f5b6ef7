/* discs.c — chart meshes, their topology and their halving (discs.h). */
#include "discs.h"

#include <stdlib.h>
#include <string.h>

#include "triangle_geometry.h"
#include "union_find.h"

/* ---- corners glued across edges (a union-find) ---- */

/* The chart neighbours over glued edges, and the corners glued across them
 * (corner 3i+e of triangle i: vertex e). Counts the edges: a glued edge
 * once, a border edge once. */
static int64_t glue(const gb_mesh_adjacency *adjacency, gb_chart_mesh *m,
                    const uint32_t *local_of, uint32_t *parent)
{
    int64_t border = 0, glued = 0;
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        uint32_t t = m->triangles[i];
        for (int e = 0; e < 3; ++e) {
            uint32_t n = adjacency->neighbours[3 * (size_t)t + e];
            uint32_t j = n == GB_NO_NEIGHBOUR ? GB_NO_NEIGHBOUR : local_of[n];
            m->neighbours[3 * (size_t)i + e] = j;
            if (j == GB_NO_NEIGHBOUR) {
                ++border;
                continue;
            }
            ++glued;
            int f = gb_mesh_adjacency_edge_to(adjacency, n, t);
            /* t's edge e runs a -> b, n's edge f runs b -> a */
            gb_union_find_join(parent, 3 * i + e, 3 * j + (f + 1) % 3);
            gb_union_find_join(parent, 3 * i + (e + 1) % 3, 3 * j + f);
        }
    }
    return border + glued / 2;
}

static int label_vertices(const gb_scene *scene, gb_chart_mesh *m, uint32_t *parent)
{
    uint32_t corner_count = 3 * m->triangle_count;
    uint32_t *label = malloc(corner_count * sizeof *label);
    if (!label)
        return 0;
    m->vertex_count = 0;
    for (uint32_t c = 0; c < corner_count; ++c) {
        uint32_t root = gb_union_find_root(parent, c);
        label[c] = root == c ? m->vertex_count++ : label[root];
        m->corners[c] = label[c];
    }
    free(label);
    m->positions = malloc(3 * (size_t)m->vertex_count * sizeof *m->positions);
    if (!m->positions)
        return 0;
    for (uint32_t c = 0; c < corner_count; ++c)
        gb_triangle_corner(scene, m->triangles[c / 3], (int)(c % 3),
                           m->positions + 3 * (size_t)m->corners[c]);
    return 1;
}

gb_result gb_chart_mesh_build(const gb_scene *scene, const gb_mesh_adjacency *adjacency,
                              const uint32_t *triangles, uint32_t triangle_count,
                              uint32_t *local_of, gb_chart_mesh *mesh, gb_error *error)
{
    memset(mesh, 0, sizeof *mesh);
    mesh->triangle_count = triangle_count;
    mesh->triangles = triangles;
    size_t corners = 3 * (size_t)triangle_count;
    mesh->corners = malloc(corners * sizeof *mesh->corners);
    mesh->neighbours = malloc(corners * sizeof *mesh->neighbours);
    uint32_t *parent = malloc(corners * sizeof *parent);
    int ok = mesh->corners && mesh->neighbours && parent;
    if (ok) {
        for (uint32_t i = 0; i < triangle_count; ++i)
            local_of[triangles[i]] = i;
        for (uint32_t c = 0; c < corners; ++c)
            parent[c] = c;
        int64_t edges = glue(adjacency, mesh, local_of, parent);
        for (uint32_t i = 0; i < triangle_count; ++i)
            local_of[triangles[i]] = GB_NO_NEIGHBOUR;
        ok = label_vertices(scene, mesh, parent);
        mesh->euler = (int64_t)mesh->vertex_count - edges + triangle_count;
    }
    free(parent);
    gb_result result = GB_OK;
    if (ok)
        result = gb_chart_mesh_components(mesh, NULL, NULL, &mesh->components, error);
    else
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (chart mesh)");
    if (result != GB_OK)
        gb_chart_mesh_free(mesh);
    return result;
}

void gb_chart_mesh_free(gb_chart_mesh *mesh)
{
    free(mesh->corners);
    free(mesh->positions);
    free(mesh->neighbours);
    memset(mesh, 0, sizeof *mesh);
}

/* ---- floods ---- */

/* Breadth-first from the queued seeds over glued edges between kept
 * triangles: each reached triangle takes the label of the one it was
 * reached from. queue holds the seeds (count of them) and has room for
 * every triangle. */
static void flood(const gb_chart_mesh *m, const uint8_t *keep, uint32_t *label, uint32_t *queue,
                  uint32_t count)
{
    for (uint32_t head = 0; head < count; ++head) {
        uint32_t i = queue[head];
        for (int e = 0; e < 3; ++e) {
            uint32_t j = m->neighbours[3 * (size_t)i + e];
            if (j != GB_NO_NEIGHBOUR && (!keep || keep[j]) && label[j] == GB_NO_NEIGHBOUR) {
                label[j] = label[i];
                queue[count++] = j;
            }
        }
    }
}

gb_result gb_chart_mesh_components(const gb_chart_mesh *m, const uint8_t *keep,
                                   uint32_t *component, uint32_t *component_count,
                                   gb_error *error)
{
    uint32_t *label = malloc(m->triangle_count * sizeof *label);
    uint32_t *queue = malloc(m->triangle_count * sizeof *queue);
    if (!label || !queue) {
        free(label);
        free(queue);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (components)");
    }
    for (uint32_t i = 0; i < m->triangle_count; ++i)
        label[i] = GB_NO_NEIGHBOUR;
    *component_count = 0;
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        if ((keep && !keep[i]) || label[i] != GB_NO_NEIGHBOUR)
            continue;
        label[i] = (*component_count)++;
        queue[0] = i;
        flood(m, keep, label, queue, 1);
    }
    for (uint32_t i = 0; component && i < m->triangle_count; ++i)
        if (!keep || keep[i])
            component[i] = label[i];
    free(label);
    free(queue);
    return GB_OK;
}

static void centroid(const gb_chart_mesh *m, uint32_t i, double c[3])
{
    c[0] = c[1] = c[2] = 0.0;
    for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
            c[d] += m->positions[3 * (size_t)m->corners[3 * i + k] + d] / 3.0;
}

/* The triangle whose centroid is farthest from point (the first of ties). */
static uint32_t farthest_from(const gb_chart_mesh *m, const double point[3])
{
    uint32_t best = 0;
    double best_distance = -1.0;
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        double c[3], d = 0.0;
        centroid(m, i, c);
        for (int k = 0; k < 3; ++k)
            d += (c[k] - point[k]) * (c[k] - point[k]);
        if (d > best_distance) {
            best_distance = d;
            best = i;
        }
    }
    return best;
}

gb_result gb_chart_mesh_split(const gb_chart_mesh *m, uint32_t *part, uint32_t *part_count,
                              gb_error *error)
{
    if (m->components > 1)
        return gb_chart_mesh_components(m, NULL, part, part_count, error);
    uint32_t *queue = malloc(m->triangle_count * sizeof *queue);
    if (!queue)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (split)");
    double middle[3] = {0.0, 0.0, 0.0}, c[3];
    for (uint32_t i = 0; i < m->triangle_count; ++i) {
        centroid(m, i, c);
        for (int k = 0; k < 3; ++k)
            middle[k] += c[k] / m->triangle_count;
        part[i] = GB_NO_NEIGHBOUR;
    }
    uint32_t a = farthest_from(m, middle);
    centroid(m, a, c);
    uint32_t b = farthest_from(m, c);
    if (b == a)  /* every centroid at one point: any other triangle */
        b = (a + 1) % m->triangle_count;
    part[a] = 0;
    part[b] = 1;
    queue[0] = a;
    queue[1] = b;
    flood(m, NULL, part, queue, 2);
    *part_count = 2;
    free(queue);
    return GB_OK;
}
