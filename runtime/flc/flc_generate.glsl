// FLC pass 1 (Laurent et al. 2016, Sec. 6), what its two pipelines share:
// the regular one's compute pass over the VPL triangles
// (flc_generate.comp.glsl) and the divergent one's geometry shader after the
// tessellation (flc_tess.geom.glsl). The lights; Alg. 1 (flc_level); and
// make_vpl, the VPL of one triangle or none: u_i by Alg. 2, y_i jittered
// over the triangle, the radiosity B = rho E of each side, E(t_i) the
// irradiance of incident_light.glsl's lights on a side of the triangle
// (its geometric normal), shadowed as the direct pass does but through the
// scene-wide maps. Patches is the divergent buffer; Commands the two indirect draws, [0, 4) the tessellation's (3
// vertices a patch), [4, 8) the divergent VPLs' splatting. Needs flc.c's
// prelude (MAX_SUBDIVISION, MAX_TESS_LEVEL).
#include "runtime/lights.glsl"
struct Triangle { vec4 p0_material; vec4 p1_key; vec4 p2_area; };
#include "runtime/flc/flc_vpl.glsl"
layout(std430, binding = 3) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = 4) readonly buffer Albedos { vec4 albedos[]; };
layout(std430, binding = 5) writeonly buffer Vpls { Vpl vpls[]; };
layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };
layout(std430, binding = 7) buffer Commands { uint commands[8]; };
uniform uint u_rand;
uniform bool keep_all;
uniform float S_bar[16];
uniform float S[16];
uniform uint tiles;
#include "runtime/flc/flc_common.glsl"
#include "runtime/spot_falloff.glsl"
#include "runtime/incident_light.glsl"
// The irradiance on the side ng of a triangle at p, from every light.
vec3 irradiance(vec3 p, vec3 ng) {
    vec3 E = vec3(0.0), wi;
    for (int i = 0; i < point_count; ++i)
        E += point_incident(i, p, ng, wi) * max(dot(ng, wi), 0.0);
    for (int i = 0; i < plane_count; ++i)
        E += plane_incident(i, p, ng, wi) * max(dot(ng, wi), 0.0);
    return E;
}
// Alg. 1
int flc_level(float u, float area) {
    if (keep_all)
        return N;
    for (int k = 0; k <= N; ++k)
        if (u < area / S_bar[k])
            return k;
    return -1;
}
bool make_vpl(vec3 p0, vec3 p1, vec3 p2, float area, uint key, uint material,
              out Vpl vpl) {
    uint u_i = flc_hash(key ^ u_rand); // Alg. 2
    int level = flc_level(flc_uniform(u_i), area);
    vec3 e1 = p1 - p0, e2 = p2 - p0;
    vec3 cross_product = cross(e1, e2);
    float twice_area = length(cross_product);
    vpl.position_level = vec4(0.0, 0.0, 0.0, -1.0);
    if (level < 0 || !(twice_area > 0.0) || isinf(twice_area))
        return false;
    uint b1 = flc_hash(u_i), b2 = flc_hash(b1), b3 = flc_hash(b2);
    float s = sqrt(flc_uniform(b1)), v = flc_uniform(b2); // jittered y_i
    vec3 y = p0 + s * (1.0 - v) * e1 + s * v * e2;
    vec3 n = cross_product / twice_area;
    vec3 rho = albedos[material].rgb;
    if (keep_all) // weight area, not S_N
        rho *= 0.5 * twice_area / S[N];
    vpl.position_level = vec4(y, float(level));
    vpl.normal_tile = vec4(n, float(b3 % tiles));
    vpl.front = vec4(rho * irradiance(y, n), 0.0); // radiosity B = rho E
    vpl.back = vec4(rho * irradiance(y, -n), 0.0);
    return true;
}
// The tessellation of a divergent triangle (gb_flc_tessellation).
uvec2 flc_tessellation(float area) {
    float t = sqrt(2.0 / 3.0) * min(sqrt(area / S_bar[N]), float(MAX_SUBDIVISION));
    uint c = max(1u, uint(ceil(t / float(MAX_TESS_LEVEL))));
    return uvec2(c, max(2u, 2u * uint(ceil(t / (2.0 * float(c))))));
}
