#include "flc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gl_util.h"
#include "progress.h"

/* The seed of v_rand (per vertex, at load) and of u_rand (per frame). */
#define FLC_SEED 0x464c43u
enum {
    SSBO_TRIANGLES = 3,
    SSBO_ALBEDOS = 4,
    SSBO_VPLS = 5,
    SSBO_PATCHES = 6,
    SSBO_COMMANDS = 7,
    UNIT_SPLAT = 10,
    UNIT_ACCUMULATED = 11,
    GENERATE_GROUP = 64,
    VPL_BYTES = 64,
};

/* GLSL twins of gb_flc_hash, gb_flc_uniform and gb_flc_support. */
#define GLSL_FLC_COMMON                                                            \
    "const float PI = 3.14159265358979323846;\n"                                   \
    "uniform int N;\n"                                                             \
    "uniform float D[17];\n"                                                       \
    "uint flc_hash(uint v) {\n"                                                    \
    "    uint state = v * 747796405u + 2891336453u;\n"                             \
    "    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;\n"    \
    "    return (word >> 22u) ^ word;\n"                                           \
    "}\n"                                                                          \
    "float flc_uniform(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }\n" \
    "float flc_support(int k, float d) {\n"                                        \
    "    if (k > 0 && d <= D[k - 1]) return 0.0;\n"                                \
    "    if (k > 0 && d < D[k]) return (d - D[k - 1]) / (D[k] - D[k - 1]);\n"        \
    "    if (k == N || d <= D[k]) return 1.0;\n"                                   \
    "    if (d < D[k + 1]) return (D[k + 1] - d) / (D[k + 1] - D[k]);\n"             \
    "    return 0.0;\n"                                                            \
    "}\n"

#define GLSL_VPL                                                                   \
    "struct Vpl { vec4 position_level; vec4 normal_tile; vec4 front; vec4 back; };\n"

/* Pass 1, shared by the regular pipeline (a compute pass over the VPL
 * triangles) and the divergent one (the geometry shader after the
 * tessellation): lights, Alg. 1, and make_vpl, the VPL of one triangle or
 * none. E(t_i) follows runtime/direct_light.c's lights and shadow-map bias,
 * as irradiance on a side of the triangle (its geometric normal). Patches and
 * Commands are the divergent buffer and the two indirect draws (PATCH_*,
 * COMMAND_*). */
