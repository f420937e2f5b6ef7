// Implicit visibility's display (Dong 2007, 4.3.1), vertices of the finer
// mesh: each element's incident radiance E / pi on its front and its back
// (Algorithm 1, steps 8-11), to be interpolated over the triangles.
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 incident_front;
layout(location = 2) in vec3 incident_back;
uniform mat4 view;
uniform mat4 projection;
out vec3 vertex_front;
out vec3 vertex_back;
void main() {
    vertex_front = incident_front;
    vertex_back = incident_back;
    gl_Position = projection * (view * vec4(position, 1.0));
}
