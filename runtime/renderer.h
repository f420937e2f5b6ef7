/* renderer.h — one frame of the runtime, pass after pass (Noël & Biri 2014,
 * V): shadow maps (once: the scene and its lights are static), the geometry
 * pass into the G-buffer, direct light into the HDR output, then the GI
 * method's indirect light added on top (none for the direct method), each
 * pass timed (timings.h). The window presents the output; headless rendering
 * reads it back.
 *
 * Needs a current OpenGL 4.5 context (context.h) for its whole life; the
 * scene must outlive the renderer.
 *   gb_renderer_create → per frame: gb_renderer_draw, [gb_renderer_present],
 *   gb_renderer_finish_frame → gb_renderer_destroy (also on a zeroed one).
 */
#ifndef GB_RENDERER_H
#define GB_RENDERER_H

#include "direct_light.h"
#include "gbuffer.h"
#include "gl_util.h"
#include "gpu_scene.h"
#include "image.h"
#include "methods.h"
#include "output.h"
#include "progress.h"
#include "result.h"
#include "scene.h"
#include "shadow_maps.h"
#include "timings.h"
#include "view.h"

typedef struct gb_renderer_options {
    gb_method method;           /* 0: direct */
    gb_terms terms;             /* 0: both */
    int width, height;          /* the frame's size, pixels (> 0) */
    gb_shadow_options shadow;   /* zeroed: defaults */
    int no_shadows;             /* debug: every light fully visible */
    int finish_passes;          /* glFinish after each timed pass, so that its
                                   timestamps hold its work on renderers that
                                   defer it to the flush (llvmpipe); --timings */
    const gb_bake *bake;        /* the bake's files (bake.h), or NULL; must outlive
                                   the renderer */
    gb_method_parameters parameters;
    gb_progress_callback progress;  /* may be NULL: given to the method's setup
                                   (gb_indirect_setup) */
    void *progress_user;
} gb_renderer_options;

typedef struct gb_renderer {
    const gb_scene *scene;
    gb_renderer_options options;
    gb_gl_errors *errors;
    gb_gpu_scene gpu_scene;
    gb_gbuffer gbuffer;
    gb_shadow_maps shadows;
    gb_direct_light direct;
    gb_output output;
    gb_timings timings;
    double frame_start;         /* gb_seconds() at the last draw */
    void *method_state[GB_METHOD_COUNT];    /* each GI method's, once created */
    uint32_t method_frames[GB_METHOD_COUNT];/* frames drawn with each method */
} gb_renderer;

/* errors: the context's collector, checked after setup and each frame. */
gb_result gb_renderer_create(const gb_scene *scene, const gb_renderer_options *options,
                             gb_gl_errors *errors, gb_renderer *renderer, gb_error *error);
gb_result gb_renderer_resize(gb_renderer *renderer, int width, int height, gb_error *error);
/* Changes the method (GB_ERROR_UNSUPPORTED when this build lacks it, or the
 * method's create error, e.g. a baked file it needs is missing) or the terms. */
gb_result gb_renderer_set_method(gb_renderer *renderer, gb_method method, gb_error *error);
void gb_renderer_set_terms(gb_renderer *renderer, gb_terms terms);
/* Draws the frame seen from view into the output. */
void gb_renderer_draw(gb_renderer *renderer, const gb_view *view);
/* Presents the output in the window's framebuffer of width x height. */
void gb_renderer_present(gb_renderer *renderer, int width, int height);
/* Collects the frame's timings and checks for GL errors. */
gb_result gb_renderer_finish_frame(gb_renderer *renderer, gb_error *error);
/* The output's linear RGB (allocated here; the caller frees it). */
gb_result gb_renderer_read(gb_renderer *renderer, gb_image *image, gb_error *error);
void gb_renderer_destroy(gb_renderer *renderer);

#endif
