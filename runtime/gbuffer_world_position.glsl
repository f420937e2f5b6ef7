// world_position(pixel, size, depth): the world point that pixel of a
// size-pixel target shows at G-buffer depth (reversed, mat4.h). Needs
// gbuffer_textures.glsl's view uniforms before it.
vec3 world_position(ivec2 pixel, ivec2 size, float depth) {
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(size) - 1.0;
    float z = -near / depth;
    return (view_to_world * vec4(ndc * tan_half_fov * -z, z, 1.0)).xyz;
}
