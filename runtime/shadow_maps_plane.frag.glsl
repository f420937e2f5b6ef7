// 2-D shadow map: depth only, nothing to write.
#version 450 core
void main() {
}
