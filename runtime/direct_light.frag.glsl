// Direct light (Noël & Biri 2014, V.E): at the pixel's surface, the light
// of every point and plane light (incident_light.glsl) reflected by
// common/brdf.h's BRDF, plus the emission seen; the background where no
// surface was drawn. Directional lights are shadowed through the cascades
// fitted to the view (shadow_cascades.h) once they are.
#version 450 core
#include "runtime/lights.glsl"
struct Cascade { mat4 world_to_clip; vec4 far_texel; };
layout(std430, binding = 3) readonly buffer Cascades { Cascade cascades[]; };
#include "runtime/gbuffer_textures.glsl"
layout(binding = 11) uniform sampler2DArrayShadow shadow_cascades;
layout(binding = 10) uniform sampler2D environment_map;
uniform vec3 environment;
uniform bool has_environment_map;
out vec4 radiance;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/brdf.glsl"
#define SHADOW_CASCADES
#include "runtime/incident_light.glsl"
#include "runtime/gbuffer_surface.glsl"
// f(wo, wi) E dot(n, wi); nothing arrives through the surface.
vec3 reflected(Surface s, vec3 wi, vec3 E) {
    if (dot(s.ng, wi) <= 0.0)
        return vec3(0.0);
    float n_dot_wi = dot(s.n, wi);
    vec3 f = brdf_eval(s.Kd, s.Ks, s.Ns, dot(s.n, s.wo), n_dot_wi, dot(s.wo, wi));
    return f * E * n_dot_wi;
}
vec3 point_light(int i, Surface s) {
    vec3 wi;
    vec3 E = point_incident(i, s.position, s.ng, wi);
    return E == vec3(0.0) ? vec3(0.0) : reflected(s, wi, E);
}
vec3 plane_light(int i, Surface s) {
    vec3 wi;
    vec3 E = plane_incident(i, s.position, s.ng, wi);
    return E == vec3(0.0) ? vec3(0.0) : reflected(s, wi, E);
}
// A directional light's cascade (shadow_cascades.h): the first whose
// slice reaches the surface's depth along the view, with slope_offsets.
float cascade_visibility(int first, vec3 p, vec3 ng, float cos_light) {
    float depth = dot(p - view_to_world[3].xyz, -view_to_world[2].xyz);
    int c = 0;
    while (c + 1 < cascade_count && depth > cascades[first + c].far_texel.x)
        ++c;
    Cascade k = cascades[first + c];
    vec2 offsets = slope_offsets(k.far_texel.y, cos_light);
    return map_visibility(shadow_cascades, k.world_to_clip, first + c, p + ng * offsets.x,
                          DEPTH_BIAS + offsets.y * k.far_texel.z);
}
// The background toward the pixel: formats/environment.h's lat-long
// lookup (row 0 is +y; the middle column looks along -z).
vec3 background(ivec2 pixel) {
    if (!has_environment_map)
        return environment;
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(textureSize(gbuffer_depth, 0)) - 1.0;
    vec3 d = normalize(mat3(view_to_world) * vec3(ndc * tan_half_fov, -1.0));
    float u = atan(d.x, -d.z) / (2.0 * 3.14159265358979) + 0.5;
    float v = acos(clamp(d.y, -1.0, 1.0)) / 3.14159265358979;
    return textureLod(environment_map, vec2(u, v), 0.0).rgb;
}
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    if (depth <= 0.0) {
        radiance = vec4(background(pixel), 1.0);
        return;
    }
    Surface s = surface_at(pixel, depth);
    vec3 L = texelFetch(gbuffer_emission, pixel, 0).rgb;
    for (int i = 0; i < point_count; ++i)
        L += point_light(i, s);
    for (int i = 0; i < plane_count; ++i)
        L += plane_light(i, s);
    radiance = vec4(L, 1.0);
}
