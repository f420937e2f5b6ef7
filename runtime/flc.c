#include "flc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* The seed of v_rand (per vertex, at load) and of u_rand (per frame). */
#define FLC_SEED 0x464c43u
enum {
    SSBO_TRIANGLES = 3,
    SSBO_ALBEDOS = 4,
    SSBO_VPLS = 5,
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

/* Pass 1: one VPL per VPL triangle, or none (level -1). E(t_i) follows
 * runtime/direct_light.c's lights and shadow-map bias, as irradiance on a
 * side of the triangle (its geometric normal). */
static const char generate_shader[] =
    "#version 450 core\n"
    "layout(local_size_x = 64) in;\n"
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
    "layout(binding = 8) uniform samplerCubeArrayShadow shadow_cubes;\n"
    "layout(binding = 9) uniform sampler2DArrayShadow shadow_planes;\n"
    "uniform uint triangle_count;\n"
    "uniform uint u_rand;\n"
    "uniform float S_bar[16];\n"
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
    "    for (int k = 0; k <= N; ++k)\n"
    "        if (u < area / S_bar[k])\n"
    "            return k;\n"
    "    return -1;\n"
    "}\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    if (i >= triangle_count)\n"
    "        return;\n"
    "    Triangle t = triangles[i];\n"
    "    uint u_i = flc_hash(floatBitsToUint(t.p1_key.w) ^ u_rand);\n"   /* Alg. 2 */
    "    int level = flc_level(flc_uniform(u_i), t.p2_area.w);\n"
    "    vec3 p0 = t.p0_material.xyz, e1 = t.p1_key.xyz - p0, e2 = t.p2_area.xyz - p0;\n"
    "    vec3 cross_product = cross(e1, e2);\n"
    "    float twice_area = length(cross_product);\n"
    "    if (level < 0 || !(twice_area > 0.0) || isinf(twice_area)) {\n"
    "        vpls[i].position_level = vec4(0.0, 0.0, 0.0, -1.0);\n"
    "        return;\n"
    "    }\n"
    "    uint b1 = flc_hash(u_i), b2 = flc_hash(b1), b3 = flc_hash(b2);\n"
    "    float s = sqrt(flc_uniform(b1)), v = flc_uniform(b2);\n"      /* jittered y_i */
    "    vec3 y = p0 + s * (1.0 - v) * e1 + s * v * e2;\n"
    "    vec3 n = cross_product / twice_area;\n"
    "    vec3 rho = albedos[floatBitsToUint(t.p0_material.w)].rgb;\n"
    "    Vpl vpl;\n"
    "    vpl.position_level = vec4(y, float(level));\n"
    "    vpl.normal_tile = vec4(n, float(b3 % tiles));\n"
    "    vpl.front = vec4(rho * irradiance(y, n), 0.0);\n"      /* radiosity B = rho E */
    "    vpl.back = vec4(rho * irradiance(y, -n), 0.0);\n"
    "    vpls[i] = vpl;\n"
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
    "void main() {\n"
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
    "    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(full_size) - 1.0;\n"
    "    float z = -near / depth;\n"
    "    vec3 x = (view_to_world * vec4(ndc * tan_half_fov * -z, z, 1.0)).xyz;\n"
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
    uint32_t triangle_count;
    GLuint generate_program, splat_program, resolve_program, composite_program;
    GLuint triangle_buffer, albedo_buffer, vpl_buffer, empty_vertex_array;
    int width, height, tile_width, tile_height;
    GLuint splat_texture, splat_framebuffer, accumulated_texture, accumulated_framebuffer;
    uint32_t accumulated;           /* frames in the accumulation */
    gb_mat4 last_view, last_projection;
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
}

/* Compiles and links the stages of one program (types[i], sources[i]). */
static gb_result build_program(const char *name, const GLenum *types,
                               const char *const *sources, int count, GLuint *program,
                               gb_error *error)
{
    char log[2048] = "";
    GLint ok = 1;
    *program = glCreateProgram();
    for (int i = 0; i < count && ok; ++i) {
        GLuint shader = glCreateShader(types[i]);
        glShaderSource(shader, 1, &sources[i], NULL);
        glCompileShader(shader);
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok)
            glGetShaderInfoLog(shader, sizeof log, NULL, log);
        glAttachShader(*program, shader);
        glDeleteShader(shader);
    }
    if (ok) {
        glLinkProgram(*program);
        glGetProgramiv(*program, GL_LINK_STATUS, &ok);
        if (!ok)
            glGetProgramInfoLog(*program, sizeof log, NULL, log);
    }
    if (ok)
        return GB_OK;
    glDeleteProgram(*program);
    *program = 0;
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "flc: %s shader: %s", name, log);
}

