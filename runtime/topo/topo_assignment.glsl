// LA (Noël & Biri 2014, §V.C) on the GPU, the twin of gb_topo_assign
// (topo_assignment.c): one invocation per geometry cluster walks the VPLs
// in order and calls emit(g, n, vpl, group) for each entry of its list: a
// VPL of the cluster's own visibility cluster (group NO), or one whose
// route group toward it has a route whose gates' cones reach the cluster's
// sphere. The stage that includes this defines emit
// (topo_assignment_count.comp.glsl, topo_assignment_write.comp.glsl).
layout(local_size_x = 64) in;
struct VPL { vec4 position; vec4 normal; vec4 power; };
struct GeometryCluster { vec4 sphere; uvec4 info; };
layout(std430, binding = 3) readonly buffer VPLs { VPL vpls[]; };
struct Gate { vec4 disk; vec4 normal; };
layout(std430, binding = 4) readonly buffer Gates { Gate gates[]; };
layout(std430, binding = 5) buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = 6) writeonly buffer Entries { uvec2 entries[]; };
layout(std430, binding = 7) readonly buffer Clusters { GeometryCluster clusters[]; };
layout(std430, binding = 8) readonly buffer VPLClusters { int vpl_cluster[]; };
layout(std430, binding = 9) readonly buffer GroupOffsets { uint group_offsets[]; };
layout(std430, binding = 10) readonly buffer Routes { uvec4 routes[]; };
layout(std430, binding = 11) readonly buffer Groups { uvec4 groups[]; };
uniform uint cluster_count;
uniform uint vpl_count;
uniform bool gates_on;
const uint NO = 0xffffffffu;
// gb_topo_cone_hits_sphere, operation for operation
bool cone_hits_sphere(vec3 p, vec4 gate, vec3 centre, float radius) {
    vec3 axis = gate.xyz - p;
    float d2 = axis.x * axis.x + axis.y * axis.y + axis.z * axis.z;
    float d = sqrt(d2);
    if (!(d > gate.w))
        return true;
    axis /= d;
    float h = sqrt(d2 + gate.w * gate.w);
    float cos_half = d / h, sin_half = gate.w / h;
    vec3 v = centre - p;
    float l2 = v.x * v.x + v.y * v.y + v.z * v.z;
    float along = v.x * axis.x + v.y * axis.y + v.z * axis.z;
    float l = sqrt(l2);
    if (l <= radius)
        return true;
    float cos_v = along / l;
    float sin_s = radius / l, cos_s = sqrt(max(0.0, 1.0 - sin_s * sin_s));
    float cos_limit = cos_half * cos_s - sin_half * sin_s;
    float sin_limit = sin_half * cos_s + cos_half * sin_s;
    if (sin_limit < 0.0)
        return true;
    return cos_v >= cos_limit;
}
bool route_hits_sphere(vec3 p, uvec4 route, vec3 centre, float radius) {
    return cone_hits_sphere(p, gates[route.x].disk, centre, radius) &&
           (route.y == NO ||
            cone_hits_sphere(p, gates[route.y].disk, centre, radius));
}
void emit(uint g, inout uint n, uint vpl, uint gate);
void main() {
    uint g = gl_GlobalInvocationID.x;
    if (g >= cluster_count)
        return;
    GeometryCluster gc = clusters[g];
    uint n = 0u;
    for (uint v = 0u; v < vpl_count; ++v) {
        int c = vpl_cluster[v];
        if (c < 0)
            continue;
        if (uint(c) == gc.info.x) {
            emit(g, n, v, NO);
            continue;
        }
        if (!gates_on)
            continue;
        uint lo = group_offsets[c], hi = group_offsets[c + 1];
        while (lo < hi) {
            uint mid = lo + (hi - lo) / 2u;
            if (groups[mid].x < gc.info.x) lo = mid + 1u; else hi = mid;
        }
        if (lo == group_offsets[c + 1] || groups[lo].x != gc.info.x)
            continue;
        for (uint k = groups[lo].y; k < groups[lo].y + groups[lo].z; ++k)
            if (route_hits_sphere(vpls[v].position.xyz, routes[k],
                                  gc.sphere.xyz, gc.sphere.w)) {
                emit(g, n, v, lo);
                break;
            }
    }
    ranges[g].y = n;
}