static const char generate_common[] =
    "struct PointLight { vec4 position_range; vec4 intensity_one_sided; vec4 normal; };\n"
    "struct PlaneLight { mat4 world_to_clip; vec4 position_kind; vec4 direction_texel;\n"
    "                    vec4 intensity; vec4 cone; };\n"
    "struct Triangle { vec4 p0_material; vec4 p1_key; vec4 p2_area; };\n"
    GLSL_VPL
    "layout(std430, binding = 1) readonly buffer PointLights { PointLight point_lights[]; };\n"
    "layout(std430, binding = 2) readonly buffer PlaneLights { PlaneLight plane_lights[]; };\n"
    "layout(std430, binding = 3) readonly buffer Triangles { Triangle triangles[]; };\n"
    "layout(std430, binding = 4) readonly buffer Albedos { vec4 albedos[]; };\n"
    "layout(std430, binding = 5) writeonly buffer Vpls { Vpl vpls[]; };\n"
    "layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };\n"
    "layout(std430, binding = 7) buffer Commands { uint commands[8]; };\n"
    "layout(binding = 8) uniform samplerCubeArrayShadow shadow_cubes;\n"
    "layout(binding = 9) uniform sampler2DArrayShadow shadow_planes;\n"
    "uniform uint u_rand;\n"
    "uniform bool keep_all;\n"
    "uniform float S_bar[16];\n"
    "uniform float S[16];\n"
    "uniform uint tiles;\n"
    "uniform int point_count;\n"
    "uniform int plane_count;\n"
    "uniform float cube_texel;\n"
    "uniform bool shadows;\n"
    "const float NORMAL_OFFSET = 1.5;\n"
    "const float DEPTH_BIAS = 2e-5;\n"
    GLSL_FLC_COMMON
    "float spot_falloff(float cos_angle, float cone_angle_degrees,\n"
    "                   float falloff_angle_degrees) {\n"
    "    float cos_cone = cos(cone_angle_degrees * (PI / 180.0));\n"
    "    float cos_falloff = cos(falloff_angle_degrees * (PI / 180.0));\n"
    "    if (cos_angle <= cos_cone)\n"
    "        return 0.0;\n"
    "    if (cos_angle >= cos_falloff || cos_falloff <= cos_cone)\n"
    "        return 1.0;\n"
    "    float t = (cos_angle - cos_cone) / (cos_falloff - cos_cone);\n"
    "    return t * t * (3.0 - 2.0 * t);\n"
    "}\n"
    "float point_visibility(int i, vec3 p, vec3 ng, float distance) {\n"
    "    if (!shadows)\n"
    "        return 1.0;\n"
    "    PointLight l = point_lights[i];\n"
    "    vec3 q = p + ng * (NORMAL_OFFSET * cube_texel * distance);\n"
    "    vec3 d = q - l.position_range.xyz;\n"
    "    float reference = length(d) / l.position_range.w - DEPTH_BIAS;\n"
    "    return texture(shadow_cubes, vec4(d, float(i)), reference);\n"
    "}\n"
    "vec3 point_irradiance(int i, vec3 p, vec3 ng) {\n"
    "    PointLight l = point_lights[i];\n"
    "    vec3 to_light = l.position_range.xyz - p;\n"
    "    float r2 = dot(to_light, to_light);\n"
    "    float r = sqrt(r2);\n"
    "    vec3 wi = to_light / r;\n"
    "    vec3 I = l.intensity_one_sided.rgb;\n"
    "    if (l.intensity_one_sided.w > 0.5)\n"
    "        I *= max(0.0, -dot(l.normal.xyz, wi));\n"
    "    float cosine = dot(ng, wi);\n"
    "    if (cosine <= 0.0 || I == vec3(0.0))\n"
    "        return vec3(0.0);\n"
    "    return I * (cosine / r2) * point_visibility(i, p, ng, r);\n"
    "}\n"
    "float plane_visibility(int i, vec3 p, vec3 ng, float texel) {\n"
    "    if (!shadows)\n"
    "        return 1.0;\n"
    "    vec4 clip = plane_lights[i].world_to_clip * vec4(p + ng * (NORMAL_OFFSET * texel), 1.0);\n"
    "    vec3 ndc = clip.xyz / clip.w;\n"
    "    return texture(shadow_planes, vec4(0.5 * ndc.xy + 0.5, float(i), ndc.z + DEPTH_BIAS));\n"
    "}\n"
    "vec3 plane_irradiance(int i, vec3 p, vec3 ng) {\n"
    "    PlaneLight l = plane_lights[i];\n"
    "    vec3 d = l.direction_texel.xyz;\n"
    "    float texel = l.direction_texel.w;\n"
    "    if (l.position_kind.w > 0.5) {\n"
    "        float cosine = dot(ng, -d);\n"
    "        if (cosine <= 0.0)\n"
    "            return vec3(0.0);\n"
    "        return l.intensity.rgb * cosine * plane_visibility(i, p, ng, texel);\n"
    "    }\n"
    "    vec3 to_light = l.position_kind.xyz - p;\n"
    "    float r2 = dot(to_light, to_light);\n"
    "    vec3 wi = to_light / sqrt(r2);\n"
    "    float falloff = spot_falloff(dot(d, -wi), l.cone.x, l.cone.y);\n"
    "    float cosine = dot(ng, wi);\n"
    "    if (falloff <= 0.0 || cosine <= 0.0)\n"
    "        return vec3(0.0);\n"
    "    float axial = max(dot(d, -to_light), 0.0);\n"
    "    return l.intensity.rgb * (falloff * cosine / r2)\n"
    "           * plane_visibility(i, p, ng, texel * axial);\n"
    "}\n"
    "vec3 irradiance(vec3 p, vec3 ng) {\n"
    "    vec3 E = vec3(0.0);\n"
    "    for (int i = 0; i < point_count; ++i)\n"
    "        E += point_irradiance(i, p, ng);\n"
    "    for (int i = 0; i < plane_count; ++i)\n"
    "        E += plane_irradiance(i, p, ng);\n"
    "    return E;\n"
    "}\n"
    /* Alg. 1 */
    "int flc_level(float u, float area) {\n"
    "    if (keep_all)\n"
    "        return N;\n"
    "    for (int k = 0; k <= N; ++k)\n"
    "        if (u < area / S_bar[k])\n"
    "            return k;\n"
    "    return -1;\n"
    "}\n"
    "bool make_vpl(vec3 p0, vec3 p1, vec3 p2, float area, uint key, uint material,\n"
    "              out Vpl vpl) {\n"
    "    uint u_i = flc_hash(key ^ u_rand);\n"                         /* Alg. 2 */
    "    int level = flc_level(flc_uniform(u_i), area);\n"
    "    vec3 e1 = p1 - p0, e2 = p2 - p0;\n"
    "    vec3 cross_product = cross(e1, e2);\n"
    "    float twice_area = length(cross_product);\n"
    "    vpl.position_level = vec4(0.0, 0.0, 0.0, -1.0);\n"
    "    if (level < 0 || !(twice_area > 0.0) || isinf(twice_area))\n"
    "        return false;\n"
    "    uint b1 = flc_hash(u_i), b2 = flc_hash(b1), b3 = flc_hash(b2);\n"
    "    float s = sqrt(flc_uniform(b1)), v = flc_uniform(b2);\n"      /* jittered y_i */
    "    vec3 y = p0 + s * (1.0 - v) * e1 + s * v * e2;\n"
    "    vec3 n = cross_product / twice_area;\n"
    "    vec3 rho = albedos[material].rgb;\n"
    "    if (keep_all)\n"                    /* weight area, not S_N */
    "        rho *= 0.5 * twice_area / S[N];\n"
    "    vpl.position_level = vec4(y, float(level));\n"
    "    vpl.normal_tile = vec4(n, float(b3 % tiles));\n"
    "    vpl.front = vec4(rho * irradiance(y, n), 0.0);\n"      /* radiosity B = rho E */
    "    vpl.back = vec4(rho * irradiance(y, -n), 0.0);\n"
    "    return true;\n"
    "}\n"
    /* The tessellation of a divergent triangle (gb_flc_tessellation). */
    "uvec2 flc_tessellation(float area) {\n"
    "    float t = sqrt(2.0 / 3.0) * min(sqrt(area / S_bar[N]), float(MAX_SUBDIVISION));\n"
    "    uint c = max(1u, uint(ceil(t / float(MAX_TESS_LEVEL))));\n"
    "    return uvec2(c, max(2u, 2u * uint(ceil(t / (2.0 * float(c))))));\n"
    "}\n";

/* Pass 1 of the regular pipeline: one VPL per regular VPL triangle of [first,
 * first + triangle_count), or none (level -1); a divergent one (area > S̄_N)
 * is appended instead to the divergent buffer as the c x c cells of its
 * barycentric grid (up and down triangles: c^2 patches of 3 vertices), each
 * to be tessellated at level m (the paper's first pass, which stores the
 * divergent triangles for the second, indirect, draw). */
static const char generate_main[] =
    "uniform uint first;\n"
    "uniform uint triangle_count;\n"
    "uniform uint patch_capacity;\n"
    "void main() {\n"
    "    if (gl_GlobalInvocationID.x >= triangle_count)\n"
    "        return;\n"
    "    uint i = first + gl_GlobalInvocationID.x;\n"
    "    Triangle t = triangles[i];\n"
    "    float area = t.p2_area.w;\n"
    "    if (area > S_bar[N]) {\n"
    "        vpls[i].position_level = vec4(0.0, 0.0, 0.0, -1.0);\n"
    "        uvec2 cm = flc_tessellation(area);\n"
    "        uint c = cm.x, base = atomicAdd(commands[0], 3u * c * c) / 3u, k = base;\n"
    "        for (uint b = 0u; b < c; ++b)\n"
    "            for (uint a = 0u; a + b < c; ++a) {\n"
    "                if (k < patch_capacity)\n"
    "                    patches[k] = uvec4(i, a | (b << 8) | (1u << 16), c, cm.y);\n"
    "                ++k;\n"
    "                if (a + b + 1u < c && k < patch_capacity)\n"
    "                    patches[k] = uvec4(i, a | (b << 8), c, cm.y);\n"
    "                k += a + b + 1u < c ? 1u : 0u;\n"
    "            }\n"
    "        return;\n"
    "    }\n"
    "    Vpl vpl;\n"
    "    make_vpl(t.p0_material.xyz, t.p1_key.xyz, t.p2_area.xyz, area,\n"
    "             floatBitsToUint(t.p1_key.w), floatBitsToUint(t.p0_material.w), vpl);\n"
    "    vpls[i] = vpl;\n"
    "}\n";

