// Implicit visibility's display (Dong 2007, 4.3.1), fragments: the
// interpolated incident radiance into the method's own target.
#version 450 core
in vec3 vertex_incident;
out vec4 incident;
void main() { incident = vec4(vertex_incident, 1.0); }
