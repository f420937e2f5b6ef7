/* lightmap — the light octree baked into the atlas as an EXR, and the
 * scene with it as a glTF binary (lightmap.h, glb_export.h). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "atlas.h"
#include "cli.h"
#include "depfile.h"
#include "glb_export.h"
#include "image.h"
#include "light_octree.h"
#include "lightmap.h"
#include "output_file.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: lightmap [options] SCENE NAME.atlas NAME.lot -o OUT.exr [--glb OUT.glb]\n"
    "       lightmap [options] --paths --quality N SCENE NAME.atlas -o OUT.exr\n"
    "Bakes the light octree NAME.lot of SCENE into its atlas NAME.atlas\n"
    "(vivianloc-2007 4.2.3): per texel, the indirect irradiance on the plane of\n"
    "the triangle nearest the texel's centre, within sqrt 2 texels (W/m^2,\n"
    "linear RGB, without the albedo: a viewer multiplies Kd / pi): with\n"
    "--quality 0 the octree read there, trilinear as the octree display does;\n"
    "else a final gather of --quality rays reading the octree where they meet\n"
    "the scene (or, with --paths, tracing paths on), from the side of each\n"
    "triangle that looks into the open, on the texels --accuracy picks (Ward's\n"
    "irradiance interpolation), the others the mean of gathered neighbours.\n"
    "Then the rest of the padding's gutter\n"
    "(formats/FORMATS.md, \"Rendering into an atlas\", as gbview does). Writes a linear\n"
    "float EXR and, with --glb, the scene as a glTF 2.0 binary with the atlas\n"
    "UVs as TEXCOORD_1 and the lightmap as an embedded PNG (formats/FORMATS.md,\n"
    "\"glTF export\"). The files depend on the inputs only, never on --threads.\n"
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    gb_lightmap_options lightmap;
    const char *output, *glb, *scene, *atlas, *octree;
} arguments;

/* A macro's value as a string literal, for the help's defaults. */
#define TEXT_OF(value) #value
#define DEFAULT_TEXT(macro) TEXT_OF(macro)

enum { OPTION_GLB = 256, OPTION_QUALITY, OPTION_PATHS, OPTION_BOUNCES, OPTION_ACCURACY };

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the lightmap to write (.exr)"),
    GB_CLI_OPTION(OPTION_GLB, "glb", "FILE", "also the scene as a glTF binary (.glb)"),
    GB_CLI_OPTION(OPTION_QUALITY, "quality", "N",
                  "final gather rays per texel, 0..65536: more\n"
                  "rays, less noise (default 0: the octree read at\n"
                  "the texel, no rays)"),
    GB_CLI_OPTION(OPTION_PATHS, "paths", NULL,
                  "the gather traces paths on from where its rays\n"
                  "meet the scene (unbiased, the octree unused)\n"
                  "rather than reading the octree there"),
    GB_CLI_OPTION(OPTION_BOUNCES, "bounces", "B",
                  "reflections a gather's paths trace before they\n"
                  "read the octree, 1..16 (default 1: the final\n"
                  "gather; more push the octree's errors further\n"
                  "away, for more noise and time)"),
    GB_CLI_OPTION(OPTION_ACCURACY, "accuracy", "A",
                  "a texel between gathered ones takes their mean\n"
                  "when each is within A of it by Ward's error: its\n"
                  "distance over that gather's mean distance to the\n"
                  "scene, plus sqrt(1 - n.n'); 0..1 (default "
                  DEFAULT_TEXT(GB_LIGHTMAP_ACCURACY) "; 0:\n"
                  "every texel gathers)"),
    GB_CLI_SEED("N", "the gathers' random streams (default 0)"),
    GB_CLI_THREADS(256, NULL),
    GB_CLI_STATS("print texels, seconds, bytes and the PNG's error"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    switch (option) {
    case 'o': a->output = text; return 0;
    case OPTION_GLB: a->glb = text; return 0;
    case OPTION_QUALITY:
        return gb_cli_int(command.tool, "quality", text, 0, 65536, &a->lightmap.quality);
    case OPTION_PATHS: a->lightmap.paths = 1; return 0;
    case OPTION_BOUNCES:
        return gb_cli_int(command.tool, "bounces", text, 1, 16, &a->lightmap.bounces);
    case OPTION_ACCURACY:
        return gb_cli_number_keep_zero(command.tool, "accuracy", text, 0.0, 1.0,
                                       &a->lightmap.accuracy);
    default: abort();   /* an entry with no case here */
    }
}

