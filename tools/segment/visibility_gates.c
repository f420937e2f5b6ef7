/* visibility_gates.c — a disk at the middle of every edge between clusters. */
#include "visibility_gates.h"

#include <math.h>
#include <stdlib.h>

/* The gate of edge e; -1 when its nodes coincide. */
static int make_gate(const gb_segmentation *s, uint32_t e, gb_visibility_gate *gate)
{
    uint32_t a = s->edges[2 * e], b = s->edges[2 * e + 1];
    const gb_segmented_node *n1 = &s->nodes[a], *n2 = &s->nodes[b];
    double d[3], length2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        d[i] = (double)n2->position[i] - (double)n1->position[i];
        length2 += d[i] * d[i];
    }
    if (!(length2 > 0.0))
        return -1;
    double length = sqrt(length2);
    for (int i = 0; i < 3; ++i) {
        gate->centre[i] = (float)(0.5 * ((double)n1->position[i] + (double)n2->position[i]));
        gate->normal[i] = (float)(d[i] / length);
    }
    gate->radius = fminf(n1->radius, n2->radius);
    gate->clusters[0] = s->cluster[a];
    gate->clusters[1] = s->cluster[b];
    gate->edge = e;
    return 0;
}

gb_result gb_visibility_gates(gb_segmentation *out, gb_error *error)
{
    uint32_t count = 0;
    for (uint32_t e = 0; e < out->edge_count; ++e)
        count += out->cluster[out->edges[2 * e]] != out->cluster[out->edges[2 * e + 1]];
    out->gates = malloc(count ? count * sizeof *out->gates : 1);
    if (!out->gates)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u gates", count);
    out->gate_count = 0;
    for (uint32_t e = 0; e < out->edge_count; ++e) {
        if (out->cluster[out->edges[2 * e]] == out->cluster[out->edges[2 * e + 1]])
            continue;
        if (make_gate(out, e, &out->gates[out->gate_count]))
            return gb_fail(error, GB_ERROR_INVALID,
                           "edge %u joins two clusters but its nodes coincide", e);
        ++out->gate_count;
    }
    return GB_OK;
}
