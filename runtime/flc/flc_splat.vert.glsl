// FLC pass 2 (Laurent et al. 2016), splatting, vertices: one point a VPL,
// its index for the geometry stage.
#version 450 core
flat out int v_index;
void main() {
    v_index = gl_VertexID;
}
