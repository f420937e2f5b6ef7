/* indirect_method.h — what a GI method gives the renderer: its indirect
 * light, added onto the frame's direct light.
 *
 * Each method lives in its own folder under runtime/ (topo/, octree/, flc/,
 * implicit/, flc_iv/), reaches the core only through this header and the
 * core's, never another method's files (but flc_iv/, which is flc/ and
 * implicit/ combined, and uses their headers), and exports one const gb_indirect_method, listed in
 * methods.c. The renderer calls create when the method is first used (with a
 * current GL context), draw once a frame with the output framebuffer bound,
 * additive blending on (glBlendFunc(GL_ONE, GL_ONE)) and depth test off, and
 * destroy with the renderer. The state is the method's own: create allocates
 * it, destroy frees it. Methods that keep screen-sized buffers compare
 * frame->width/height with theirs and reallocate.
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
} gb_indirect_setup;

typedef struct gb_indirect_frame {
    const gb_gbuffer *gbuffer;
    const gb_shadow_maps *shadows;
    const gb_view *view;
    const gb_mat4 *view_matrix, *projection;
    int width, height;
    uint32_t frame_index;       /* 0, 1, 2 ... since the method was created */
    gb_timings *timings;
} gb_indirect_frame;

typedef struct gb_indirect_method {
    gb_result (*create)(const gb_indirect_setup *setup, void **state, gb_error *error);
    void (*draw)(void *state, const gb_indirect_frame *frame);
    void (*destroy)(void *state);
} gb_indirect_method;

#endif
