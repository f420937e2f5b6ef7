/* implicit_hidden.c — hidden sides of elements and the elements shown in
 * their place (implicit_hidden.h).
 *
 * The finer triangles go into a uniform grid of one element size a cell,
 * each into the cells its box, widened by the hiding distance, overlaps:
 * a triangle that a ray of that length from an element's centre meets
 * lies in the centre's cell. The ray test is Moller-Trumbore in double.
 * Then, a side at a time, a breadth-first pass over the finer mesh's
 * edges within a segment: each layer's hidden elements take, of their
 * neighbours already given one, the shown element nearest to them (ties:
 * the lower index), decided for the whole layer before it is written, so
 * the result does not depend on the order of the scan.
 */
#include "implicit_hidden.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vec3.h"

typedef struct grid {
    float origin[3], cell;
    int dims[3];
    uint32_t *first;            /* cells + 1 */
    uint32_t *triangles;        /* first[cells] */
} grid;

enum { GRID_MAX_CELLS = 1 << 22 };

static uint32_t triangle_segment(const gb_implicit_model *m, uint32_t t)
{
    return m->nodes[m->vertex_element[m->triangles[3 * (size_t)t]]].segment;
}

static const float *corner(const gb_implicit_model *m, uint32_t t, int k)
{
    return &m->vertices[3 * (size_t)m->triangles[3 * (size_t)t + k]];
}

static int cell_of(const grid *g, float x, int k)
{
    int c = (int)floorf((x - g->origin[k]) / g->cell);
    return c < 0 ? 0 : c >= g->dims[k] ? g->dims[k] - 1 : c;
}

/* The cells of triangle t's box widened by reach: lo[3], hi[3]. */
static void triangle_cells(const grid *g, const gb_implicit_model *m, uint32_t t, float reach,
                           int lo[3], int hi[3])
{
    for (int k = 0; k < 3; ++k) {
        float a = corner(m, t, 0)[k], b = corner(m, t, 1)[k], c = corner(m, t, 2)[k];
        lo[k] = cell_of(g, fminf(a, fminf(b, c)) - reach, k);
        hi[k] = cell_of(g, fmaxf(a, fmaxf(b, c)) + reach, k);
    }
}

static size_t cell_index(const grid *g, int x, int y, int z)
{
    return ((size_t)z * g->dims[1] + y) * g->dims[0] + x;
}

/* Two passes over the triangles: count a cell's, then fill. */
static gb_result make_grid(const gb_implicit_model *m, float reach, grid *g, gb_error *error)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m->vertex_count; ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = fminf(lo[k], m->vertices[3 * (size_t)v + k]);
            hi[k] = fmaxf(hi[k], m->vertices[3 * (size_t)v + k]);
        }
    g->cell = m->element_size > 0.0f ? m->element_size : 1.0f;
    for (;;) {
        size_t cells = 1;
        for (int k = 0; k < 3; ++k) {
            g->origin[k] = lo[k] - reach;
            g->dims[k] = (int)((hi[k] - lo[k] + 2.0f * reach) / g->cell) + 1;
            cells *= (size_t)g->dims[k];
        }
        if (cells <= GRID_MAX_CELLS)
            break;
        g->cell *= 2.0f;
    }
    size_t cells = (size_t)g->dims[0] * g->dims[1] * g->dims[2];
    g->first = calloc(cells + 1, sizeof *g->first);
    if (!g->first)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    size_t total = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (uint32_t t = 0; t < m->triangle_count; ++t) {
            int a[3], b[3];
            triangle_cells(g, m, t, reach, a, b);
            for (int z = a[2]; z <= b[2]; ++z)
                for (int y = a[1]; y <= b[1]; ++y)
                    for (int x = a[0]; x <= b[0]; ++x) {
                        size_t c = cell_index(g, x, y, z);
                        if (pass == 0)
                            ++g->first[c + 1];
                        else
                            g->triangles[g->first[c]++] = t;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < cells; ++c)
                g->first[c + 1] += g->first[c];
            total = g->first[cells];
            if (total > UINT32_MAX / 2)
                return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: too many triangles");
            g->triangles = malloc(total * sizeof *g->triangles + 1);
            if (!g->triangles)
                return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
        }
    }
    /* the fill moved each first[c] to the next cell's start: back one */
    memmove(&g->first[1], &g->first[0], cells * sizeof *g->first);
    g->first[0] = 0;
    return GB_OK;
}