static gb_result build_programs(flc_state *s, gb_error *error)
{
    static const GLenum compute[] = {GL_COMPUTE_SHADER};
    static const GLenum splat[] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
    const char *generate_sources[] = {generate_shader};
    const char *splat_sources[] = {splat_vertex_shader, splat_geometry_shader,
                                   splat_fragment_shader};
    gb_result result = build_program("VPL generation", compute, generate_sources, 1,
                                     &s->generate_program, error);
    if (result == GB_OK)
        result = build_program("splatting", splat, splat_sources, 3, &s->splat_program, error);
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
    gb_result result = gb_flc_triangles_build(s->scene, &s->levels, seed, &triangles, error);
    if (result != GB_OK)
        return result;
    s->triangle_count = triangles.count;
    size_t count = triangles.count ? triangles.count : 1;
    glCreateBuffers(1, &s->triangle_buffer);
    glNamedBufferStorage(s->triangle_buffer, (GLsizeiptr)(count * sizeof *triangles.items),
                         triangles.count ? triangles.items : NULL, 0);
    gb_flc_triangles_free(&triangles);
    glCreateBuffers(1, &s->vpl_buffer);
    glNamedBufferStorage(s->vpl_buffer, (GLsizeiptr)(count * VPL_BYTES), NULL, 0);
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
    GLuint programs[] = {s->generate_program, s->splat_program, s->resolve_program,
                         s->composite_program};
    for (int i = 0; i < 4; ++i)
        if (programs[i])
            glDeleteProgram(programs[i]);
    GLuint buffers[] = {s->triangle_buffer, s->albedo_buffer, s->vpl_buffer};
    for (int i = 0; i < 3; ++i)
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
    if (parameters->flc_levels > GB_FLC_MAX_LEVELS)
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

/* Pass 1. */
static void generate_vpls(flc_state *s, const gb_indirect_frame *frame)
{
    GLuint program = s->generate_program;
    uint32_t u_rand = gb_flc_hash(frame->frame_index * 0x9e3779b9u ^ gb_flc_hash(FLC_SEED));
    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "triangle_count"),
                        s->triangle_count);
    glProgramUniform1ui(program, glGetUniformLocation(program, "u_rand"), u_rand);
    glProgramUniform1ui(program, glGetUniformLocation(program, "tiles"),
                        1u << (2 * s->tiling));
    glProgramUniform1fv(program, glGetUniformLocation(program, "S_bar"), s->levels.N + 1,
                        s->levels.S_bar);
    set_levels(program, &s->levels);
    set_int(program, "point_count", (int)frame->shadows->point_count);
    set_int(program, "plane_count", (int)frame->shadows->plane_count);
    set_float(program, "cube_texel", 2.0f / (float)frame->shadows->cube_size);
    set_int(program, "shadows", frame->shadows->drawn);   /* not drawn with --no-shadows */
    gb_shadow_maps_bind(frame->shadows);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_TRIANGLES, s->triangle_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_ALBEDOS, s->albedo_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glDispatchCompute((s->triangle_count + GENERATE_GROUP - 1) / GENERATE_GROUP, 1, 1);
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
}

/* Pass 2. */
static void splat_vpls(flc_state *s, const gb_indirect_frame *frame)
{
    static const float zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, s->splat_framebuffer);
    glViewport(0, 0, s->tile_width << s->tiling, s->tile_height << s->tiling);
    glClearNamedFramebufferfv(s->splat_framebuffer, GL_COLOR, 0, zero);
    glUseProgram(s->splat_program);
    set_splat_uniforms(s, frame);
    gb_gbuffer_bind(frame->gbuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SSBO_VPLS, s->vpl_buffer);
    glBindVertexArray(s->empty_vertex_array);
    glDrawArrays(GL_POINTS, 0, (GLsizei)s->triangle_count);
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
    generate_vpls(s, frame);
    splat_vpls(s, frame);
    resolve(s);
    ++s->accumulated;
    composite(s, (GLuint)target);
}

const gb_indirect_method gb_flc_method = {
    .create = flc_create,
    .draw = flc_draw,
    .destroy = flc_destroy,
};
