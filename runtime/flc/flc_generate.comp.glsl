// FLC pass 1 of the regular pipeline (Laurent et al. 2016, Sec. 6): one VPL
// per regular VPL triangle of [first, first + triangle_count), or none
// (level -1); a divergent one (area > S̄_N) is appended instead to the
// divergent buffer as the c x c cells of its barycentric grid (up and down
// triangles: c^2 patches of 3 vertices), each to be tessellated at level m
// (the paper's first pass, which stores the divergent triangles for the
// second, indirect, draw). After flc.c's prelude (#version and constants).
layout(local_size_x = 64) in;
#include "runtime/flc/flc_generate.glsl"
uniform uint first;
uniform uint triangle_count;
uniform uint patch_capacity;
void main() {
    if (gl_GlobalInvocationID.x >= triangle_count)
        return;
    uint i = first + gl_GlobalInvocationID.x;
    Triangle t = triangles[i];
    float area = t.p2_area.w;
    if (area > S_bar[N]) {
        vpls[i].position_level = vec4(0.0, 0.0, 0.0, -1.0);
        uvec2 cm = flc_tessellation(area);
        uint c = cm.x, base = atomicAdd(commands[0], 3u * c * c) / 3u, k = base;
        for (uint b = 0u; b < c; ++b)
            for (uint a = 0u; a + b < c; ++a) {
                if (k < patch_capacity)
                    patches[k] = uvec4(i, a | (b << 8) | (1u << 16), c, cm.y);
                ++k;
                if (a + b + 1u < c && k < patch_capacity)
                    patches[k] = uvec4(i, a | (b << 8), c, cm.y);
                k += a + b + 1u < c ? 1u : 0u;
            }
        return;
    }
    Vpl vpl;
    make_vpl(t.p0_material.xyz, t.p1_key.xyz, t.p2_area.xyz, area,
             floatBitsToUint(t.p1_key.w), floatBitsToUint(t.p0_material.w), vpl);
    vpls[i] = vpl;
}
