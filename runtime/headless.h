/* headless.h — the headless face of gbview: an EGL surfaceless context, a
 * renderer, K frames from one of the scene's cameras, the last one read
 * back. How tests, CI and benchmarks render. With renderer.budget_ms > 0
 * the frames are drawn as the window draws them (gb_renderer_refine) until
 * K full-resolution images are shown or the image is final.
 */
#ifndef GB_HEADLESS_H
#define GB_HEADLESS_H

#include <stdint.h>

#include "image.h"
#include "renderer.h"
#include "result.h"
#include "scene.h"
#include "timings.h"

typedef struct gb_headless_options {
    gb_renderer_options renderer;   /* width, height 0: the camera's resolution */
    uint32_t camera;                /* index into scene->cameras */
    int frames;                     /* 0: 1 */
    int supersample;                /* 0 or 1: none; S: renders S x S samples a
                                       pixel, on a regular grid, averaged (the
                                       reference's box filter) */
} gb_headless_options;

/* Renders into image (RGB, linear, allocated here; the caller frees it).
 * timings, when not NULL, gets the frames' times (its GL names zeroed: it
 * needs no destroy). */
gb_result gb_render_headless(const gb_scene *scene, const gb_headless_options *options,
                             gb_image *image, gb_timings *timings, gb_error *error);

#endif
