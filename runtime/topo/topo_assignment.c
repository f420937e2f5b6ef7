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

#include "array_reserve.h"
#include "topo.h"

static uint32_t beyond(const gb_visibility_gate *gate, uint32_t c)
{
    return gate->clusters[0] == c ? gate->clusters[1] : gate->clusters[0];
}

/* The routes out of cluster c, written from routes[0] when routes is not
 * NULL; returns their count. */
static uint32_t routes_of(const gb_segmentation *s, const gb_topo_gates *g, uint32_t c,
                          gb_topo_route *routes)
{
    uint32_t n = 0;
    for (uint32_t k = g->offsets[c]; k < g->offsets[c + 1]; ++k) {
        uint32_t first = g->gates[k], d = beyond(&s->gates[first], c);
        if (routes)
            routes[n] = (gb_topo_route){{first, GB_TOPO_NO_GATE}, d};
        ++n;
        for (uint32_t j = g->offsets[d]; j < g->offsets[d + 1]; ++j) {
            uint32_t second = g->gates[j], e = beyond(&s->gates[second], d);
            if (second == first || e == c)
                continue;
            if (routes)
                routes[n] = (gb_topo_route){{first, second}, e};
            ++n;
        }
    }
    return n;
}

/* By target, then in the order made (qsort is not stable: the order made
 * is kept in the gates' indices, which grow along it within a target). */
static int compare_routes(const void *a, const void *b)
{
    const gb_topo_route *x = a, *y = b;
    if (x->target != y->target)
        return x->target < y->target ? -1 : 1;
    for (int i = 0; i < GB_TOPO_ROUTE_GATES; ++i)
        if (x->gates[i] != y->gates[i])
            return x->gates[i] < y->gates[i] ? -1 : 1;
    return 0;
}

/* The routes of each cluster sorted by target, and one group per (cluster,
 * target): LA tests a VPL against the routes of one group and stores it
 * once, with the group. */
static gb_result build_groups(gb_topo_gates *g, gb_error *error)
{
    uint32_t count = 0;
    for (uint32_t c = 0; c < g->cluster_count; ++c) {
        gb_topo_route *r = &g->routes[g->route_offsets[c]];
        uint32_t n = g->route_offsets[c + 1] - g->route_offsets[c];
        qsort(r, n, sizeof *r, compare_routes);
        for (uint32_t k = 0; k < n; ++k)
            count += k == 0 || r[k].target != r[k - 1].target;
    }
    g->group_offsets = calloc((size_t)g->cluster_count + 1, sizeof *g->group_offsets);
    g->groups = malloc(((size_t)count + 1) * sizeof *g->groups);
    if (!g->group_offsets || !g->groups) {
        gb_topo_gates_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    }
    g->group_count = 0;
    for (uint32_t c = 0; c < g->cluster_count; ++c) {
        for (uint32_t k = g->route_offsets[c]; k < g->route_offsets[c + 1]; ++k) {
            if (k == g->route_offsets[c] || g->routes[k].target != g->routes[k - 1].target)
                g->groups[g->group_count++] = (gb_topo_route_group){g->routes[k].target, k, 0};
            g->groups[g->group_count - 1].count++;
        }
        g->group_offsets[c + 1] = g->group_count;
    }
    return GB_OK;
}

static gb_result build_routes(const gb_segmentation *s, gb_topo_gates *g, gb_error *error)
{
    g->route_offsets = calloc((size_t)g->cluster_count + 1, sizeof *g->route_offsets);
    if (!g->route_offsets) {
        gb_topo_gates_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    }
    for (uint32_t c = 0; c < g->cluster_count; ++c)
        g->route_offsets[c + 1] = g->route_offsets[c] + routes_of(s, g, c, NULL);
    g->route_count = g->route_offsets[g->cluster_count];
    g->routes = malloc(((size_t)g->route_count + 1) * sizeof *g->routes);
    if (!g->routes) {
        gb_topo_gates_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "LA: out of memory");
    }
    for (uint32_t c = 0; c < g->cluster_count; ++c)
        routes_of(s, g, c, &g->routes[g->route_offsets[c]]);
    return build_groups(g, error);
}

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
    return build_routes(s, g, error);
}