/* The divergent pipeline's second draw (glDrawArraysIndirect of the
 * patches, rasterizer off): the vertex shader puts the corners of patch
 * gl_VertexID / 3 in the base triangle's barycentric coordinates (a, b);
 * the control shader sets every level to m; the evaluation shader makes each
 * sub-vertex in model space with v_rand_tess, a hash of its barycentric
 * coordinates (Fig. 8: the pattern depends only on the area, so the value
 * follows the sub-vertex from frame to frame); the geometry shader makes the
 * sub-triangle's VPL (u_i from the base key XOR the three v_rand_tess, Alg.
 * 2) and appends it after the regular ones, counting it in the splatting's
 * indirect draw. */
static const char tess_vertex_shader[] =
    "#version 450 core\n"
    "layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };\n"
    "uniform uint patch_capacity;\n"
    "out vec2 v_ab;\n"
    "out uint v_patch;\n"
    "void main() {\n"
    "    uint p = uint(gl_VertexID) / 3u, corner = uint(gl_VertexID) % 3u;\n"
    "    uvec4 q = p < patch_capacity ? patches[p] : uvec4(0u, 0u, 1u, 0u);\n"
    "    vec2 g = vec2(float(q.y & 255u), float((q.y >> 8) & 255u));\n"
    "    if ((q.y >> 16) != 0u)\n"                                    /* up */
    "        g += corner == 1u ? vec2(1.0, 0.0) : corner == 2u ? vec2(0.0, 1.0) : vec2(0.0);\n"
    "    else\n"                                                       /* down */
    "        g += corner == 0u ? vec2(1.0, 0.0) : corner == 1u ? vec2(1.0) : vec2(0.0, 1.0);\n"
    "    v_ab = g / float(max(q.z, 1u));\n"
    "    v_patch = p;\n"
    "}\n";

static const char tess_control_shader[] =
    "#version 450 core\n"
    "layout(vertices = 3) out;\n"
    "layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };\n"
    "uniform uint patch_capacity;\n"
    "in vec2 v_ab[];\n"
    "in uint v_patch[];\n"
    "out vec2 c_ab[];\n"
    "patch out uint c_patch;\n"
    "void main() {\n"
    "    c_ab[gl_InvocationID] = v_ab[gl_InvocationID];\n"
    "    if (gl_InvocationID == 0) {\n"
    "        uint p = v_patch[0];\n"
    "        float m = p < patch_capacity ? float(patches[p].w) : 0.0;\n"  /* 0: culled */
    "        gl_TessLevelOuter[0] = m;\n"
    "        gl_TessLevelOuter[1] = m;\n"
    "        gl_TessLevelOuter[2] = m;\n"
    "        gl_TessLevelInner[0] = m;\n"
    "        c_patch = p;\n"
    "    }\n"
    "}\n";

static const char tess_evaluation_shader[] =
    "layout(triangles, equal_spacing, ccw) in;\n"
    "struct Triangle { vec4 p0_material; vec4 p1_key; vec4 p2_area; };\n"
    "layout(std430, binding = 3) readonly buffer Triangles { Triangle triangles[]; };\n"
    "layout(std430, binding = 6) buffer Patches { uvec4 patches[]; };\n"
    "in vec2 c_ab[];\n"
    "patch in uint c_patch;\n"
    "out vec3 e_position;\n"
    "out uint e_random;\n"
    "out uint e_patch;\n"
    "uint flc_hash(uint v) {\n"
    "    uint state = v * 747796405u + 2891336453u;\n"
    "    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;\n"
    "    return (word >> 22u) ^ word;\n"
    "}\n"
    "void main() {\n"
    "    vec3 w = gl_TessCoord;\n"
    "    vec2 ab = w.x * c_ab[0] + w.y * c_ab[1] + w.z * c_ab[2];\n"
    "    Triangle t = triangles[patches[c_patch].x];\n"
    "    vec3 p0 = t.p0_material.xyz;\n"
    "    e_position = p0 + ab.x * (t.p1_key.xyz - p0) + ab.y * (t.p2_area.xyz - p0);\n"
    "    uvec2 g = uvec2(round(clamp(ab, 0.0, 1.0) * TESS_GRID));\n"  /* gb_flc_tess_coord_random */
    "    e_random = flc_hash(flc_hash(g.x) ^ (g.y * 0x9e3779b9u));\n"
    "    e_patch = c_patch;\n"
    "    gl_Position = vec4(0.0);\n"
    "}\n";

static const char tess_geometry_main[] =
    "layout(triangles) in;\n"
    "layout(points, max_vertices = 1) out;\n"
    "in vec3 e_position[];\n"
    "in uint e_random[];\n"
    "in uint e_patch[];\n"
    "uniform uint divergent_first;\n"
    "uniform uint divergent_capacity;\n"
    "void main() {\n"
    "    Triangle t = triangles[patches[e_patch[0]].x];\n"
    "    uint key = floatBitsToUint(t.p1_key.w) ^ e_random[0] ^ e_random[1] ^ e_random[2];\n"
    "    vec3 p0 = e_position[0], p1 = e_position[1], p2 = e_position[2];\n"
    "    float area = 0.5 * length(cross(p1 - p0, p2 - p0));\n"
    "    Vpl vpl;\n"
    "    if (!make_vpl(p0, p1, p2, area, key, floatBitsToUint(t.p0_material.w), vpl))\n"
    "        return;\n"
    "    uint slot = atomicAdd(commands[4], 1u);\n"
    "    if (slot < divergent_capacity)\n"
    "        vpls[divergent_first + slot] = vpl;\n"
    "}\n";

static const char splat_vertex_shader[] =
    "#version 450 core\n"
    "flat out int v_index;\n"
    "void main() {\n"
    "    v_index = gl_VertexID;\n"
    "}\n";

/* Pass 2a: a quad a side, over the screen rectangle of the ball
 * d(t_i, x) <= D_{k+1} (Eq. 13: centre y + n D/2, radius D/2), put in the
 * VPL's tile. */
