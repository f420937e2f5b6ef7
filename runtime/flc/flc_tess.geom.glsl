// FLC's divergent pipeline, geometry: the sub-triangle's VPL (u_i from the
// base key XOR the three v_rand_tess, Alg. 2), appended after the regular
// ones and counted in the splatting's indirect draw. After flc.c's prelude.
#include "runtime/flc/flc_generate.glsl"
layout(triangles) in;
layout(points, max_vertices = 1) out;
in vec3 e_position[];
in uint e_random[];
in uint e_patch[];
uniform uint divergent_first;
uniform uint divergent_capacity;
void main() {
    Triangle t = triangles[patches[e_patch[0]].x];
    uint key = floatBitsToUint(t.p1_key.w) ^ e_random[0] ^ e_random[1] ^ e_random[2];
    vec3 p0 = e_position[0], p1 = e_position[1], p2 = e_position[2];
    float area = 0.5 * length(cross(p1 - p0, p2 - p0));
    Vpl vpl;
    if (!make_vpl(p0, p1, p2, area, key, floatBitsToUint(t.p0_material.w), vpl))
        return;
    uint slot = atomicAdd(commands[4], 1u);
    if (slot < divergent_capacity)
        vpls[divergent_first + slot] = vpl;
}
