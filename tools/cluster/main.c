/* cluster — the light octree of a scene from its photon map (cluster.h). */

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cluster.h"
#include "light_octree.h"
#include "output_file.h"
#include "photon_map.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: cluster [options] SCENE IN.phot -o OUT.lot\n"
    "Clusters the photon map IN.phot of SCENE into a light octree of virtual\n"
    "directional lights (vivianloc-2007; formats/FORMATS.md, \"Light octree\"). The\n"
    "file depends on the seed, never on --threads.\n"
    "\n"
    "  -o, --output FILE       the light octree to write\n"
    "  -d, --depth N           octree depth (delta), 1..10 (default 6: 64^3 leaves)\n"
    "  -k, --knn K             most photons gathered per leaf (default 300)\n"
    "  -r, --radius R          largest gathering radius, world units\n"
    "                          (default 3 leaf edges)\n"
    "      --vdls K_MAX        most VDLs per leaf, 1..64 (default 8)\n"
    "      --max-spread DEG    fewest VDLs whose spread is at most DEG degrees\n"
    "                          (default 15; 0: always K_MAX)\n"
    "      --restarts N        k-means runs per leaf and k, the best kept, 1..64\n"
    "                          (default 1)\n"
    "      --seed N            k-means++ seed (default 0)\n"
    "  -t, --threads N         threads (default: every core)\n"
    "      --stats             print leaves, VDLs and seconds on stdout\n"
    "  -q, --quiet             no progress bar, no warnings\n"
    "  -h, --help              this help\n"
    "  -V, --version           the version\n";

typedef struct arguments {
    gb_cluster_options cluster;
    const char *output, *scene, *photons;
    int quiet, stats;
} arguments;

enum { OPTION_VDLS = 256, OPTION_SPREAD, OPTION_RESTARTS, OPTION_SEED, OPTION_STATS };

static int parse_unsigned(const char *text, uint64_t low, uint64_t high, uint64_t *value)
{
    char *end;
    errno = 0;
    unsigned long long parsed = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || parsed < low || parsed > high)
        return 0;
    *value = parsed;
    return 1;
}

static int parse_float(const char *text, float low, float high, float *value)
{
    char *end;
    errno = 0;
    float parsed = strtof(text, &end);
    if (errno || end == text || *end || !isfinite(parsed) || parsed < low || parsed > high)
        return 0;
    *value = parsed;
    return 1;
}

/* Stores one option with a value; returns 0 when the value is bad. */
static int parse_value(int option, const char *text, arguments *a)
{
    uint64_t value;
    gb_cluster_options *o = &a->cluster;
    switch (option) {
    case 'o':
        a->output = text;
        return 1;
    case 'd':
        return parse_unsigned(text, 1, GB_LIGHT_OCTREE_MAX_DEPTH, &value) &&
               (o->depth = (unsigned)value, 1);
    case 'k':
        return parse_unsigned(text, 1, 100000, &value) && (o->knn = (unsigned)value, 1);
    case 'r':
        return parse_float(text, 1e-30f, 1e30f, &o->radius);
    case OPTION_VDLS:
        return parse_unsigned(text, 1, GB_LIGHT_OCTREE_MAX_VDLS, &value) &&
               (o->vdls_max = (unsigned)value, 1);
    case OPTION_SPREAD:
        /* 0 means "always K_max", which the library spells as negative */
        return parse_float(text, 0.0f, 180.0f, &o->max_spread) &&
               (o->max_spread = o->max_spread == 0.0f ? -1.0f : o->max_spread, 1);
    case OPTION_RESTARTS:
        return parse_unsigned(text, 1, 64, &value) && (o->restarts = (unsigned)value, 1);
    case OPTION_SEED:
        return parse_unsigned(text, 0, UINT64_MAX, &o->seed);
    case 't':
        return parse_unsigned(text, 1, 256, &value) && (o->threads = (int)value, 1);
    }
    return 0;
}

static int parse_option(int option, const char *text, arguments *a, const char *name)
{
    if (option == 'q') {
        a->quiet = 1;
        return 1;
    }
    if (option == OPTION_STATS) {
        a->stats = 1;
        return 1;
    }
    if (parse_value(option, text, a))
        return 1;
    fprintf(stderr, "cluster: bad value \"%s\" for option %s\n", text ? text : "", name);
    return 0;
}

/* The long name of an option, for messages. */
static const char *option_name(const struct option *options, int option)
{
    static char short_name[3] = "-?";
    for (const struct option *o = options; o->name; ++o)
        if (o->val == option)
            return o->name;
    short_name[1] = (char)option;
    return short_name;
}

