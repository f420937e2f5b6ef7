// The first ring of the atlas's gutter (octree_atlas.h): a texel no
// triangle covers, beside texels that are, takes the octree's irradiance
// on the plane of the nearest triangle of its chart: of the triangles
// covering its 8 neighbours, the one whose point nearest the texel's
// centre is nearest (ties: the smaller index), extended to the centre (its
// barycentric weights there, some negative) and evaluated as the render
// into the atlas evaluates a covered texel. A bilinear read inside a
// triangle reaches at most this ring, which thus holds the field the walk
// shows, extended linearly across the border: no seam
// (tools/lightmap/texel_cover.c is the CPU twin).
#version 450 core
layout(std430, binding = 3) readonly buffer Corners { float corners[]; };
layout(binding = 0) uniform sampler2D covered;
layout(binding = 1) uniform usampler2D triangle_ids;
out vec4 irradiance;
#include "runtime/octree/octree_irradiance.glsl"
const uint CORNER_FLOATS = 11u;
vec2 corner_uv(uint t, int c) {
    uint base = (3u * t + uint(c)) * CORNER_FLOATS;
    return vec2(corners[base], corners[base + 1u]) * vec2(textureSize(covered, 0));
}
vec3 corner_vector(uint t, int c, uint offset) {
    uint base = (3u * t + uint(c)) * CORNER_FLOATS + offset;
    return vec3(corners[base], corners[base + 1u], corners[base + 2u]);
}
float cross2(vec2 a, vec2 b) {
    return a.x * b.y - a.y * b.x;
}
// The barycentric weights of q (texel units) in triangle t, and in w the
// squared distance from q to the triangle's nearest point.
vec4 weights_and_distance(uint t, vec2 q) {
    vec2 p[3] = vec2[3](corner_uv(t, 0), corner_uv(t, 1), corner_uv(t, 2));
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
    ivec2 texel = ivec2(gl_FragCoord.xy), size = textureSize(covered, 0);
    irradiance = texelFetch(covered, texel, 0);
    if (irradiance.a > 0.0)
        return;
    vec2 q = vec2(texel) + 0.5;
    uint chosen = 0u;
    vec4 best = vec4(0.0, 0.0, 0.0, 1e30);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 n = texel + ivec2(dx, dy);
            if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size)))
                continue;
            uint id = texelFetch(triangle_ids, n, 0).r;
            if (id == 0u)
                continue;
            vec4 point = weights_and_distance(id - 1u, q);
            if (point.w < best.w || (point.w == best.w && id < chosen)) {
                best = point;
                chosen = id;
            }
        }
    if (chosen == 0u)
        return;
    uint t = chosen - 1u;
    vec3 x = vec3(0.0), n = vec3(0.0), ng = normalize(corner_vector(t, 0, 8u));
    for (int c = 0; c < 3; ++c) {
        x += best[c] * corner_vector(t, c, 2u);
        n += best[c] * corner_vector(t, c, 5u);
    }
    n = length(n) > 0.0 ? normalize(n) : ng;
    if (dot(n, ng) < 0.0)
        n = -n;
    irradiance = vec4(interpolate(x, n, ng), 1.0);
}
