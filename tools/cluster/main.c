/* cluster — the light octree of a scene from its photon map (cluster.h). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "depfile.h"
#include "cluster.h"
#include "light_octree.h"
#include "output_file.h"
#include "photon_map.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: cluster [options] SCENE IN.phot -o OUT.lot\n"
    "       cluster --merge PART0.lot PART1.lot ... -o OUT.lot\n"
    "Clusters the photon map IN.phot of SCENE into a light octree of virtual\n"
    "directional lights (vivianloc-2007; formats/FORMATS.md, \"Light octree\"). The\n"
    "file depends on the seed, never on --threads.\n"
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: --seed, --threads, --stats, --depfile, -q */
    gb_cluster_options cluster;
    const char *output, *scene, *photons;
    char **parts;               /* --merge: the parts */
    int part_count;
    int merge;
} arguments;

enum { OPTION_RADIUS = 256, OPTION_VDLS, OPTION_TOLERANCE, OPTION_RESTARTS,
       OPTION_INTERPOLATION, OPTION_SHARD, OPTION_MERGE };

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the light octree to write"),
    GB_CLI_OPTION('d', "depth", "N",
                  "octree depth (delta), 1..10 (default 6: 64^3 leaves;\n"
                  "the paper finds quality improving over delta 4..6)"),
    GB_CLI_OPTION('k', "knn", "K",
                  "most photons gathered per leaf (default 300: the\n"
                  "paper's Fig. 17; its leaves held 50 to 500)"),
    GB_CLI_OPTION(OPTION_RADIUS, "radius", "R",
                  "largest gathering radius, world units\n"
                  "(default 3 leaf edges)"),
    GB_CLI_OPTION(OPTION_VDLS, "vdls", "K_MAX", "most VDLs per leaf, 1..64 (default 8)"),
    GB_CLI_OPTION(OPTION_TOLERANCE, "tolerance", "T",
                  "the fewest VDLs a leaf whose irradiance at the\n"
                  "normals around it is within T of its photons',\n"
                  "relative (default 0.2; 0: always K_MAX, the paper)"),
    GB_CLI_OPTION(OPTION_RESTARTS, "restarts", "N",
                  "k-means runs per leaf and k, the best kept, 1..64\n"
                  "(default 1)"),
    GB_CLI_OPTION(OPTION_INTERPOLATION, "interpolation", "HOW",
                  "between leaves, as the runtime and lightmap read the\n"
                  "octree: surface (default: each leaf weighed by how\n"
                  "near its plane and normal are to the point's, no\n"
                  "light from another surface) or trilinear (the\n"
                  "paper's)"),
    GB_CLI_SEED("N", "k-means++ seed (default 0)"),
    GB_CLI_THREADS(256, NULL),
    GB_CLI_OPTION(OPTION_SHARD, "shard", "I/N",
                  "cluster only part I of N of the leaves (a range of\n"
                  "the leaf order; the others get no VDL), indexing\n"
                  "only the photons they can gather"),
    GB_CLI_OPTION(OPTION_MERGE, "merge", NULL,
                  "join the N parts given, in order 0/N .. N-1/N, into\n"
                  "the octree of the whole run, byte for byte"),
    GB_CLI_STATS("print leaves, VDLs, photons indexed and seconds"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    gb_cluster_options *o = &a->cluster;
    int status;
    switch (option) {
    case 'o': a->output = text; return 0;
    case OPTION_MERGE: a->merge = 1; return 0;
    case OPTION_SHARD:
        return gb_cli_fraction(command.tool, "shard", text, &o->part, &o->part_count);
    case 'd':
        return gb_cli_uint(command.tool, "depth", text, 1, GB_LIGHT_OCTREE_MAX_DEPTH, &o->depth);
    case 'k': return gb_cli_uint(command.tool, "knn", text, 1, 100000, &o->knn);
    case OPTION_RADIUS: return gb_cli_float(command.tool, "radius", text, 1e-30, 1e30, &o->radius);
    case OPTION_VDLS:
        return gb_cli_uint(command.tool, "vdls", text, 1, GB_LIGHT_OCTREE_MAX_VDLS, &o->vdls_max);
    case OPTION_TOLERANCE:
        status = gb_cli_float(command.tool, "tolerance", text, 0.0, 180.0, &o->tolerance);
        /* 0 means "always K_max", which the library spells as negative */
        if (status == 0 && o->tolerance == 0.0f)
            o->tolerance = -1.0f;
        return status;
    case OPTION_RESTARTS: return gb_cli_uint(command.tool, "restarts", text, 1, 64, &o->restarts);
    case OPTION_INTERPOLATION: {
        static const char *const names[] = {"trilinear", "surface"};
        int index;
        status = gb_cli_choice(command.tool, "interpolation", text, names, 2, &index);
        o->interpolation = (uint32_t)index;
        return status;
    }
    default: abort();   /* an entry with no case here */
    }
}

