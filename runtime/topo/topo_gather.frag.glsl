// IL (Noël & Biri 2014, §V.D): each fragment gathers the VPLs LA assigned
// to its geometry cluster (clusters.y), a VPL stored with a route group
// only when the fragment is in the cone from the VPL through the gates of
// one of its routes (the implicit shadow); each VPL a virtual spherical
// light of radius R (Hasan et al. 2009): G's 1/r^2 becomes the solid angle
// of the sphere over pi R^2 (topo_gather.c).
#version 450 core
struct VPL { vec4 position; vec4 normal; vec4 power; };
layout(std430, binding = 3) readonly buffer VPLs { VPL vpls[]; };
struct Gate { vec4 disk; vec4 normal; };
layout(std430, binding = 4) readonly buffer Gates { Gate gates[]; };
layout(std430, binding = 5) readonly buffer Ranges { uvec2 ranges[]; };
layout(std430, binding = 6) readonly buffer Entries { uvec2 entries[]; };
layout(std430, binding = 10) readonly buffer Routes { uvec4 routes[]; };
layout(std430, binding = 11) readonly buffer Groups { uvec4 groups[]; };
#include "runtime/gbuffer_textures.glsl"
uniform float vsl_radius2;     // R^2
uniform int vpl_count;
uniform bool every_vpl;
out vec4 radiance;
const uint NO = 0xffffffffu;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/brdf.glsl"
#include "runtime/gbuffer_surface.glsl"
// The cone from p through the gate's disk; from within the disk's
// radius, the segment to x through the disk (topo_assignment.c).
bool in_gate_cone(vec3 p, uint gate, vec3 x) {
    vec4 g = gates[gate].disk;
    vec3 axis = g.xyz - p;
    float d = length(axis);
    if (d <= g.w) {
        vec3 n = gates[gate].normal.xyz;
        float dp = dot(p - g.xyz, n), dx = dot(x - g.xyz, n);
        if (!(dp * dx < 0.0))
            return false;
        vec3 q = p + (dp / (dp - dx)) * (x - p) - g.xyz;
        return dot(q, q) <= g.w * g.w;
    }
    float cos_half = d / sqrt(d * d + g.w * g.w);
    vec3 v = x - p;
    return dot(v, axis / d) >= cos_half * length(v);
}
bool in_route(vec3 p, uint route, vec3 x) {
    uvec4 r = routes[route];
    return in_gate_cone(p, r.x, x) && (r.y == NO || in_gate_cone(p, r.y, x));
}
bool in_group(vec3 p, uint group, vec3 x) {
    uvec4 g = groups[group];
    for (uint k = g.y; k < g.y + g.z; ++k)
        if (in_route(p, k, x))
            return true;
    return false;
}
// Omega(d) / (pi R^2), Omega = 2 pi (1 - sqrt(1 - R^2 / d^2)) the solid
// angle of the sphere at distance d, the whole hemisphere within it:
// 2 / (d^2 + d sqrt(d^2 - R^2)) for d > R (no cancellation), 2 / R^2 within.
float vsl_kernel(float d2) {
    return d2 <= vsl_radius2 ? 2.0 / vsl_radius2
                             : 2.0 / (d2 + sqrt(d2 * (d2 - vsl_radius2)));
}
vec3 vpl_light(uint i, Surface s) {
    VPL l = vpls[i];
    vec3 to_vpl = l.position.xyz - s.position;
    float d2 = dot(to_vpl, to_vpl);
    if (d2 <= 0.0)
        return vec3(0.0);
    vec3 wi = to_vpl * inversesqrt(d2);
    float emission = max(0.0, -dot(l.normal.xyz, wi)) / PI;
    float n_dot_wi = dot(s.n, wi);
    if (emission <= 0.0 || dot(s.ng, wi) <= 0.0)
        return vec3(0.0);
    vec3 f = brdf_eval(s.Kd, s.Ks, s.Ns, dot(s.n, s.wo), n_dot_wi, dot(s.wo, wi));
    return f * l.power.rgb * (emission * n_dot_wi * vsl_kernel(d2));
}
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    radiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (depth <= 0.0)
        return;
    Surface s = surface_at(pixel, depth);
    uint g = texelFetch(gbuffer_clusters, pixel, 0).y;
    vec3 L = vec3(0.0);
    if (every_vpl || g == NO) {
        for (int i = 0; i < vpl_count; ++i)
            L += vpl_light(uint(i), s);
    } else {
        uvec2 range = ranges[g];
        for (uint k = range.x; k < range.x + range.y; ++k) {
            uvec2 e = entries[k];
            if (e.y == NO || in_group(vpls[e.x].position.xyz, e.y, s.position))
                L += vpl_light(e.x, s);
        }
    }
    radiance = vec4(L, 1.0);
}
