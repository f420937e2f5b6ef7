/* flc_passes.c — Table 1 of Laurent et al. 2016 on this machine: ms per pass
 * of Forward Light Cuts, headless on the scene's first camera: G-buffer (each
 * frame) and shadow maps (drawn once, the scene being static), the regular
 * pipeline (VPL generation + splatting of the regular triangles), the
 * divergent pipeline (the same for the divergent triangles' sub-triangles),
 * upscaling + blur (untiling, blur, accumulation and composite), the whole
 * indirect pass and the full frame. Means over the frames after the first;
 * the FLC passes are closed by glFinish and timed by the wall clock
 * (gb_flc_measure), the others by runtime/timings.h.
 *
 *   flc_passes SCENE WxH FRAMES [--navg N] [--tiling T] [--levels L]
 *              [--no-decimation] [--indirect] [-o OUT.exr]
 * prints a header and one line: navg tiling levels scene triangles
 * (regular+divergent) gbuffer sm regular divergent upscale indirect frame
 * (ms), the VPLs the tessellation made a frame, and the process's CPU ms
 * over the FLC passes (regular + divergent + upscale: llvmpipe's threads,
 * less sensitive to other jobs than the wall clock).
 * --no-decimation keeps every VPL triangle (GB_FLC_NO_DECIMATION);
 * --indirect renders the indirect light only (for imgdiff against
 * `reference --mode indirect1-unshadowed`); -o writes the last frame.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../runtime/flc/flc.h"
#include "headless_frames.h"

typedef struct run {
    const char *scene, *output;
    int width, height, frames;
    gb_method_parameters parameters;
    gb_terms terms;
} run;

static gb_result measure(const gb_scene *scene, const run *r, gb_error *error)
{
    gb_renderer_options options = {.width = r->width, .height = r->height,
                                   .method = GB_METHOD_FLC, .terms = r->terms,
                                   .parameters = r->parameters};
    headless_frames h;
    gb_result result = headless_frames_create(scene, &options, &h, error);
    if (result != GB_OK)
        return result;
    gb_renderer *renderer = &h.renderer;
    for (int i = 0; i < r->frames && result == GB_OK; ++i) {
        result = headless_frames_draw(&h, error);
        if (i == 0)     /* the first frame compiles the shaders: not measured */
            gb_flc_measure(renderer->method_state[GB_METHOD_FLC], 1);
    }
    if (result == GB_OK && r->output) {
        gb_image image;
        result = gb_renderer_read(renderer, &image, error);
        if (result == GB_OK)
            result = gb_image_write(r->output, &image, error);
        gb_image_free(&image);
    }
    if (result == GB_OK) {
        gb_flc_pass_times t;
        gb_flc_times(renderer->method_state[GB_METHOD_FLC], &t);
        double n = t.frames ? t.frames : 1;
        const gb_timings *timings = &renderer->timings;
        const gb_flc_parameters *p = &r->parameters.flc;
        int levels = p->levels > 0 ? p->levels : GB_FLC_DEFAULT_LEVELS;
        char level_text[16];
        snprintf(level_text, sizeof level_text, p->levels == GB_FLC_NO_DECIMATION ? "all"
                                                                                       : "%d",
                 levels);
        printf("%5.0f %6d %6s %8u+%-7u %8.1f %8.1f %9.1f %9.1f %8.1f %9.1f %9.1f %9.0f %9.1f\n",
               p->n_avg > 0 ? p->n_avg : GB_FLC_DEFAULT_N_AVG, p->tiling,
               level_text, t.regular_triangles, t.divergent_triangles,
               gb_timings_mean_ms(timings, GB_PASS_GBUFFER),
               gb_timings_mean_ms(timings, GB_PASS_SHADOW_MAPS), t.regular_ms / n,
               t.divergent_ms / n, t.resolve_ms / n,
               gb_timings_mean_ms(timings, GB_PASS_INDIRECT_LIGHT),
               gb_timings_mean_ms(timings, GB_PASS_COUNT), (double)t.divergent_vpls / n,
               t.cpu_ms / n);
    }
    headless_frames_destroy(&h);
    return result;
}

static int usage(void)
{
    fprintf(stderr, "usage: flc_passes SCENE WxH FRAMES [--navg N] [--tiling T] [--levels L]"
                    " [--no-decimation] [--indirect] [-o OUT.exr]\n");
    return 2;
}

int main(int argc, char **argv)
{
    run r = {0};
    if (argc < 4 || sscanf(argv[2], "%dx%d", &r.width, &r.height) != 2 || r.width <= 0 ||
        r.height <= 0 || (r.frames = atoi(argv[3])) < 2)
        return usage();
    r.scene = argv[1];
    for (int i = 4; i < argc; ++i) {
        const char *a = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--no-decimation"))
            r.parameters.flc.levels = GB_FLC_NO_DECIMATION;
        else if (!strcmp(a, "--indirect"))
            r.terms = GB_TERMS_INDIRECT;
        else if (!value)
            return usage();
        else if (!strcmp(a, "--navg"))
            r.parameters.flc.n_avg = (float)atof(value), ++i;
        else if (!strcmp(a, "--tiling"))
            r.parameters.flc.tiling = atoi(value), ++i;
        else if (!strcmp(a, "--levels"))
            r.parameters.flc.levels = atoi(value), ++i;
        else if (!strcmp(a, "-o"))
            r.output = value, ++i;
        else
            return usage();
    }
    gb_error error;
    gb_scene scene;
    gb_scene_options scene_options = {.load_textures = 1};     /* as gbview */
    if (gb_scene_load(r.scene, &scene_options, &scene, &error) != GB_OK) {
        fprintf(stderr, "flc_passes: %s\n", error.message);
        return 1;
    }
    printf(" navg tiling levels  triangles reg+div  gbuf ms    SM ms  regular  divergent"
           "  upscale  indirect     frame  tess VPLs  FLC CPU   (%dx%d, ms)\n", r.width,
           r.height);
    int status = 0;
    if (measure(&scene, &r, &error) != GB_OK) {
        fprintf(stderr, "flc_passes: %s\n", error.message);
        status = 1;
    }
    gb_scene_free(&scene);
    return status;
}
