// The atlas display's UV pass (octree_atlas.h), pixels: the atlas UV seen.
#version 450 core
in vec2 v_uv;
out vec2 uv;
void main() {
    uv = v_uv;
}
