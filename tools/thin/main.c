/* thin — the curvilinear skeleton of a voxelized scene's empty space and its
 * nearest-node grid (tools/thin/thin.h). Parses options, reads the voxel
 * file, calls gb_thin, writes the two files. */

#include <getopt.h>
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "output_file.h"
#include "progress.h"
#include "skeleton.h"
#include "thin.h"
#include "voxel_grid.h"

static const char usage[] =
    "usage: thin [options] IN.vdb -o OUT.skel [--grid OUT.grid.vdb]\n"
    "Computes the curvilinear skeleton of the empty space of IN.vdb (written by\n"
    "voxelize) by directional collapse of its cubical complex, keeping the lines\n"
    "whose lifespan exceeds persistence * (opening - distance) + min-lifespan\n"
    "iterations, and writes it to OUT.skel; with --grid, also the OpenVDB int32\n"
    "grid \"nearest_node\": every voxel's geodesic nearest skeleton node.\n"
    "\n"
    "  -o, --output FILE        the skeleton file (required)\n"
    "  -g, --grid FILE          the nearest-node grid\n"
    "  -p, --persistence S      scale of opening - distance (default 1; 0 keeps\n"
    "                           every line as soon as it appears)\n"
    "  -l, --min-lifespan N     iterations added to the threshold (default 0)\n"
    "  -j, --threads N          threads for the nearest-node grid when it needs\n"
    "                           Dijkstra (default 2; the output does not depend on it)\n"
    "  -s, --stats              print counts and timings on stdout\n"
    "  -q, --quiet              no progress bar\n"
    "  -h, --help               this help\n"
    "  -V, --version            the version\n";

typedef struct arguments {
    const char *input, *output, *grid;
    gb_thin_options options;
    int quiet, stats;
} arguments;

/* One option into args; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *args = context;
    switch (option) {
    case 'o': args->output = text; return 0;
    case 'g': args->grid = text; return 0;
    case 's': args->stats = 1; return 0;
    case 'q': args->quiet = 1; return 0;
    case 'p':
        return gb_cli_number_keep_zero("thin", "persistence", text, 0.0, 1e6,
                                       &args->options.persistence);
    case 'l':
        return gb_cli_number_keep_zero("thin", "min-lifespan", text, 0.0, 1e6,
                                       &args->options.min_lifespan);
    default:
        return gb_cli_int("thin", "threads", text, 1, GB_THIN_MAX_THREADS,
                          &args->options.threads);
    }
}

/* GB_CLI_GO_ON, else the exit status (0 after --help and --version). */
static int parse_arguments(int argc, char **argv, arguments *args)
{
    static const struct option options[] = {
        GB_CLI_VALUE("output", 'o'),
        GB_CLI_VALUE("grid", 'g'),
        GB_CLI_VALUE("persistence", 'p'),
        GB_CLI_VALUE("min-lifespan", 'l'),
        GB_CLI_VALUE("threads", 'j'),
        GB_CLI_FLAG("stats", 's'),
        GB_CLI_OPTIONS_END,
    };
    int status = gb_cli_options("thin", usage, argc, argv, options, parse_option, args);
    if (status != GB_CLI_GO_ON)
        return status;
    if (optind != argc - 1 || !args->output)
        return gb_cli_usage_error("thin", "expected one IN.vdb and -o OUT.skel");
    args->input = argv[optind];
    return GB_CLI_GO_ON;
}

static void print_stats(const gb_skeleton *s, const gb_thin_stats *stats)
{
    printf("voxels          %d x %d x %d\n", s->grid_size[0], s->grid_size[1], s->grid_size[2]);
    printf("empty voxels    %llu\n", (unsigned long long)stats->empty_voxels);
    printf("nodes           %u\n", s->node_count);
    printf("edges           %u\n", s->edge_count);
    printf("iterations      %u\n", stats->iterations);
    printf("cavities opened %u\n", stats->cavities_opened);
    printf("squares left    %llu\n", (unsigned long long)stats->squares_left);
    printf("seconds         maps %.3f, collapse %.3f, graph %.3f, nearest %.3f\n",
           stats->seconds_maps, stats->seconds_collapse, stats->seconds_graph,
           stats->seconds_nearest);
}

/* The grid first: if the skeleton then fails, the new grid is removed so
 * that a failed run leaves no output. */
static int write_outputs(const arguments *args, const gb_voxel_grid *grid,
                         const gb_skeleton *skeleton, const int32_t *nearest)
{
    gb_error error;
    if (args->grid &&
        gb_voxel_grid_write_int32(args->grid, grid, "nearest_node", nearest, &error)) {
        fprintf(stderr, "thin: %s\n", error.message);
        return 1;
    }
    if (gb_skeleton_write(args->output, skeleton, &error)) {
        fprintf(stderr, "thin: %s\n", error.message);
        struct stat status;  /* never a device, a FIFO or a symlink */
        if (args->grid && lstat(args->grid, &status) == 0 && S_ISREG(status.st_mode))
            unlink(args->grid);
        return 1;
    }
    return 0;
}

static int run(const arguments *args)
{
    gb_voxel_grid grid = {0};
    gb_error error;
    if (gb_voxel_grid_read(args->input, &grid, &error)) {
        fprintf(stderr, "thin: %s\n", error.message);
        return 1;
    }
    /* the reader's OpenVDB trees are freed, but glibc keeps their heap
     * pages: give them back before the big arrays of thin */
    malloc_trim(0);
    gb_thin_options options = args->options;
    gb_progress progress;
    gb_progress_begin_for(&progress, "thin", args->quiet, &options.progress,
                          &options.progress_user);
    gb_skeleton skeleton;
    gb_thin_stats stats;
    int32_t *nearest = NULL;
    gb_result result = gb_thin(&grid, &options, &skeleton, args->grid ? &nearest : NULL, &stats,
                               &error);
    gb_progress_end(&progress);
    /* only the frame is needed from here: give the memory back for writing */
    free(grid.surface);
    free(grid.distance);
    grid.surface = NULL;
    grid.distance = NULL;
    int status = 0;
    if (result) {
        fprintf(stderr, "thin: %s: %s\n", args->input, error.message);
        status = 1;
    } else {
        status = write_outputs(args, &grid, &skeleton, nearest);
    }
    if (!status && args->stats)
        print_stats(&skeleton, &stats);
    gb_skeleton_free(&skeleton);
    free(nearest);
    gb_voxel_grid_free(&grid);
    return status;
}

int main(int argc, char **argv)
{
    arguments args;
    memset(&args, 0, sizeof args);
    int parsed = parse_arguments(argc, argv, &args);
    if (parsed != GB_CLI_GO_ON)
        return parsed;
    gb_error error;
    if (gb_output_file_check(args.output, &error) != GB_OK ||
        (args.grid && gb_output_file_check(args.grid, &error) != GB_OK)) {
        fprintf(stderr, "thin: %s\n", error.message);
        return 1;
    }
    int status = run(&args);
    if (fflush(stdout) != 0)
        status = 1;
    return status;
}
