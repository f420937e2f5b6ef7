// The render into the atlas (octree_atlas.h), texels, of one side (`side`
// 1: the side the winding faces, layer 0; -1: the back, layer 1): a texel whose centre
// lies within reach of the triangle takes the octree's irradiance on the
// triangle's plane there (its barycentric weights, extended past the edges),
// alpha 1 (filled); its depth is that distance, so that of several
// triangles the nearest keeps the texel (ties: the first drawn, the smaller
// index). tools/lightmap/texel_cover.c is the CPU twin.
#version 450 core
#include "runtime/octree/octree_atlas_corners.glsl"
uniform float reach;
uniform float side;
flat in uint v_triangle;
out vec4 irradiance;
#include "runtime/octree/octree_irradiance.glsl"
float cross2(vec2 a, vec2 b) {
    return a.x * b.y - a.y * b.x;
}
// The barycentric weights of q in triangle t, and in w the squared
// distance from q to the triangle's nearest point.
vec4 weights_and_distance(uint t, vec2 q) {
    vec2 p[3] = vec2[3](corner_texel(t, 0), corner_texel(t, 1), corner_texel(t, 2));
    float area = cross2(p[1] - p[0], p[2] - p[0]);
    vec3 w = vec3(cross2(p[2] - p[1], q - p[1]), cross2(p[0] - p[2], q - p[2]),
                  cross2(p[1] - p[0], q - p[0])) / area;
    if (all(greaterThanEqual(w, vec3(0.0))))
        return vec4(w, 0.0);
    float nearest = 1e30;
    for (int e = 0; e < 3; ++e) {
        vec2 a = p[e], b = p[(e + 1) % 3];
        float s = clamp(dot(q - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
        vec2 d = q - mix(a, b, s);
        nearest = min(nearest, dot(d, d));
    }
    return vec4(w, nearest);
}
void main() {
    uint t = v_triangle;
    vec4 point = weights_and_distance(t, floor(gl_FragCoord.xy) + 0.5);
    if (point.w > reach * reach)
        discard;
    gl_FragDepth = 0.5 * point.w / max(reach * reach, 1e-6);
    vec3 x = vec3(0.0), n = vec3(0.0), ng = side * normalize(corner_vector(t, 0, 8u));
    for (int c = 0; c < 3; ++c) {
        x += point[c] * corner_vector(t, c, 2u);
        n += point[c] * corner_vector(t, c, 5u);
    }
    n = length(n) > 0.0 ? normalize(n) : ng;
    if (dot(n, ng) < 0.0)
        n = -n;
    irradiance = vec4(interpolate(x, n, ng), 1.0);
}