void gb_topo_gates_free(gb_topo_gates *g)
{
    free(g->offsets);
    free(g->gates);
    free(g->route_offsets);
    free(g->routes);
    free(g->group_offsets);
    free(g->groups);
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

/* p within the disk's radius of its centre, where the cone degenerates:
 * whether the segment from p to x crosses the disk. */
static int segment_crosses_disk(const float p[3], const gb_visibility_gate *gate,
                                const float x[3])
{
    float dp = 0.0f, dx = 0.0f;
    for (int a = 0; a < 3; ++a) {
        dp += (p[a] - gate->centre[a]) * gate->normal[a];
        dx += (x[a] - gate->centre[a]) * gate->normal[a];
    }
    if (!(dp * dx < 0.0f))
        return 0;
    float t = dp / (dp - dx), r2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
        float q = p[a] + t * (x[a] - p[a]) - gate->centre[a];
        r2 += q * q;
    }
    return r2 <= gate->radius * gate->radius;
}

int gb_topo_cone_contains(const float p[3], const gb_visibility_gate *gate, const float x[3])
{
    float axis[3], cos_half, sin_half;
    if (!gate_cone(p, gate, axis, &cos_half, &sin_half))
        return segment_crosses_disk(p, gate, x);
    float v[3], l2 = 0.0f, along = 0.0f;
    for (int a = 0; a < 3; ++a) {
        v[a] = x[a] - p[a];
        l2 += v[a] * v[a];
        along += v[a] * axis[a];
    }
    return along >= cos_half * sqrtf(l2);
}

uint32_t gb_topo_group_of(const gb_topo_gates *gates, uint32_t from, uint32_t to)
{
    uint32_t lo = gates->group_offsets[from], hi = gates->group_offsets[from + 1];
    while (lo < hi) {       /* groups sorted by target */
        uint32_t mid = lo + (hi - lo) / 2;
        if (gates->groups[mid].target < to)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < gates->group_offsets[from + 1] && gates->groups[lo].target == to
               ? lo : GB_TOPO_NO_GATE;
}

int gb_topo_group_contains(const float p[3], const gb_segmentation *s, const gb_topo_gates *gates,
                           uint32_t group, const float x[3])
{
    const gb_topo_route_group *g = &gates->groups[group];
    for (uint32_t k = g->first; k < g->first + g->count; ++k)
        if (gb_topo_route_contains(p, s, &gates->routes[k], x))
            return 1;
    return 0;
}

int gb_topo_route_contains(const float p[3], const gb_segmentation *s,
                           const gb_topo_route *route, const float x[3])
{
    for (int i = 0; i < GB_TOPO_ROUTE_GATES && route->gates[i] != GB_TOPO_NO_GATE; ++i)
        if (!gb_topo_cone_contains(p, &s->gates[route->gates[i]], x))
            return 0;
    return 1;
}

static int route_hits_sphere(const float p[3], const gb_segmentation *s,
                             const gb_topo_route *route, const float centre[3], float radius)
{
    for (int i = 0; i < GB_TOPO_ROUTE_GATES && route->gates[i] != GB_TOPO_NO_GATE; ++i)
        if (!gb_topo_cone_hits_sphere(p, &s->gates[route->gates[i]], centre, radius))
            return 0;
    return 1;
}

static int add_entry(gb_topo_assignment *out, uint32_t vpl, uint32_t gate)
{
    if (!gb_array_reserve(&out->entries, &out->entry_capacity, out->entry_count + 1,
                          sizeof *out->entries))
        return 0;
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
        uint32_t group = gb_topo_group_of(gates, (uint32_t)c, g->visibility_cluster);
        if (group == GB_TOPO_NO_GATE)
            continue;
        const gb_topo_route_group *routes = &gates->groups[group];
        for (uint32_t k = routes->first; k < routes->first + routes->count; ++k)
            if (route_hits_sphere(vpls->vpls[v].position, s, &gates->routes[k], g->centre,
                                  g->radius)) {
                if (!add_entry(out, v, group))
                    return 0;
                break;
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
