// FLC's divergent pipeline, tessellation control: every level of the
// patch to its m (0 culls it).
#version 450 core
layout(vertices = 3) out;
layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };
uniform uint patch_capacity;
in vec2 v_ab[];
in uint v_patch[];
out vec2 c_ab[];
patch out uint c_patch;
void main() {
    c_ab[gl_InvocationID] = v_ab[gl_InvocationID];
    if (gl_InvocationID == 0) {
        uint p = v_patch[0];
        float m = p < patch_capacity ? float(patches[p].w) : 0.0; // 0: culled
        gl_TessLevelOuter[0] = m;
        gl_TessLevelOuter[1] = m;
        gl_TessLevelOuter[2] = m;
        gl_TessLevelInner[0] = m;
        c_patch = p;
    }
}
