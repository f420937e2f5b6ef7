/* photons_rate — the photon tracer's speed against Embree's raw rate on the
 * same scene, in the same run.
 *
 *   photons_rate [--threads N] [--count N] [--rounds N] SCENE...
 *
 * For each scene, in --rounds alternating rounds:
 *   raw      rtcIntersect1 on incoherent rays (origins uniform in the scene's
 *            bounds, directions uniform on the sphere, drawn in advance) on N
 *            threads, on the Embree scene the tracer builds (high quality,
 *            robust);
 *   photons  gb_photons_trace of --count photons (default 1 000 000) on N
 *            threads, every ray it traces over its tracing time.
 * Both in wall time and in process CPU time (which other processes sharing
 * the cores disturb less); medians printed, one line per scene:
 *   scene tris th raw phot ratio raw_cpu phot_cpu ratio_cpu Mphot/s total_s
 *   total_cpu_s stored B/photon
 * (Mrays per second; *_cpu: per CPU-second times the thread count; total_s:
 * the whole gb_photons_trace call, BVH build included; total_cpu_s: the
 * tracing's CPU seconds over the threads plus the build, what an unloaded
 * machine would take).
 */
#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tools/photons/photons.h"
#include "rate_rounds.h"
#include "raw_ray_rate.h"
#include "progress.h"
#include "random.h"

enum { COLUMNS = 10 };


typedef struct photon_run {
    rate rays;
    double photons_per_second, total_seconds, total_cpu_seconds;
    uint64_t stored;
} photon_run;

static int photon_rate(const gb_scene *scene, const gb_photons_options *options,
                       photon_run *run, gb_error *error)
{
    gb_photon_map map;
    gb_photons_stats stats;
    double start = gb_seconds();
    if (gb_photons_trace(scene, options, &map, &stats, error) != GB_OK)
        return 0;
    run->total_seconds = gb_seconds() - start;
    run->stored = map.count;
    gb_photon_map_free(&map);
    double mrays = 1e-6 * (double)stats.rays;
    run->rays = (rate){mrays / stats.seconds, mrays / stats.cpu_seconds * options->threads};
    run->photons_per_second = (double)stats.paths / stats.seconds;
    run->total_cpu_seconds = stats.cpu_seconds / options->threads + stats.build_seconds;
    return 1;
}

typedef struct photons_bench {
    const gb_photons_options *options;
    int rounds;
    uint64_t stored;            /* the last round's stored photons */
} photons_bench;

static int photons_round(const gb_scene *scene, void *user, double *row, gb_error *error)
{
    photons_bench *bench = user;
    rate raw = raw_rate(scene, bench->options->threads, error);
    photon_run run;
    if (raw.wall <= 0 || !photon_rate(scene, bench->options, &run, error))
        return 0;
    double columns[COLUMNS] = {raw.wall, run.rays.wall, run.rays.wall / raw.wall, raw.cpu,
                               run.rays.cpu, run.rays.cpu / raw.cpu,
                               1e-6 * run.photons_per_second, run.total_seconds,
                               run.total_cpu_seconds, 0.0};
    memcpy(row, columns, sizeof columns);
    bench->stored = run.stored;
    return 1;
}

static int photons_line(const gb_scene *scene, const char *name, void *user, gb_error *error)
{
    photons_bench *bench = user;
    double m[COLUMNS];
    if (!rate_medians(scene, bench->rounds, COLUMNS, photons_round, bench, m, error))
        return 0;
    printf("%-14s %7u %2d %6.2f %6.2f %5.2f %7.2f %7.2f %5.2f %7.3f %7.3f %7.3f %8llu %3d\n",
           name, scene->triangle_count, bench->options->threads, m[0], m[1], m[2], m[3], m[4],
           m[5], m[6], m[7], m[8], (unsigned long long)bench->stored, GB_PHOTON_SIZE);
    return 1;
}

int main(int argc, char **argv)
{
    gb_photons_options options = {.count = GB_PHOTONS_DEFAULT_COUNT, .threads = 2};
    static const struct option long_options[] = {
        {"threads", required_argument, NULL, 't'},
        {"count", required_argument, NULL, 'n'},
        {"rounds", required_argument, NULL, 'r'},
        {NULL, 0, NULL, 0},
    };
    int option, rounds = 3;
    while ((option = getopt_long(argc, argv, "t:n:r:", long_options, NULL)) != -1) {
        if (option == 'r')
            rounds = atoi(optarg);
        else if (option == 't')
            options.threads = atoi(optarg);
        else if (option == 'n')
            options.count = strtoull(optarg, NULL, 10);
        else
            return fputs("usage: photons_rate [--threads N] [--count N] [--rounds N] "
                         "SCENE...\n", stderr), 2;
    }
    if (options.threads < 1 || options.threads > MAX_THREADS || options.count < 1 ||
        rounds < 1 || rounds > MAX_ROUNDS || optind >= argc)
        return fputs("photons_rate: bad arguments\n", stderr), 2;
    printf("%-14s %7s %2s %6s %6s %5s %7s %7s %5s %7s %7s %7s %8s %3s\n", "# scene", "tris",
           "th", "raw", "phot", "ratio", "raw_cpu", "ph_cpu", "ratio", "Mphot/s", "total_s",
           "cpu_s", "stored", "B");
    photons_bench bench = {.options = &options, .rounds = rounds};
    return rate_scenes("photons_rate", argv + optind, argc - optind, photons_line, &bench);
}
