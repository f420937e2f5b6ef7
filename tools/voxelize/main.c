/* voxelize — scene to the OpenVDB file of its surfaces and empty space
 * (noel-biri-2014, section IV.A; formats/FORMATS.md, "Voxel
 * file"). Parses the command line and calls tools/voxelize/voxelize.h. */

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auto_resolution.h"

#include "cli.h"
#include "depfile.h"
#include "output_file.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"
#include "voxel_grid.h"
#include "voxelize.h"

static const char usage[] =
    "usage: voxelize [options] SCENE -o OUT.vdb\n"
    "Voxelizes SCENE (.scene, .obj, .obj.gz, .ply, .off or .stl) into OUT.vdb: the\n"
    "voxels every triangle touches (grid 'surface') and the others ('empty'), both\n"
    "sparse.\n"
    "\n";

enum { OPTION_PAD = 256 };

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    const char *scene, *output;
    long resolution, pad;
    int automatic;
} arguments;

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the OpenVDB file to write (required)"),
    GB_CLI_OPTION('r', "resolution", "N|auto",
                  "voxels along the longest side of the scene (default\n"
                  "256, at most 2048); voxels are cubes. An opening stays\n"
                  "open in the skeleton when two voxels span it: at 256,\n"
                  "down to 1/128 of the longest side (a door, most gaps\n"
                  "between columns); raise -r for narrower ones. auto:\n"
                  "of 16, 32 ... 512, the first whose empty space has the\n"
                  "topology (components, Euler characteristic) of half\n"
                  "and twice it, so that what is open there spans two\n"
                  "voxels; else 512; said on stderr. Not the default:\n"
                  "the checks cost up to six more passes, and scenes\n"
                  "with gaps never settle"),
    GB_CLI_OPTION(OPTION_PAD, "pad", "N",
                  "empty voxels around the scene (default 2, at most 64)"),
    GB_CLI_DEPFILE("a make rule: OUT.vdb and every file read (-MD)"),
    GB_CLI_THREADS(64, "threads (default 2)"),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One SCENE, and -o; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *parsed = context;
    if (count != 1)
        return gb_cli_usage_error(command.tool, "expected one SCENE");
    if (!parsed->output)
        return gb_cli_usage_error(command.tool, "no output file: give -o OUT.vdb");
    parsed->scene = operands[0];
    return GB_CLI_GO_ON;
}

/* One option into parsed; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *parsed = context;
    switch (option) {
    case 'o': parsed->output = text; return 0;
    case 'r':
        parsed->automatic = strcmp(text, "auto") == 0;
        if (parsed->automatic)
            return 0;
        return gb_cli_integer(command.tool, "resolution", text, 1, GB_VOXELIZE_MAX_RESOLUTION,
                              &parsed->resolution);
    case OPTION_PAD:
        return gb_cli_integer(command.tool, "pad", text, 0, GB_VOXELIZE_MAX_PAD, &parsed->pad);
    default: abort();   /* an entry with no case here */
    }
}

static const gb_cli_command command = {"voxelize", usage, parse_option,
                                       check_operands, entries, 25, NULL};

/* The bar shows voxelizing as 90 % of the work and writing as the rest. */
static int report_voxelizing(void *bar, double fraction)
{
    return gb_progress_report(bar, 0.9 * fraction);
}

/* -r auto: the resolution into options, and why on stderr. */
static gb_result choose_resolution(const gb_scene *scene, int quiet, gb_voxelize_options *options,
                                   gb_error *error)
{
    gb_auto_resolution choice;
    gb_result result = gb_voxelize_auto_resolution(scene, options, &choice, error);
    if (result != GB_OK)
        return result;
    options->resolution = choice.resolution;
    if (quiet)
        return GB_OK;
    char seen[256] = "";
    for (uint32_t i = choice.checked >= 3 ? choice.checked - 3 : 0; i < choice.checked; ++i)
        snprintf(seen + strlen(seen), sizeof seen - strlen(seen), "%s%u: %" PRIu64 " and %" PRId64,
                 seen[0] ? ", " : "", choice.resolutions[i], choice.topology[i].components,
                 choice.topology[i].euler);
    fprintf(stderr, "voxelize: -r auto: %u (%s; components and Euler characteristic of the "
            "empty space at %s)\n", choice.resolution,
            choice.settled ? "the same at three resolutions"
                           : "the largest checked: no three agreed, the mesh may have gaps",
            seen);
    return GB_OK;
}

static gb_result voxelize_file(void *context, gb_error *error)
{
    const arguments *parsed = context;
    gb_result result =
        gb_output_files_check((const char *[]){parsed->output, parsed->shared.depfile}, 2, error);
    if (result != GB_OK)
        return result;
    gb_scene scene;
    gb_voxel_grid grid = {0};
    gb_progress bar;
    gb_progress_begin(&bar, command.tool, parsed->shared.quiet);
    gb_voxelize_options options = {
        .resolution = (uint32_t)parsed->resolution,
        .pad = parsed->pad == 0 ? GB_VOXELIZE_NO_PAD : (int32_t)parsed->pad,
        .thread_count = parsed->shared.threads ? parsed->shared.threads
                                               : GB_VOXELIZE_DEFAULT_THREADS,
        .progress = report_voxelizing,
        .progress_user = &bar,
    };
    result = gb_scene_load(parsed->scene, NULL, &scene, error);
    if (result != GB_OK) {
        gb_scene_free(&scene);
        return result;
    }
    if (!parsed->shared.quiet)
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY);
    gb_error reason;
    if (parsed->automatic)
        result = choose_resolution(&scene, parsed->shared.quiet, &options, &reason);
    if (result == GB_OK)
        result = gb_voxelize_scene(&scene, &options, &grid, &reason);
    if (result != GB_OK)
        gb_fail(error, result, "%s: %s", parsed->scene, reason.message);
    else
        result = gb_voxel_grid_write_and_free(parsed->output, &grid, error);
    if (result == GB_OK && parsed->shared.depfile)
        result = gb_depfile_write_scene(parsed->shared.depfile, parsed->output, &scene, NULL,
                                        error);
    if (result == GB_OK)
        gb_progress_report(&bar, 1.0);
    gb_progress_end(&bar);
    gb_voxel_grid_free(&grid);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    arguments defaults = {.resolution = GB_VOXELIZE_DEFAULT_RESOLUTION,
                          .pad = GB_VOXELIZE_DEFAULT_PAD};
    return gb_cli_main(&command, argc, argv, voxelize_file, &defaults);
}
