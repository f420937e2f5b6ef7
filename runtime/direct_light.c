#include "direct_light.h"

#include <math.h>
#include <string.h>

#include "gl_util.h"

/* The GLSL twin of common/brdf.h: the same functions under the same names
 * (without the gb_ prefix); change both together. */
#define GLSL_BRDF                                                                  \
    "const float PI = 3.14159265358979323846;\n"                                   \
    "float phong_normalization(float Ns) { return (Ns + 2.0) / (2.0 * PI); }\n"    \
    "float phong_cos_mirror(float n_dot_wo, float n_dot_wi, float wo_dot_wi) {\n"  \
    "    return 2.0 * n_dot_wo * n_dot_wi - wo_dot_wi;\n"                           \
    "}\n"                                                                          \
    "float phong_lobe(float Ns, float cos_mirror) {\n"                             \
    "    return cos_mirror > 0.0 ? phong_normalization(Ns) * pow(cos_mirror, Ns) : 0.0;\n" \
    "}\n"                                                                          \
    "vec3 brdf_eval(vec3 Kd, vec3 Ks, float Ns, float n_dot_wo, float n_dot_wi,\n"  \
    "               float wo_dot_wi) {\n"                                          \
    "    if (n_dot_wo <= 0.0 || n_dot_wi <= 0.0)\n"                                \
    "        return vec3(0.0);\n"                                                  \
    "    float lobe = phong_lobe(Ns, phong_cos_mirror(n_dot_wo, n_dot_wi, wo_dot_wi));\n" \
    "    return Kd / PI + Ks * lobe;\n"                                            \
    "}\n"                                                                          \
    "float spot_falloff(float cos_angle, float cone_angle_degrees,\n"              \
    "                   float falloff_angle_degrees) {\n"                          \
    "    float cos_cone = cos(cone_angle_degrees * (PI / 180.0));\n"               \
    "    float cos_falloff = cos(falloff_angle_degrees * (PI / 180.0));\n"         \
    "    if (cos_angle <= cos_cone)\n"                                             \
    "        return 0.0;\n"                                                        \
    "    if (cos_angle >= cos_falloff || cos_falloff <= cos_cone)\n"               \
    "        return 1.0;\n"                                                        \
    "    float t = (cos_angle - cos_cone) / (cos_falloff - cos_cone);\n"           \
    "    return t * t * (3.0 - 2.0 * t);\n"                                        \
    "}\n"                                                                          \
    "float inverse_square(float r2) { return 1.0 / r2; }\n"

/* Shadow-map bias: the receiver moves along its geometric normal by
 * NORMAL_OFFSET texels of the map, and the compared depth by DEPTH_BIAS. */
#define GLSL_SHADOW_BIAS "const float NORMAL_OFFSET = 1.5;\nconst float DEPTH_BIAS = 2e-5;\n"

