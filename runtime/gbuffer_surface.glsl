// struct Surface and surface_at(pixel, depth): everything the G-buffer says
// of a pixel, in world space (wo toward the eye). Needs
// gbuffer_textures.glsl and gbuffer_octahedral.glsl before it.
struct Surface { vec3 position, n, ng, wo, Kd, Ks; float Ns; };
Surface surface_at(ivec2 pixel, float depth) {
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(textureSize(gbuffer_depth, 0)) - 1.0;
    float z = -near / depth;
    vec3 view_position = vec3(ndc * tan_half_fov * -z, z);
    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);
    mat3 rotation = mat3(view_to_world);
    Surface s;
    s.position = (view_to_world * vec4(view_position, 1.0)).xyz;
    s.n = normalize(rotation * oct_decode(normals.xy));
    s.ng = normalize(rotation * oct_decode(normals.zw));
    s.wo = normalize(rotation * -view_position);
    s.Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;
    vec4 glossy = texelFetch(gbuffer_glossy, pixel, 0);
    s.Ks = glossy.rgb;
    s.Ns = glossy.a;
    return s;
}
