// LA, first pass: each geometry cluster's count of entries, into
// ranges[g].y (the CPU then sums them into each list's first entry).
#version 450 core
#include "runtime/topo/topo_assignment.glsl"
void emit(uint g, inout uint n, uint vpl, uint gate) { ++n; }
