// Cube shadow map: the depth stored is the distance to the light over its
// range, what the lighting passes compare (shadow_maps.h).
#version 450 core
uniform vec3 light_position;
uniform float range;
in vec3 v_world;
void main() {
    gl_FragDepth = length(v_world - light_position) / range;
}
