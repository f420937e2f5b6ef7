// Forward Light Cuts with implicit visibility (flc_iv.h), the element-id
// pass, triangles of implicit visibility's finer mesh: each fragment gets
// the triangle's three elements (as shown on each side: implicit_hidden.h)
// and its barycentric weights, so that the visibility is interpolated over
// the triangle as implicit visibility's display is (4.3.1).
#version 450 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
flat in uint vertex_front[];
flat in uint vertex_back[];
flat out uvec3 triangle_front;
flat out uvec3 triangle_back;
out vec2 barycentric;           // the weights of corners 1 and 2
void main() {
    uvec3 front = uvec3(vertex_front[0], vertex_front[1], vertex_front[2]);
    uvec3 back = uvec3(vertex_back[0], vertex_back[1], vertex_back[2]);
    for (int k = 0; k < 3; ++k) {
        triangle_front = front;
        triangle_back = back;
        barycentric = vec2(k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
        gl_Position = gl_in[k].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
