// The scene's lights as shadow_maps.h lays them out on the GPU (std430 at
// GB_SSBO_POINT_LIGHTS and GB_SSBO_PLANE_LIGHTS, the shadow maps at
// GB_UNIT_SHADOW_CUBES and GB_UNIT_SHADOW_PLANES) and the uniforms that
// count them: what the direct pass (direct_light.frag.glsl) and FLC's VPLs
// (flc/flc_generate.glsl) read, declared once.
struct PointLight { vec4 position_range; vec4 intensity_one_sided; vec4 normal; };
struct PlaneLight { mat4 world_to_clip; vec4 position_kind; vec4 direction_texel;
                    vec4 intensity; vec4 cone; };
layout(std430, binding = 1) readonly buffer PointLights { PointLight point_lights[]; };
layout(std430, binding = 2) readonly buffer PlaneLights { PlaneLight plane_lights[]; };
layout(binding = 8) uniform samplerCubeArrayShadow shadow_cubes;
layout(binding = 9) uniform sampler2DArrayShadow shadow_planes;
uniform int point_count;
uniform int plane_count;
uniform bool shadows;           // false: every light fully visible
uniform float cube_texel;       // a cube face's texel at distance 1