/* SCENE NAME.atlas NAME.lot, and -o; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (!a->output || count < 2 + !a->lightmap.paths || count > 3)
        return gb_cli_usage_error(command.tool, "expected SCENE NAME.atlas NAME.lot and -o "
                                              "OUT.exr (no NAME.lot needed with --paths)");
    a->scene = operands[0];
    a->atlas = operands[1];
    a->octree = count == 3 ? operands[2] : NULL;
    a->lightmap.threads = a->shared.threads;
    a->lightmap.seed = a->shared.seed;
    if ((a->lightmap.paths || a->lightmap.bounces || a->lightmap.accuracy != 0.0) &&
        a->lightmap.quality == 0)
        return gb_cli_usage_error(command.tool, "--paths, --bounces and --accuracy need "
                                                "--quality N > 0");
    if (a->lightmap.paths && a->lightmap.bounces)
        return gb_cli_usage_error(command.tool, "--bounces reads the octree: not with --paths");
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"lightmap", usage, parse_option,
                                       check_operands, entries, 26, NULL};

static long file_bytes(const char *path)
{
    FILE *file = fopen(path, "rb");
    long size = -1;
    if (file && fseek(file, 0, SEEK_END) == 0)
        size = ftell(file);
    if (file)
        fclose(file);
    return size;
}

static void print_stats(const arguments *a, const gb_lightmap_stats *s,
                        const gb_glb_export_stats *g, const gb_atlas *atlas)
{
    printf("width %u\nheight %u\ncovered_texels %llu\ngutter_texels %llu\nrays %llu\n"
           "threads %d\nseconds %.3f\nbytes %ld\n", atlas->header.width, atlas->header.height,
           (unsigned long long)s->covered, (unsigned long long)s->gutter,
           (unsigned long long)s->rays, s->threads, s->seconds, file_bytes(a->output));
    if (a->glb)
        printf("glb_vertices %llu\nglb_primitives %u\nglb_scale %.9g\npng_relative_mse %.3g\n"
               "glb_seconds %.3f\nglb_bytes %ld\n", (unsigned long long)g->vertices,
               g->primitives, g->scale, g->png_relative_mse, g->seconds, file_bytes(a->glb));
}

/* Every output writable and named as its format wants, before any work. */
static gb_result check_outputs(const arguments *a, gb_error *error)
{
    gb_result result = gb_image_check_output(a->output, error);
    if (result == GB_OK)
        result = gb_output_files_check((const char *[]){a->glb, a->shared.depfile}, 2, error);
    return result;
}

static gb_result read_inputs(const arguments *a, gb_scene *scene, gb_atlas *atlas,
                             gb_light_octree *octree, gb_error *error)
{
    /* the gathers read Kd at their hits, textures included, as photons does */
    gb_scene_options scene_options = {.load_textures = a->lightmap.quality > 0};
    gb_result result = gb_scene_load(a->scene, &scene_options, scene, error);
    if (result == GB_OK && !a->shared.quiet)
        gb_scene_warn(command.tool, scene, GB_WARN_GEOMETRY);
    if (result == GB_OK)
        result = gb_atlas_read(a->atlas, atlas, error);
    if (result == GB_OK)
        result = gb_atlas_check_scene(atlas, scene->hash, scene->triangle_count, a->atlas,
                                      error);
    if (result == GB_OK && a->octree)
        result = gb_light_octree_read(a->octree, octree, error);
    if (result == GB_OK && a->octree)
        result = gb_light_octree_check_scene(octree, scene->hash, a->octree, error);
    return result;
}

static gb_result bake(arguments *a, const gb_scene *scene, const gb_atlas *atlas,
                      const gb_light_octree *octree, gb_image *image,
                      gb_lightmap_stats *stats, gb_error *error)
{
    gb_progress progress;
    gb_progress_begin_for(&progress, command.tool, a->shared.quiet, &a->lightmap.progress,
                          &a->lightmap.progress_user);
    gb_result result = gb_lightmap_bake(scene, atlas, a->octree ? octree : NULL, &a->lightmap,
                                        image, stats, error);
    gb_progress_end(&progress);
    return result;
}

/* The make rule: the EXR from the scene's files, the atlas, the octree and
 * the textures the glTF embedded or the gathers read. */
static gb_result write_depfile(const arguments *a, const gb_scene *scene, gb_error *error)
{
    const char **inputs = malloc((scene->input_count + 2 + scene->material_count) *
                                 sizeof *inputs);
    if (!inputs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    uint32_t count = 0;
    for (uint32_t i = 0; i < scene->input_count; ++i)
        inputs[count++] = scene->inputs[i];
    inputs[count++] = a->atlas;
    if (a->octree)
        inputs[count++] = a->octree;
    int textures_read = a->glb || a->lightmap.quality > 0;
    for (uint32_t m = 0; textures_read && m < scene->material_count; ++m)
        if (scene->materials[m].map_Kd)
            inputs[count++] = scene->materials[m].map_Kd;
    gb_result result = gb_depfile_write(a->shared.depfile, a->output, inputs, count, error);
    free(inputs);
    return result;
}

/* The EXR, after the glTF binary (whose textures are likelier to fail):
 * when the EXR cannot be written, the glTF binary just written goes too,
 * so that a failed run leaves no output (a device or FIFO stays). */
static gb_result write_lightmap(const arguments *a, const gb_image *image, gb_error *error)
{
    gb_result result = gb_image_write(a->output, image, error);
    struct stat status;
    if (result != GB_OK && a->glb && stat(a->glb, &status) == 0 && S_ISREG(status.st_mode))
        unlink(a->glb);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    gb_result result = check_outputs(a, error);
    if (result != GB_OK)
        return result;
    gb_scene scene;
    gb_atlas atlas;
    gb_light_octree octree;
    gb_image image = {0};
    gb_lightmap_stats stats = {0};
    gb_glb_export_stats glb = {0};
    memset(&atlas, 0, sizeof atlas);
    memset(&octree, 0, sizeof octree);
    result = read_inputs(a, &scene, &atlas, &octree, error);
    if (result == GB_OK)
        result = bake(a, &scene, &atlas, &octree, &image, &stats, error);
    if (result == GB_OK && a->glb)
        result = gb_glb_export(a->glb, &scene, &atlas, &image, &glb, error);
    if (result == GB_OK)
        result = write_lightmap(a, &image, error);
    if (result == GB_OK && a->shared.depfile)
        result = write_depfile(a, &scene, error);
    if (result == GB_OK && a->shared.stats)
        print_stats(a, &stats, &glb, &atlas);
    gb_image_free(&image);
    gb_light_octree_free(&octree);
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
