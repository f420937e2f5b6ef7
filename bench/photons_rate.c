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
#include "raw_ray_rate.h"
#include "progress.h"
#include "random.h"

enum { MAX_ROUNDS = 15, COLUMNS = 10 };


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

/* Medians over the rounds of every column. */
static int measure(const gb_scene *scene, const gb_photons_options *options, int rounds,
                   double out[COLUMNS], uint64_t *stored, gb_error *error)
{
    double values[COLUMNS][MAX_ROUNDS];
    for (int r = 0; r < rounds; ++r) {
        rate raw = raw_rate(scene, options->threads, error);
        photon_run run;
        if (raw.wall <= 0 || !photon_rate(scene, options, &run, error))
            return 0;
        double row[COLUMNS] = {raw.wall, run.rays.wall, run.rays.wall / raw.wall, raw.cpu,
                               run.rays.cpu, run.rays.cpu / raw.cpu,
                               1e-6 * run.photons_per_second, run.total_seconds,
                               run.total_cpu_seconds, 0.0};
        for (int k = 0; k < COLUMNS; ++k)
            values[k][r] = row[k];
        *stored = run.stored;
    }
    for (int k = 0; k < COLUMNS; ++k)
        out[k] = median(values[k], rounds);
    return 1;
}

static int bench_scene(const char *path, const gb_photons_options *options, int rounds)
{
    gb_scene scene;
    gb_error error;
    gb_scene_options scene_options = {.load_textures = 1};
    if (gb_scene_load(path, &scene_options, &scene, &error) != GB_OK) {
        fprintf(stderr, "photons_rate: %s\n", error.message);
        return 1;
    }
    double m[COLUMNS];
    uint64_t stored = 0;
    int measured = measure(&scene, options, rounds, m, &stored, &error);
    if (measured) {
        const char *name = strrchr(path, '/');
        printf("%-14s %7u %2d %6.2f %6.2f %5.2f %7.2f %7.2f %5.2f %7.3f %7.3f %7.3f %8llu %3d\n",
               name ? name + 1 : path, scene.triangle_count, options->threads, m[0], m[1], m[2],
               m[3], m[4], m[5], m[6], m[7], m[8], (unsigned long long)stored, GB_PHOTON_SIZE);
        fflush(stdout);
    } else {
        fprintf(stderr, "photons_rate: %s\n", error.message);
    }
    gb_scene_free(&scene);
    return measured ? 0 : 1;
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
    int status = 0;
    for (int i = optind; i < argc; ++i)
        status |= bench_scene(argv[i], &options, rounds);
    return status;
}
