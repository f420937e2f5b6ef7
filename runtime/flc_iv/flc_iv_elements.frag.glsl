// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, fragments: the element seen at the pixel.
#version 450 core
flat in uint vertex_element;
out uint element;
void main() { element = vertex_element; }
