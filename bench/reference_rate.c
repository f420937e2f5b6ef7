/* reference_rate — rays per second of the reference renderer against raw
 * Embree on the same scene, in the same run, with two yardsticks.
 *
 *   reference_rate [--threads N] [--spp N] [--resolution WxH] [--rounds N] SCENE...
 *
 * The reference rate is every ray it traces (rtcIntersect1 and rtcOccluded1)
 * over its rendering time, in full mode (path tracing) on the scene's first
 * camera. The yardsticks, both on N threads on an Embree scene built exactly
 * as the reference builds it (high quality, robust):
 *   path  the main one, like for like (bench/raw_path_rate.h): raw
 *         rtcIntersect1 / rtcOccluded1 on the rays the reference's paths are
 *         made of (camera rays through the same pixels, samples and tiles,
 *         at each hit the same shadow rays toward the lights, one cosine
 *         bounce), with no shading; paths stop after 3 bounces, where the
 *         reference's Russian roulette starts, so they can be a little
 *         shorter than the reference's: both rays-per-sample are printed;
 *   raw   for context (bench/raw_ray_rate.h): rtcIntersect1 alone on
 *         incoherent rays (origins uniform in the scene's bounds, directions
 *         uniform on the sphere, drawn in advance), which the reference's
 *         coherent camera rays and cheap shadow rays can outrun.
 * All three are measured in --rounds alternating rounds, in wall time and in
 * process CPU time (which other processes sharing the cores disturb less),
 * and the medians printed, one line per scene:
 *   scene triangles threads ref path ratio raw ratio_raw
 *         ref_cpu path_cpu ratio_cpu raw_cpu ratio_raw_cpu ref_rays path_rays
 * (Mrays per second; *_cpu: Mrays per CPU-second times the thread count;
 * ratio: ref / path, ratio_raw: ref / raw; *_rays: rays per camera sample).
 */
#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rate_rounds.h"
#include "raw_path_rate.h"
#include "raw_ray_rate.h"
#include "../tools/reference/reference.h"
#include "progress.h"
#include "random.h"

enum { COLUMNS = 12 };

static rate reference_rate(const gb_scene *scene, const gb_reference_options *options,
                           double *rays_per_sample, gb_error *error)
{
    gb_image image;
    gb_reference_stats stats;
    if (gb_reference_render(scene, options, &image, &stats, error) != GB_OK)
        return (rate){-1, -1};
    gb_image_free(&image);
    *rays_per_sample = (double)stats.rays / (double)stats.samples;
    double mrays = 1e-6 * (double)stats.rays;
    return (rate){mrays / stats.seconds, mrays / stats.cpu_seconds * options->threads};
}

/* The columns of one round: reference, path yardstick, ratio, raw
 * yardstick, ratio, the same five in CPU time, then rays per sample. */
static int measure_round(const gb_scene *scene, void *user, double *row, gb_error *error)
{
    const gb_reference_options *options = user;
    double ref_rays = 0, path_rays = 0;
    rate raw = raw_rate(scene, options->threads, error);
    rate path = raw.wall > 0 ? raw_path_rate(scene, options, &path_rays, error) : raw;
    rate ref = path.wall > 0 ? reference_rate(scene, options, &ref_rays, error) : path;
    if (ref.wall <= 0)
        return 0;
    double columns[COLUMNS] = {ref.wall, path.wall, ref.wall / path.wall,
                               raw.wall, ref.wall / raw.wall,
                               ref.cpu, path.cpu, ref.cpu / path.cpu,
                               raw.cpu, ref.cpu / raw.cpu,
                               ref_rays, path_rays};
    memcpy(row, columns, sizeof columns);
    return 1;
}

typedef struct reference_bench {
    gb_reference_options *options;
    int rounds;
} reference_bench;

static int reference_line(const gb_scene *scene, const char *name, void *user,
                          gb_error *error)
{
    const reference_bench *bench = user;
    double m[COLUMNS];
    if (!rate_medians(scene, bench->rounds, COLUMNS, measure_round, bench->options, m, error))
        return 0;
    printf("%-16s %8u %2d %6.2f %6.2f %5.2f %6.2f %5.2f %7.2f %7.2f %5.2f %7.2f %5.2f "
           "%6.1f %6.1f\n", name, scene->triangle_count, bench->options->threads,
           m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11]);
    return 1;
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
    printf("%-16s %8s %2s %6s %6s %5s %6s %5s %7s %7s %5s %7s %5s %6s %6s\n", "# scene", "tris",
           "th", "ref", "path", "ratio", "raw", "r_raw", "ref_cpu", "pathcpu", "ratio",
           "raw_cpu", "r_raw", "r_rays", "p_rays");
    reference_bench bench = {.options = &options, .rounds = rounds};
    return rate_scenes("reference_rate", argv + optind, argc - optind, reference_line, &bench);
}
