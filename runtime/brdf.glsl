// The GLSL twin of common/brdf.h: the same functions under the same names
// (without the gb_ prefix); change both together.
const float PI = 3.14159265358979323846;
float phong_normalization(float Ns) { return (Ns + 2.0) / (2.0 * PI); }
float phong_cos_mirror(float n_dot_wo, float n_dot_wi, float wo_dot_wi) {
    return 2.0 * n_dot_wo * n_dot_wi - wo_dot_wi;
}
float phong_lobe(float Ns, float cos_mirror) {
    return cos_mirror > 0.0 ? phong_normalization(Ns) * pow(cos_mirror, Ns) : 0.0;
}
vec3 brdf_eval(vec3 Kd, vec3 Ks, float Ns, float n_dot_wo, float n_dot_wi,
               float wo_dot_wi) {
    if (n_dot_wo <= 0.0 || n_dot_wi <= 0.0)
        return vec3(0.0);
    float lobe = phong_lobe(Ns, phong_cos_mirror(n_dot_wo, n_dot_wi, wo_dot_wi));
    return Kd / PI + Ks * lobe;
}
#include "runtime/spot_falloff.glsl"
float inverse_square(float r2) { return 1.0 / r2; }
