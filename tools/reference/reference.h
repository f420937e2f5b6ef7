/* reference.h — the ground-truth renderer of gibake: Monte Carlo light
 * transport with Embree, against which every real-time method measures its
 * error. The `reference` tool parses options and calls gb_reference_render.
 *
 * What each mode renders (a "bounce" is a reflection at a surface; the
 * conventions of light and BRDF are those of common/brdf.h):
 *   full                  every path with min_bounces..bounces reflections:
 *                         path tracing, next-event estimation of every light
 *                         with multiple importance sampling for area lights,
 *                         Russian roulette after 3 bounces (a path goes
 *                         on with probability min(1, max throughput));
 *   direct                emitters seen directly and light reflected once
 *                         (= full with bounces 0..1);
 *   indirect1             light reflected exactly twice (= full with 2..2);
 *   indirect1-unshadowed  the same, with the segment between the first and
 *                         the second reflection never blocked: every surface
 *                         along a sampled direction reflects its direct light
 *                         toward the first (what Forward Light Cuts estimates);
 *   vpl                   the light of a VPL set (formats/vpl.h) reflected
 *                         once, with exact visibility: the sum over every VPL
 *                         at each sample (no clamping of the 1/r^2).
 * So direct + indirect1 + full(min_bounces 3) = full, up to noise.
 *
 * Deterministic: pixel i draws its random numbers from PCG32 stream i of the
 * seed, so the image does not depend on the number of threads. A pixel is the
 * mean of spp samples jittered uniformly over its square (box filter).
 *
 * Options: a zeroed gb_reference_options means the defaults. The progress
 * callback gets the fraction of tiles done; returning nonzero cancels the
 * render, which then fails with GB_ERROR_INTERRUPTED.
 */
#ifndef GB_REFERENCE_H
#define GB_REFERENCE_H

#include <stdint.h>

#include "image.h"
#include "progress.h"
#include "scene.h"
#include "vpl.h"

typedef enum gb_reference_mode {
    GB_REFERENCE_FULL = 0,
    GB_REFERENCE_DIRECT,
    GB_REFERENCE_INDIRECT1,
    GB_REFERENCE_INDIRECT1_UNSHADOWED,
    GB_REFERENCE_VPL,
} gb_reference_mode;

enum {
    GB_REFERENCE_DEFAULT_SPP = 64,
    GB_REFERENCE_DEFAULT_VPL_SPP = 4,   /* vpl mode sums every VPL per sample */
    GB_REFERENCE_DEFAULT_BOUNCES = 64,
    };

typedef struct gb_reference_options {
    gb_reference_mode mode;
    int spp;                    /* samples per pixel; 0: 64 (4 in vpl mode) */
    uint64_t seed;
    uint32_t camera;            /* index into scene->cameras */
    int width, height;          /* 0: the camera's resolution */
    int threads;                /* 0: every core */
    int bounces;                /* full: most reflections; 0: 64 */
    int min_bounces;            /* full: fewest reflections; 0 */
    const gb_vpl_set *vpls;     /* vpl: the set, made from this scene */
    uint32_t tile, tile_count;  /* --tile I/N: only the tiles t of the image with
                                   t % N == I (tiles of GB_REFERENCE_TILE_SIZE
                                   pixels, in rows) are rendered, the rest black;
                                   tile_count 0 or 1: the whole image */
    gb_progress_callback progress; /* called from the calling thread; may be NULL */
    void *progress_user;
} gb_reference_options;

typedef struct gb_reference_stats {
    uint64_t rays;              /* rtcIntersect1 and rtcOccluded1 calls */
    uint64_t samples;
    uint64_t nonfinite_samples; /* dropped (NaN or infinite) */
    double seconds;             /* rendering, without the BVH build */
    double cpu_seconds;         /* CPU time of the process while rendering */
    double build_seconds;
} gb_reference_stats;

/* Renders camera options->camera of scene into image (allocated here, RGB,
 * linear; the caller frees it). stats may be NULL. */
gb_result gb_reference_render(const gb_scene *scene, const gb_reference_options *options,
                              gb_image *image, gb_reference_stats *stats, gb_error *error);

/* The side of the square tiles the image is rendered in (and split in by
 * --tile). */
enum { GB_REFERENCE_TILE_SIZE = 16 };

/* The image made from count renders of --tile 0/count .. count-1/count
 * (tiles[i] the one of I = i, all of one size): each pixel taken from the
 * render its tile belongs to, so the bytes are those of the whole render.
 * merged is allocated here; names[i] names tiles[i] in messages. */
gb_result gb_reference_merge_tiles(const gb_image *tiles, const char *const *names,
                                   uint32_t count, gb_image *merged, gb_error *error);

/* The mode named "full", "direct", "indirect1", "indirect1-unshadowed" or
 * "vpl"; GB_ERROR_ARGUMENT for an unknown name. */
gb_result gb_reference_mode_parse(const char *name, gb_reference_mode *mode, gb_error *error);

#endif
