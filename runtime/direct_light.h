/* direct_light.h — the deferred direct lighting pass (Noël & Biri 2014,
 * V.E): a full-screen pass that reads the G-buffer and the lights with their
 * shadow maps and writes linear HDR radiance into the bound framebuffer:
 *   emitters seen directly (the G-buffer's emission)
 *   + light reflected once from every point, spot, directional light and
 *     area-light emitter, times its shadow-map visibility (a directional
 *     light through its cascades when the view is still, shadow_maps.h)
 * and the environment's radiance where no surface was drawn. The light of
 * the environment reflected by surfaces comes in as the scene's
 * directional lights that stand for it (common/environment_lights.h), with
 * their shadows. The BRDF and light conventions are common/brdf.h's,
 * mirrored in GLSL function for function (brdf.glsl; the pass is
 * direct_light.frag.glsl).
 *
 * Create → draw each frame → destroy (also on a zeroed one).
 */
#ifndef GB_DIRECT_LIGHT_H
#define GB_DIRECT_LIGHT_H

#include <epoxy/gl.h>

#include "gbuffer.h"
#include "result.h"
#include "shadow_maps.h"
#include "view.h"

typedef struct gb_direct_light {
    GLuint program;
    GLuint empty_vertex_array;
    GLuint environment_map;     /* the scene's lat-long map, or 0: its colour */
} gb_direct_light;

typedef struct gb_direct_inputs {
    const gb_gbuffer *gbuffer;
    const gb_shadow_maps *shadows;
    const gb_view *view;
    float environment[3];
    int shadows_enabled;        /* 0: every light fully visible (a debug mode) */
    int cascades;               /* 0: directional lights through their
                                   scene-wide maps (the cascades are not
                                   fitted to this view) */
} gb_direct_inputs;

/* environment_map: the scene's loaded map (copied to the GPU), or NULL. */
gb_result gb_direct_light_create(gb_direct_light *pass, const gb_texture *environment_map,
                                 gb_error *error);
/* Draws into the bound framebuffer (the viewport is the G-buffer's). */
void gb_direct_light_draw(gb_direct_light *pass, const gb_direct_inputs *inputs);
void gb_direct_light_destroy(gb_direct_light *pass);

#endif
