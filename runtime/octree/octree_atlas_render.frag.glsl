// The render into the atlas (octree_atlas.h), texels: the octree's
// irradiance at the texel's world point, alpha 1 (filled), and the
// triangle that covers it (its index + 1; 0 where none does).
#version 450 core
in vec3 v_position;
in vec3 v_normal;
flat in vec3 v_face_normal;
flat in uint v_triangle;
layout(location = 0) out vec4 irradiance;
layout(location = 1) out uint triangle_id;
#include "runtime/octree/octree_irradiance.glsl"
void main() {
    vec3 ng = normalize(v_face_normal);
    vec3 n = normalize(v_normal);
    if (dot(n, ng) < 0.0)
        n = -n;
    irradiance = vec4(interpolate(v_position, n, ng), 1.0);
    triangle_id = v_triangle + 1u;
}
