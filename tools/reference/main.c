/* reference — renders a camera of a scene with Embree: the ground truth every
 * gibake method measures its error against (tools/reference/reference.h). */

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "depfile.h"
#include "output_file.h"
#include "image.h"
#include "progress.h"
#include "reference.h"
#include "scene.h"
#include "scene_warnings.h"
#include "vpl.h"

static const char usage[] =
    "usage: reference [options] SCENE -o OUT.exr\n"
    "       reference --merge TILE0.exr TILE1.exr ... -o OUT.exr\n"
    "Renders a camera of SCENE with Embree into a linear EXR: ground truth for the\n"
    "real-time methods. The image depends on the seed, never on --threads.\n"
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    gb_reference_options render;
    const char *scene_path, *output, *vpl_path;
    char **tiles;               /* --merge: the parts */
    int tile_count;
    int png, mode_given, merge;
} arguments;

enum { OPTION_MODE = 256, OPTION_VPL, OPTION_SPP, OPTION_MIN_BOUNCES, OPTION_PNG, OPTION_TILE,
       OPTION_MERGE };

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the image to write (.exr: linear; .png: sRGB)"),
    GB_CLI_OPTION(OPTION_MODE, "mode", "MODE",
                  "full (default), direct, indirect1,\n"
                  "indirect1-unshadowed, vpl\n"
                  "  direct     emitters seen and light reflected once\n"
                  "  indirect1  light reflected exactly twice\n"
                  "  indirect1-unshadowed  the same, ignoring what blocks\n"
                  "             the segment between the two reflections\n"
                  "  full       path tracing, --min-bounces..--bounces\n"
                  "  vpl        the light of the VPL set --vpl FILE,\n"
                  "             reflected once, with shadow rays"),
    GB_CLI_OPTION(OPTION_VPL, "vpl", "FILE", "the VPL set of vpl mode (implies --mode vpl)"),
    GB_CLI_OPTION(OPTION_SPP, "spp", "N",
                  "samples per pixel (default 64; 4 in vpl mode, where\n"
                  "each sample sums every VPL)"),
    GB_CLI_SEED("N", NULL),
    GB_CLI_OPTION('c', "camera", "N", "the scene's camera N, from 0 (default 0)"),
    GB_CLI_OPTION('r', "resolution", "WxH", "image size (default: the camera's)"),
    GB_CLI_THREADS(256, NULL),
    GB_CLI_OPTION('b', "bounces", "N",
                  "full: most reflections per path (default 64;\n"
                  "Russian roulette after 3)"),
    GB_CLI_OPTION(OPTION_MIN_BOUNCES, "min-bounces", "N",
                  "full: fewest reflections (default 0; 3 gives what\n"
                  "direct and indirect1 leave out)"),
    GB_CLI_OPTION(OPTION_TILE, "tile", "I/N",
                  "render only part I of N of the image (its 16x16\n"
                  "tiles t with t mod N = I; the rest black): a shard"),
    GB_CLI_OPTION(OPTION_MERGE, "merge", NULL,
                  "join the N parts given, in order 0/N .. N-1/N, into\n"
                  "the image of the whole render, byte for byte"),
    GB_CLI_OPTION(OPTION_PNG, "png", NULL, "also write OUT.png, sRGB, beside OUT.exr"),
    GB_CLI_STATS("print rays, seconds (wall, CPU) and rays per second\n"
                 "on stdout"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One numeric option into a; 0, else the exit status. */
static int parse_number(int option, const char *text, arguments *a)
{
    gb_reference_options *r = &a->render;
    long camera;
    int status;
    switch (option) {
    case OPTION_SPP: return gb_cli_int(command.tool, "spp", text, 1, 1 << 30, &r->spp);
    case 'b': return gb_cli_int(command.tool, "bounces", text, 1, 1 << 20, &r->bounces);
    case OPTION_MIN_BOUNCES:
        return gb_cli_int(command.tool, "min-bounces", text, 0, 1 << 20, &r->min_bounces);
    case OPTION_TILE:
        return gb_cli_fraction(command.tool, "tile", text, &r->tile, &r->tile_count);
    case 'r':
        return gb_cli_size(command.tool, "resolution", text, GB_CLI_MAX_IMAGE_SIDE, &r->width,
                           &r->height);
    case 'c':
        if ((status = gb_cli_integer(command.tool, "camera", text, 0, UINT32_MAX, &camera)) == 0)
            r->camera = (uint32_t)camera;
        return status;
    default: abort();   /* an entry with no case here */
    }
}

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    gb_error error;
    switch (option) {
    case 'o': a->output = text; return 0;
    case OPTION_VPL: a->vpl_path = text; return 0;
    case OPTION_PNG: a->png = 1; return 0;
    case OPTION_MERGE: a->merge = 1; return 0;
    case OPTION_MODE:
        a->mode_given = 1;
        if (gb_reference_mode_parse(text, &a->render.mode, &error) == GB_OK)
            return 0;
        return gb_cli_usage_error(command.tool, "%s", error.message);
    default: return parse_number(option, text, a);
    }
}

