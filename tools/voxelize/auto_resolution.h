/* auto_resolution.h — voxelize -r auto: the resolution at which the empty
 * space's topology stops changing, found coarse to fine.
 *
 * From GB_AUTO_RESOLUTION_FIRST up, doubling, the scene's surface is marked
 * and the empty space's components and Euler
 * characteristic counted (empty_topology.h). The first r whose counts equal
 * those at 2r and 4r is where the topology stops changing; 2r is chosen, so
 * that every opening already open at r is at least two voxels wide (the
 * rule of voxelize -r's help for an opening to stay open in the skeleton).
 * Two agreeing resolutions were not enough: the classroom's empty space has
 * the same counts at 16 and 32 by chance, and other ones at 64. If no
 * three agree up to GB_AUTO_RESOLUTION_MAX, that is chosen, unsettled: a
 * scene whose small gaps keep opening (meshes that are not closed) has no
 * resolution where its topology stops changing. */
#ifndef GB_AUTO_RESOLUTION_H
#define GB_AUTO_RESOLUTION_H

#include <stdint.h>

#include "empty_topology.h"
#include "result.h"
#include "scene.h"
#include "voxelize.h"

enum {
    GB_AUTO_RESOLUTION_FIRST = 16,
    GB_AUTO_RESOLUTION_MAX = 512,
    GB_AUTO_RESOLUTION_STEPS = 6,   /* 16, 32, ... 512 */
};

typedef struct gb_auto_resolution {
    uint32_t resolution;            /* the choice */
    int settled;                    /* 1: two resolutions agreed; 0: none did */
    uint32_t checked;               /* resolutions counted, in order: */
    uint32_t resolutions[GB_AUTO_RESOLUTION_STEPS];
    gb_empty_topology topology[GB_AUTO_RESOLUTION_STEPS];
} gb_auto_resolution;

/* options (NULL: defaults) give the pad and threads of the checks; their
 * resolution and progress are ignored. */
gb_result gb_voxelize_auto_resolution(const gb_scene *scene, const gb_voxelize_options *options,
                                      gb_auto_resolution *choice, gb_error *error);

#endif
