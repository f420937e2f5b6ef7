/* atlas_inputs.h — what bench/atlas_seams.c and bench/lightmap_error.c
 * read: SCENE NAME.atlas A.exr B.exr [CAMERA], the atlas checked against
 * the scene, A and B of one size with RGB.
 *
 *   atlas_inputs in;
 *   if (atlas_inputs_read(&in, argc, argv, "lightmap_error")) ...compare...
 *   atlas_inputs_free(&in);
 *
 * The caller owns `in` (atlas_inputs_free, also after a failed read).
 */
#ifndef GB_BENCH_ATLAS_INPUTS_H
#define GB_BENCH_ATLAS_INPUTS_H

#include <stdio.h>
#include <stdlib.h>

#include "atlas.h"
#include "image.h"
#include "scene.h"

typedef struct atlas_inputs {
    gb_scene scene;
    gb_atlas atlas;
    gb_image a, b;
    int camera;
} atlas_inputs;

/* 1 when every input reads and fits; else 0, the reason printed after
 * "tool: ". */
static inline int atlas_inputs_read(atlas_inputs *in, int argc, char **argv, const char *tool)
{
    gb_error error = {0};
    *in = (atlas_inputs){.camera = argc == 6 ? atoi(argv[5]) : 0};
    if (argc != 5 && argc != 6) {
        fprintf(stderr, "usage: %s SCENE NAME.atlas A.exr B.exr [CAMERA]\n", tool);
        return 0;
    }
    if (gb_scene_load(argv[1], NULL, &in->scene, &error) != GB_OK ||
        gb_atlas_read(argv[2], &in->atlas, &error) != GB_OK ||
        gb_atlas_check_scene(&in->atlas, in->scene.hash, in->scene.triangle_count, argv[2],
                             &error) != GB_OK ||
        gb_image_read(argv[3], &in->a, &error) != GB_OK ||
        gb_image_read(argv[4], &in->b, &error) != GB_OK) {
        fprintf(stderr, "%s: %s\n", tool, error.message);
        return 0;
    }
    if (in->a.width != in->b.width || in->a.height != in->b.height || in->a.channels < 3 ||
        in->b.channels < 3) {
        fprintf(stderr, "%s: the images differ in size or have no RGB\n", tool);
        return 0;
    }
    if (in->camera < 0 || (uint32_t)in->camera >= in->scene.camera_count) {
        fprintf(stderr, "%s: no camera %d\n", tool, in->camera);
        return 0;
    }
    return 1;
}

static inline void atlas_inputs_free(atlas_inputs *in)
{
    gb_image_free(&in->a);
    gb_image_free(&in->b);
    gb_atlas_free(&in->atlas);
    gb_scene_free(&in->scene);
}

#endif