static const char splat_geometry_shader[] =
    "#version 450 core\n"
    "layout(points) in;\n"
    "layout(triangle_strip, max_vertices = 8) out;\n"
    GLSL_VPL
    "layout(std430, binding = 5) readonly buffer Vpls { Vpl vpls[]; };\n"
    "flat in int v_index[];\n"
    "flat out vec3 g_position;\n"
    "flat out vec3 g_normal;\n"
    "flat out vec3 g_radiosity;\n"
    "flat out int g_level;\n"
    "uniform mat4 view_projection;\n"
    "uniform float near;\n"
    "uniform ivec2 full_size;\n"
    "uniform ivec2 tile_size;\n"
    "uniform ivec2 splat_size;\n"
    "uniform int scale;\n"
    GLSL_FLC_COMMON
    "struct Side { vec3 position, normal, radiosity; int level; };\n"
    "void corner(Side side, float x, float y) {\n"
    "    g_position = side.position;\n"
    "    g_normal = side.normal;\n"
    "    g_radiosity = side.radiosity;\n"
    "    g_level = side.level;\n"
    "    gl_Position = vec4(2.0 * vec2(x, y) / vec2(splat_size) - 1.0, 0.0, 1.0);\n"
    "    EmitVertex();\n"
    "}\n"
    /* The ball's rectangle in pixels of the full frame; false when off screen. */
    "bool screen_rect(vec3 centre, float radius, out vec2 lo, out vec2 hi) {\n"
    "    lo = vec2(0.0);\n"
    "    hi = vec2(full_size);\n"
    "    vec2 low = vec2(1e30), high = vec2(-1e30);\n"
    "    for (int c = 0; c < 8; ++c) {\n"
    "        vec3 s = vec3((c & 1) != 0 ? 1.0 : -1.0, (c & 2) != 0 ? 1.0 : -1.0,\n"
    "                      (c & 4) != 0 ? 1.0 : -1.0);\n"
    "        vec4 clip = view_projection * vec4(centre + radius * s, 1.0);\n"
    "        if (clip.w < 0.5 * near)\n"
    "            return true;\n"
    "        low = min(low, clip.xy / clip.w);\n"
    "        high = max(high, clip.xy / clip.w);\n"
    "    }\n"
    "    lo = max(floor((0.5 * low + 0.5) * vec2(full_size)), vec2(0.0));\n"
    "    hi = min(ceil((0.5 * high + 0.5) * vec2(full_size)), vec2(full_size));\n"
    "    return all(lessThan(lo, hi));\n"
    "}\n"
    "void splat_side(Side side, ivec2 tile) {\n"
    "    if (side.radiosity == vec3(0.0))\n"
    "        return;\n"
    "    vec2 lo, hi;\n"
    "    if (side.level < N) {\n"
    "        float R = D[side.level + 1];\n"
    "        if (!screen_rect(side.position + side.normal * (0.5 * R), 0.5 * R, lo, hi))\n"
    "            return;\n"
    "    } else {\n"
    "        lo = vec2(0.0);\n"
    "        hi = vec2(full_size);\n"
    "    }\n"
    "    vec2 origin = vec2(tile * tile_size);\n"
    "    vec2 a = origin + floor(lo / float(scale));\n"
    "    vec2 b = origin + min(ceil(hi / float(scale)), vec2(tile_size));\n"
    "    corner(side, a.x, a.y);\n"
    "    corner(side, b.x, a.y);\n"
    "    corner(side, a.x, b.y);\n"
    "    corner(side, b.x, b.y);\n"
    "    EndPrimitive();\n"
    "}\n"
    "uniform int vpl_count;\n"
    "void main() {\n"
    "    if (v_index[0] >= vpl_count)\n"     /* past the divergent VPLs' room */
    "        return;\n"
    "    Vpl vpl = vpls[v_index[0]];\n"
    "    int level = int(vpl.position_level.w);\n"
    "    if (level < 0)\n"
    "        return;\n"
    "    int t = int(vpl.normal_tile.w);\n"
    "    ivec2 tile = ivec2(t % scale, t / scale);\n"
    "    vec3 y = vpl.position_level.xyz, n = vpl.normal_tile.xyz;\n"
    "    splat_side(Side(y, n, vpl.front.rgb, level), tile);\n"
    "    splat_side(Side(y, -n, vpl.back.rgb, level), tile);\n"
    "}\n";

/* Pass 2b: at the receiver x of the pixel, H(t_i, x, n_x) S_k f^k(d(t_i, x))
 * (Eqs. 5, 10, 14, 16) without rho_x / pi, times the number of tiles. */
static const char splat_fragment_shader[] =
    "#version 450 core\n"
    "layout(binding = 1) uniform sampler2D gbuffer_normal;\n"
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "uniform mat4 view_to_world;\n"
    "uniform vec2 tan_half_fov;\n"
    "uniform float near;\n"
    "uniform ivec2 full_size;\n"
    "uniform ivec2 tile_size;\n"
    "uniform int scale;\n"
    "uniform float S[16];\n"
    "uniform float epsilon;\n"
    "uniform float tile_weight;\n"
    "flat in vec3 g_position;\n"
    "flat in vec3 g_normal;\n"
    "flat in vec3 g_radiosity;\n"
    "flat in int g_level;\n"
    "out vec4 splat;\n"
    GB_GLSL_OCTAHEDRAL
    GB_GLSL_WORLD_POSITION
    GLSL_FLC_COMMON
    "void main() {\n"
    "    ivec2 f = ivec2(gl_FragCoord.xy);\n"
    "    ivec2 tile = f / tile_size;\n"
    "    ivec2 pixel = (f - tile * tile_size) * scale + tile;\n"
    "    if (any(greaterThanEqual(pixel, full_size)))\n"
    "        discard;\n"
    "    float depth = texelFetch(gbuffer_depth, pixel, 0).r;\n"
    "    if (depth <= 0.0)\n"
    "        discard;\n"
    "    vec3 x = world_position(pixel, full_size, depth);\n"
    "    vec4 normals = texelFetch(gbuffer_normal, pixel, 0);\n"
    "    mat3 rotation = mat3(view_to_world);\n"
    "    vec3 n = normalize(rotation * oct_decode(normals.xy));\n"
    "    vec3 ng = normalize(rotation * oct_decode(normals.zw));\n"
    "    vec3 to_x = x - g_position;\n"
    "    float r2 = dot(to_x, to_x);\n"
    "    float along = dot(g_normal, to_x);\n"
    "    if (!(along > 0.0))\n"
    "        discard;\n"
    "    float f_k = flc_support(g_level, r2 / along);\n"   /* d(t_i, x), Eq. 14 */
    "    float r = sqrt(r2);\n"
    "    vec3 wi = -to_x / r;\n"
    "    float cos_x = dot(n, wi);\n"
    "    if (f_k <= 0.0 || cos_x <= 0.0 || dot(ng, wi) <= 0.0)\n"
    "        discard;\n"
    "    float cos_y = along / r;\n"
    "    float transfer = cos_x * cos_y / max(r2, epsilon * epsilon);\n"  /* d_i = max(eps, |xy|) */
    "    splat = vec4(g_radiosity * (transfer * S[g_level] * f_k * tile_weight / PI), 0.0);\n"
    "}\n";

