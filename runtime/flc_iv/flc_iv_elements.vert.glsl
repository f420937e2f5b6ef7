// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, vertices of implicit visibility's finer mesh: each triangle takes
// the element of its provoking vertex, as shown on each side (a hidden
// side shows a seen element of its surface: implicit_hidden.h).
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in uint element_front;
layout(location = 2) in uint element_back;
uniform mat4 view;
uniform mat4 projection;
flat out uint vertex_front;
flat out uint vertex_back;
void main() {
    vertex_front = element_front;
    vertex_back = element_back;
    gl_Position = projection * (view * vec4(position, 1.0));
}
