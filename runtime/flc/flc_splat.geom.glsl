// FLC pass 2a: a quad a side of each VPL, over the screen rectangle of the
// ball d(t_i, x) <= D_{k+1} (Eq. 13: centre y + n D/2, radius D/2), put
// in the VPL's tile; the last level covers the screen.
#version 450 core
layout(points) in;
layout(triangle_strip, max_vertices = 8) out;
#include "runtime/flc/flc_vpl.glsl"
layout(std430, binding = 5) readonly buffer Vpls { Vpl vpls[]; };
flat in int v_index[];
flat out vec3 g_position;
flat out vec3 g_normal;
flat out vec3 g_radiosity;
flat out int g_level;
uniform mat4 view_projection;
uniform float near;
uniform ivec2 full_size;
uniform ivec2 tile_size;
uniform ivec2 splat_size;
uniform int scale;
#include "runtime/flc/flc_common.glsl"
struct Side { vec3 position, normal, radiosity; int level; };
void corner(Side side, float x, float y) {
    g_position = side.position;
    g_normal = side.normal;
    g_radiosity = side.radiosity;
    g_level = side.level;
    gl_Position = vec4(2.0 * vec2(x, y) / vec2(splat_size) - 1.0, 0.0, 1.0);
    EmitVertex();
}
// The ball's rectangle in pixels of the full frame; false when off screen.
bool screen_rect(vec3 centre, float radius, out vec2 lo, out vec2 hi) {
    lo = vec2(0.0);
    hi = vec2(full_size);
    vec2 low = vec2(1e30), high = vec2(-1e30);
    for (int c = 0; c < 8; ++c) {
        vec3 s = vec3((c & 1) != 0 ? 1.0 : -1.0, (c & 2) != 0 ? 1.0 : -1.0,
                      (c & 4) != 0 ? 1.0 : -1.0);
        vec4 clip = view_projection * vec4(centre + radius * s, 1.0);
        if (clip.w < 0.5 * near)
            return true;
        low = min(low, clip.xy / clip.w);
        high = max(high, clip.xy / clip.w);
    }
    lo = max(floor((0.5 * low + 0.5) * vec2(full_size)), vec2(0.0));
    hi = min(ceil((0.5 * high + 0.5) * vec2(full_size)), vec2(full_size));
    return all(lessThan(lo, hi));
}
void splat_side(Side side, ivec2 tile) {
    if (side.radiosity == vec3(0.0))
        return;
    vec2 lo, hi;
    if (side.level < N) {
        float R = D[side.level + 1];
        if (!screen_rect(side.position + side.normal * (0.5 * R), 0.5 * R, lo, hi))
            return;
    } else {
        lo = vec2(0.0);
        hi = vec2(full_size);
    }
    vec2 origin = vec2(tile * tile_size);
    vec2 a = origin + floor(lo / float(scale));
    vec2 b = origin + min(ceil(hi / float(scale)), vec2(tile_size));
    corner(side, a.x, a.y);
    corner(side, b.x, a.y);
    corner(side, a.x, b.y);
    corner(side, b.x, b.y);
    EndPrimitive();
}
uniform int vpl_count;
void main() {
    if (v_index[0] >= vpl_count) // past the divergent VPLs' room
        return;
    Vpl vpl = vpls[v_index[0]];
    int level = int(vpl.position_level.w);
    if (level < 0)
        return;
    int t = int(vpl.normal_tile.w);
    ivec2 tile = ivec2(t % scale, t / scale);
    vec3 y = vpl.position_level.xyz, n = vpl.normal_tile.xyz;
    splat_side(Side(y, n, vpl.front.rgb, level), tile);
    splat_side(Side(y, -n, vpl.back.rgb, level), tile);
}