/* Pass 3: untile and blur into the accumulation: the mean of the pixel's
 * 2^tiling block over the pixels of its surface, times rho_x / pi. */
static const char resolve_shader[] =
    "#version 450 core\n"
    "layout(binding = 1) uniform sampler2D gbuffer_normal;\n"
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(binding = 3) uniform sampler2D gbuffer_diffuse;\n"
    "layout(binding = 10) uniform sampler2D splats;\n"
    "uniform ivec2 full_size;\n"
    "uniform ivec2 tile_size;\n"
    "uniform int scale;\n"
    "out vec4 radiance;\n"
    "const float PI = 3.14159265358979323846;\n"
    GB_GLSL_OCTAHEDRAL
    "vec3 splat_at(ivec2 q) {\n"
    "    ivec2 tile = q % scale;\n"
    "    return texelFetch(splats, tile * tile_size + q / scale, 0).rgb;\n"
    "}\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_FragCoord.xy);\n"
    "    float depth = texelFetch(gbuffer_depth, p, 0).r;\n"
    "    radiance = vec4(0.0);\n"
    "    if (depth <= 0.0)\n"
    "        return;\n"
    "    vec3 ng = oct_decode(texelFetch(gbuffer_normal, p, 0).zw);\n"
    "    vec3 sum = vec3(0.0);\n"
    "    float count = 0.0;\n"
    "    ivec2 start = p - ivec2(scale / 2);\n"
    "    for (int j = 0; j < scale; ++j)\n"
    "        for (int i = 0; i < scale; ++i) {\n"
    "            ivec2 q = start + ivec2(i, j);\n"
    "            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, full_size)))\n"
    "                continue;\n"
    "            float depth_q = texelFetch(gbuffer_depth, q, 0).r;\n"
    "            vec3 ng_q = oct_decode(texelFetch(gbuffer_normal, q, 0).zw);\n"
    "            bool same = q == p || (depth_q > 0.0 && dot(ng, ng_q) > 0.9 &&\n"
    "                                   abs(depth / depth_q - 1.0) < 0.05);\n"
    "            if (same) {\n"
    "                sum += splat_at(q);\n"
    "                count += 1.0;\n"
    "            }\n"
    "        }\n"
    "    vec3 rho = texelFetch(gbuffer_diffuse, p, 0).rgb;\n"
    "    radiance = vec4(rho / PI * sum / count, 0.0);\n"
    "}\n";

/* Pass 4: the mean of the accumulated frames, added onto the output. */
static const char composite_shader[] =
    "#version 450 core\n"
    "layout(binding = 11) uniform sampler2D accumulated;\n"
    "uniform float inverse_count;\n"
    "out vec4 radiance;\n"
    "void main() {\n"
    "    radiance = vec4(texelFetch(accumulated, ivec2(gl_FragCoord.xy), 0).rgb * inverse_count,\n"
    "                    0.0);\n"
    "}\n";

typedef struct flc_state {
    const gb_scene *scene;
    gb_flc_levels levels;
    float epsilon;
    int tiling;
    uint32_t triangle_count, regular_count;   /* regular ones first, divergent ones whole */
    uint32_t patch_capacity, divergent_capacity;  /* room for the tessellation */
    GLuint generate_program, splat_program, tess_program, resolve_program, composite_program;
    GLuint triangle_buffer, albedo_buffer, vpl_buffer, empty_vertex_array;
    GLuint patch_buffer, command_buffer;
    int width, height, tile_width, tile_height;
    GLuint splat_texture, splat_framebuffer, accumulated_texture, accumulated_framebuffer;
    uint32_t accumulated;           /* frames in the accumulation */
    gb_mat4 last_view, last_projection;
    int measuring;
    gb_flc_pass_times times;
} flc_state;

void gb_flc_scene_levels(const gb_scene *scene, const gb_method_parameters *parameters,
                         gb_flc_levels *levels)
{
    double diagonal = 0.0;
    for (int c = 0; c < 3; ++c) {
        double side = (double)scene->bounds_max[c] - scene->bounds_min[c];
        diagonal += side * side;
    }
    double R_scene = 0.5 * sqrt(diagonal);
    double N_avg = parameters->flc_n_avg > 0.0f ? parameters->flc_n_avg : GB_FLC_DEFAULT_N_AVG;
    double mu = parameters->flc_mu > 1.0f ? parameters->flc_mu : GB_FLC_DEFAULT_MU;
    int count = parameters->flc_levels > 0 ? parameters->flc_levels : GB_FLC_DEFAULT_LEVELS;
    gb_flc_levels_make(GB_FLC_D_NEAR_FRACTION * R_scene, N_avg, mu, count - 1, levels);
    levels->keep_all = parameters->flc_levels == GB_FLC_NO_DECIMATION;
}

/* "#version 450 core" and the constants the GLSL shares with
 * flc_decimation.h, into text: the first part of the stages that start
 * without it. */
static const char *flc_prelude(char *text, size_t size)
{
    snprintf(text, size,
             "#version 450 core\n#define MAX_SUBDIVISION %uu\n#define MAX_TESS_LEVEL %uu\n"
             "#define TESS_GRID %u.0\n", (unsigned)GB_FLC_MAX_SUBDIVISION,
             (unsigned)GB_FLC_MAX_TESS_LEVEL, (unsigned)GB_FLC_TESS_GRID);
    return text;
}

