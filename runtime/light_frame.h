/* light_frame.h — the frame a shadow map looks from: forward the way the
 * light travels, right and up across it (right = forward x up_hint), what
 * gb_mat4_view takes. shadow_maps.c's maps and shadow_cascades.c's
 * cascades share it. Plain values; nothing is allocated. */
#ifndef GB_LIGHT_FRAME_H
#define GB_LIGHT_FRAME_H

#include <math.h>

#include "mat4.h"

typedef struct gb_light_frame {
    gb_vec3 position, forward, right, up;
} gb_light_frame;

/* An axis far from forward: the up of a light's view. */
static inline gb_vec3 gb_light_up_hint(gb_vec3 forward)
{
    return fabsf(forward.y) < 0.9f ? gb_vec3_make(0, 1, 0) : gb_vec3_make(1, 0, 0);
}

static inline gb_light_frame gb_light_frame_make(gb_vec3 position, gb_vec3 forward,
                                                 gb_vec3 up_hint)
{
    gb_light_frame f = {position, gb_vec3_normalize(forward), {0, 0, 0}, {0, 0, 0}};
    f.right = gb_vec3_normalize(gb_vec3_cross(f.forward, up_hint));
    f.up = gb_vec3_cross(f.right, f.forward);
    return f;
}

static inline gb_mat4 gb_light_frame_view(const gb_light_frame *f)
{
    return gb_mat4_view(f->position, f->forward, f->right, f->up);
}

#endif
