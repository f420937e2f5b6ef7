/* gbview — the runtime: shows a scene and its baked global illumination in
 * a window, or renders it headless into an image (the headers in runtime/). This file
 * only parses options. */

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake.h"
#include "cli.h"
#include "environment_lights.h"
#include "flc/flc.h"
#include "headless.h"
#include "image.h"
#include "methods.h"
#include "output_file.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"
#include "timings.h"
#include "window.h"

static const char tool[] = "gbview";

static const char usage[] =
    "usage: gbview [options] SCENE\n"
    "Shows SCENE (.scene or a mesh) with its global illumination in a window, or\n"
    "with --headless renders it without a display (EGL, Mesa surfaceless) into -o.\n"
    "\n";

static const char window_keys[] =
    "\n"
    "Window keys: mouse (left button held) and W A S D Q E fly, Shift faster,\n"
    "wheel: speed; right button held: orbit about the point under the cursor;\n"
    "M next method, T direct/indirect/both, C next camera, B print the view as a\n"
    ".scene camera line, H keys, F1 HUD, F12 or P screenshot, Esc quit.\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    const char *scene_path, *output, *bake;
    gb_method method;
    gb_renderer_options renderer;
    long camera, frames, supersample;
    int environment_lights;     /* -1: by the environment's share of the light */
    int budget_given;
    int headless, timings;
} arguments;

enum {
    OPTION_HEADLESS = 256,
    OPTION_TIMINGS,
    OPTION_BAKE,
    OPTION_AREA_SAMPLES,
    OPTION_ENVIRONMENT_LIGHTS,
    OPTION_SHADOW_SIZE,
    OPTION_CASCADE_SIZE,
    OPTION_NO_SHADOWS,
    OPTION_SUPERSAMPLE,
    OPTION_TERMS,
    OPTION_BUDGET,
    OPTION_METHOD_FIRST = 512,  /* + k: the k-th of method_options */
};

/* gbview's own options, before the methods' (main() appends them), and the
 * last. */
static const gb_cli_entry own_entries[] = {
    GB_CLI_OPTION(OPTION_HEADLESS, "headless", NULL,
                  "render without a window; write the last frame to -o"),
    GB_CLI_OPTION('c', "camera", "N", "the scene's camera N, from 0 (default 0)"),
    GB_CLI_OPTION('m', "method", "M",
                  "direct (default); topo, octree, flc, implicit,\n"
                  "flc-iv (FLC shadowed by implicit visibility's bins)\n"
                  "when this build has them"),
    GB_CLI_OPTION('f', "frames", "K",
                  "frames to render (headless: default 1); in a window,\n"
                  "quit after K frames"),
    GB_CLI_OPTION('o', "output", "FILE",
                  "the image: .exr linear (compares with `reference`),\n"
                  ".png sRGB; in a window, where screenshots go\n"
                  "(and, with --frames, the last frame)"),
    GB_CLI_OPTION('r', "resolution", "WxH", "frame size (default: the camera's)"),
    GB_CLI_OPTION(OPTION_TIMINGS, "timings", NULL,
                  "print per-pass GPU times (ms) on stdout (each pass\n"
                  "is finished before its end time is taken)"),
    GB_CLI_OPTION(OPTION_BAKE, "bake", "DIR",
                  "use the files baked for SCENE in DIR\n"
                  "(NAME.vdb .skel .grid.vdb .seg .lot .atlas); a\n"
                  "missing or bad one is reported and skipped"),
    GB_CLI_OPTION(OPTION_AREA_SAMPLES, "area-samples", "N",
                  "shadowed point emitters approximating the area\n"
                  "lights, power-weighted (default 16; 0: none)"),
    GB_CLI_OPTION(OPTION_ENVIRONMENT_LIGHTS, "environment-lights", "N",
                  "directional lights, with shadow maps, standing\n"
                  "for the environment's light on surfaces (median\n"
                  "cut; default 64 times the sky's share of the\n"
                  "light power: 64 for a scene lit by its sky\n"
                  "alone; 0: none, the sky only seen)"),
    GB_CLI_OPTION(OPTION_SHADOW_SIZE, "shadow-size", "N",
                  "side of the 2-D shadow maps; cube faces get half\n"
                  "(default 1024)"),
    GB_CLI_OPTION(OPTION_CASCADE_SIZE, "cascade-size", "N",
                  "side of each of the 4 maps fitted to the view for\n"
                  "a directional light (default 2048; 0: none, the\n"
                  "scene-wide map only)"),
    GB_CLI_OPTION(OPTION_SUPERSAMPLE, "supersample", "S",
                  "headless: S x S samples a pixel, averaged (default\n"
                  "1), the box filter of `reference`"),
    GB_CLI_OPTION(OPTION_NO_SHADOWS, "no-shadows", NULL, "debug: every light fully visible"),
    GB_CLI_OPTION(OPTION_TERMS, "terms", "T",
                  "both (default), direct or indirect: the light drawn"),
    GB_CLI_OPTION(OPTION_BUDGET, "budget", "MS",
                  "in the window, a frame's milliseconds (default 50):\n"
                  "each frame draws the parts of the image that fit,\n"
                  "and the image is shown when whole; 0: whole images"),
    GB_CLI_ENTRIES_END,
};
static const gb_cli_entry last_entries[] = {
    GB_CLI_QUIET("no warnings, no progress bar (the links of implicit\n"
                 "and flc-iv show one on a terminal)"),
    GB_CLI_ENTRIES_END,
};

