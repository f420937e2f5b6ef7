// vdl_direction(uint bits): a VDL's direction as stored (octahedral 2 x 16
// bits, x in bits 0..15) decoded as gb_photon_unpack_direction does. Needs
// runtime/gbuffer_octahedral.glsl before it.
vec3 vdl_direction(uint bits) {
    vec2 q = (vec2(float(bits & 0xffffu), float(bits >> 16)) - 32768.0)
           / 32767.0;
    return oct_decode(q);
}
