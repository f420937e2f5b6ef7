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

/* Every method's parameters, as gbview's options set them
 * (method_parameters.h). */
typedef struct gb_method_parameters gb_method_parameters;

/* A method's gbview options, declared in its folder (topo/topo_options.c
 * ...) as an array ended by an entry whose name is NULL, and listed with
 * the method in methods.c: gbview's main() makes its --help lines,
 * getopt's table and the parsing from them. parse stores value (NULL for a
 * flag) into the method's field of parameters and returns GB_EXIT_SUCCESS
 * or, after a usage error printed by common/cli.h's functions (tool
 * "gbview", the option's name), GB_EXIT_USAGE. Every string is static. */
typedef struct gb_method_option {
    const char *name;           /* --NAME, without the dashes */
    const char *value_name;     /* "N" of "--NAME N"; NULL for a flag */
    const char *help;           /* its --help text after the option's column,
                                   '\n' between lines (cli.h's gb_cli_entry) */
    int (*parse)(const char *name, const char *value, gb_method_parameters *parameters);
} gb_method_option;

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
