/* implicit_closed_parts.c — the mesh's connected parts, closed or open
 * (implicit_closed_parts.h): the corners welded by position through a
 * hash, each edge's uses in either direction counted in a hash of edges,
 * the triangles sharing an edge joined in a union-find. */
#include "implicit_closed_parts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "union_find.h"

/* splitmix64's finaliser: the hash of both tables. */
static uint64_t mix(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* The least power of two of at least 4/3 count (tables at most 3/4 full). */
static size_t table_size(size_t count)
{
    size_t size = 16;
    while (3 * size < 4 * count)
        size *= 2;
    return size;
}

static uint32_t position_bits(float x)
{
    x += 0.0f;                  /* -0 and +0 are one position */
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

/* welded[c] for each of the 3 triangle_count corners: the first corner at
 * its position (its three floats' bits). */
static int weld_corners(const float *positions, const uint32_t *indices, size_t corners,
                        uint32_t *welded)
{
    size_t size = table_size(corners);
    uint32_t *table = malloc(size * sizeof *table);
    if (!table)
        return 0;
    memset(table, 0xff, size * sizeof *table);
    for (size_t c = 0; c < corners; ++c) {
        const float *p = &positions[3 * (size_t)indices[c]];
        uint32_t x = position_bits(p[0]), y = position_bits(p[1]), z = position_bits(p[2]);
        size_t slot = mix(((uint64_t)x << 32 | y) ^ mix(z)) & (size - 1);
        for (;; slot = (slot + 1) & (size - 1)) {
            uint32_t other = table[slot];
            if (other == UINT32_MAX) {
                table[slot] = (uint32_t)c;
                welded[c] = (uint32_t)c;
                break;
            }
            const float *q = &positions[3 * (size_t)indices[other]];
            if (position_bits(q[0]) == x && position_bits(q[1]) == y &&
                position_bits(q[2]) == z) {
                welded[c] = other;
                break;
            }
        }
    }
    free(table);
    return 1;
}

/* An undirected edge (its welded corners, the lesser first) and its uses:
 * from the lesser corner to the greater and back (counted up to 2), and
 * the first triangle that used it. */
typedef struct edge_uses {
    uint64_t key;               /* UINT64_MAX: empty */
    uint32_t triangle;
    uint8_t forward, backward;
} edge_uses;

/* Counts triangle t's directed edge u -> v and joins t with the edge's
 * first triangle. */
static void use_edge(edge_uses *edges, size_t size, uint32_t *parent, uint32_t t, uint32_t u,
                     uint32_t v)
{
    uint64_t key = u < v ? (uint64_t)u << 32 | v : (uint64_t)v << 32 | u;
    size_t slot = mix(key) & (size - 1);
    while (edges[slot].key != key && edges[slot].key != UINT64_MAX)
        slot = (slot + 1) & (size - 1);
    edge_uses *e = &edges[slot];
    if (e->key == UINT64_MAX)
        *e = (edge_uses){key, t, 0, 0};
    else
        gb_union_find_join(parent, e->triangle, t);
    uint8_t *count = u < v ? &e->forward : &e->backward;
    if (*count < 2)
        ++*count;
}

/* The solid angle of triangle abc seen from p, signed by its winding
 * (Van Oosterom and Strackee 1983): over a closed part, 4 pi times the
 * number of times it winds around p. */
static double solid_angle(const float *a, const float *b, const float *c, const float *p)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = (double)a[k] - p[k];
        v[k] = (double)b[k] - p[k];
        w[k] = (double)c[k] - p[k];
    }
    double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double triple = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                    u[2] * (v[0] * w[1] - v[1] * w[0]);
    double below = lu * lv * lw + (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * lw +
                   (v[0] * w[0] + v[1] * w[1] + v[2] * w[2]) * lu +
                   (w[0] * u[0] + w[1] * u[1] + w[2] * u[2]) * lv;
    return 2.0 * atan2(triple, below);
}

/* What decides whether a closed part's back is seen. */
typedef struct part {
    double volume;              /* signed: > 0 when its fronts face out */
    float box_min[3], box_max[3];
} part;

/* Sets open[root] for each closed part (root: its least triangle,
 * parent[t] for every t) whose fronts face into its volume or that holds
 * one of the points, by its winding number about them. */
static int open_closed_parts(const float *positions, const uint32_t *indices,
                             uint32_t triangle_count, const uint32_t *parent,
                             const uint8_t *skip, const float *points, uint32_t point_count,
                             uint8_t *open)
{
    uint32_t *id = malloc((size_t)triangle_count * sizeof *id + 1), count = 0;
    for (uint32_t t = 0; id && t < triangle_count; ++t)
        id[t] = parent[t] == t ? count++ : id[parent[t]];
    part *parts = malloc((size_t)count * sizeof *parts + 1);
    double *winding = calloc((size_t)count * point_count + 1, sizeof *winding);
    if (!id || !parts || !winding) {
        free(id);
        free(parts);
        free(winding);
        return 0;
    }
    for (uint32_t i = 0; i < count; ++i)
        parts[i] = (part){0.0, {INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (int pass = 0; pass < 2; ++pass)
        for (uint32_t t = 0; t < triangle_count; ++t) {
            part *q = &parts[id[t]];
            if (skip[t] || open[parent[t]])
                continue;
            const float *p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = &positions[3 * (size_t)indices[3 * (size_t)t + k]];
            if (pass == 0) {
                /* the volume: the tetrahedra from the origin, p0 . (p1 x p2) / 6 */
                double c[3] = {(double)p[1][1] * p[2][2] - (double)p[1][2] * p[2][1],
                               (double)p[1][2] * p[2][0] - (double)p[1][0] * p[2][2],
                               (double)p[1][0] * p[2][1] - (double)p[1][1] * p[2][0]};
                q->volume += (p[0][0] * c[0] + p[0][1] * c[1] + p[0][2] * c[2]) / 6.0;
                for (int v = 0; v < 3; ++v)
                    for (int k = 0; k < 3; ++k) {
                        q->box_min[k] = fminf(q->box_min[k], p[v][k]);
                        q->box_max[k] = fmaxf(q->box_max[k], p[v][k]);
                    }
                continue;
            }
            for (uint32_t i = 0; i < point_count; ++i) {
                const float *x = &points[3 * (size_t)i];
                int in_box = 1;
                for (int k = 0; k < 3; ++k)
                    in_box &= x[k] >= q->box_min[k] && x[k] <= q->box_max[k];
                if (in_box)
                    winding[(size_t)id[t] * point_count + i] += solid_angle(p[0], p[1], p[2], x);
            }
        }
    for (uint32_t t = 0; t < triangle_count; ++t) {
        if (parent[t] != t || skip[t] || open[t])
            continue;
        int holds = 0;
        for (uint32_t i = 0; i < point_count; ++i)
            holds |= fabs(winding[(size_t)id[t] * point_count + i]) > 2.0 * M_PI;
        open[t] = !(parts[id[t]].volume > 0.0) || holds;
    }
    free(id);
    free(parts);
    free(winding);
    return 1;
}

gb_result gb_implicit_open_triangles(const float *positions, const uint32_t *indices,
                                     uint32_t triangle_count, const float *points,
                                     uint32_t point_count, uint8_t *open, gb_error *error)
{
    size_t corners = 3 * (size_t)triangle_count, size = table_size(corners);
    uint32_t *welded = malloc(corners * sizeof *welded + 1);
    uint32_t *parent = malloc((size_t)triangle_count * sizeof *parent + 1);
    uint8_t *skip = malloc((size_t)triangle_count + 1);
    edge_uses *edges = malloc(size * sizeof *edges);
    int ok = welded && parent && skip && edges &&
             weld_corners(positions, indices, corners, welded);
    if (ok) {
        for (size_t i = 0; i < size; ++i)
            edges[i].key = UINT64_MAX;
        for (uint32_t t = 0; t < triangle_count; ++t) {
            parent[t] = t;
            const uint32_t *w = &welded[3 * (size_t)t];
            /* two corners at one position: no part */
            skip[t] = w[0] == w[1] || w[1] == w[2] || w[2] == w[0];
            for (int k = 0; !skip[t] && k < 3; ++k)
                use_edge(edges, size, parent, t, w[k], w[(k + 1) % 3]);
        }
        /* A part is open where one of its edges is not used once each way. */
        memset(open, 0, triangle_count);
        for (size_t i = 0; i < size; ++i)
            if (edges[i].key != UINT64_MAX && (edges[i].forward != 1 || edges[i].backward != 1))
                open[gb_union_find_root(parent, edges[i].triangle)] = 1;
        for (uint32_t t = 0; t < triangle_count; ++t)
            parent[t] = gb_union_find_root(parent, t);
        ok = open_closed_parts(positions, indices, triangle_count, parent, skip, points,
                               point_count, open);
        for (uint32_t t = 0; ok && t < triangle_count; ++t)
            open[t] = skip[t] ? 0 : open[parent[t]];
    }
    free(welded);
    free(parent);
    free(skip);
    free(edges);
    return ok ? GB_OK : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
}

gb_result gb_implicit_open_segments(const gb_scene *scene, gb_implicit_model *model,
                                    gb_error *error)
{
    uint8_t *open = malloc((size_t)scene->triangle_count + 1);
    model->segment_open = calloc((size_t)model->segment_count + 1, 1);
    if (!open || !model->segment_open) {
        free(open);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    /* the places an eye or a light may be: the cameras, the point and spot lights */
    uint32_t count = 0;
    size_t most = (size_t)scene->camera_count + scene->light_count;
    float *points = malloc(3 * most * sizeof(float) + 1);
    for (uint32_t i = 0; points && i < scene->camera_count; ++i, ++count)
        memcpy(&points[3 * (size_t)count], scene->cameras[i].position, 3 * sizeof(float));
    for (uint32_t i = 0; points && i < scene->light_count; ++i)
        if (scene->lights[i].type != GB_LIGHT_DIRECTIONAL)
            memcpy(&points[3 * (size_t)count++], scene->lights[i].position, 3 * sizeof(float));
    gb_result result = points ? gb_implicit_open_triangles(scene->positions, scene->indices,
                                                           scene->triangle_count, points, count,
                                                           open, error)
                              : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    free(points);
    for (uint32_t t = 0; result == GB_OK && t < scene->triangle_count; ++t)
        model->segment_open[model->triangle_segment[t]] |= open[t];
    free(open);
    return result;
}
