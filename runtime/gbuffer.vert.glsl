// The geometry pass (Noël & Biri 2014, V.A), vertices: view-space normals,
// the texture coordinates and the material for the G-buffer's fragments.
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 face_normal;
layout(location = 3) in vec2 texcoord;
layout(location = 4) in uint material;
uniform mat4 view;
uniform mat4 projection;
out vec3 v_normal;
flat out vec3 v_face_normal;
out vec2 v_texcoord;
flat out uint v_material;
void main() {
    v_normal = mat3(view) * normal;
    v_face_normal = mat3(view) * face_normal;
    v_texcoord = texcoord;
    v_material = material;
    gl_Position = projection * (view * vec4(position, 1.0));
}
