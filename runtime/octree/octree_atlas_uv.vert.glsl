// The atlas display's UV pass (octree_atlas.h), vertices: the scene seen
// as the G-buffer sees it (gbuffer.vert.glsl's transform), each corner
// carrying its atlas UV, and the view-space point and face normal that
// tell which side is seen.
#version 450 core
layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 position;
layout(location = 3) in vec3 face_normal;
uniform mat4 view;
uniform mat4 projection;
out vec2 v_uv;
out vec3 v_view_position;
flat out vec3 v_view_face_normal;
void main() {
    v_uv = uv;
    vec4 seen = view * vec4(position, 1.0);
    v_view_position = seen.xyz;
    v_view_face_normal = mat3(view) * face_normal;
    gl_Position = projection * seen;
}
