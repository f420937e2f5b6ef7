/* atlas — a scene's lightmap atlas: charts, CGAL LSCM UVs, packing
 * (tools/atlas/atlas_build.h). Parses options, loads the scene, calls
 * gb_atlas_build, writes the file. */

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas.h"
#include "atlas_build.h"
#include "cli.h"
#include "depfile.h"
#include "output_file.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: atlas [options] SCENE -o OUT.atlas\n"
    "Cuts the triangles of SCENE into charts, maps each by least-squares conformal\n"
    "maps (CGAL) and packs them into one lightmap atlas (vivianloc-2007 4.2.3;\n"
    "formats/FORMATS.md, \"Atlas\"). Charts grow over shared edges while every\n"
    "normal stays within --cone of the chart's first; each is cut until it is a\n"
    "disc. No two triangles overlap in the atlas (tested exactly before writing)\n"
    "and every triangle has a positive UV area.\n"
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    gb_atlas_options atlas;
    const char *scene, *output;
    int size_given;
} arguments;

enum { OPTION_SIZE = 256, OPTION_TEXELS, OPTION_PADDING, OPTION_CONE };

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the atlas to write (required)"),
    GB_CLI_OPTION(OPTION_SIZE, "size", "N",
                  "an N x N atlas, at the largest texel density at\n"
                  "which the charts fit (default 1024)"),
    GB_CLI_OPTION(OPTION_TEXELS, "texels-per-unit", "T",
                  "this texel density instead; the atlas is as large\n"
                  "as the charts need (at most 16384 a side)"),
    GB_CLI_OPTION(OPTION_PADDING, "padding", "P",
                  "texels of gutter around every chart (default 2)"),
    GB_CLI_OPTION(OPTION_CONE, "cone", "DEGREES",
                  "largest angle between a chart's normals and its\n"
                  "first triangle's, 1..90 (default 70)"),
    GB_CLI_STATS("print charts, fill ratio (the triangles' UV area\n"
                 "in texels over the atlas's width x height), max and\n"
                 "mean angle distortion (degrees, per triangle corner:\n"
                 "|UV angle - 3-D angle|) and seconds"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    gb_atlas_options *o = &a->atlas;
    switch (option) {
    case 'o': a->output = text; return 0;
    case OPTION_SIZE:
        a->size_given = 1;
        return gb_cli_uint(command.tool, "size", text, 8, GB_ATLAS_MAX_SIZE, &o->size);
    case OPTION_TEXELS:
        return gb_cli_number(command.tool, "texels-per-unit", text, 1e-9, 1e9,
                             &o->texels_per_unit);
    case OPTION_PADDING: return gb_cli_uint(command.tool, "padding", text, 0, 64, &o->padding);
    case OPTION_CONE:
        return gb_cli_number(command.tool, "cone", text, 1.0, 90.0, &o->cone_degrees);
    default: abort();   /* an entry with no case here */
    }
}

/* SCENE, and -o; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (count != 1 || !a->output)
        return gb_cli_usage_error(command.tool, "expected one SCENE and -o OUT.atlas");
    if (a->size_given && a->atlas.texels_per_unit > 0.0)
        return gb_cli_usage_error(command.tool,
                                  "--size and --texels-per-unit exclude each other");
    a->scene = operands[0];
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"atlas", usage, parse_option,
                                       check_operands, entries, 27, NULL};

static void print_stats(const gb_atlas_stats *s, const gb_atlas *atlas, const char *output)
{
    const gb_atlas_header *h = &atlas->header;
    printf("charts %u\nfill_ratio %.4f\nmax_angle_distortion %.3f\n"
           "mean_angle_distortion %.3f\nneedle_corners %" PRIu64 "\nseconds %.3f\n",
           s->charts, s->fill_ratio, s->max_angle_distortion, s->mean_angle_distortion,
           s->needle_corners, s->seconds);
    printf("size %ux%u\ntexels_per_unit %.6g\ntriangles %u\ngrown_charts %u\n"
           "lone_triangles %u\n", h->width, h->height, (double)h->texels_per_unit,
           h->triangle_count, s->grown_charts, s->lone_triangles);
    /* why charts were split (atlas_build.h, parameterize.h) */
    printf("split_not_disc %u\nsplit_lscm_failed %u\nsplit_folded %u\nsplit_overlapping %u\n"
           "split_wasteful %u\nlaid_alone_collapsed %u\nsplit_overlapping_packed %u\n"
           "packings %u\n", s->splits, s->lscm_failures, s->folded, s->overlapping, s->wasteful,
           s->collapsed, s->self_overlaps, s->rounds);
    FILE *file = fopen(output, "rb");
    if (file && fseek(file, 0, SEEK_END) == 0)
        printf("bytes %ld\n", ftell(file));
    if (file)
        fclose(file);
}

static gb_result make_atlas(arguments *a, const gb_scene *scene, gb_error *error)
{
    gb_progress progress;
    gb_progress_begin_for(&progress, command.tool, a->shared.quiet, &a->atlas.progress,
                          &a->atlas.progress_user);
    gb_atlas atlas;
    gb_atlas_stats stats;
    gb_result result = gb_atlas_build(scene, &a->atlas, &atlas, &stats, error);
    gb_progress_end(&progress);
    if (result == GB_OK)
        result = gb_atlas_write(a->output, &atlas, error);
    if (result == GB_OK && a->shared.stats)
        print_stats(&stats, &atlas, a->output);
    gb_atlas_free(&atlas);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    gb_result result =
        gb_output_files_check((const char *[]){a->output, a->shared.depfile}, 2, error);
    if (result != GB_OK)
        return result;
    gb_scene scene;
    result = gb_scene_load(a->scene, NULL, &scene, error);
    if (result == GB_OK && !a->shared.quiet)
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY);
    if (result == GB_OK)
        result = make_atlas(a, &scene, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_depfile_write_scene(a->shared.depfile, a->output, &scene, NULL, error);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    arguments a = {0};
    a.atlas.padding = GB_ATLAS_DEFAULT_PADDING;
    return gb_cli_main(&command, argc, argv, run, &a);
}
