// FLC pass 2b: at the receiver x of the pixel, H(t_i, x, n_x) S_k
// f^k(d(t_i, x)) (Eqs. 5, 10, 14, 16) without rho_x / pi, times the number
// of tiles, times flc_visibility (flc.h; flc_unshadowed.frag.glsl: 1). The
// "#version" and flc_visibility come first, from flc.c.
#include "runtime/gbuffer_textures.glsl"
uniform ivec2 full_size;
uniform ivec2 tile_size;
uniform int scale;
uniform float S[16];
uniform float epsilon;
uniform float tile_weight;
flat in vec3 g_position;
flat in vec3 g_normal;
flat in vec3 g_radiosity;
flat in int g_level;
out vec4 splat;
#include "runtime/gbuffer_octahedral.glsl"
#include "runtime/gbuffer_world_position.glsl"
#include "runtime/flc/flc_common.glsl"
void main() {
    ivec2 f = ivec2(gl_FragCoord.xy);
    ivec2 tile = f / tile_size;
    ivec2 pixel = (f - tile * tile_size) * scale + tile;
    if (any(greaterThanEqual(pixel, full_size)))
        discard;
    float depth = texelFetch(gbuffer_depth, pixel, 0).r;
    if (depth <= 0.0)
        discard;
    vec3 x = world_position(pixel, full_size, depth);
    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);
    mat3 rotation = mat3(view_to_world);
    vec3 n = normalize(rotation * oct_decode(normals.xy));
    vec3 ng = normalize(rotation * oct_decode(normals.zw));
    vec3 to_x = x - g_position;
    float r2 = dot(to_x, to_x);
    float along = dot(g_normal, to_x);
    if (!(along > 0.0))
        discard;
    float f_k = flc_support(g_level, r2 / along); // d(t_i, x), Eq. 14
    float r = sqrt(r2);
    vec3 wi = -to_x / r;
    float cos_x = dot(n, wi);
    if (f_k <= 0.0 || cos_x <= 0.0 || dot(ng, wi) <= 0.0)
        discard;
    float visible = flc_visibility(pixel, x, g_position);
    if (visible <= 0.0)
        discard;
    float cos_y = along / r;
    float transfer = cos_x * cos_y / max(r2, epsilon * epsilon); // d_i = max(eps, |xy|)
    splat = vec4(g_radiosity * (transfer * S[g_level] * f_k * tile_weight / PI) * visible, 0.0);
}
