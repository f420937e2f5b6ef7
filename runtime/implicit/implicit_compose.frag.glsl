// Implicit visibility's compose: Kd (the G-buffer's, texture included)
// times the incident radiance of the mesh pass, added onto the output.
#version 450 core
layout(binding = 2) uniform sampler2D gbuffer_depth;
layout(binding = 3) uniform sampler2D gbuffer_diffuse;
layout(binding = 10) uniform sampler2D incident;
out vec4 radiance;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(gbuffer_depth, pixel, 0).r <= 0.0) {
        radiance = vec4(0.0);
        return;
    }
    vec3 Kd = texelFetch(gbuffer_diffuse, pixel, 0).rgb;
    radiance = vec4(Kd * texelFetch(incident, pixel, 0).rgb, 0.0);
}