/* One SCENE, -o, and --vpl with vpl mode; GB_CLI_GO_ON, else the exit
 * status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (a->merge) {
        if (count < 2 || !a->output)
            return gb_cli_usage_error(command.tool, "--merge: expected the parts TILE0 "
                                                   "TILE1 ... and -o OUT");
        if (a->shared.depfile || a->render.tile_count)
            return gb_cli_usage_error(command.tool, "--merge takes neither --depfile "
                                                   "nor --tile");
        a->tiles = operands;
        a->tile_count = count;
        return GB_CLI_GO_ON;
    }
    if (count != 1 || !a->output)
        return gb_cli_usage_error(command.tool, "expected one SCENE and -o OUT");
    a->scene_path = operands[0];
    a->render.seed = a->shared.seed;
    a->render.threads = a->shared.threads;
    if (a->vpl_path && !a->mode_given)
        a->render.mode = GB_REFERENCE_VPL;
    if ((a->render.mode == GB_REFERENCE_VPL) != (a->vpl_path != NULL))
        return gb_cli_usage_error(command.tool, "--vpl FILE goes with --mode vpl, and only "
                                               "with it");
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"reference", usage, parse_option,
                                       check_operands, entries, 26, NULL};

/* OUT.exr -> OUT.png; any other name gets ".png" appended. */
static char *png_path(const char *output)
{
    size_t length = strlen(output);
    char *path = malloc(length + 5);
    if (!path)
        return NULL;
    memcpy(path, output, length + 1);
    if (length > 4 && strcmp(path + length - 4, ".exr") == 0)
        length -= 4;
    memcpy(path + length, ".png", 5);
    return path;
}

static gb_result write_images(const arguments *a, const gb_image *image, gb_error *error)
{
    gb_result result = gb_image_write(a->output, image, error);
    if (result != GB_OK || !a->png)
        return result;
    char *path = png_path(a->output);
    if (!path)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    result = gb_image_write(path, image, error);
    free(path);
    return result;
}

/* Before rendering: each image's format and folder. */
static gb_result check_outputs(const arguments *a, gb_error *error)
{
    gb_result result = gb_image_check_output(a->output, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_output_file_check(a->shared.depfile, error);
    if (result != GB_OK || !a->png)
        return result;
    char *path = png_path(a->output);
    if (!path)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    result = gb_image_check_output(path, error);
    free(path);
    return result;
}

static void print_stats(const gb_reference_stats *stats)
{
    printf("rays %" PRIu64 "\nseconds %.3f\ncpu_seconds %.3f\nbuild_seconds %.3f\n"
           "mrays_per_second %.3f\nnonfinite_samples %" PRIu64 "\n",
           stats->rays, stats->seconds, stats->cpu_seconds, stats->build_seconds,
           stats->seconds > 0 ? 1e-6 * (double)stats->rays / stats->seconds : 0.0,
           stats->nonfinite_samples);
}

static gb_result render(arguments *a, const gb_scene *scene, gb_error *error)
{
    gb_progress progress;
    gb_progress_begin_for(&progress, command.tool, a->shared.quiet, &a->render.progress,
                          &a->render.progress_user);
    gb_image image;
    gb_reference_stats stats;
    gb_result result = gb_reference_render(scene, &a->render, &image, &stats, error);
    gb_progress_end(&progress);
    if (result == GB_OK)
        result = write_images(a, &image, error);
    if (result == GB_OK && a->shared.stats)
        print_stats(&stats);
    gb_image_free(&image);
    return result;
}

/* --merge: the parts read, joined and written. */
static gb_result merge_tiles(const arguments *a, gb_error *error)
{
    gb_image *tiles = calloc((size_t)a->tile_count, sizeof *tiles);
    if (!tiles)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    gb_result result = GB_OK;
    for (int i = 0; i < a->tile_count && result == GB_OK; ++i)
        result = gb_image_read(a->tiles[i], &tiles[i], error);
    gb_image merged = {0};
    if (result == GB_OK)
        result = gb_reference_merge_tiles(tiles, (const char *const *)a->tiles,
                                          (uint32_t)a->tile_count, &merged, error);
    if (result == GB_OK)
        result = write_images(a, &merged, error);
    gb_image_free(&merged);
    for (int i = 0; i < a->tile_count; ++i)
        gb_image_free(&tiles[i]);
    free(tiles);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    gb_result result = check_outputs(a, error);
    if (result == GB_OK && a->merge)
        return merge_tiles(a, error);
    if (result != GB_OK)
        return result;
    gb_scene scene;
    gb_scene_options scene_options = {.load_textures = 1};
    result = gb_scene_load(a->scene_path, &scene_options, &scene, error);
    if (result != GB_OK)
        return result;
    if (!a->shared.quiet)     /* with no light the image is black, as it should be */
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    gb_vpl_set vpls = {0};
    if (a->vpl_path) {
        result = gb_vpl_read(a->vpl_path, &vpls, error);
        if (result == GB_OK)
            result = gb_vpl_check_scene(&vpls, scene.hash, a->vpl_path, error);
        a->render.vpls = &vpls;
    }
    if (result == GB_OK)
        result = render(a, &scene, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_depfile_write_scene(a->shared.depfile, a->output, &scene, a->vpl_path, error);
    gb_vpl_free(&vpls);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
