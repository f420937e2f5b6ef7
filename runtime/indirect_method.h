/* indirect_method.h — what a GI method gives the renderer: its indirect
 * light, added onto the frame's direct light.
 *
 * Each method lives in its own folder under runtime/ (topo/, octree/, flc/,
 * implicit/, flc_iv/), reaches the core only through this header and the
 * core's, never another method's files (but flc_iv/, which is flc/ and
 * implicit/ combined, and uses their headers), and exports one const
 * gb_indirect_method, listed in methods.c.
 *
 * Lifetime. The renderer calls create when the method is first used (with a
 * current GL context) and destroy with the renderer. The state is the
 * method's own: create allocates it, destroy frees it. A method whose setup
 * is long CPU work (implicit's links) may also give prepare: the GL-free
 * part of create, which the window runs on a worker thread while it shows
 * direct light (renderer.h); create then finds its result in
 * setup->prepared and takes it over, also when it fails. prepare reports
 * to setup->progress and fails when asked to stop; discard frees a
 * prepared result create never took. Without prepare, create does all of
 * it.
 *
 * Drawing. An image of one view is drawn in parts, to fit the renderer's
 * frame budget (renderer.h): draw is called for part 0, 1 ... parts - 1,
 * with the output framebuffer bound, additive blending on
 * (glBlendFunc(GL_ONE, GL_ONE)), depth test off and the scissor test on
 * the part's band of rows (frame->band). A method does its per-view work
 * (compute passes, its own targets, CPU work) at part 0, with the scissor
 * test off for what must cover the whole view, and its per-pixel output
 * passes within the band; a method that cuts its work otherwise (flc: by
 * VPLs) turns the scissor off and adds its whole image at the last part.
 * The image is the same bytes whatever the number of parts. draw returns a
 * gb_image_state: whether another image of the same view would be better
 * (the window keeps drawing while it would). Methods that keep screen-sized
 * buffers compare frame->width/height with theirs and reallocate.
 */
#ifndef GB_INDIRECT_METHOD_H
#define GB_INDIRECT_METHOD_H

#include <stdint.h>

#include "bake.h"
#include "gbuffer.h"
#include "gpu_scene.h"
#include "mat4.h"
#include "progress.h"
#include "result.h"
#include "scene.h"
#include "shadow_maps.h"
#include "timings.h"
#include "view.h"

/* The parameters of every method, set from gbview's options; a zero field
 * means the method's default. Each method adds its own fields here. */
typedef struct gb_method_parameters {
    int vpls;                   /* topo: number of VPLs (--vpls) */
    const char *write_vpls;     /* topo: write the VPL set here (--write-vpls) */
    int topo_visibility;        /* topo: gb_topo_visibility, full (0), clusters, none */
    int bins;                   /* implicit, flc-iv: cube-map bins per face edge (--bins) */
    int visibility_filter;      /* flc-iv: GB_FLC_IV_BILINEAR (0) or _NEAREST (--bin-filter) */
    int bounces;                /* implicit: 1 or 2 (--bounces) */
    int paper_rules;            /* implicit: 1 for the links by the paper's rules
                                   alone, faster and coarser (--paper-rules) */
    float flc_mu;               /* flc: mu > 1 of S_k = S0 mu^k, Eq. 17 (--mu; 2) */
    float flc_n_avg;            /* flc: N_avg of Eq. 1 (--navg; 256) */
    float flc_epsilon;          /* flc: the distance clamp epsilon, world units
                                   (--epsilon; 0.01 x the scene's radius) */
    int flc_tiling;             /* flc: 4^tiling interleaved tiles (--tiling; 0) */
    int flc_levels;             /* flc: N + 1, the number of levels (--levels; 6) */
    const char *atlas;          /* octree: show it through this atlas file (--atlas);
                                   "none": the walk; NULL: the bake's NAME.atlas
                                   when it has one, else the walk */
} gb_method_parameters;

typedef struct gb_indirect_setup {
    const gb_scene *scene;
    const gb_gpu_scene *gpu_scene;
    const gb_shadow_maps *shadows;
    const gb_bake *bake;        /* NULL when gbview was given no bake folder; the
                                   method borrows its files (bake.h) */
    const gb_method_parameters *parameters;
    int width, height;
    gb_progress_callback progress;  /* may be NULL: a method whose setup takes
                                   long (implicit's links) reports its fraction
                                   done, and stops (fails) when asked to */
    void *progress_user;
    void *prepared;             /* create: prepare's result, or NULL when
                                   prepare did not run (create does it all) */
} gb_indirect_setup;

typedef struct gb_indirect_frame {
    const gb_gbuffer *gbuffer;
    const gb_shadow_maps *shadows;
    const gb_view *view;
    const gb_mat4 *view_matrix, *projection;
    int width, height;
    uint32_t frame_index;       /* images since the method was created: 0, 1, 2 ...
                                   (the same for every part of one image) */
    int part, parts;            /* 0 <= part < parts (1: a whole image at once) */
    int band[2];                /* the part's rows, first and count: the scissor box */
    double budget_ms;           /* what a part may take, 0 for no limit: startup
                                   work a method slices (octree's atlas) */
    gb_timings *timings;
} gb_indirect_frame;

/* What the image a draw finished is, against the next one of the same view. */
typedef enum gb_image_state {
    GB_IMAGE_FINAL = 0,         /* what this view gives: nothing left to draw */
    GB_IMAGE_REFINABLE,         /* a sample: the next image adds one (flc) */
    GB_IMAGE_PROVISIONAL,       /* a stand-in while setup work goes on (octree's
                                   atlas): it does not count as an image */
} gb_image_state;

typedef struct gb_indirect_method {
    gb_result (*create)(const gb_indirect_setup *setup, void **state, gb_error *error);
    /* A gb_image_state, at the last part; anything at the others. */
    int (*draw)(void *state, const gb_indirect_frame *frame);
    void (*destroy)(void *state);
    /* Optional (see above): create's CPU work, without GL, on any thread. */
    gb_result (*prepare)(const gb_indirect_setup *setup, void **prepared, gb_error *error);
    void (*discard)(void *prepared);
} gb_indirect_method;

#endif