/* Whether the ray o + s d (d unit), 0 < near < s <= far, meets triangle t,
 * its normal within GB_IMPLICIT_HIDDEN_DEGREES of the ray's line. */
static int ray_meets(const gb_implicit_model *m, uint32_t t, const float o[3], const float d[3],
                     double near, double far)
{
    const float *a = corner(m, t, 0), *b = corner(m, t, 1), *c = corner(m, t, 2);
    double e1[3], e2[3], p[3], s[3], q[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
        s[k] = (double)o[k] - a[k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double n_length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(n_length > 0.0))      /* a degenerate triangle meets nothing */
        return 0;
    double facing = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / n_length;
    if (!(fabs(facing) >= cos(GB_IMPLICIT_HIDDEN_DEGREES * 3.14159265358979323846 / 180.0)))
        return 0;
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    if (u < 0.0 || u > 1.0)
        return 0;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    if (v < 0.0 || u + v > 1.0)
        return 0;
    double distance = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return distance > near && distance <= far;
}

static int side_hidden(const gb_implicit_model *m, const grid *g, uint32_t e, float facing,
                       float reach)
{
    const gb_implicit_node *node = &m->nodes[e];
    float d[3] = {facing * node->normal[0], facing * node->normal[1], facing * node->normal[2]};
    if (!(gb_dot3(d, d) > 0.5f))
        return 0;
    size_t c = cell_index(g, cell_of(g, node->position[0], 0), cell_of(g, node->position[1], 1),
                          cell_of(g, node->position[2], 2));
    for (uint32_t i = g->first[c]; i < g->first[c + 1]; ++i) {
        uint32_t t = g->triangles[i];
        if (triangle_segment(m, t) != node->segment &&
            ray_meets(m, t, node->position, d, 1e-4 * reach, reach))
            return 1;
    }
    return 0;
}

/* The elements joined by a finer triangle's edge within one segment, as
 * lists: neighbours of e at [first[e], first[e + 1]). */
static gb_result make_neighbours(const gb_implicit_model *m, uint32_t **first,
                                 uint32_t **neighbours, gb_error *error)
{
    *first = calloc((size_t)m->element_count + 1, sizeof **first);
    *neighbours = malloc(6 * (size_t)m->triangle_count * sizeof **neighbours + 1);
    if (!*first || !*neighbours)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    for (int pass = 0; pass < 2; ++pass) {
        for (uint32_t t = 0; t < m->triangle_count; ++t)
            for (int k = 0; k < 3; ++k) {
                uint32_t a = m->vertex_element[m->triangles[3 * (size_t)t + k]];
                uint32_t b = m->vertex_element[m->triangles[3 * (size_t)t + (k + 1) % 3]];
                if (a == b || m->nodes[a].segment != m->nodes[b].segment)
                    continue;
                if (pass == 0) {
                    ++(*first)[a + 1];
                    ++(*first)[b + 1];
                } else {
                    (*neighbours)[(*first)[a]++] = b;
                    (*neighbours)[(*first)[b]++] = a;
                }
            }
        if (pass == 0)
            for (uint32_t e = 0; e < m->element_count; ++e)
                (*first)[e + 1] += (*first)[e];
    }
    memmove(&(*first)[1], &(*first)[0], (size_t)m->element_count * sizeof **first);
    (*first)[0] = 0;
    return GB_OK;
}

static float distance2(const gb_implicit_model *m, uint32_t a, uint32_t b)
{
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k) {
        float d = m->nodes[a].position[k] - m->nodes[b].position[k];
        d2 += d * d;
    }
    return d2;
}

