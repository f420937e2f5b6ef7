// The light of each of the scene's lights (runtime/lights.glsl) arriving at
// a surface point p of geometric normal ng, shadowed through its map: what
// the direct pass reflects (direct_light.frag.glsl) and FLC's VPLs gather
// (flc/flc_generate.glsl), written once. point_incident and plane_incident
// return the irradiance E on a surface facing the light and set wi, the
// unit direction toward it; E is 0 when no light reaches ng's side.
// Needs runtime/lights.glsl and runtime/spot_falloff.glsl before it. A pass
// that fits cascades to its view (shadow_cascades.h) defines
// SHADOW_CASCADES and, after this file, cascade_visibility.
//
// Shadow-map bias: the receiver moves along ng by NORMAL_OFFSET texels of
// a scene-wide plane map and its compared depth by DEPTH_BIAS; cube maps
// and cascades scale their offsets by the light's incidence
// (slope_offsets), so that surfaces facing the light move little and
// contact shadows stay.
const float NORMAL_OFFSET = 1.5;
const float DEPTH_BIAS = 2e-5;
const float SLOPE_NORMAL_OFFSET = 0.25;
const float SLOPE_DEPTH_BIAS = 0.5;
#ifdef SHADOW_CASCADES
uniform int cascade_count;      // a directional light's cascades; 0: not fitted
float cascade_visibility(int first, vec3 p, vec3 ng, float cos_light);
#endif
// The receiver's offsets for a map of world texel size texel lit at
// cos_light: SLOPE_NORMAL_OFFSET texels along the normal times the sine
// of the incidence, and SLOPE_DEPTH_BIAS texels of depth times its
// tangent, what a texel's footprint spans along the light.
vec2 slope_offsets(float texel, float cos_light) {
    float cosine = clamp(cos_light, 1e-3, 1.0), sine = sqrt(1.0 - cosine * cosine);
    return texel * vec2(SLOPE_NORMAL_OFFSET * sine, SLOPE_DEPTH_BIAS * min(sine / cosine, 10.0));
}
// The map through world_to_clip at layer of sampler maps, seen from the
// (offset) receiver p, its depth moved by bias.
float map_visibility(sampler2DArrayShadow maps, mat4 world_to_clip, int layer, vec3 p,
                     float bias) {
    vec4 clip = world_to_clip * vec4(p, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return texture(maps, vec4(0.5 * ndc.xy + 0.5, float(layer), ndc.z + bias));
}
float point_visibility(int i, vec3 p, vec3 ng, float distance, float cos_light) {
    if (!shadows)
        return 1.0;
    PointLight l = point_lights[i];
    vec2 offsets = slope_offsets(cube_texel * distance, cos_light);
    vec3 d = p + ng * offsets.x - l.position_range.xyz;
    float reference = (length(d) - offsets.y) / l.position_range.w - DEPTH_BIAS;
    return texture(shadow_cubes, vec4(d, float(i)), reference);
}
vec3 point_incident(int i, vec3 p, vec3 ng, out vec3 wi) {
    PointLight l = point_lights[i];
    vec3 to_light = l.position_range.xyz - p;
    float r2 = dot(to_light, to_light);
    float r = sqrt(r2);
    wi = to_light / r;
    vec3 I = l.intensity_one_sided.rgb;
    if (l.intensity_one_sided.w > 0.5)
        I *= max(0.0, -dot(l.normal.xyz, wi));
    float cosine = dot(ng, wi);
    if (cosine <= 0.0 || I == vec3(0.0))
        return vec3(0.0);
    return I / (r2 + l.normal.w) * point_visibility(i, p, ng, r, cosine);
}
float plane_visibility(int i, vec3 p, vec3 ng, float texel, float cos_light) {
    if (!shadows)
        return 1.0;
#ifdef SHADOW_CASCADES
    int cascade = int(plane_lights[i].cone.z);
    if (cascade >= 0 && cascade_count > 0)
        return cascade_visibility(cascade * cascade_count, p, ng, cos_light);
#endif
    return map_visibility(shadow_planes, plane_lights[i].world_to_clip, i,
                          p + ng * (NORMAL_OFFSET * texel), DEPTH_BIAS);
}
vec3 plane_incident(int i, vec3 p, vec3 ng, out vec3 wi) {
    PlaneLight l = plane_lights[i];
    vec3 d = l.direction_texel.xyz;
    float texel = l.direction_texel.w;
    if (l.position_kind.w > 0.5) {
        wi = -d;
        float cosine = dot(ng, wi);
        if (cosine <= 0.0)
            return vec3(0.0);
        return l.intensity.rgb * plane_visibility(i, p, ng, texel, cosine);
    }
    vec3 to_light = l.position_kind.xyz - p;
    float r2 = dot(to_light, to_light);
    wi = to_light / sqrt(r2);
    float falloff = spot_falloff(dot(d, -wi), l.cone.x, l.cone.y);
    if (falloff <= 0.0 || dot(ng, wi) <= 0.0)
        return vec3(0.0);
    float axial = max(dot(d, -to_light), 0.0);
    return l.intensity.rgb * (falloff / r2) * plane_visibility(i, p, ng, texel * axial, 1.0);
}
