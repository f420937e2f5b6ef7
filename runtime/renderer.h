/* renderer.h — one image of the runtime, pass after pass (Noël & Biri 2014,
 * V): shadow maps (once: the scene and its lights are static), the geometry
 * pass into the G-buffer, direct light into the HDR output, then the GI
 * method's indirect light added on top (none for the direct method), each
 * pass timed (timings.h). The window presents the output; headless rendering
 * reads it back.
 *
 * Two ways to draw:
 *   whole images  gb_renderer_draw: the image at once (headless, tests, the
 *                 report; --budget 0 in the window);
 *   to a budget   gb_renderer_refine, called once a frame by the window:
 *                 while the view moves, a whole image at the resolution
 *                 divided by what fits the budget (frame_budget.h); once it
 *                 is still, images at twice the resolution each until the
 *                 full one, each cut into parts of the method's (bands of
 *                 rows, indirect_method.h) that fit the budget, then more
 *                 images while the method refines them (flc's samples).
 *                 Only complete images are shown, and the last full one is
 *                 the same bytes as gb_renderer_draw's of that view.
 *
 * Needs a current OpenGL 4.5 context (context.h) for its whole life; the
 * scene must outlive the renderer.
 *   gb_renderer_create → per frame: gb_renderer_draw or _refine,
 *   [gb_renderer_present], gb_renderer_finish_frame → gb_renderer_destroy
 *   (also on a zeroed one).
 */
#ifndef GB_RENDERER_H
#define GB_RENDERER_H

#include "direct_light.h"
#include "frame_budget.h"
#include "gbuffer.h"
#include "gl_util.h"
#include "gpu_scene.h"
#include "image.h"
#include "method_parameters.h"
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
    double budget_ms;           /* gb_renderer_refine's frame budget (> 0) */
    int background_setup;       /* a method's prepare (indirect_method.h) runs on
                                   a thread: gb_renderer_poll_setup */
} gb_renderer_options;

/* Where gb_renderer_refine is, for the window's HUD. */
typedef struct gb_renderer_status {
    int divisor;                /* the shown image's resolution: full / divisor */
    int part, parts;            /* of the image being drawn; part 0 of 1 when none is */
    uint32_t images;            /* full-resolution images of this view shown
                                   (not the provisional ones) */
    int provisional;            /* the shown image stands in while the method's
                                   setup goes on (octree's atlas) */
    int converged;              /* the shown image is final: nothing left to draw */
    double setup_fraction;      /* of the method's setup on its thread, -1: none */
} gb_renderer_status;

typedef struct gb_renderer {
    const gb_scene *scene;
    gb_renderer_options options;
    gb_gl_errors *errors;
    gb_gpu_scene gpu_scene;
    gb_gbuffer gbuffer;
    gb_shadow_maps shadows;
    gb_direct_light direct;
    gb_output output;           /* the image being drawn */
    gb_output shown;            /* gb_renderer_refine: the last complete image */
    gb_timings timings;
    gb_frame_budget budget;
    gb_view view;               /* gb_renderer_refine's last */
    int restart;                /* the next refine draws a new image: the view,
                                   size, method or terms changed */
    int divisor;                /* of the image being drawn */
    int moving;                 /* it is drawn while the view moves: the
                                   directional lights' scene-wide maps, not
                                   cascades redrawn every frame */
    int part, parts;            /* its next part, and how many */
    double image_ms;            /* its parts' times so far */
    gb_renderer_status status;
    struct gb_background_setup *setup_job;  /* the method's prepare on its thread */
    gb_method setup_method;
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
/* Draws the whole image seen from view into the output (status as refine's). */
void gb_renderer_draw(gb_renderer *renderer, const gb_view *view);
/* Draws toward the image seen from view within options.budget_ms (above);
 * *changed nonzero when the image to present changed. */
gb_result gb_renderer_refine(gb_renderer *renderer, const gb_view *view, int *changed,
                             gb_error *error);
/* With background_setup: looks at the method's setup on its thread; once
 * prepared, creates the method (its error, if it fails) and starts the
 * image again. Until then the method draws no indirect light. */
gb_result gb_renderer_poll_setup(gb_renderer *renderer, gb_error *error);
/* Presents the image (refine's last complete one) in the window's
 * framebuffer of width x height, scaled to it. */
void gb_renderer_present(gb_renderer *renderer, int width, int height);
/* Collects the frame's timings and checks for GL errors. */
gb_result gb_renderer_finish_frame(gb_renderer *renderer, gb_error *error);
/* The world point the pixel at (x, y) of the last G-buffer shows, x and y
 * in [0, 1) from the top left; 0 where it shows no surface. */
int gb_renderer_point_at(gb_renderer *renderer, const gb_view *view, float x, float y,
                         gb_vec3 *point);
/* The image's linear RGB (refine's last complete one; allocated here, the
 * caller frees it). */
gb_result gb_renderer_read(gb_renderer *renderer, gb_image *image, gb_error *error);
void gb_renderer_destroy(gb_renderer *renderer);

#endif
