/* thin — the curvilinear skeleton of a voxelized scene's empty space and its
 * nearest-node grid (tools/thin/thin.h). Parses options, reads the voxel
 * file, calls gb_thin, writes the two files. */

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
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    const char *input, *output, *grid;
    gb_thin_options options;
} arguments;

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the skeleton file (required)"),
    GB_CLI_OPTION('g', "grid", "FILE", "the nearest-node grid"),
    GB_CLI_OPTION('p', "persistence", "S",
                  "scale of opening - distance (default 1; 0 keeps\n"
                  "every line as soon as it appears)"),
    GB_CLI_OPTION('l', "min-lifespan", "N", "iterations added to the threshold (default 0)"),
    GB_CLI_THREADS(GB_THIN_MAX_THREADS,
                   "threads for the collapse (a power of two, up to 8)\n"
                   "and for the nearest-node grid (default 2; the\n"
                   "output does not depend on it)"),
    GB_CLI_STATS("print counts and timings on stdout"),
    GB_CLI_QUIET("no progress bar"),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into args; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *args = context;
    switch (option) {
    case 'o': args->output = text; return 0;
    case 'g': args->grid = text; return 0;
    case 'p':
        return gb_cli_number_keep_zero(command.tool, "persistence", text, 0.0, 1e6,
                                       &args->options.persistence);
    case 'l':
        return gb_cli_number_keep_zero(command.tool, "min-lifespan", text, 0.0, 1e6,
                                       &args->options.min_lifespan);
    default: abort();   /* an entry with no case here */
    }
}

/* One IN.vdb, and -o; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *args = context;
    if (count != 1 || !args->output)
        return gb_cli_usage_error(command.tool, "expected one IN.vdb and -o OUT.skel");
    args->input = operands[0];
    args->options.threads = args->shared.threads;
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"thin", usage, parse_option,
                                       check_operands, entries, 27, NULL};

static void print_stats(const gb_skeleton *s, const gb_thin_stats *stats)
{
    printf("voxels          %d x %d x %d\n", s->grid_size[0], s->grid_size[1], s->grid_size[2]);
    printf("empty voxels    %llu\n", (unsigned long long)stats->empty_voxels);
    printf("nodes           %u\n", s->node_count);
    printf("edges           %u\n", s->edge_count);
    printf("iterations      %u (%u on all threads)\n", stats->iterations,
           stats->shared_iterations);
    printf("pairs removed   %llu\n", (unsigned long long)stats->pairs_removed);
    printf("cells examined  %llu\n", (unsigned long long)stats->cells_examined);
    printf("cavities opened %u\n", stats->cavities_opened);
    printf("squares left    %llu\n", (unsigned long long)stats->squares_left);
    printf("seconds         maps %.3f, collapse %.3f, graph %.3f, nearest %.3f\n",
           stats->seconds_maps, stats->seconds_collapse, stats->seconds_graph,
           stats->seconds_nearest);
    printf("cpu seconds     skeleton %.3f, nearest %.3f\n", stats->cpu_seconds_skeleton,
           stats->cpu_seconds_nearest);
}

/* The grid first (nearest is freed on the way): if the skeleton then fails,
 * the new grid is removed so that a failed run leaves no output. */
static gb_result write_outputs(const arguments *args, const gb_voxel_grid *grid,
                               const gb_skeleton *skeleton, int32_t *nearest, gb_error *error)
{
    gb_result result = GB_OK;
    if (args->grid)
        result = gb_voxel_grid_write_int32_and_free(args->grid, grid, "nearest_node", nearest,
                                                    error);
    if (result != GB_OK)
        return result;
    result = gb_skeleton_write(args->output, skeleton, error);
    struct stat status;  /* never a device, a FIFO or a symlink */
    if (result != GB_OK && args->grid && lstat(args->grid, &status) == 0 &&
        S_ISREG(status.st_mode))
        unlink(args->grid);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    const arguments *args = context;
    gb_voxel_grid grid = {0};
    /* before the work: both outputs can be written */
    gb_result result = gb_output_files_check((const char *[]){args->output, args->grid}, 2, error);
    if (result == GB_OK)
        result = gb_voxel_grid_read(args->input, &grid, error);
    if (result != GB_OK)
        return result;
    /* the reader's OpenVDB trees are freed, but glibc keeps their heap
     * pages: give them back before the big arrays of thin */
    malloc_trim(0);
    gb_thin_options options = args->options;
    gb_progress progress;
    gb_progress_begin_for(&progress, command.tool, args->shared.quiet, &options.progress,
                          &options.progress_user);
    gb_skeleton skeleton;
    gb_thin_stats stats;
    int32_t *nearest = NULL;
    gb_error reason;
    /* only the frame is kept from here: the surface is given back once read */
    result = gb_thin_and_free(&grid, &options, &skeleton, args->grid ? &nearest : NULL, &stats,
                              &reason);
    gb_progress_end(&progress);
    if (result != GB_OK)
        gb_fail(error, result, "%s: %s", args->input, reason.message);
    else
        result = write_outputs(args, &grid, &skeleton, nearest, error);
    if (result == GB_OK && args->shared.stats)
        print_stats(&skeleton, &stats);
    gb_skeleton_free(&skeleton);
    gb_voxel_grid_free(&grid);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
