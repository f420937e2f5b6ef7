/* headless_render.h — what the unit tests of the runtime's renders share:
 * the Cornell box of the tree (scenes/cornell/cornell.scene, found through
 * $GB_ROOT, default "."), the headless render with its failure printed, and
 * the reference renderer's image to hold it against, and the relative MSE
 * of tools/imgdiff.
 *
 *   gb_scene scene;
 *   if (!load_cornell(&scene)) ...               // the reason printed
 *   gb_headless_options options = {...};
 *   if (render_headless(&scene, &options, &image)) ...   // image: the caller's
 *   if (render_reference(&scene, &reference_options, &reference)) ...
 *   double e = relative_mse(&image, &reference);  // INFINITY if not comparable
 *
 * Each returns 0 (relative_mse INFINITY) with "# reason" printed when it
 * cannot (succeeded does that for any gb_result); the caller frees what it
 * gets (gb_scene_free, gb_image_free).
 */
#ifndef GB_HEADLESS_RENDER_H
#define GB_HEADLESS_RENDER_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../../runtime/headless.h"
#include "image_error.h"
#include "../../tools/reference/reference.h"
#include "scene.h"

/* The root of the tree: $GB_ROOT, or "." when it is unset or empty. */
static inline const char *tree_root(void)
{
    const char *env = getenv("GB_ROOT");
    return env && *env ? env : ".";
}

/* 1 when result is GB_OK; else 0, with error's message printed. */
static inline int succeeded(gb_result result, const gb_error *error)
{
    if (result == GB_OK)
        return 1;
    printf("# %s\n", error->message);
    return 0;
}

static inline int load_cornell(gb_scene *scene)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/scenes/cornell/cornell.scene", tree_root());
    gb_error error;
    return succeeded(gb_scene_load(path, NULL, scene, &error), &error);
}

static inline int render_headless(const gb_scene *scene, const gb_headless_options *options,
                                  gb_image *image)
{
    gb_error error;
    return succeeded(gb_render_headless(scene, options, image, NULL, &error), &error);
}

static inline int render_reference(const gb_scene *scene, const gb_reference_options *options,
                                   gb_image *image)
{
    gb_error error;
    return succeeded(gb_reference_render(scene, options, image, NULL, &error), &error);
}

static inline double relative_mse(const gb_image *image, const gb_image *reference)
{
    gb_image_error measures;
    gb_error error;
    return succeeded(gb_image_error_compute(image, reference, NULL, &measures, &error), &error)
               ? measures.relative_mse
               : INFINITY;
}

#endif
