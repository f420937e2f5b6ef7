// FLC pass 4: the mean of the accumulated frames, added onto the output.
#version 450 core
layout(binding = 11) uniform sampler2D accumulated;
uniform float inverse_count;
out vec4 radiance;
void main() {
    radiance = vec4(texelFetch(accumulated, ivec2(gl_FragCoord.xy), 0).rgb * inverse_count,
                    0.0);
}
