// The atlas display's UV pass (octree_atlas.h), pixels: the atlas UV seen,
// and the layer of the side seen (0: the side the winding faces, 1: the
// back).
#version 450 core
in vec2 v_uv;
in vec3 v_view_position;
flat in vec3 v_view_face_normal;
out vec3 uv_layer;
void main() {
    uv_layer = vec3(v_uv, dot(v_view_face_normal, -v_view_position) < 0.0 ? 1.0 : 0.0);
}
