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

/* The help before the methods' options (indirect_method.h) and after. */
static const char usage_head[] =
    "usage: gbview [options] SCENE\n"
    "Shows SCENE (.scene or a mesh) with its global illumination in a window, or\n"
    "with --headless renders it without a display (EGL, Mesa surfaceless) into -o.\n"
    "\n"
    "      --headless          render without a window; write the last frame to -o\n"
    "  -c, --camera N          the scene's camera N, from 0 (default 0)\n"
    "  -m, --method M          direct (default); topo, octree, flc, implicit,\n"
    "                          flc-iv (FLC shadowed by implicit visibility's bins)\n"
    "                          when this build has them\n"
    "  -f, --frames K          frames to render (headless: default 1); in a window,\n"
    "                          quit after K frames\n"
    "  -o, --output FILE       the image: .exr linear (compares with `reference`),\n"
    "                          .png sRGB; in a window, where screenshots go\n"
    "                          (and, with --frames, the last frame)\n"
    "  -r, --resolution WxH    frame size (default: the camera's)\n"
    "      --timings           print per-pass GPU times (ms) on stdout (each pass\n"
    "                          is finished before its end time is taken)\n"
    "      --bake DIR          use the files baked for SCENE in DIR\n"
    "                          (NAME.vdb .skel .grid.vdb .seg .lot .atlas); a\n"
    "                          missing or bad one is reported and skipped\n"
    "      --area-samples N    shadowed point emitters approximating the area\n"
    "                          lights, power-weighted (default 16; 0: none)\n"
    "      --environment-lights N  directional lights, with shadow maps, standing\n"
    "                          for the environment's light on surfaces (median\n"
    "                          cut; default 64 times the sky's share of the\n"
    "                          light power: 64 for a scene lit by its sky\n"
    "                          alone; 0: none, the sky only seen)\n"
    "      --shadow-size N     side of the 2-D shadow maps; cube faces get half\n"
    "                          (default 1024)\n"
    "      --cascade-size N    side of each of the 4 maps fitted to the view for\n"
    "                          a directional light (default 2048; 0: none, the\n"
    "                          scene-wide map only)\n"
    "      --supersample S     headless: S x S samples a pixel, averaged (default\n"
    "                          1), the box filter of `reference`\n"
    "      --no-shadows        debug: every light fully visible\n"
    "      --terms T           both (default), direct or indirect: the light drawn\n"
    "      --budget MS         in the window, a frame's milliseconds (default 50):\n"
    "                          each frame draws the parts of the image that fit,\n"
    "                          and the image is shown when whole; 0: whole images\n";

static const char usage_tail[] =
    "  -q, --quiet             no warnings, no progress bar (the links of implicit\n"
    "                          and flc-iv show one on a terminal)\n"
    "  -h, --help              this help\n"
    "  -V, --version           the version\n"
    "\n"
    "Window keys: mouse (left button held) and W A S D Q E fly, Shift faster,\n"
    "wheel: speed; right button held: orbit about the point under the cursor;\n"
    "M next method, T direct/indirect/both, C next camera, B print the view as a\n"
    ".scene camera line, H keys, F1 HUD, F12 or P screenshot, Esc quit.\n";

typedef struct arguments {
    const char *scene_path, *output, *bake;
    gb_method method;
    gb_renderer_options renderer;
    long camera, frames, supersample;
    int environment_lights;     /* -1: by the environment's share of the light */
    int budget_given;
    int headless, timings, quiet;
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

/* gbview's own options; main() appends the methods'. */
static const struct option own_options[] = {
    GB_CLI_FLAG("headless", OPTION_HEADLESS),
    GB_CLI_VALUE("camera", 'c'),
    GB_CLI_VALUE("method", 'm'),
    GB_CLI_VALUE("frames", 'f'),
    GB_CLI_VALUE("output", 'o'),
    GB_CLI_VALUE("resolution", 'r'),
    GB_CLI_FLAG("timings", OPTION_TIMINGS),
    GB_CLI_VALUE("bake", OPTION_BAKE),
    GB_CLI_VALUE("area-samples", OPTION_AREA_SAMPLES),
    GB_CLI_VALUE("environment-lights", OPTION_ENVIRONMENT_LIGHTS),
    GB_CLI_VALUE("shadow-size", OPTION_SHADOW_SIZE),
    GB_CLI_VALUE("cascade-size", OPTION_CASCADE_SIZE),
    GB_CLI_FLAG("no-shadows", OPTION_NO_SHADOWS),
    GB_CLI_VALUE("supersample", OPTION_SUPERSAMPLE),
    GB_CLI_VALUE("terms", OPTION_TERMS),
    GB_CLI_VALUE("budget", OPTION_BUDGET),
};

static int parse_terms(const char *value, gb_terms *terms)
{
    const char *names[GB_TERMS_COUNT];
    for (int t = 0; t < GB_TERMS_COUNT; ++t)
        names[t] = t == GB_TERMS_BOTH ? "both" : gb_terms_name((gb_terms)t);
    int chosen;
    int status = gb_cli_choice("gbview", "terms", value, names, GB_TERMS_COUNT, &chosen);
    if (status == 0)
        *terms = (gb_terms)chosen;
    return status;
}

/* The options of the methods and of the renderer; 0, else the exit status. */
/* A count in 0..most into *out, 0 given as -1: the renderer's "none" (its 0
 * is the default). 0, else the exit status. */
static int parse_count_or_none(const char *name, const char *value, int most, int *out)
{
    int status = gb_cli_int("gbview", name, value, 0, most, out);
    if (status == 0 && *out == 0)
        *out = -1;
    return status;
}

/* The methods' options (indirect_method.h), in the order of gb_method, and
 * how many: option code OPTION_METHOD_FIRST + k is method_options[k]. */
enum { MOST_METHOD_OPTIONS = 64 };
static const gb_method_option *method_options[MOST_METHOD_OPTIONS];
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
    case 'q': a->quiet = 1; return 0;
    case OPTION_BUDGET:
        a->budget_given = 1;
        return gb_cli_number("gbview", "budget", value, 0.0, 1e6, &r->budget_ms);
    case OPTION_SUPERSAMPLE:
        return gb_cli_integer("gbview", "supersample", value, 1, 16, &a->supersample);
    case 'c': return gb_cli_integer("gbview", "camera", value, 0, 1 << 30, &a->camera);
    case 'f': return gb_cli_integer("gbview", "frames", value, 1, 1 << 30, &a->frames);
    case 'm':
        if (gb_method_parse(value, &a->method, &error) == GB_OK)
            return 0;
        return gb_cli_usage_error("gbview", "%s", error.message);
    case 'r':
        return gb_cli_size("gbview", "resolution", value, GB_CLI_MAX_IMAGE_SIDE, &r->width,
                           &r->height);
    case OPTION_AREA_SAMPLES:
        return parse_count_or_none("area-samples", value, 4096, &r->shadow.area_samples);
    case OPTION_ENVIRONMENT_LIGHTS:
        return gb_cli_int("gbview", "environment-lights", value, 0, 1024,
                          &a->environment_lights);
    case OPTION_CASCADE_SIZE:
        return parse_count_or_none("cascade-size", value, 16384, &r->shadow.cascade_size);
    case OPTION_SHADOW_SIZE:
        return gb_cli_int("gbview", "shadow-size", value, 16, 16384, &r->shadow.size);
    case OPTION_TERMS: return parse_terms(value, &r->terms);
    }
    abort(); /* an option of the table without its case */
}

