/* texel_gather.h — the lightmap's covered texels by final gather
 * (final_gather.h), in two passes of atlas rows on a work queue:
 *   1. probes: per triangle that covers a texel, one per texel it covers,
 *      at least GB_TEXEL_GATHER_MIN_PROBES and at most
 *      GB_TEXEL_GATHER_MAX_PROBES, each a point drawn uniformly over it
 *      and one direction, from each side, say how open
 *      that side is; the more open side is the one the whole triangle
 *      keeps (the side the winding faces on a tie): one side per triangle,
 *      so that no surface is speckled with both;
 *   2. the gather: `rays` directions from the kept side, on the texels
 *      texel_interpolation.h chooses, coarsest lattice first, one pass
 *      per stride; the others interpolated between them.
 * Texel i's gather draws from PCG32 stream i of the seed, and triangle t's
 * sides' probes from streams T + 2 t and T + 2 t + 1, T the atlas's texel
 * count: the image never depends on the number of threads.
 *
 * The caller owns every argument; the tables for Embree and the lights are
 * built and freed here.
 */
#ifndef GB_TEXEL_GATHER_H
#define GB_TEXEL_GATHER_H

#include <stdint.h>

#include "atlas.h"
#include "image.h"
#include "light_octree.h"
#include "progress.h"
#include "result.h"
#include "scene.h"
#include "texel_cover.h"

enum {
    GB_TEXEL_GATHER_MIN_PROBES = 16,    /* per side of a triangle that covers a texel */
    GB_TEXEL_GATHER_MAX_PROBES = 64,    /* per side of a triangle */
    GB_TEXEL_GATHER_PATH_BOUNCES = 64,  /* --paths: most reflections, as reference's */
};
/* final_gather.h's near_distance, over the scene's bounding diagonal */
#define GB_TEXEL_GATHER_NEAR_FRACTION 0.01f

typedef struct gb_texel_gather {
    const gb_scene *scene;
    const gb_atlas *atlas;
    const gb_texel_cover *cover;    /* the texels to fill */
    const gb_light_octree *octree;  /* read at the hits; NULL: paths traced on */
    int rays;                       /* per texel, >= 1 */
    int octree_bounces;             /* final_gather.h's, >= 1 */
    double accuracy;                /* Ward's a (texel_interpolation.h); 0: every texel gathers */
    uint64_t seed;
    int threads;                    /* 0: every core */
    gb_progress_callback progress;  /* of the gather pass; may be NULL */
    void *progress_user;
} gb_texel_gather;

/* Fills image's covered texels (3 channels, the atlas's size); adds the
 * rays traced to *rays and sets *threads to the threads used. */
gb_result gb_texel_gather_bake(const gb_texel_gather *gather, gb_image *image, uint64_t *rays,
                               int *threads, gb_error *error);

#endif
