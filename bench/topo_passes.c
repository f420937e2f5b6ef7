/* topo_passes.c — Table I of Noël & Biri 2014 on this machine: ms per pass
 * of the topological method (GP = G-buffer + visibility clusters, IUGC, LA,
 * IL) and the frame, headless, means over the frames after the first.
 * IUGC is the GPU pass (topo_geometry_clusters_gpu.c); the last column is
 * the CPU reference IUGC (GB_TOPO_IUGC=cpu: G-buffer read back, clusters
 * sent back) timed on a second renderer right after, for comparison.
 *
 *   topo_passes SCENE BAKE_DIR WIDTHxHEIGHT FRAMES VPLS...
 * prints one line per VPL count: vpls gp iugc la il total iugc_cpu (ms).
 */
#include <stdio.h>
#include <stdlib.h>

#include "../runtime/topo/topo.h"
#include "headless_frames.h"

typedef struct pass_ms {
    double gp, iugc, la, il, total;
} pass_ms;

/* Means of FRAMES frames after the first; iugc: "gpu" or "cpu". */
static gb_result measure(const gb_scene *scene, const gb_bake *bake, int width,
                         int height, int frames, int vpls, const char *iugc, pass_ms *ms,
                         gb_error *error)
{
    setenv("GB_TOPO_IUGC", iugc, 1);
    gb_renderer_options options = {.width = width, .height = height, .method = GB_METHOD_TOPO,
                                   .bake = bake, .parameters = {.vpls = vpls}};
    headless_frames h;
    gb_result result = headless_frames_create(scene, &options, &h, error);
    if (result != GB_OK)
        return result;
    gb_renderer *renderer = &h.renderer;
    gb_topo_pass_times first = {0}, all = {0};
    for (int i = 0; i < frames && result == GB_OK; ++i) {
        result = headless_frames_draw(&h, error);
        if (i == 0)
            gb_topo_times(renderer->method_state[GB_METHOD_TOPO], &first);
    }
    if (result == GB_OK) {
        gb_topo_times(renderer->method_state[GB_METHOD_TOPO], &all);
        double n = all.frames - first.frames > 0 ? all.frames - first.frames : 1;
        ms->gp = gb_timings_mean_ms(&renderer->timings, GB_PASS_GBUFFER) +
                 (all.clusters_ms - first.clusters_ms) / n;
        ms->iugc = (all.iugc_ms - first.iugc_ms) / n;
        ms->la = (all.la_ms - first.la_ms) / n;
        ms->il = (all.il_ms - first.il_ms) / n;
        ms->total = gb_timings_mean_ms(&renderer->timings, GB_PASS_COUNT);
    }
    headless_frames_destroy(&h);
    return result;
}

int main(int argc, char **argv)
{
    int width, height;
    if (argc < 6 || sscanf(argv[3], "%dx%d", &width, &height) != 2) {
        fprintf(stderr, "usage: topo_passes SCENE BAKE_DIR WxH FRAMES VPLS...\n");
        return 2;
    }
    gb_error error;
    gb_scene scene;
    gb_bake *bake = NULL;
    if (gb_scene_load(argv[1], NULL, &scene, &error) != GB_OK ||
        gb_bake_open(&scene, argv[1], argv[2], &bake, &error) != GB_OK) {
        fprintf(stderr, "topo_passes: %s\n", error.message);
        return 1;
    }
    printf(" vpls     GP ms   IUGC ms     LA ms     IL ms  total ms  IUGC CPU ms   (%dx%d)\n",
           width, height);
    int status = 0;
    for (int i = 5; i < argc && !status; ++i) {
        pass_ms gpu, cpu;
        int vpls = atoi(argv[i]), frames = atoi(argv[4]);
        if (measure(&scene, bake, width, height, frames, vpls, "gpu", &gpu, &error) != GB_OK ||
            measure(&scene, bake, width, height, frames, vpls, "cpu", &cpu, &error) != GB_OK) {
            fprintf(stderr, "topo_passes: %s\n", error.message);
            status = 1;
            break;
        }
        printf("%5d %9.1f %9.1f %9.1f %9.1f %9.1f %12.1f\n", vpls, gpu.gp, gpu.iugc, gpu.la,
               gpu.il, gpu.total, cpu.iugc);
        fflush(stdout);
    }
    gb_bake_release(bake);
    gb_scene_free(&scene);
    return status;
}
