// One round of the atlas's gutter (octree_atlas.h), in one of its two
// layers: a texel no triangle filled takes the mean of its 8 neighbours
// filled before this round.
#version 450 core
layout(binding = 0) uniform sampler2DArray previous;
uniform int layer;
out vec4 texel;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(previous, 0).xy;
    texel = texelFetch(previous, ivec3(p, layer), 0);
    if (texel.a > 0.0)
        return;
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            vec4 neighbour = texelFetch(previous, ivec3(q, layer), 0);
            if (neighbour.a > 0.0) {
                sum += neighbour.rgb;
                count += 1.0;
            }
        }
    texel = count > 0.0 ? vec4(sum / count, 1.0) : vec4(0.0);
}
