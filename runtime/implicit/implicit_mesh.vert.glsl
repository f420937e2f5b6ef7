// Implicit visibility's display (Dong 2007, 4.3.1), vertices of the finer
// mesh: each element's incident radiance E / pi (Algorithm 1, steps 8-11),
// to be interpolated over the triangles.
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 incident;
uniform mat4 view;
uniform mat4 projection;
out vec3 vertex_incident;
void main() {
    vertex_incident = incident;
    gl_Position = projection * (view * vec4(position, 1.0));
}