static gb_result build_programs(flc_state *s, gb_error *error)
{
    char prelude[256];
    const char *pre = flc_prelude(prelude, sizeof prelude);
    const char *generate[] = {pre, "layout(local_size_x = 64) in;\n", generate_common,
                              generate_main, NULL};
    const char *splat_vertex[] = {splat_vertex_shader, NULL};
    const char *splat_geometry[] = {splat_geometry_shader, NULL};
    const char *splat_fragment[] = {splat_fragment_shader, NULL};
    const char *tess_vertex[] = {tess_vertex_shader, NULL};
    const char *tess_control[] = {tess_control_shader, NULL};
    const char *tess_evaluation[] = {pre, tess_evaluation_shader, NULL};
    const char *tess_geometry[] = {pre, generate_common, tess_geometry_main, NULL};
    const gb_gl_stage generation[] = {{GL_COMPUTE_SHADER, generate}};
    const gb_gl_stage splatting[] = {{GL_VERTEX_SHADER, splat_vertex},
                                     {GL_GEOMETRY_SHADER, splat_geometry},
                                     {GL_FRAGMENT_SHADER, splat_fragment}};
    const gb_gl_stage tessellation[] = {{GL_VERTEX_SHADER, tess_vertex},
                                        {GL_TESS_CONTROL_SHADER, tess_control},
                                        {GL_TESS_EVALUATION_SHADER, tess_evaluation},
                                        {GL_GEOMETRY_SHADER, tess_geometry}};
    gb_result result = gb_gl_program_stages("flc VPL generation", generation, 1,
                                            &s->generate_program, error);
    if (result == GB_OK)
        result = gb_gl_program_stages("flc splatting", splatting, 3, &s->splat_program, error);
    if (result == GB_OK)
        result = gb_gl_program_stages("flc divergent tessellation", tessellation, 4,
                                      &s->tess_program, error);
    if (result == GB_OK)
        result = gb_gl_program("flc untile and blur", gb_gl_fullscreen_vertex_shader,
                               resolve_shader, &s->resolve_program, error);
    if (result == GB_OK)
        result = gb_gl_program("flc composite", gb_gl_fullscreen_vertex_shader,
                               composite_shader, &s->composite_program, error);
    return result;
}

/* rho of every material: Kd, times its texture's mean when it has one. */
static GLuint make_albedo_buffer(const gb_scene *scene)
{
    size_t count = scene->material_count ? scene->material_count : 1;
    float *albedo = calloc(4 * count, sizeof *albedo);
    for (uint32_t m = 0; albedo && m < scene->material_count; ++m) {
        const gb_material *material = &scene->materials[m];
        const gb_texture *texture = &material->texture;
        size_t pixels = (size_t)texture->width * (size_t)texture->height;
        for (int c = 0; c < 3; ++c) {
            double mean = 1.0;
            if (pixels && texture->rgb) {
                mean = 0.0;
                for (size_t i = 0; i < pixels; ++i)
                    mean += texture->rgb[3 * i + c];
                mean /= (double)pixels;
            }
            albedo[4 * m + c] = (float)(material->Kd[c] * mean);
        }
    }
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, (GLsizeiptr)(4 * count * sizeof(float)), albedo, 0);
    free(albedo);
    return buffer;
}

static gb_result make_buffers(flc_state *s, uint64_t seed, gb_error *error)
{
    gb_flc_triangles triangles;
    gb_result result = gb_flc_triangles_build_whole(s->scene, &s->levels, seed, &triangles,
                                                    error);
    if (result != GB_OK)
        return result;
    if (triangles.count + triangles.tessellated_bound > GB_FLC_MAX_TRIANGLES) {
        gb_flc_triangles_free(&triangles);
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "flc: room for %llu VPLs of divergent triangles (at most %u): "
                       "lower N_avg", (unsigned long long)triangles.tessellated_bound,
                       GB_FLC_MAX_TRIANGLES);
    }
    s->triangle_count = triangles.count;
    s->regular_count = triangles.regular_count;
    s->patch_capacity = (uint32_t)triangles.patch_bound;
    s->divergent_capacity = (uint32_t)triangles.tessellated_bound;
    s->times.regular_triangles = triangles.regular_count;
    s->times.divergent_triangles = triangles.divergent_count;
    size_t count = triangles.count ? triangles.count : 1;
    glCreateBuffers(1, &s->triangle_buffer);
    glNamedBufferStorage(s->triangle_buffer, (GLsizeiptr)(count * sizeof *triangles.items),
                         triangles.count ? triangles.items : NULL, 0);
    gb_flc_triangles_free(&triangles);
    glCreateBuffers(1, &s->vpl_buffer);
    glNamedBufferStorage(s->vpl_buffer,
                         (GLsizeiptr)((count + s->divergent_capacity) * VPL_BYTES), NULL, 0);
    glCreateBuffers(1, &s->patch_buffer);
    glNamedBufferStorage(s->patch_buffer,
                         (GLsizeiptr)((s->patch_capacity + 1) * 4 * sizeof(uint32_t)), NULL, 0);
    glCreateBuffers(1, &s->command_buffer);
    glNamedBufferStorage(s->command_buffer, 8 * sizeof(uint32_t), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    s->albedo_buffer = make_albedo_buffer(s->scene);
    glCreateVertexArrays(1, &s->empty_vertex_array);
    return GB_OK;
}

static void destroy_targets(flc_state *s)
{
    GLuint textures[] = {s->splat_texture, s->accumulated_texture};
    GLuint framebuffers[] = {s->splat_framebuffer, s->accumulated_framebuffer};
    for (int i = 0; i < 2; ++i) {
        if (textures[i])
            glDeleteTextures(1, &textures[i]);
        if (framebuffers[i])
            glDeleteFramebuffers(1, &framebuffers[i]);
    }
    s->splat_texture = s->accumulated_texture = 0;
    s->splat_framebuffer = s->accumulated_framebuffer = 0;
    s->width = s->height = 0;
}

static GLuint make_target(int width, int height, GLuint *texture)
{
    GLuint framebuffer;
    *texture = gb_gl_texture_2d(GL_RGBA32F, width, height);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, *texture, 0);
    glNamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    return framebuffer;
}

/* The tiled splat buffer (4^tiling tiles of ceil(size / 2^tiling)) and the
 * accumulation, for a frame of width x height. */