static const char fragment_shader[] =
    "#version 450 core\n"
    "struct PointLight { vec4 position_range; vec4 intensity_one_sided; vec4 normal; };\n"
    "struct PlaneLight { mat4 world_to_clip; vec4 position_kind; vec4 direction_texel;\n"
    "                    vec4 intensity; vec4 cone; };\n"
    "layout(std430, binding = 1) readonly buffer PointLights { PointLight point_lights[]; };\n"
    "layout(std430, binding = 2) readonly buffer PlaneLights { PlaneLight plane_lights[]; };\n"
    "layout(binding = 1) uniform sampler2D gbuffer_normal;\n"
    "layout(binding = 2) uniform sampler2D gbuffer_depth;\n"
    "layout(binding = 3) uniform sampler2D gbuffer_diffuse;\n"
    "layout(binding = 4) uniform sampler2D gbuffer_glossy;\n"
    "layout(binding = 6) uniform sampler2D gbuffer_emission;\n"
    "layout(binding = 8) uniform samplerCubeArrayShadow shadow_cubes;\n"
    "layout(binding = 9) uniform sampler2DArrayShadow shadow_planes;\n"
    "layout(binding = 10) uniform sampler2D environment_map;\n"
    "uniform mat4 view_to_world;\n"
    "uniform vec2 tan_half_fov;\n"
    "uniform float near;\n"
    "uniform vec3 environment;\n"
    "uniform bool has_environment_map;\n"
    "uniform int point_count;\n"
    "uniform int plane_count;\n"
    "uniform bool shadows;\n"
    "uniform float cube_texel;\n"
    "out vec4 radiance;\n"
    GB_GLSL_OCTAHEDRAL
    GLSL_BRDF
    GLSL_SHADOW_BIAS
    GB_GLSL_SURFACE
    /* f(wo, wi) E dot(n, wi); nothing arrives through the surface. */
    "vec3 reflected(Surface s, vec3 wi, vec3 E) {\n"
    "    if (dot(s.ng, wi) <= 0.0)\n"
    "        return vec3(0.0);\n"
    "    float n_dot_wi = dot(s.n, wi);\n"
    "    vec3 f = brdf_eval(s.Kd, s.Ks, s.Ns, dot(s.n, s.wo), n_dot_wi, dot(s.wo, wi));\n"
    "    return f * E * n_dot_wi;\n"
    "}\n"
    "float point_visibility(int i, Surface s, float distance) {\n"
    "    if (!shadows)\n"
    "        return 1.0;\n"
    "    PointLight l = point_lights[i];\n"
    "    vec3 p = s.position + s.ng * (NORMAL_OFFSET * cube_texel * distance);\n"
    "    vec3 d = p - l.position_range.xyz;\n"
    "    float reference = length(d) / l.position_range.w - DEPTH_BIAS;\n"
    "    return texture(shadow_cubes, vec4(d, float(i)), reference);\n"
    "}\n"
    "vec3 point_light(int i, Surface s) {\n"
    "    PointLight l = point_lights[i];\n"
    "    vec3 to_light = l.position_range.xyz - s.position;\n"
    "    float r2 = dot(to_light, to_light);\n"
    "    float r = sqrt(r2);\n"
    "    vec3 wi = to_light / r;\n"
    "    vec3 I = l.intensity_one_sided.rgb;\n"
    "    if (l.intensity_one_sided.w > 0.5)\n"
    "        I *= max(0.0, -dot(l.normal.xyz, wi));\n"
    "    if (dot(s.ng, wi) <= 0.0 || I == vec3(0.0))\n"
    "        return vec3(0.0);\n"
    "    return reflected(s, wi, I * inverse_square(r2)) * point_visibility(i, s, r);\n"
    "}\n"
    "float plane_visibility(int i, Surface s, float texel) {\n"
    "    if (!shadows)\n"
    "        return 1.0;\n"
    "    vec3 p = s.position + s.ng * (NORMAL_OFFSET * texel);\n"
    "    vec4 clip = plane_lights[i].world_to_clip * vec4(p, 1.0);\n"
    "    vec3 ndc = clip.xyz / clip.w;\n"
    "    return texture(shadow_planes, vec4(0.5 * ndc.xy + 0.5, float(i), ndc.z + DEPTH_BIAS));\n"
    "}\n"
    "vec3 plane_light(int i, Surface s) {\n"
    "    PlaneLight l = plane_lights[i];\n"
    "    vec3 d = l.direction_texel.xyz;\n"
    "    float texel = l.direction_texel.w;\n"
    "    if (l.position_kind.w > 0.5) {\n"
    "        if (dot(s.ng, -d) <= 0.0)\n"
    "            return vec3(0.0);\n"
    "        return reflected(s, -d, l.intensity.rgb) * plane_visibility(i, s, texel);\n"
    "    }\n"
    "    vec3 to_light = l.position_kind.xyz - s.position;\n"
    "    float r2 = dot(to_light, to_light);\n"
    "    float r = sqrt(r2);\n"
    "    vec3 wi = to_light / r;\n"
    "    float falloff = spot_falloff(dot(d, -wi), l.cone.x, l.cone.y);\n"
    "    if (falloff <= 0.0 || dot(s.ng, wi) <= 0.0)\n"
    "        return vec3(0.0);\n"
    "    float axial = max(dot(d, -to_light), 0.0);\n"
    "    return reflected(s, wi, l.intensity.rgb * falloff * inverse_square(r2))\n"
    "           * plane_visibility(i, s, texel * axial);\n"
    "}\n"
    /* The background toward the pixel: formats/environment.h's lat-long
     * lookup (row 0 is +y; the middle column looks along -z). */
    "vec3 background(ivec2 pixel) {\n"
    "    if (!has_environment_map)\n"
    "        return environment;\n"
    "    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(textureSize(gbuffer_depth, 0)) - 1.0;\n"
    "    vec3 d = normalize(mat3(view_to_world) * vec3(ndc * tan_half_fov, -1.0));\n"
    "    float u = atan(d.x, -d.z) / (2.0 * 3.14159265358979) + 0.5;\n"
    "    float v = acos(clamp(d.y, -1.0, 1.0)) / 3.14159265358979;\n"
    "    return textureLod(environment_map, vec2(u, v), 0.0).rgb;\n"
    "}\n"
    "void main() {\n"
    "    ivec2 pixel = ivec2(gl_FragCoord.xy);\n"
    "    float depth = texelFetch(gbuffer_depth, pixel, 0).r;\n"
    "    if (depth <= 0.0) {\n"
    "        radiance = vec4(background(pixel), 1.0);\n"
    "        return;\n"
    "    }\n"
    "    Surface s = surface_at(pixel, depth);\n"
    "    vec3 L = texelFetch(gbuffer_emission, pixel, 0).rgb;\n"
    "    for (int i = 0; i < point_count; ++i)\n"
    "        L += point_light(i, s);\n"
    "    for (int i = 0; i < plane_count; ++i)\n"
    "        L += plane_light(i, s);\n"
    "    radiance = vec4(L, 1.0);\n"
    "}\n";

