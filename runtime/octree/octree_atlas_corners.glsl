// The atlas's triangles as octree_atlas.c uploads them: 11 floats a corner
// (atlas UV, world position, shading normal, face normal), 3 corners a
// triangle, at SSBO binding 3; UVs scaled to texels by atlas_size.
layout(std430, binding = 3) readonly buffer Corners { float corners[]; };
uniform vec2 atlas_size;
const uint CORNER_FLOATS = 11u;
vec2 corner_texel(uint t, int c) {
    uint base = (3u * t + uint(c)) * CORNER_FLOATS;
    return vec2(corners[base], corners[base + 1u]) * atlas_size;
}
vec3 corner_vector(uint t, int c, uint offset) {
    uint base = (3u * t + uint(c)) * CORNER_FLOATS + offset;
    return vec3(corners[base], corners[base + 1u], corners[base + 2u]);
}