static void prepare_targets(flc_state *s, int width, int height)
{
    if (width == s->width && height == s->height)
        return;
    destroy_targets(s);
    int scale = 1 << s->tiling;
    s->width = width;
    s->height = height;
    s->tile_width = (width + scale - 1) / scale;
    s->tile_height = (height + scale - 1) / scale;
    s->splat_framebuffer = make_target(s->tile_width * scale, s->tile_height * scale,
                                       &s->splat_texture);
    s->accumulated_framebuffer = make_target(width, height, &s->accumulated_texture);
    s->accumulated = 0;
}

static void flc_destroy(void *state)
{
    flc_state *s = state;
    if (!s)
        return;
    destroy_targets(s);
    GLuint programs[] = {s->generate_program, s->splat_program, s->tess_program,
                         s->resolve_program, s->composite_program};
    for (int i = 0; i < 5; ++i)
        if (programs[i])
            glDeleteProgram(programs[i]);
    GLuint buffers[] = {s->triangle_buffer, s->albedo_buffer, s->vpl_buffer, s->patch_buffer,
                        s->command_buffer};
    for (int i = 0; i < 5; ++i)
        if (buffers[i])
            glDeleteBuffers(1, &buffers[i]);
    if (s->empty_vertex_array)
        glDeleteVertexArrays(1, &s->empty_vertex_array);
    free(s);
}

static float default_epsilon(const gb_flc_levels *levels)
{
    return GB_FLC_EPSILON_FRACTION / GB_FLC_D_NEAR_FRACTION * levels->D_near;
}

static gb_result flc_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    const gb_method_parameters *parameters = setup->parameters;
    if (parameters->flc_tiling < 0 || parameters->flc_tiling > GB_FLC_MAX_TILING)
        return gb_fail(error, GB_ERROR_ARGUMENT, "flc: tiling %d is not in 0..%d",
                       parameters->flc_tiling, GB_FLC_MAX_TILING);
    if (parameters->flc_levels > GB_FLC_MAX_LEVELS ||
        (parameters->flc_levels < 0 && parameters->flc_levels != GB_FLC_NO_DECIMATION))
        return gb_fail(error, GB_ERROR_ARGUMENT, "flc: %d levels: at most %d",
                       parameters->flc_levels, GB_FLC_MAX_LEVELS);
    flc_state *s = calloc(1, sizeof *s);
    if (!s)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc: out of memory");
    s->scene = setup->scene;
    s->tiling = parameters->flc_tiling;
    gb_flc_scene_levels(setup->scene, parameters, &s->levels);
    s->epsilon = parameters->flc_epsilon > 0.0f ? parameters->flc_epsilon
                                                : default_epsilon(&s->levels);
    gb_result result = build_programs(s, error);
    if (result == GB_OK)
        result = make_buffers(s, FLC_SEED, error);
    if (result != GB_OK) {
        flc_destroy(s);
        return result;
    }
    prepare_targets(s, setup->width, setup->height);
    *state = s;
    return GB_OK;
}

static void set_int(GLuint program, const char *name, int value)
{
    glProgramUniform1i(program, glGetUniformLocation(program, name), value);
}

static void set_float(GLuint program, const char *name, float value)
{
    glProgramUniform1f(program, glGetUniformLocation(program, name), value);
}

static void set_size(GLuint program, const char *name, int x, int y)
{
    glProgramUniform2i(program, glGetUniformLocation(program, name), x, y);
}

static void set_levels(GLuint program, const gb_flc_levels *levels)
{
    set_int(program, "N", levels->N);
    glProgramUniform1fv(program, glGetUniformLocation(program, "D"), levels->N + 2, levels->D);
}

static void set_tiles(GLuint program, const flc_state *s)
{
    set_size(program, "full_size", s->width, s->height);
    set_size(program, "tile_size", s->tile_width, s->tile_height);
    set_int(program, "scale", 1 << s->tiling);
}

/* Pass 1's uniforms and bindings in program (the compute pass or the
 * tessellation's geometry shader). */
static void prepare_generation(flc_state *s, GLuint program, const gb_indirect_frame *frame)
{
    uint32_t u_rand = gb_flc_hash(frame->frame_index * 0x9e3779b9u ^ gb_flc_hash(FLC_SEED));
    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "u_rand"), u_rand);
    glProgramUniform1ui(program, glGetUniformLocation(program, "tiles"),
                        1u << (2 * s->tiling));
    glProgramUniform1fv(program, glGetUniformLocation(program, "S_bar"), s->levels.N + 1,
                        s->levels.S_bar);
    glProgramUniform1fv(program, glGetUniformLocation(program, "S"), s->levels.N + 1,
                        s->levels.S);
    set_int(program, "keep_all", s->levels.keep_all);
    set_levels(program, &s->levels);
    set_int(program, "point_count", (int)frame->shadows->point_count);
    set_int(program, "plane_count", (int)frame->shadows->plane_count);
    set_float(program, "cube_texel", 2.0f / (float)frame->shadows->cube_size);
    set_int(program, "shadows", frame->shadows->drawn);   /* not drawn with --no-shadows */
    gb_shadow_maps_bind(frame->shadows);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_TRIANGLES, s->triangle_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_ALBEDOS, s->albedo_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_PATCHES, s->patch_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_COMMANDS, s->command_buffer);
    glProgramUniform1ui(program, glGetUniformLocation(program, "patch_capacity"),
                        s->patch_capacity);
}

/* Pass 1 over the VPL triangles [first, first + count). */
static void generate_vpls(flc_state *s, uint32_t first, uint32_t count)
{
    GLuint program = s->generate_program;
    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "first"), first);
    glProgramUniform1ui(program, glGetUniformLocation(program, "triangle_count"), count);
    glDispatchCompute((count + GENERATE_GROUP - 1) / GENERATE_GROUP, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

static void set_splat_uniforms(const flc_state *s, const gb_indirect_frame *frame)
{
    GLuint program = s->splat_program;
    const gb_view *view = frame->view;
    gb_mat4 view_projection = gb_mat4_multiply(frame->projection, frame->view_matrix);
    gb_mat4 view_to_world = gb_view_inverse_matrix(view);
    float tan_y = tanf(0.5f * view->fov_y * 3.14159265358979f / 180.0f);
    float aspect = (float)frame->width / (float)frame->height;
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view_projection"), 1,
                              GL_FALSE, view_projection.m);
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view_to_world"), 1,
                              GL_FALSE, view_to_world.m);
    glProgramUniform2f(program, glGetUniformLocation(program, "tan_half_fov"), tan_y * aspect,
                       tan_y);
    set_float(program, "near", view->near);
    set_size(program, "splat_size", s->tile_width << s->tiling, s->tile_height << s->tiling);
    set_tiles(program, s);
    set_levels(program, &s->levels);
    glProgramUniform1fv(program, glGetUniformLocation(program, "S"), s->levels.N + 1,
                        s->levels.S);
    set_float(program, "epsilon", s->epsilon);
    set_float(program, "tile_weight", (float)(1 << (2 * s->tiling)));
    set_int(program, "vpl_count", (int)(s->triangle_count + s->divergent_capacity));
}

