// FLC pass 3: untile and blur into the accumulation: the mean of the
// pixel's 2^tiling block over the pixels of its surface, times rho_x / pi.
#version 450 core
#include "runtime/gbuffer_textures.glsl"
layout(binding = 10) uniform sampler2D splats;
uniform ivec2 full_size;
uniform ivec2 tile_size;
uniform int scale;
out vec4 radiance;
const float PI = 3.14159265358979323846;
#include "runtime/gbuffer_octahedral.glsl"
vec3 splat_at(ivec2 q) {
    ivec2 tile = q % scale;
    return texelFetch(splats, tile * tile_size + q / scale, 0).rgb;
}
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(gbuffer_depth, p, 0).r;
    radiance = vec4(0.0);
    if (depth <= 0.0)
        return;
    vec3 ng = oct_decode(texelFetch(gbuffer_normal, p, 0).zw);
    vec3 sum = vec3(0.0);
    float count = 0.0;
    ivec2 start = p - ivec2(scale / 2);
    for (int j = 0; j < scale; ++j)
        for (int i = 0; i < scale; ++i) {
            ivec2 q = start + ivec2(i, j);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, full_size)))
                continue;
            float depth_q = texelFetch(gbuffer_depth, q, 0).r;
            vec3 ng_q = oct_decode(texelFetch(gbuffer_normal, q, 0).zw);
            bool same = q == p || (depth_q > 0.0 && dot(ng, ng_q) > 0.9 &&
                                   abs(depth / depth_q - 1.0) < 0.05);
            if (same) {
                sum += splat_at(q);
                count += 1.0;
            }
        }
    vec3 rho = texelFetch(gbuffer_diffuse, p, 0).rgb;
    radiance = vec4(rho / PI * sum / count, 0.0);
}
