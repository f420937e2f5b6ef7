// FLC's divergent pipeline, tessellation evaluation: each sub-vertex in
// model space with v_rand_tess, a hash of its barycentric coordinates
// (Fig. 8: the pattern depends only on the area, so the value follows the
// sub-vertex from frame to frame). After flc.c's prelude (#version and
// TESS_GRID).
layout(triangles, equal_spacing, ccw) in;
struct Triangle { vec4 p0_material; vec4 p1_key; vec4 p2_area; };
layout(std430, binding = 3) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };
in vec2 c_ab[];
patch in uint c_patch;
out vec3 e_position;
out uint e_random;
out uint e_patch;
#include "runtime/flc/flc_hash.glsl"
void main() {
    vec3 w = gl_TessCoord;
    vec2 ab = w.x * c_ab[0] + w.y * c_ab[1] + w.z * c_ab[2];
    Triangle t = triangles[patches[c_patch].x];
    vec3 p0 = t.p0_material.xyz;
    e_position = p0 + ab.x * (t.p1_key.xyz - p0) + ab.y * (t.p2_area.xyz - p0);
    uvec2 g = uvec2(round(clamp(ab, 0.0, 1.0) * TESS_GRID)); // gb_flc_tess_coord_random
    e_random = flc_hash(flc_hash(g.x) ^ (g.y * 0x9e3779b9u));
    e_patch = c_patch;
    gl_Position = vec4(0.0);
}
