// The render into the atlas (octree_atlas.h), vertices: each triangle drawn
// at its atlas UVs (v = 0 at row 0, formats/atlas.h), its edges pushed out
// by `reach` texels (gb_atlas_reach), so that its fragments include every
// texel whose centre lies within reach of it: each corner moved to where
// its two edges, offset, meet (the miter bounded for needles).
#version 450 core
#include "runtime/octree/octree_atlas_corners.glsl"
uniform float reach;
flat out uint v_triangle;
void main() {
    uint t = uint(gl_VertexID) / 3u;
    int k = gl_VertexID % 3;
    vec2 p = corner_texel(t, k);
    vec2 before = normalize(p - corner_texel(t, (k + 2) % 3));
    vec2 after = normalize(corner_texel(t, (k + 1) % 3) - p);
    // counterclockwise: the outside is on the right of each edge
    vec2 out_before = vec2(before.y, -before.x), out_after = vec2(after.y, -after.x);
    vec2 offset = (out_before + out_after) * reach / max(1.0 + dot(out_before, out_after), 0.05);
    v_triangle = t;
    gl_Position = vec4(2.0 * (p + offset) / atlas_size - 1.0, 0.0, 1.0);
}
