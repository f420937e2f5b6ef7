// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, fragments: the three elements of the triangle seen at the pixel,
// those of the side seen (the finer triangles keep the scene's winding, as
// in implicit_mesh), and the weights of the second and third as two 16-bit
// fractions.
#version 450 core
flat in uvec3 triangle_front;
flat in uvec3 triangle_back;
in vec2 barycentric;
out uvec4 elements;
void main() {
    uvec3 e = gl_FrontFacing ? triangle_front : triangle_back;
    elements = uvec4(e, packUnorm2x16(clamp(barycentric, 0.0, 1.0)));
}
