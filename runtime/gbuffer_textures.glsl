// The G-buffer's textures at the units gb_gbuffer_bind binds them to
// (GB_UNIT_GBUFFER_*, gbuffer.h), and the view uniforms that turn a pixel
// and its depth back into a world point (gbuffer_world_position.glsl,
// gbuffer_surface.glsl). Every pass that reads the G-buffer includes it in
// place of its own declarations; what a pass does not use, the compiler drops.
layout(binding = 1) uniform sampler2D gbuffer_normal;
layout(binding = 2) uniform sampler2D gbuffer_depth;
layout(binding = 3) uniform sampler2D gbuffer_diffuse;
layout(binding = 4) uniform sampler2D gbuffer_glossy;
layout(binding = 5) uniform usampler2D gbuffer_clusters;
layout(binding = 6) uniform sampler2D gbuffer_emission;
uniform mat4 view_to_world;
uniform vec2 tan_half_fov;
uniform float near;