/* The map as a float RGB texture: bilinear, wrapping round in u, clamped in v. */
static GLuint environment_texture(const gb_texture *map)
{
    GLuint texture;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGB32F, map->width, map->height);
    glTextureSubImage2D(texture, 0, 0, 0, map->width, map->height, GL_RGB, GL_FLOAT, map->rgb);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

gb_result gb_direct_light_create(gb_direct_light *pass, const gb_texture *environment_map,
                                 gb_error *error)
{
    memset(pass, 0, sizeof *pass);
    gb_result result = gb_gl_program("direct light", gb_gl_fullscreen_vertex_shader,
                                     fragment_shader, &pass->program, error);
    if (result != GB_OK)
        return result;
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    if (environment_map && environment_map->rgb)
        pass->environment_map = environment_texture(environment_map);
    return GB_OK;
}

static void set_uniforms(GLuint program, GLuint environment_map, const gb_direct_inputs *in)
{
    const gb_view *view = in->view;
    gb_mat4 view_to_world = gb_view_inverse_matrix(view);
    float tan_y = tanf(0.5f * view->fov_y * 3.14159265358979f / 180.0f);
    float aspect = (float)in->gbuffer->width / (float)in->gbuffer->height;
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "view_to_world"), 1,
                              GL_FALSE, view_to_world.m);
    glProgramUniform2f(program, glGetUniformLocation(program, "tan_half_fov"), tan_y * aspect,
                       tan_y);
    glProgramUniform1f(program, glGetUniformLocation(program, "near"), view->near);
    glProgramUniform3fv(program, glGetUniformLocation(program, "environment"), 1,
                        in->environment);
    glProgramUniform1i(program, glGetUniformLocation(program, "has_environment_map"),
                       environment_map != 0);
    glProgramUniform1i(program, glGetUniformLocation(program, "point_count"),
                       (GLint)in->shadows->point_count);
    glProgramUniform1i(program, glGetUniformLocation(program, "plane_count"),
                       (GLint)in->shadows->plane_count);
    glProgramUniform1i(program, glGetUniformLocation(program, "shadows"), in->shadows_enabled);
    glProgramUniform1f(program, glGetUniformLocation(program, "cube_texel"),
                       2.0f / (float)in->shadows->cube_size);
}

void gb_direct_light_draw(gb_direct_light *pass, const gb_direct_inputs *inputs)
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(pass->program);
    set_uniforms(pass->program, pass->environment_map, inputs);
    glBindTextureUnit(10, pass->environment_map);
    gb_gbuffer_bind(inputs->gbuffer);
    gb_shadow_maps_bind(inputs->shadows);
    gb_gl_draw_fullscreen(pass->empty_vertex_array);
}

void gb_direct_light_destroy(gb_direct_light *pass)
{
    if (pass->program)
        glDeleteProgram(pass->program);
    if (pass->empty_vertex_array)
        glDeleteVertexArrays(1, &pass->empty_vertex_array);
    if (pass->environment_map)
        glDeleteTextures(1, &pass->environment_map);
    memset(pass, 0, sizeof *pass);
}
