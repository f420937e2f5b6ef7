// The GLSL twins of gb_flc_hash, gb_flc_uniform and gb_flc_support, f^k of
// Eq. 16 (flc_decimation.h), and the levels' uniforms: N, the last level,
// and D, D_k = sqrt(S0 mu^k) (Eq. 18).
const float PI = 3.14159265358979323846;
uniform int N;
uniform float D[17];
#include "runtime/flc/flc_hash.glsl"
float flc_uniform(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }
float flc_support(int k, float d) {
    if (k > 0 && d <= D[k - 1]) return 0.0;
    if (k > 0 && d < D[k]) return (d - D[k - 1]) / (D[k] - D[k - 1]);
    if (k == N || d <= D[k]) return 1.0;
    if (d < D[k + 1]) return (D[k + 1] - d) / (D[k + 1] - D[k]);
    return 0.0;
}
