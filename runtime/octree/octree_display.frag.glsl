// The light octree's display (Vivianloc 2007, §4.2): at the pixel's world
// point, the VDL sums of the 8 leaves around it (each walked from the root,
// Figure 6), trilinear between the leaf centres over those with VDLs (the
// holes of Fig. 16c), times Kd / π (octree.h).
#version 450 core
#include "runtime/gbuffer_textures.glsl"
uniform ivec2 full_size;
out vec4 radiance;
#include "runtime/gbuffer_world_position.glsl"
#include "runtime/octree/octree_irradiance.glsl"
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float d = texelFetch(gbuffer_depth, pixel, 0).r;
    if (d <= 0.0) {
        radiance = vec4(0.0);
        return;
    }
    vec3 x = world_position(pixel, full_size, d);
    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);
    mat3 rotation = mat3(view_to_world);
    vec3 n = normalize(rotation * oct_decode(normals.xy));
    vec3 ng = normalize(rotation * oct_decode(normals.zw));
    vec3 Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;
    radiance = vec4(Kd / PI * interpolate(x, n, ng), 0.0);
}
