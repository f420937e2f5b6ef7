// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, fragments: the element seen at the pixel, that of the side seen
// (the finer triangles keep the scene's winding, as in implicit_mesh).
#version 450 core
flat in uint vertex_front;
flat in uint vertex_back;
out uint element;
void main() { element = gl_FrontFacing ? vertex_front : vertex_back; }
