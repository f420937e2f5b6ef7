// flc_hash(v): the GLSL twin of gb_flc_hash (flc_decimation.h), the integer
// hash behind every random value (PCG, Jarzynski & Olano 2020).
uint flc_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