/* The method chosen, if this build has it: GB_CLI_GO_ON, else a usage error. */
static int check_method(arguments *a)
{
    gb_error error;
    a->renderer.method = a->method;
    if (gb_method_check(a->method, &error) != GB_OK)
        return gb_cli_usage_error("gbview", "%s", error.message);
    return GB_CLI_GO_ON;
}

/* One SCENE, something to write with --headless, and a method this build
 * has; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (count != 1)
        return gb_cli_usage_error("gbview", "expected one SCENE");
    a->scene_path = operands[0];
    if (a->headless && !a->output && !a->timings && !a->renderer.parameters.topo.write_vpls)
        return gb_cli_usage_error("gbview", "--headless writes nothing without -o FILE, "
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
    if (result == GB_OK && !a->quiet)  /* with no light every method draws black, as it should */
        gb_scene_warn("gbview", &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    a->renderer.bake = bake;
    setup_bar bar = {.quiet = a->quiet};
    a->renderer.progress = report_setup;
    a->renderer.progress_user = &bar;
    if (result == GB_OK)
        result = render(&scene, a, error);
    gb_bake_release(bake);
    gb_scene_free(&scene);
    return result;
}

/* One option's help at usage + length, as usage_head's: the option
 * in a column of HELP_COLUMN, then help, its later lines indented to that
 * column. The new length. */
enum { HELP_COLUMN = 26 };
static int append_option_help(char *usage, size_t size, int length, const gb_method_option *o)
{
    int start = length;
    length += snprintf(usage + length, size - length, "      --%s%s%s", o->name,
                       o->value_name ? " " : "", o->value_name ? o->value_name : "");
    int column = length - start < HELP_COLUMN ? HELP_COLUMN - (length - start) : 2;
    for (const char *line = o->help; *line;) {
        const char *end = strchr(line, '\n');
        int n = end ? (int)(end - line) : (int)strlen(line);
        length += snprintf(usage + length, size - length, "%*s%.*s\n", column, "", n, line);
        column = HELP_COLUMN;
        line += end ? n + 1 : n;
    }
    return length;
}

/* The methods' options after own_options in options (GB_CLI_OPTIONS_END
 * last), and their help lines between usage_head and usage_tail in usage. */
static void add_method_options(struct option *options, char *usage, size_t size)
{
    static const struct option end[] = {GB_CLI_OPTIONS_END};
    size_t own = sizeof own_options / sizeof own_options[0];
    memcpy(options, own_options, sizeof own_options);
    int length = snprintf(usage, size, "%s", usage_head);
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        for (const gb_method_option *o = gb_method_options((gb_method)m); o && o->name; ++o) {
            int k = method_option_count++;
            method_options[k] = o;
            options[own + k] = (struct option){o->name, o->value_name ? required_argument
                                                                      : no_argument,
                                               NULL, OPTION_METHOD_FIRST + k};
            length = append_option_help(usage, size, length, o);
        }
    memcpy(options + own + method_option_count, end, sizeof end);
    snprintf(usage + length, size - length, "%s", usage_tail);
}

int main(int argc, char **argv)
{
    static struct option options[sizeof own_options / sizeof own_options[0] +
                                 MOST_METHOD_OPTIONS + 4];
    static char usage[8192];
    add_method_options(options, usage, sizeof usage);
    const gb_cli_command command = {.tool = "gbview", .usage = usage, .options = options,
                                    .option = parse_option, .operands = check_operands};
    return gb_cli_main(&command, argc, argv, run,
                       &(arguments){.environment_lights = -1});
}
