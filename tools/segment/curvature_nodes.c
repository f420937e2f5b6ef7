/* curvature_nodes.c — curv(n) = dist(n, L1Lk) / maxball(n), loops opened,
 * lines split at curvature nodes. */
#include "curvature_nodes.h"

#include <math.h>

#include "segmentation.h"

/* Distance from p to the segment [a, b] (to a when a and b coincide). */
static double distance_to_segment(const float p[3], const float a[3], const float b[3])
{
    double ab[3], ap[3], ab2 = 0.0, t = 0.0;
    for (int i = 0; i < 3; ++i) {
        ab[i] = (double)b[i] - (double)a[i];
        ap[i] = (double)p[i] - (double)a[i];
        ab2 += ab[i] * ab[i];
        t += ap[i] * ab[i];
    }
    t = ab2 > 0.0 ? fmin(fmax(t / ab2, 0.0), 1.0) : 0.0;
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        double d = ap[i] - t * ab[i];
        d2 += d * d;
    }
    return sqrt(d2);
}

double gb_curv(const gb_skeleton *s, uint32_t node, uint32_t first, uint32_t last)
{
    double dist = distance_to_segment(s->nodes[node].position, s->nodes[first].position,
                                      s->nodes[last].position);
    return gb_line_ratio(dist, s->nodes[node].radius);
}

/* The interior node of largest curv of a loop path (ties: smaller index). */
static uint32_t loop_split(const gb_skeleton *s, const uint32_t *path, uint32_t length,
                           double *curv)
{
    uint32_t best = 1;
    *curv = gb_curv(s, path[1], path[0], path[0]);
    for (uint32_t i = 2; i + 1 < length; ++i) {
        double c = gb_curv(s, path[i], path[0], path[0]);
        if (c > *curv || (c == *curv && path[i] < path[best])) {
            best = i;
            *curv = c;
        }
    }
    return best;
}

uint32_t gb_open_loops(const gb_skeleton *skeleton, const gb_lines *lines, uint8_t *node_class)
{
    uint32_t opened = 0;
    for (uint32_t i = 0; i < lines->count; ++i) {
        const uint32_t *path = lines->nodes + lines->offsets[i];
        uint32_t length = lines->offsets[i + 1] - lines->offsets[i];
        /* a simple graph has no loop of fewer than two interior nodes */
        if (path[0] != path[length - 1] || length < 3)
            continue;
        double curv;
        uint32_t split = loop_split(skeleton, path, length, &curv);
        node_class[path[split]] = curv > 1.0 ? GB_NODE_CURVATURE : GB_NODE_TOPOLOGY;
        ++opened;
    }
    return opened;
}

gb_result gb_curvature_nodes(const gb_skeleton *skeleton, const gb_lines *lines,
                             uint8_t *node_class, uint32_t *count, gb_error *error)
{
    return gb_lines_split(skeleton, lines, gb_curv, GB_NODE_CURVATURE, node_class, count,
                          error);
}
