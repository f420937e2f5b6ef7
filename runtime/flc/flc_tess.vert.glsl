// FLC's divergent pipeline, the second draw (glDrawArraysIndirect of the
// patches, rasterizer off), vertices: the corners of patch gl_VertexID / 3
// in the base triangle's barycentric coordinates (a, b).
#version 450 core
layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };
uniform uint patch_capacity;
out vec2 v_ab;
out uint v_patch;
void main() {
    uint p = uint(gl_VertexID) / 3u, corner = uint(gl_VertexID) % 3u;
    uvec4 q = p < patch_capacity ? patches[p] : uvec4(0u, 0u, 1u, 0u);
    vec2 g = vec2(float(q.y & 255u), float((q.y >> 8) & 255u));
    if ((q.y >> 16) != 0u) // up
        g += corner == 1u ? vec2(1.0, 0.0) : corner == 2u ? vec2(0.0, 1.0) : vec2(0.0);
    else // down
        g += corner == 0u ? vec2(1.0, 0.0) : corner == 1u ? vec2(1.0) : vec2(0.0, 1.0);
    v_ab = g / float(max(q.z, 1u));
    v_patch = p;
}
