// The render into the atlas (octree_atlas.h), vertices: each triangle
// corner placed at its atlas UV, v = 0 at row 0 (formats/atlas.h).
#version 450 core
layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec3 face_normal;
out vec3 v_position;
out vec3 v_normal;
flat out vec3 v_face_normal;
flat out uint v_triangle;
void main() {
    v_triangle = uint(gl_VertexID) / 3u;
    v_position = position;
    v_normal = normal;
    v_face_normal = face_normal;
    gl_Position = vec4(2.0 * uv - 1.0, 0.0, 1.0);
}