/* One side's shown elements (shown[e], NO_NODE while undecided on entry
 * for the hidden ones), layer by layer; next: element_count scratch. */
static void spread_shown(const gb_implicit_model *m, const uint32_t *first,
                         const uint32_t *neighbours, uint32_t *shown, uint32_t *next)
{
    for (;;) {
        int changed = 0;
        for (uint32_t e = 0; e < m->element_count; ++e) {
            next[e] = shown[e];
            if (shown[e] != GB_IMPLICIT_NO_NODE)
                continue;
            float best = INFINITY;
            for (uint32_t i = first[e]; i < first[e + 1]; ++i) {
                uint32_t candidate = shown[neighbours[i]];
                if (candidate == GB_IMPLICIT_NO_NODE)
                    continue;
                float d2 = distance2(m, e, candidate);
                if (d2 < best || (d2 == best && candidate < next[e])) {
                    best = d2;
                    next[e] = candidate;
                }
            }
            changed |= next[e] != GB_IMPLICIT_NO_NODE;
        }
        memcpy(shown, next, (size_t)m->element_count * sizeof *shown);
        if (!changed)
            break;
    }
    for (uint32_t e = 0; e < m->element_count; ++e)
        if (shown[e] == GB_IMPLICIT_NO_NODE)
            shown[e] = e;       /* hidden with all its segment: itself */
}

gb_result gb_implicit_shown_elements(const gb_implicit_model *m, uint32_t *shown,
                                     uint8_t *hidden_out, uint32_t *hidden_count,
                                     gb_error *error)
{
    uint32_t elements = m->element_count;
    float reach = GB_IMPLICIT_HIDDEN_DISTANCE * m->element_size;
    grid g = {0};
    uint32_t *first = NULL, *neighbours = NULL;
    uint32_t *next = malloc((size_t)elements * sizeof *next + 1);
    uint8_t *hidden = calloc(2 * (size_t)elements + 1, 1);
    gb_result result = next && hidden ? GB_OK
                                      : gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                                                "implicit: out of memory");
    if (result == GB_OK)
        result = make_grid(m, reach, &g, error);
    if (result == GB_OK)
        result = make_neighbours(m, &first, &neighbours, error);
    uint32_t count = 0;
    for (int side = 0; result == GB_OK && side < GB_IMPLICIT_SIDES; ++side) {
        uint32_t *side_shown = &shown[(size_t)side * elements];
        uint8_t *side_hidden_flags = &hidden[(size_t)side * elements];
        int any = 0;
        for (uint32_t e = 0; e < elements; ++e) {
            int own = side == GB_IMPLICIT_FRONT || gb_implicit_node_two_sided(m, &m->nodes[e]);
            side_hidden_flags[e] =
                own ? (uint8_t)side_hidden(m, &g, e, side ? -1.0f : 1.0f, reach)
                    : hidden[e];
            any |= side_hidden_flags[e];
            count += own && side_hidden_flags[e];
            side_shown[e] = side_hidden_flags[e] ? GB_IMPLICIT_NO_NODE : e;
        }
        if (any)
            spread_shown(m, first, neighbours, side_shown, next);
        /* a back that is its front's (one-sided) shows what the front shows */
        for (uint32_t e = 0; side == GB_IMPLICIT_BACK && e < elements; ++e)
            if (!gb_implicit_node_two_sided(m, &m->nodes[e]))
                side_shown[e] = shown[e];
    }
    if (result == GB_OK && hidden_out)
        memcpy(hidden_out, hidden, 2 * (size_t)elements);
    if (result == GB_OK && hidden_count)
        *hidden_count = count;
    free(g.first);
    free(g.triangles);
    free(first);
    free(neighbours);
    free(next);
    free(hidden);
    return result;
}
