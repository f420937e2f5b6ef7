/* method_cycle.h — the window's M key: the next GI method after the
 * current one that this build, scene and bake can run. One that cannot
 * (topo or octree without their baked files) is skipped, and why is told
 * once a session, not at every press.
 */
#ifndef GB_METHOD_CYCLE_H
#define GB_METHOD_CYCLE_H

#include "methods.h"
#include "renderer.h"

typedef struct gb_method_cycle {
    int told[GB_METHOD_COUNT];  /* why the method was skipped has been told */
} gb_method_cycle;              /* zeroed: nothing told yet */

/* Sets the first method after the renderer's that it can switch to
 * (gb_renderer_set_method) and returns it; the renderer's own when no
 * other can run. report (may be NULL) gets "METHOD skipped: why" once a
 * method. */
gb_method gb_method_cycle_next(gb_method_cycle *cycle, gb_renderer *renderer,
                               void (*report)(void *user, const char *message), void *user);

#endif
