// Implicit visibility's display (Dong 2007, 4.3.1), fragments: the
// interpolated incident radiance of the side seen into the method's own
// target. The front face is that of the G-buffer pass (gbuffer.frag.glsl):
// the finer triangles keep the scene's winding, and an element's normal is
// the sum of theirs.
#version 450 core
in vec3 vertex_front;
in vec3 vertex_back;
out vec4 incident;
void main() { incident = vec4(gl_FrontFacing ? vertex_front : vertex_back, 1.0); }
