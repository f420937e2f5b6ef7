/* reference_rate — rays per second of the reference renderer against
 * Embree's raw rate on the same scene, in the same run.
 *
 *   reference_rate [--threads N] [--spp N] [--resolution WxH] SCENE...
 *
 * For each scene: the raw rate is rtcIntersect1 on incoherent rays (origins
 * uniform in the scene's bounds, directions uniform on the sphere, drawn in
 * advance), on N threads, on an Embree scene built exactly as the reference
 * builds it (high quality, robust). The reference rate is every ray it
 * traces (rtcIntersect1 and rtcOccluded1) over its rendering time, in full
 * mode (path tracing) on the scene's first camera. Both are measured in
 * --rounds alternating rounds, in wall time and in process CPU time (which
 * other processes sharing the cores disturb less), and the medians printed,
 * one line per scene:
 *   scene triangles threads raw ref ratio raw_cpu ref_cpu ratio_cpu
 * (Mrays per second; *_cpu: Mrays per CPU-second times the thread count).
 */
#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "raw_ray_rate.h"
#include "../tools/reference/reference.h"
#include "progress.h"
#include "random.h"

enum { MAX_ROUNDS = 15 };


static rate reference_rate(const gb_scene *scene, const gb_reference_options *options,
                           gb_error *error)
{
    gb_image image;
    gb_reference_stats stats;
    if (gb_reference_render(scene, options, &image, &stats, error) != GB_OK)
        return (rate){-1, -1};
    gb_image_free(&image);
    double mrays = 1e-6 * (double)stats.rays;
    return (rate){mrays / stats.seconds, mrays / stats.cpu_seconds * options->threads};
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *values, int count)
{
    qsort(values, (size_t)count, sizeof *values, compare_doubles);
    return count % 2 ? values[count / 2] : 0.5 * (values[count / 2 - 1] + values[count / 2]);
}

/* Medians over the rounds of raw, reference and their ratio, wall and CPU. */
static int measure(const gb_scene *scene, const gb_reference_options *options, int rounds,
                   double out[6], gb_error *error)
{
    double values[6][MAX_ROUNDS];
    for (int r = 0; r < rounds; ++r) {
        rate raw = raw_rate(scene, options->threads, error);
        rate reference = raw.wall > 0 ? reference_rate(scene, options, error) : raw;
        if (reference.wall <= 0)
            return 0;
        double row[6] = {raw.wall, reference.wall, reference.wall / raw.wall,
                         raw.cpu, reference.cpu, reference.cpu / raw.cpu};
        for (int k = 0; k < 6; ++k)
            values[k][r] = row[k];
    }
    for (int k = 0; k < 6; ++k)
        out[k] = median(values[k], rounds);
    return 1;
}

static int bench_scene(const char *path, gb_reference_options *options, int rounds)
{
    gb_scene scene;
    gb_error error;
    gb_scene_options scene_options = {.load_textures = 1};
    if (gb_scene_load(path, &scene_options, &scene, &error) != GB_OK) {
        fprintf(stderr, "reference_rate: %s\n", error.message);
        return 1;
    }
    double m[6];
    int measured = measure(&scene, options, rounds, m, &error);
    if (measured) {
        const char *name = strrchr(path, '/');
        printf("%-16s %8u %2d %7.2f %7.2f %6.2f %8.2f %8.2f %6.2f\n", name ? name + 1 : path,
               scene.triangle_count, options->threads, m[0], m[1], m[2], m[3], m[4], m[5]);
        fflush(stdout);
    } else {
        fprintf(stderr, "reference_rate: %s\n", error.message);
    }
    gb_scene_free(&scene);
    return measured ? 0 : 1;
}

int main(int argc, char **argv)
{
    gb_reference_options options = {.mode = GB_REFERENCE_FULL, .spp = 4, .width = 320,
                                     .height = 240, .threads = 1};
    static const struct option long_options[] = {
        {"threads", required_argument, NULL, 't'},
        {"spp", required_argument, NULL, 's'},
        {"resolution", required_argument, NULL, 'r'},
        {"rounds", required_argument, NULL, 'n'},
        {NULL, 0, NULL, 0},
    };
    int option, rounds = 3;
    while ((option = getopt_long(argc, argv, "t:s:r:n:", long_options, NULL)) != -1) {
        if (option == 'n')
            rounds = atoi(optarg);
        else if (option == 't')
            options.threads = atoi(optarg);
        else if (option == 's')
            options.spp = atoi(optarg);
        else if (option == 'r' && sscanf(optarg, "%dx%d", &options.width, &options.height) == 2)
            continue;
        else
            return fputs("usage: reference_rate [--threads N] [--spp N] [--resolution WxH] "
                         "[--rounds N] SCENE...\n", stderr), 2;
    }
    if (options.threads < 1 || options.threads > MAX_THREADS || options.spp < 1 ||
        rounds < 1 || rounds > MAX_ROUNDS || optind >= argc)
        return fputs("reference_rate: bad arguments\n", stderr), 2;
    printf("%-16s %8s %2s %7s %7s %6s %8s %8s %6s\n", "# scene", "tris", "th", "raw", "ref",
           "ratio", "raw_cpu", "ref_cpu", "ratio");
    int status = 0;
    for (int i = optind; i < argc; ++i)
        status |= bench_scene(argv[i], &options, rounds);
    return status;
}
