// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, vertices of implicit visibility's finer mesh: each triangle takes
// the element of its provoking vertex.
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in uint element;
uniform mat4 view;
uniform mat4 projection;
flat out uint vertex_element;
void main() {
    vertex_element = element;
    gl_Position = projection * (view * vec4(position, 1.0));
}
