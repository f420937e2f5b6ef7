/* topo_assignment.c — LA (Noël & Biri 2014, §V.C): the VPLs each geometry
 * cluster gathers. A VPL of the cluster's own visibility cluster is seen
 * (implicitly visible); a VPL of another visibility cluster reaches it only
 * through a gate of the VPL's cluster: the cone with the VPL at its apex
 * around the gate's disk must meet the geometry cluster's bounding sphere,
 * and the VPL is stored with that gate so that IL tests each fragment
 * against the cone. Runs on the CPU. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "topo.h"

gb_result gb_topo_gates_build(const gb_segmentation *s, gb_topo_gates *g, gb_error *error)
{
    memset(g, 0, sizeof *g);
    g->cluster_count = s->cluster_count;
    g->offsets = calloc((size_t)s->cluster_count + 1, sizeof *g->offsets);
    g->gates = malloc(((size_t)s->gate_count * 2 + 1) * sizeof *g->gates);
    if (!g->offsets || !g->gates) {
        gb_topo_gates_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    }
    for (uint32_t i = 0; i < s->gate_count; ++i)
        for (int side = 0; side < 2; ++side)
            if (side == 0 || s->gates[i].clusters[1] != s->gates[i].clusters[0])
                g->offsets[s->gates[i].clusters[side] + 1]++;
    for (uint32_t c = 0; c < s->cluster_count; ++c)
        g->offsets[c + 1] += g->offsets[c];
    uint32_t *fill = calloc((size_t)s->cluster_count + 1, sizeof *fill);
    if (!fill) {
        gb_topo_gates_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    }
    for (uint32_t i = 0; i < s->gate_count; ++i)
        for (int side = 0; side < 2; ++side)
            if (side == 0 || s->gates[i].clusters[1] != s->gates[i].clusters[0]) {
                uint32_t c = s->gates[i].clusters[side];
                g->gates[g->offsets[c] + fill[c]++] = i;
            }
    free(fill);
    return GB_OK;
}

void gb_topo_gates_free(gb_topo_gates *g)
{
    free(g->offsets);
    free(g->gates);
    memset(g, 0, sizeof *g);
}

/* Axis (unit), cos and sin of the half-angle of the cone from p through gate. */
static int gate_cone(const float p[3], const gb_visibility_gate *gate, float axis[3],
                     float *cos_half, float *sin_half)
{
    float d2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
        axis[a] = gate->centre[a] - p[a];
        d2 += axis[a] * axis[a];
    }
    float d = sqrtf(d2);
    if (!(d > gate->radius))    /* the VPL touches the disk: every direction */
        return 0;
    for (int a = 0; a < 3; ++a)
        axis[a] /= d;
    float h = sqrtf(d2 + gate->radius * gate->radius);
    *cos_half = d / h;
    *sin_half = gate->radius / h;
    return 1;
}

int gb_topo_cone_hits_sphere(const float p[3], const gb_visibility_gate *gate,
                             const float centre[3], float radius)
{
    float axis[3], cos_half, sin_half;
    if (!gate_cone(p, gate, axis, &cos_half, &sin_half))
        return 1;
    float v[3], l2 = 0.0f, along = 0.0f;
    for (int a = 0; a < 3; ++a) {
        v[a] = centre[a] - p[a];
        l2 += v[a] * v[a];
        along += v[a] * axis[a];
    }
    float l = sqrtf(l2);
    if (l <= radius)
        return 1;
    /* angle(v, axis) <= half + asin(radius / l) */
    float cos_v = along / l;
    float sin_s = radius / l, cos_s = sqrtf(fmaxf(0.0f, 1.0f - sin_s * sin_s));
    float cos_limit = cos_half * cos_s - sin_half * sin_s;   /* cos(half + s) */
    float sin_limit = sin_half * cos_s + cos_half * sin_s;
    if (sin_limit < 0.0f)       /* half + s beyond pi */
        return 1;
    return cos_v >= cos_limit;
}

int gb_topo_cone_contains(const float p[3], const gb_visibility_gate *gate, const float x[3])
{
    float axis[3], cos_half, sin_half;
    if (!gate_cone(p, gate, axis, &cos_half, &sin_half))
        return 1;
    float v[3], l2 = 0.0f, along = 0.0f;
    for (int a = 0; a < 3; ++a) {
        v[a] = x[a] - p[a];
        l2 += v[a] * v[a];
        along += v[a] * axis[a];
    }
    return along >= cos_half * sqrtf(l2);
}

static int add_entry(gb_topo_assignment *out, uint32_t vpl, uint32_t gate)
{
    if (out->entry_count == out->entry_capacity) {
        uint32_t capacity = out->entry_capacity ? 2 * out->entry_capacity : 4096;
        gb_topo_entry *grown = realloc(out->entries, capacity * sizeof *grown);
        if (!grown)
            return 0;
        out->entries = grown;
        out->entry_capacity = capacity;
    }
    out->entries[out->entry_count++] = (gb_topo_entry){vpl, gate};
    return 1;
}

/* The entries of one geometry cluster. */
static int assign_cluster(const gb_geometry_cluster *g, const gb_vpl_set *vpls,
                          const int32_t *vpl_cluster, const gb_segmentation *s,
                          const gb_topo_gates *gates, gb_topo_visibility visibility,
                          gb_topo_assignment *out)
{
    for (uint32_t v = 0; v < vpls->count; ++v) {
        int32_t c = vpl_cluster[v];
        if (c < 0)
            continue;
        if ((uint32_t)c == g->visibility_cluster) {
            if (!add_entry(out, v, GB_TOPO_NO_GATE))
                return 0;
            continue;
        }
        if (visibility != GB_TOPO_FULL)
            continue;
        for (uint32_t k = gates->offsets[c]; k < gates->offsets[c + 1]; ++k) {
            const gb_visibility_gate *gate = &s->gates[gates->gates[k]];
            if (gb_topo_cone_hits_sphere(vpls->vpls[v].position, gate, g->centre, g->radius) &&
                !add_entry(out, v, gates->gates[k]))
                return 0;
        }
    }
    return 1;
}

gb_result gb_topo_assign(const gb_geometry_clusters *clusters, const gb_vpl_set *vpls,
                         const int32_t *vpl_cluster, const gb_segmentation *s,
                         const gb_topo_gates *gates, gb_topo_visibility visibility,
                         gb_topo_assignment *out, gb_error *error)
{
    out->entry_count = 0;
    if (clusters->count > out->cluster_count || !out->ranges) {
        uint32_t *grown = realloc(out->ranges, ((size_t)clusters->count + 1) * 2 * sizeof *grown);
        if (!grown)
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
        out->ranges = grown;
    }
    out->cluster_count = clusters->count;
    for (uint32_t i = 0; i < clusters->count; ++i) {
        out->ranges[2 * i] = out->entry_count;
        if (!assign_cluster(&clusters->clusters[i], vpls, vpl_cluster, s, gates, visibility, out))
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
        out->ranges[2 * i + 1] = out->entry_count - out->ranges[2 * i];
    }
    return GB_OK;
}

void gb_topo_assignment_free(gb_topo_assignment *assignment)
{
    free(assignment->ranges);
    free(assignment->entries);
    memset(assignment, 0, sizeof *assignment);
}
