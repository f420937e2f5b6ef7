// Cube shadow map, one face: the scene seen from a point light through
// view_projection; v_world, the world position, for the fragment stage.
#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
out vec3 v_world;
void main() {
    v_world = position;
    gl_Position = view_projection * vec4(position, 1.0);
}
