// The geometry pass (Noël & Biri 2014, V.A), fragments: the G-buffer's
// layers (gbuffer.h). Sides as in common/brdf.h: the geometric normal
// turned toward the viewer (the front face is cross(v1 - v0, v2 - v0),
// counter-clockwise on screen), the shading normal turned to its side;
// only the front face emits.
#version 450 core
struct Material { vec4 Kd_textured; vec4 Ks_Ns; vec4 Ke; };
layout(std430, binding = 0) readonly buffer Materials { Material materials[]; };
layout(binding = 0) uniform sampler2D diffuse_texture;
in vec3 v_normal;
flat in vec3 v_face_normal;
in vec2 v_texcoord;
flat in uint v_material;
layout(location = 0) out vec4 out_normal;
layout(location = 1) out vec4 out_diffuse;
layout(location = 2) out vec4 out_glossy;
layout(location = 3) out uvec2 out_clusters;
layout(location = 4) out vec4 out_emission;
#include "runtime/gbuffer_octahedral.glsl"
void main() {
    Material m = materials[v_material];
    vec3 ng = normalize(gl_FrontFacing ? v_face_normal : -v_face_normal);
    vec3 n = normalize(v_normal);
    if (!(dot(n, n) > 0.0))
        n = ng;
    if (dot(n, ng) < 0.0)
        n = -n;
    vec3 texel = m.Kd_textured.w > 0.5 ? texture(diffuse_texture, v_texcoord).rgb
                                       : vec3(1.0);
    out_normal = vec4(oct_encode(n), oct_encode(ng));
    out_diffuse = vec4(m.Kd_textured.rgb * texel, 1.0);
    out_glossy = m.Ks_Ns;
    out_clusters = uvec2(0xffffffffu);
    out_emission = vec4(gl_FrontFacing ? m.Ke.rgb : vec3(0.0), 1.0);
}