/* --terms into *terms; 0, else the exit status. */
static int parse_terms(const char *value, gb_terms *terms)
{
    const char *names[GB_TERMS_COUNT];
    for (int t = 0; t < GB_TERMS_COUNT; ++t)
        names[t] = t == GB_TERMS_BOTH ? "both" : gb_terms_name((gb_terms)t);
    int chosen;
    int status = gb_cli_choice(tool, "terms", value, names, GB_TERMS_COUNT, &chosen);
    if (status == 0)
        *terms = (gb_terms)chosen;
    return status;
}

/* A count in 0..most into *out, 0 given as -1: the renderer's "none" (its 0
 * is the default). 0, else the exit status. */
static int parse_count_or_none(const char *name, const char *value, int most, int *out)
{
    int status = gb_cli_int(tool, name, value, 0, most, out);
    if (status == 0 && *out == 0)
        *out = -1;
    return status;
}

/* The methods' options (indirect_method.h), in the order of gb_method, and
 * how many: option code OPTION_METHOD_FIRST + k is method_options[k]. */
static const gb_method_option *method_options[GB_CLI_MAX_ENTRIES];
static int method_option_count;

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *value, void *context)
{
    arguments *a = context;
    gb_renderer_options *r = &a->renderer;
    gb_error error;
    if (option >= OPTION_METHOD_FIRST) {
        const gb_method_option *o = method_options[option - OPTION_METHOD_FIRST];
        return o->parse(o->name, value, &r->parameters);
    }
    switch (option) {
    case OPTION_HEADLESS: a->headless = 1; return 0;
    case OPTION_TIMINGS: a->timings = r->finish_passes = 1; return 0;
    case OPTION_BAKE: a->bake = value; return 0;
    case OPTION_NO_SHADOWS: r->no_shadows = 1; return 0;
    case 'o': a->output = value; return 0;
    case OPTION_BUDGET:
        a->budget_given = 1;
        return gb_cli_number(tool, "budget", value, 0.0, 1e6, &r->budget_ms);
    case OPTION_SUPERSAMPLE:
        return gb_cli_integer(tool, "supersample", value, 1, 16, &a->supersample);
    case 'c': return gb_cli_integer(tool, "camera", value, 0, 1 << 30, &a->camera);
    case 'f': return gb_cli_integer(tool, "frames", value, 1, 1 << 30, &a->frames);
    case 'm':
        if (gb_method_parse(value, &a->method, &error) == GB_OK)
            return 0;
        return gb_cli_usage_error(tool, "%s", error.message);
    case 'r':
        return gb_cli_size(tool, "resolution", value, GB_CLI_MAX_IMAGE_SIDE, &r->width,
                           &r->height);
    case OPTION_AREA_SAMPLES:
        return parse_count_or_none("area-samples", value, 4096, &r->shadow.area_samples);
    case OPTION_ENVIRONMENT_LIGHTS:
        return gb_cli_int(tool, "environment-lights", value, 0, 1024,
                          &a->environment_lights);
    case OPTION_CASCADE_SIZE:
        return parse_count_or_none("cascade-size", value, 16384, &r->shadow.cascade_size);
    case OPTION_SHADOW_SIZE:
        return gb_cli_int(tool, "shadow-size", value, 16, 16384, &r->shadow.size);
    case OPTION_TERMS: return parse_terms(value, &r->terms);
    }
    abort(); /* an entry of the table without its case */
}

