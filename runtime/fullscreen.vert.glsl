// The full-screen triangle, (-1,-1), (3,-1), (-1,3), from gl_VertexID
// alone: no attribute, drawn with gb_gl_draw_fullscreen (gl_util.h).
#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