static int check_arguments(arguments *a, int argc, char **argv)
{
    if (!a->output || argc - optind != 2) {
        fprintf(stderr, "cluster: expected SCENE IN.phot and -o OUT.lot\n%s", usage);
        return 2;
    }
    a->scene = argv[optind];
    a->photons = argv[optind + 1];
    return 0;
}

/* 0: go on; -1: done (help, version); otherwise the exit status. */
static int parse_arguments(int argc, char **argv, arguments *a)
{
    static const struct option options[] = {
        {"output", required_argument, NULL, 'o'},
        {"depth", required_argument, NULL, 'd'},
        {"knn", required_argument, NULL, 'k'},
        {"radius", required_argument, NULL, 'r'},
        {"vdls", required_argument, NULL, OPTION_VDLS},
        {"max-spread", required_argument, NULL, OPTION_SPREAD},
        {"restarts", required_argument, NULL, OPTION_RESTARTS},
        {"seed", required_argument, NULL, OPTION_SEED},
        {"threads", required_argument, NULL, 't'},
        {"stats", no_argument, NULL, OPTION_STATS},
        {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    int option;
    while ((option = getopt_long(argc, argv, "o:d:k:r:t:qhV", options, NULL)) != -1) {
        if (option == 'h')
            return fputs(usage, stdout) == EOF ? 1 : -1;
        if (option == 'V')
            return puts("cluster (gibake) 0.1") == EOF ? 1 : -1;
        if (option == '?' || !parse_option(option, optarg, a, option_name(options, option)))
            return fputs(usage, stderr), 2;
    }
    return check_arguments(a, argc, argv);
}

static void print_stats(const gb_cluster_stats *s, const char *output)
{
    printf("leaves %u\nvdls %u\nthreads %d\nmean_gathered %.1f\nmean_spread_degrees %.2f\n",
           s->leaves, s->vdls, s->threads, s->mean_gathered, s->mean_spread);
    printf("octree_seconds %.3f\nindex_seconds %.3f\nquery_seconds %.3f\n"
           "queries_per_second %.0f\nkmeans_seconds %.3f\nseconds %.3f\n", s->octree_seconds,
           s->index_seconds, s->query_seconds,
           s->query_seconds > 0.0 ? (double)s->queries / s->query_seconds : 0.0,
           s->kmeans_seconds, s->seconds);
    printf("vdl_histogram");
    for (int k = 0; k <= GB_LIGHT_OCTREE_MAX_VDLS; ++k)
        if (s->vdl_histogram[k])
            printf(" %d:%u", k, s->vdl_histogram[k]);
    printf("\n");
    FILE *file = fopen(output, "rb");
    if (file && fseek(file, 0, SEEK_END) == 0)
        printf("bytes %ld\n", ftell(file));
    if (file)
        fclose(file);
}

static gb_result cluster(arguments *a, const gb_scene *scene, const gb_photon_map *map,
                         gb_error *error)
{
    gb_progress progress;
    gb_progress_begin(&progress, "cluster", a->quiet);
    a->cluster.progress = gb_progress_report;
    a->cluster.progress_user = &progress;
    gb_light_octree octree;
    gb_cluster_stats stats;
    gb_result result = gb_cluster_build(scene, map, &a->cluster, &octree, &stats, error);
    gb_progress_end(&progress);
    if (result == GB_OK)
        result = gb_light_octree_write(a->output, &octree, error);
    if (result == GB_OK && a->stats)
        print_stats(&stats, a->output);
    gb_light_octree_free(&octree);
    return result;
}

static gb_result run(arguments *a, gb_error *error)
{
    gb_scene scene;
    gb_photon_map map;
    memset(&map, 0, sizeof map);
    gb_result result = gb_scene_load(a->scene, NULL, &scene, error);
    if (result == GB_OK && !a->quiet)  /* no light: an empty map, an octree of no VDL */
        gb_scene_warn("cluster", &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    if (result == GB_OK)
        result = gb_photon_map_read(a->photons, &map, error);
    if (result == GB_OK)
        result = gb_photon_map_check_scene(&map, scene.hash, a->photons, error);
    if (result == GB_OK)
        result = cluster(a, &scene, &map, error);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    arguments a = {0};
    int status = parse_arguments(argc, argv, &a);
    if (status)
        return status < 0 ? 0 : status;
    gb_error error;
    if (gb_output_file_check(a.output, &error) != GB_OK || run(&a, &error) != GB_OK) {
        fprintf(stderr, "cluster: %s\n", error.message);
        return 1;
    }
    return fflush(stdout) == 0 ? 0 : 1;
}
