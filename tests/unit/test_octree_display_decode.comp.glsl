// test_octree_display.c, part 3: VDL directions as the CPU packed them,
// decoded by the octree pass's own GLSL, one invocation each.
#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Packed { uint packed_directions[]; };
layout(std430, binding = 1) writeonly buffer Decoded { vec4 decoded[]; };
uniform uint count;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/octree/octree_vdl_direction.glsl"
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < count)
        decoded[i] = vec4(vdl_direction(packed_directions[i]), 0.0);
}
