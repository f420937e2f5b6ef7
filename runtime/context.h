/* context.h — an OpenGL 4.5 core context for the runtime, in one of two
 * faces:
 *   headless  EGL on Mesa's surfaceless platform (no display, no window):
 *             the renderer draws into its own framebuffers; how tests, CI
 *             and benchmarks render (llvmpipe here, a GPU elsewhere);
 *   window    a GLFW window (needs a display: X11 or Wayland).
 * libepoxy loads the GL functions in both. Creating a context makes it
 * current on the calling thread and installs the GL error collector
 * (gl_util.h) on context->errors.
 *
 * The caller owns the gb_context (usually on its stack) and releases it with
 * gb_context_destroy, which also works on a zeroed one and after a failed
 * create.
 */
#ifndef GB_CONTEXT_H
#define GB_CONTEXT_H

#include "gl_util.h"
#include "result.h"

typedef struct gb_context {
    void *egl_display, *egl_context;    /* headless */
    void *window;                       /* window: the GLFWwindow */
    int glfw_initialized;
    gb_gl_errors errors;
} gb_context;

gb_result gb_context_create_headless(gb_context *context, gb_error *error);
/* A window of width x height pixels; vsync off so that frame times are the
 * renderer's. */
gb_result gb_context_create_window(gb_context *context, const char *title, int width,
                                   int height, gb_error *error);
void gb_context_destroy(gb_context *context);

/* Implemented by each face; gb_context_destroy calls both. */
void gb_context_destroy_headless(gb_context *context);
void gb_context_destroy_window(gb_context *context);

#endif
