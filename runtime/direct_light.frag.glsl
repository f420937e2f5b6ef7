// Direct light (Noël & Biri 2014, V.E): at the pixel's surface, the light
// of every point and plane light reflected by common/brdf.h's BRDF, each
// through its shadow map (shadow_maps.h), plus the emission seen; the
// background where no surface was drawn.
#version 450 core
#include "runtime/lights.glsl"
struct Cascade { mat4 world_to_clip; vec4 far_texel; };
layout(std430, binding = 3) readonly buffer Cascades { Cascade cascades[]; };
#include "runtime/gbuffer_textures.glsl"
layout(binding = 11) uniform sampler2DArrayShadow shadow_cascades;
layout(binding = 10) uniform sampler2D environment_map;
uniform vec3 environment;
uniform bool has_environment_map;
uniform int cascade_count;      // a directional light's cascades; 0: not fitted
out vec4 radiance;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/brdf.glsl"
#include "runtime/shadow_bias.glsl"
#include "runtime/gbuffer_surface.glsl"
// f(wo, wi) E dot(n, wi); nothing arrives through the surface.
vec3 reflected(Surface s, vec3 wi, vec3 E) {
    if (dot(s.ng, wi) <= 0.0)
        return vec3(0.0);
    float n_dot_wi = dot(s.n, wi);
    vec3 f = brdf_eval(s.Kd, s.Ks, s.Ns, dot(s.n, s.wo), n_dot_wi, dot(s.wo, wi));
    return f * E * n_dot_wi;
}
// The receiver's offsets for a map of world texel size texel lit at
// cos_light: SLOPE_NORMAL_OFFSET texels along the normal times the sine
// of the incidence, and SLOPE_DEPTH_BIAS texels of depth times its
// tangent, what a texel's footprint spans along the light.
vec2 slope_offsets(float texel, float cos_light) {
    float cosine = clamp(cos_light, 1e-3, 1.0), sine = sqrt(1.0 - cosine * cosine);
    return texel * vec2(SLOPE_NORMAL_OFFSET * sine, SLOPE_DEPTH_BIAS * min(sine / cosine, 10.0));
}
float point_visibility(int i, Surface s, float distance, float cos_light) {
    if (!shadows)
        return 1.0;
    PointLight l = point_lights[i];
    vec2 offsets = slope_offsets(cube_texel * distance, cos_light);
    vec3 d = s.position + s.ng * offsets.x - l.position_range.xyz;
    float reference = (length(d) - offsets.y) / l.position_range.w - DEPTH_BIAS;
    return texture(shadow_cubes, vec4(d, float(i)), reference);
}
vec3 point_light(int i, Surface s) {
    PointLight l = point_lights[i];
    vec3 to_light = l.position_range.xyz - s.position;
    float r2 = dot(to_light, to_light);
    float r = sqrt(r2);
    vec3 wi = to_light / r;
    vec3 I = l.intensity_one_sided.rgb;
    if (l.intensity_one_sided.w > 0.5)
        I *= max(0.0, -dot(l.normal.xyz, wi));
    if (dot(s.ng, wi) <= 0.0 || I == vec3(0.0))
        return vec3(0.0);
    return reflected(s, wi, I / (r2 + l.normal.w)) * point_visibility(i, s, r, dot(s.ng, wi));
}
// The map through world_to_clip at layer of sampler maps, seen from the
// (offset) receiver p, its depth moved by bias.
float map_visibility(sampler2DArrayShadow maps, mat4 world_to_clip, int layer, vec3 p,
                     float bias) {
    vec4 clip = world_to_clip * vec4(p, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return texture(maps, vec4(0.5 * ndc.xy + 0.5, float(layer), ndc.z + bias));
}
// A directional light's cascade (shadow_cascades.h): the first whose
// slice reaches the surface's depth along the view, with slope_offsets.
float cascade_visibility(int first, Surface s, float cos_light) {
    float depth = dot(s.position - view_to_world[3].xyz, -view_to_world[2].xyz);
    int c = 0;
    while (c + 1 < cascade_count && depth > cascades[first + c].far_texel.x)
        ++c;
    Cascade k = cascades[first + c];
    vec2 offsets = slope_offsets(k.far_texel.y, cos_light);
    return map_visibility(shadow_cascades, k.world_to_clip, first + c,
                          s.position + s.ng * offsets.x, DEPTH_BIAS + offsets.y * k.far_texel.z);
}
float plane_visibility(int i, Surface s, float texel, float cos_light) {
    if (!shadows)
        return 1.0;
    int cascade = int(plane_lights[i].cone.z);
    if (cascade >= 0 && cascade_count > 0)
        return cascade_visibility(cascade * cascade_count, s, cos_light);
    return map_visibility(shadow_planes, plane_lights[i].world_to_clip, i,
                          s.position + s.ng * (NORMAL_OFFSET * texel), DEPTH_BIAS);
}
vec3 plane_light(int i, Surface s) {
    PlaneLight l = plane_lights[i];
    vec3 d = l.direction_texel.xyz;
    float texel = l.direction_texel.w;
    if (l.position_kind.w > 0.5) {
        if (dot(s.ng, -d) <= 0.0)
            return vec3(0.0);
        return reflected(s, -d, l.intensity.rgb) * plane_visibility(i, s, texel, dot(s.ng, -d));
    }
    vec3 to_light = l.position_kind.xyz - s.position;
    float r2 = dot(to_light, to_light);
    float r = sqrt(r2);
    vec3 wi = to_light / r;
    float falloff = spot_falloff(dot(d, -wi), l.cone.x, l.cone.y);
    if (falloff <= 0.0 || dot(s.ng, wi) <= 0.0)
        return vec3(0.0);
    float axial = max(dot(d, -to_light), 0.0);
    return reflected(s, wi, l.intensity.rgb * falloff * inverse_square(r2))
           * plane_visibility(i, s, texel * axial, 1.0);
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