/* The method chosen, if this build has it: GB_CLI_GO_ON, else a usage error. */
static int check_method(arguments *a)
{
    gb_error error;
    a->renderer.method = a->method;
    if (gb_method_check(a->method, &error) != GB_OK)
        return gb_cli_usage_error(tool, "%s", error.message);
    return GB_CLI_GO_ON;
}

/* One SCENE, something to write with --headless, and a method this build
 * has; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (count != 1)
        return gb_cli_usage_error(tool, "expected one SCENE");
    a->scene_path = operands[0];
    if (a->headless && !a->output && !a->timings && !a->renderer.parameters.topo.write_vpls)
        return gb_cli_usage_error(tool, "--headless writes nothing without -o FILE, "
                                            "--timings or --write-vpls");
    return check_method(a);
}


/* The bake of a->bake (*bake NULL without --bake): its files are read when
 * a method asks for them, and a method that needs a missing or bad one
 * fails naming it; an error here only when the files cannot be looked for
 * at all. */
static gb_result open_bake(const gb_scene *scene, const arguments *a, gb_bake **bake,
                           gb_error *error)
{
    *bake = NULL;
    return a->bake ? gb_bake_open(scene, a->scene_path, a->bake, bake, error) : GB_OK;
}

static void report(void *user, const char *message)
{
    (void)user;
    printf("gbview: %s\n", message);
    fflush(stdout);
}

static gb_result run_headless(const gb_scene *scene, const arguments *a, gb_timings *timings,
                              gb_error *error)
{
    gb_headless_options options = {
        .renderer = a->renderer,
        .camera = (uint32_t)a->camera,
        .frames = (int)a->frames,
        .supersample = (int)a->supersample,
    };
    gb_image image;
    gb_result result = gb_render_headless(scene, &options, &image, timings, error);
    if (result == GB_OK && a->output)
        result = gb_image_write(a->output, &image, error);
    gb_image_free(&image);
    return result;
}

static gb_result run_window(const gb_scene *scene, const arguments *a, gb_timings *timings,
                            gb_error *error)
{
    const char *name = strrchr(a->scene_path, '/');
    gb_renderer_options renderer = a->renderer;
    if (!a->budget_given)
        renderer.budget_ms = GB_WINDOW_DEFAULT_BUDGET_MS;
    renderer.background_setup = 1;
    gb_window_options options = {
        .renderer = renderer,
        .log_frames = a->timings,
        .camera = (uint32_t)a->camera,
        .frames = (int)a->frames,
        .screenshot_path = a->output,
        .title = name ? name + 1 : a->scene_path,
        .report = report,
    };
    return gb_run_window(scene, &options, timings, error);
}

