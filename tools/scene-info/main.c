/* scene-info — loads a scene (.scene, .obj, .obj.gz, .ply, .off, .stl) and
 * prints what gibake sees in it: counts, lights, cameras, bounds and hash. */

#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "content_hash.h"
#include "depfile.h"
#include "output_file.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: scene-info [--quiet] [--hash FILE [--depfile FILE]] SCENE\n"
    "Loads SCENE (.scene, .obj, .obj.gz, .ply, .off or .stl) as every gibake tool\n"
    "does and prints a summary: triangles, vertices, materials, area lights and\n"
    "their emissive area, other lights, cameras, bounds and the content hash.\n"
    "Warnings (degenerate triangles dropped, undefined materials, no light) go to\n"
    "stderr.\n"
    "\n";

enum { OPTION_HASH = 256 };

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    const char *scene, *hash;
} arguments;

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION(OPTION_HASH, "hash", "FILE",
                  "instead, write to FILE the lines 'scene_hash HEX' (the\n"
                  "content hash every baked file records) and 'images_hash\n"
                  "HEX' (of the bytes of its textures and environment map),\n"
                  "which the Makefile's bake rules depend on"),
    GB_CLI_DEPFILE("with --hash: a make rule, FILE and every file read (-MD)"),
    GB_CLI_QUIET("no warnings"),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into the arguments; 0. */
static int parse_option(int option, const char *value, void *context)
{
    arguments *a = context;
    switch (option) {
    case OPTION_HASH: a->hash = value; return 0;
    default: abort();   /* an entry with no case here */
    }
}

/* One SCENE; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (count != 1)
        return gb_cli_usage_error(command.tool, "expected one SCENE");
    if (a->shared.depfile && !a->hash)
        return gb_cli_usage_error(command.tool, "--depfile names the file of --hash: give both");
    a->scene = operands[0];
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"scene-info", usage, parse_option,
                                       check_operands, entries, 22, NULL};

static double emissive_area(const gb_scene *scene)
{
    double area = 0;
    for (uint32_t i = 0; i < scene->emissive_count; ++i)
        area += gb_triangle_area(scene, scene->emissive_triangles[i]);
    return area;
}

static uint32_t emissive_materials(const gb_scene *scene)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < scene->material_count; ++i) {
        const float *Ke = scene->materials[i].Ke;
        count += Ke[0] > 0 || Ke[1] > 0 || Ke[2] > 0;
    }
    return count;
}

static uint32_t lights_of_type(const gb_scene *scene, gb_light_type type)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < scene->light_count; ++i)
        count += scene->lights[i].type == type;
    return count;
}

static void print_summary(const gb_scene *scene)
{
    printf("file            %s\n", scene->path);
    printf("triangles       %u\n", scene->triangle_count);
    printf("vertices        %u\n", scene->vertex_count);
    printf("materials       %u (%u emissive)\n", scene->material_count,
           emissive_materials(scene));
    printf("area lights     %u triangles, emissive area %.6g\n", scene->emissive_count,
           emissive_area(scene));
    printf("lights          %u point, %u spot, %u directional\n",
           lights_of_type(scene, GB_LIGHT_POINT), lights_of_type(scene, GB_LIGHT_SPOT),
           lights_of_type(scene, GB_LIGHT_DIRECTIONAL));
    printf("environment     %g %g %g\n", scene->environment[0], scene->environment[1],
           scene->environment[2]);
    printf("cameras         %u\n", scene->camera_count);
    printf("bounds          (%g %g %g) .. (%g %g %g)\n", scene->bounds_min[0],
           scene->bounds_min[1], scene->bounds_min[2], scene->bounds_max[0],
           scene->bounds_max[1], scene->bounds_max[2]);
    printf("hash            %016llx\n", (unsigned long long)scene->hash);
}

/* --hash FILE [--depfile FILE], checked before the scene is read. */
static gb_result write_hash(const arguments *a, gb_scene *scene, gb_error *error)
{
    gb_result result = gb_content_hash_write(a->hash, scene, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_depfile_write_scene(a->shared.depfile, a->hash, scene, NULL, error);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    const arguments *a = context;
    gb_result result =
        gb_output_files_check((const char *[]){a->hash, a->shared.depfile}, 2, error);
    gb_scene scene;
    if (result == GB_OK)
        result = gb_scene_load(a->scene, NULL, &scene, error);
    if (result != GB_OK)
        return result;
    if (a->hash)
        result = write_hash(a, &scene, error);
    else
        print_summary(&scene);
    if (result == GB_OK && !a->shared.quiet)
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
