// The atlas display's UV pass (octree_atlas.h), vertices: the scene seen
// as the G-buffer sees it (gbuffer.vert.glsl's transform), each corner
// carrying its atlas UV.
#version 450 core
layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 position;
uniform mat4 view;
uniform mat4 projection;
out vec2 v_uv;
void main() {
    v_uv = uv;
    gl_Position = projection * (view * vec4(position, 1.0));
}