static gb_result render(const gb_scene *scene, const arguments *a, gb_error *error)
{
    gb_timings timings;
    memset(&timings, 0, sizeof timings);
    gb_result result = a->headless ? run_headless(scene, a, &timings, error)
                                   : run_window(scene, a, &timings, error);
    if (result == GB_OK && a->timings)
        gb_timings_print(&timings, stdout);
    return result;
}

/* Before the work: the image and the VPL set can be written. */
static gb_result check_outputs(const arguments *a, gb_error *error)
{
    const char *vpls = a->renderer.parameters.topo.write_vpls;
    gb_result result = a->output ? gb_image_check_output(a->output, error) : GB_OK;
    if (result == GB_OK && vpls)
        result = gb_output_file_check(vpls, error);
    return result;
}

/* The bar of a method's long setup (the links of implicit and flc-iv), on
 * stderr when it is a terminal: begun at a setup's first report, ended
 * when it reports the work done. */
typedef struct setup_bar {
    gb_progress bar;
    int quiet, running;
} setup_bar;

static int report_setup(void *user, double fraction)
{
    setup_bar *s = user;
    if (!s->running)
        gb_progress_begin(&s->bar, "gbview: implicit links", s->quiet);
    s->running = fraction < 1.0;
    int stop = gb_progress_report(&s->bar, fraction);
    if (!s->running)
        gb_progress_end(&s->bar);
    return stop;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    gb_scene scene;
    gb_scene_options scene_options = {.load_textures = 1};
    gb_result result = check_outputs(a, error);
    if (result == GB_OK)
        result = gb_scene_load(a->scene_path, &scene_options, &scene, error);
    if (result != GB_OK)
        return result;
    gb_bake *bake;
    result = open_bake(&scene, a, &bake, error);
    /* after the bake, whose files name the scene's own lights */
    uint32_t sky = a->environment_lights >= 0
                       ? (uint32_t)a->environment_lights
                       : gb_environment_light_count(&scene, GB_MOST_ENVIRONMENT_LIGHTS);
    if (result == GB_OK)
        result = gb_scene_add_environment_lights(&scene, sky, error);
    if (result == GB_OK && !a->shared.quiet)  /* with no light every method draws black, as it should */
        gb_scene_warn(tool, &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    a->renderer.bake = bake;
    setup_bar bar = {.quiet = a->shared.quiet};
    a->renderer.progress = report_setup;
    a->renderer.progress_user = &bar;
    if (result == GB_OK)
        result = render(&scene, a, error);
    gb_bake_release(bake);
    gb_scene_free(&scene);
    return result;
}

/* own_entries, the methods' options (code OPTION_METHOD_FIRST + k), then
 * last_entries, in entries (room for GB_CLI_MAX_ENTRIES and the end). */
static void add_method_options(gb_cli_entry entries[GB_CLI_MAX_ENTRIES + 1])
{
    int count = 0;
    for (const gb_cli_entry *e = own_entries; e->name; ++e)
        entries[count++] = *e;
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        for (const gb_method_option *o = gb_method_options((gb_method)m); o && o->name; ++o) {
            int k = method_option_count++;
            method_options[k] = o;
            entries[count++] = (gb_cli_entry)GB_CLI_OPTION(OPTION_METHOD_FIRST + k, o->name,
                                                            o->value_name, o->help);
        }
    for (const gb_cli_entry *e = last_entries;; ++e) {
        entries[count++] = *e;
        if (!e->name)
            break;
    }
}

int main(int argc, char **argv)
{
    static gb_cli_entry entries[GB_CLI_MAX_ENTRIES + 1];
    add_method_options(entries);
    const gb_cli_command command = {.tool = tool, .usage = usage,
                                    .option = parse_option, .operands = check_operands,
                                    .entries = entries, .column = 26, .tail = window_keys};
    return gb_cli_main(&command, argc, argv, run,
                       &(arguments){.environment_lights = -1});
}
