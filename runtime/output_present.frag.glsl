// Present: the frame's linear radiance into the window, sRGB-encoded
// (clamped to [0, 1]); scale maps a window pixel to the frame's.
#version 450 core
layout(binding = 0) uniform sampler2D radiance;
uniform vec2 scale;
out vec4 colour;
vec3 srgb(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy * scale);
    colour = vec4(srgb(texelFetch(radiance, pixel, 0).rgb), 1.0);
}
