// The light octree through its atlas (octree_atlas.h): Kd / π times the
// irradiance the atlas holds at the pixel's UV, in the layer of the side
// seen, one bilinear fetch.
#version 450 core
#include "runtime/gbuffer_textures.glsl"
layout(binding = 7) uniform sampler2DArray atlas;
layout(binding = 8) uniform sampler2D seen_uv;
out vec4 radiance;
const float PI = 3.14159265358979;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 uv = texelFetch(seen_uv, pixel, 0).xyz;
    if (texelFetch(gbuffer_depth, pixel, 0).r <= 0.0 || uv.x < 0.0) {
        radiance = vec4(0.0);
        return;
    }
    vec3 Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;
    radiance = vec4(Kd / PI * texture(atlas, uv).rgb, 0.0);
}
