// LA, second pass: each geometry cluster's entries (VPL, route group),
// from ranges[g].x on, in the order of the CPU's list.
#version 450 core
#include "runtime/topo/topo_assignment.glsl"
void emit(uint g, inout uint n, uint vpl, uint gate) {
    entries[ranges[g].x + n] = uvec2(vpl, gate);
    ++n;
}