/* Pass 2's target, uniforms and bindings. */
static void prepare_splatting(flc_state *s, const gb_indirect_frame *frame)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat_framebuffer);
    glViewport(0, 0, s->tile_width << s->tiling, s->tile_height << s->tiling);
    glUseProgram(s->splat_program);
    set_splat_uniforms(s, frame);
    gb_gbuffer_bind(frame->gbuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glBindVertexArray(s->empty_vertex_array);
}

/* Pass 2 of the VPLs of [first, first + count). */
static void splat_vpls(flc_state *s, uint32_t first, uint32_t count)
{
    glUseProgram(s->splat_program);
    glBindVertexArray(s->empty_vertex_array);
    glDrawArrays(GL_POINTS, (GLint)first, (GLsizei)count);
}

/* The regular pipeline: VPLs of the regular triangles, generated then
 * splatted. */
static void run_regular(flc_state *s, const gb_indirect_frame *frame)
{
    if (!s->regular_count)
        return;
    prepare_generation(s, s->generate_program, frame);
    generate_vpls(s, 0, s->regular_count);
    prepare_splatting(s, frame);
    splat_vpls(s, 0, s->regular_count);
}

/* The divergent pipeline: the compute pass appends the divergent triangles'
 * cells to the divergent buffer and counts them in the first indirect draw,
 * which tessellates them and appends their VPLs after the regular ones,
 * counting them in the second indirect draw, the splatting. No CPU wait. */
static void run_divergent(flc_state *s, const gb_indirect_frame *frame)
{
    uint32_t divergent = s->triangle_count - s->regular_count;
    if (!divergent)
        return;
    const uint32_t commands[8] = {0, 1, 0, 0, 0, 1, s->triangle_count, 0};
    glNamedBufferSubData(s->command_buffer, 0, sizeof commands, commands);
    prepare_generation(s, s->generate_program, frame);
    generate_vpls(s, s->regular_count, divergent);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    GLuint program = s->tess_program;
    glUseProgram(program);
    prepare_generation(s, program, frame);
    glProgramUniform1ui(program, glGetUniformLocation(program, "divergent_first"),
                        s->triangle_count);
    glProgramUniform1ui(program, glGetUniformLocation(program, "divergent_capacity"),
                        s->divergent_capacity);
    glBindVertexArray(s->empty_vertex_array);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->command_buffer);
    glPatchParameteri(GL_PATCH_VERTICES, 3);
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArraysIndirect(GL_PATCHES, (const void *)0);
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    prepare_splatting(s, frame);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s->command_buffer);
    glDrawArraysIndirect(GL_POINTS, (const void *)(4 * sizeof(uint32_t)));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

/* The wall-clock ms since *start, after glFinish when measuring; restarts *start. */
static double lap(const flc_state *s, double *start)
{
    if (!s->measuring)
        return 0.0;
    glFinish();
    double now = gb_seconds(), ms = 1e3 * (now - *start);
    *start = now;
    return ms;
}

/* Pass 3. */
static void resolve(flc_state *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulated_framebuffer);
    glViewport(0, 0, s->width, s->height);
    glUseProgram(s->resolve_program);
    set_tiles(s->resolve_program, s);
    glBindTextureUnit(UNIT_SPLAT, s->splat_texture);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

/* Pass 4, into the framebuffer that was bound. */
static void composite(flc_state *s, GLuint target)
{
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(0, 0, s->width, s->height);
    glUseProgram(s->composite_program);
    set_float(s->composite_program, "inverse_count", 1.0f / (float)s->accumulated);
    glBindTextureUnit(UNIT_ACCUMULATED, s->accumulated_texture);
    gb_gl_draw_fullscreen(s->empty_vertex_array);
}

/* Starts the accumulation again when the view moved. */
static void restart_if_moved(flc_state *s, const gb_indirect_frame *frame)
{
    if (s->accumulated && !memcmp(&s->last_view, frame->view_matrix, sizeof s->last_view) &&
        !memcmp(&s->last_projection, frame->projection, sizeof s->last_projection))
        return;
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->accumulated_framebuffer, GL_COLOR, 0, zero);
    s->accumulated = 0;
    s->last_view = *frame->view_matrix;
    s->last_projection = *frame->projection;
}

static void flc_draw(void *state, const gb_indirect_frame *frame)
{
    flc_state *s = state;
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    prepare_targets(s, frame->width, frame->height);
    restart_if_moved(s, frame);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->splat_framebuffer, GL_COLOR, 0, zero);
    double start = 0.0;
    lap(s, &start);
    double cpu_start = s->measuring ? 1e3 * gb_cpu_seconds() : 0.0;
    run_regular(s, frame);
    double regular = lap(s, &start);
    run_divergent(s, frame);
    double divergent = lap(s, &start);
    resolve(s);
    ++s->accumulated;
    composite(s, (GLuint)target);
    if (s->measuring) {
        s->times.regular_ms += regular;
        s->times.divergent_ms += divergent;
        s->times.resolve_ms += lap(s, &start);
        s->times.cpu_ms += 1e3 * gb_cpu_seconds() - cpu_start;
        s->times.frames++;
        uint32_t made = 0;
        if (s->triangle_count > s->regular_count)
            glGetNamedBufferSubData(s->command_buffer, 4 * sizeof(uint32_t), sizeof made, &made);
        s->times.divergent_vpls += made;
    }
}

void gb_flc_measure(void *state, int on)
{
    flc_state *s = state;
    if (s)
        s->measuring = on;
}

void gb_flc_times(const void *state, gb_flc_pass_times *times)
{
    const flc_state *s = state;
    memset(times, 0, sizeof *times);
    if (s)
        *times = s->times;
}

const gb_indirect_method gb_flc_method = {
    .create = flc_create,
    .draw = flc_draw,
    .destroy = flc_destroy,
};