/* SCENE IN.phot, and -o; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (a->merge) {
        if (count < 2 || !a->output)
            return gb_cli_usage_error(command.tool, "--merge: expected the parts PART0.lot "
                                                 "PART1.lot ... and -o OUT.lot");
        if (a->shared.depfile || a->cluster.part_count || a->shared.stats)
            return gb_cli_usage_error(command.tool, "--merge takes neither --depfile, --shard "
                                                 "nor --stats");
        a->parts = operands;
        a->part_count = count;
        return GB_CLI_GO_ON;
    }
    if (!a->output || count != 2)
        return gb_cli_usage_error(command.tool, "expected SCENE IN.phot and -o OUT.lot");
    a->scene = operands[0];
    a->photons = operands[1];
    a->cluster.seed = a->shared.seed;
    a->cluster.threads = a->shared.threads;
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"cluster", usage, parse_option,
                                       check_operands, entries, 26, NULL};

static void print_stats(const gb_cluster_stats *s, const char *output)
{
    printf("leaves %u\nvdls %u\nthreads %d\nindexed_photons %llu\nmean_gathered %.1f\n"
           "mean_error %.4f\nmean_spread_degrees %.2f\n", s->leaves, s->vdls, s->threads,
           (unsigned long long)s->indexed, s->mean_gathered, s->mean_error, s->mean_spread);
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
    gb_progress_begin_for(&progress, command.tool, a->shared.quiet, &a->cluster.progress,
                          &a->cluster.progress_user);
    gb_light_octree octree;
    gb_cluster_stats stats;
    gb_result result = gb_cluster_build(scene, map, &a->cluster, &octree, &stats, error);
    gb_progress_end(&progress);
    if (result == GB_OK)
        result = gb_light_octree_write(a->output, &octree, error);
    if (result == GB_OK && a->shared.stats)
        print_stats(&stats, a->output);
    gb_light_octree_free(&octree);
    return result;
}

/* --merge: the parts read, joined and written. */
static gb_result merge_parts(const arguments *a, gb_error *error)
{
    gb_light_octree *parts = calloc((size_t)a->part_count, sizeof *parts);
    if (!parts)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    gb_result result = GB_OK;
    for (int i = 0; i < a->part_count && result == GB_OK; ++i)
        result = gb_light_octree_read(a->parts[i], &parts[i], error);
    gb_light_octree merged = {0};
    if (result == GB_OK)
        result = gb_cluster_merge(parts, (const char *const *)a->parts,
                                  (uint32_t)a->part_count, &merged, error);
    if (result == GB_OK)
        result = gb_light_octree_write(a->output, &merged, error);
    gb_light_octree_free(&merged);
    for (int i = 0; i < a->part_count; ++i)
        gb_light_octree_free(&parts[i]);
    free(parts);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    if (a->merge) {
        gb_result checked = gb_output_file_check(a->output, error);
        return checked == GB_OK ? merge_parts(a, error) : checked;
    }
    gb_result result =
        gb_output_files_check((const char *[]){a->output, a->shared.depfile}, 2, error);
    if (result != GB_OK)
        return result;
    gb_scene scene;
    gb_photon_map map;
    memset(&map, 0, sizeof map);
    result = gb_scene_load(a->scene, NULL, &scene, error);
    if (result == GB_OK && !a->shared.quiet)  /* no light: an empty map, an octree of no VDL */
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    if (result == GB_OK)
        result = gb_photon_map_read(a->photons, &map, error);
    if (result == GB_OK)
        result = gb_photon_map_check_scene(&map, scene.hash, a->photons, error);
    if (result == GB_OK)
        result = cluster(a, &scene, &map, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_depfile_write_scene(a->shared.depfile, a->output, &scene, a->photons, error);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run,
                       &(arguments){.cluster.interpolation = GB_LIGHT_OCTREE_SURFACE});
}
