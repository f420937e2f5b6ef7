/* reference — renders a camera of a scene with Embree: the ground truth every
 * gibake method measures its error against (tools/reference/reference.h). */

#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "progress.h"
#include "reference.h"
#include "scene.h"
#include "scene_warnings.h"
#include "vpl.h"

static const char usage[] =
    "usage: reference [options] SCENE -o OUT.exr\n"
    "Renders a camera of SCENE with Embree into a linear EXR: ground truth for the\n"
    "real-time methods. The image depends on the seed, never on --threads.\n"
    "\n"
    "  -o, --output FILE       the image to write (.exr: linear; .png: sRGB)\n"
    "  -m, --mode MODE         full (default), direct, indirect1,\n"
    "                          indirect1-unshadowed, vpl\n"
    "                            direct     emitters seen and light reflected once\n"
    "                            indirect1  light reflected exactly twice\n"
    "                            indirect1-unshadowed  the same, ignoring what blocks\n"
    "                                       the segment between the two reflections\n"
    "                            full       path tracing, --min-bounces..--bounces\n"
    "                            vpl        the light of the VPL set --vpl FILE,\n"
    "                                       reflected once, with shadow rays\n"
    "      --vpl FILE          the VPL set of vpl mode (implies --mode vpl)\n"
    "  -s, --spp N             samples per pixel (default 64; 4 in vpl mode, where\n"
    "                          each sample sums every VPL)\n"
    "      --seed N            random seed (default 0)\n"
    "  -c, --camera N          the scene's camera N, from 0 (default 0)\n"
    "  -r, --resolution WxH    image size (default: the camera's)\n"
    "  -t, --threads N         threads (default: every core)\n"
    "  -b, --bounces N         full: most reflections per path (default 64;\n"
    "                          Russian roulette after 3)\n"
    "      --min-bounces N     full: fewest reflections (default 0; 3 gives what\n"
    "                          direct and indirect1 leave out)\n"
    "      --png               also write OUT.png, sRGB, beside OUT.exr\n"
    "      --stats             print rays, seconds (wall, CPU) and rays per second\n"
    "                          on stdout\n"
    "  -q, --quiet             no progress bar, no warnings\n"
    "  -h, --help              this help\n"
    "  -V, --version           the version\n";

typedef struct arguments {
    gb_reference_options render;
    const char *scene_path, *output, *vpl_path;
    int png, stats, quiet, mode_given;
} arguments;

enum { OPTION_VPL = 256, OPTION_SEED, OPTION_MIN_BOUNCES, OPTION_PNG, OPTION_STATS };

static int parse_int(const char *text, long low, long high, long *value)
{
    char *end;
    errno = 0;
    long parsed = strtol(text, &end, 10);
    if (errno || end == text || *end || parsed < low || parsed > high)
        return 0;
    *value = parsed;
    return 1;
}

static int parse_seed(const char *text, uint64_t *seed)
{
    char *end;
    errno = 0;
    unsigned long long parsed = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-')
        return 0;
    *seed = parsed;
    return 1;
}

static int parse_resolution(const char *text, int *width, int *height)
{
    int w, h, consumed = 0;
    if (sscanf(text, "%dx%d%n", &w, &h, &consumed) != 2 || text[consumed] || w < 1 || h < 1)
        return 0;
    *width = w;
    *height = h;
    return 1;
}

/* Stores one numeric option; returns 0 (and says why) when it is bad. */
static int parse_number(int option, const char *text, arguments *a)
{
    long value;
    switch (option) {
    case 's':
        return parse_int(text, 1, 1L << 30, &value) && (a->render.spp = (int)value, 1);
    case 'c':
        return parse_int(text, 0, UINT32_MAX, &value) &&
               (a->render.camera = (uint32_t)value, 1);
    case 't':
        return parse_int(text, 1, 256, &value) && (a->render.threads = (int)value, 1);
    case 'b':
        return parse_int(text, 1, 1 << 20, &value) && (a->render.bounces = (int)value, 1);
    case OPTION_MIN_BOUNCES:
        return parse_int(text, 0, 1 << 20, &value) && (a->render.min_bounces = (int)value, 1);
    case OPTION_SEED:
        return parse_seed(text, &a->render.seed);
    case 'r':
        return parse_resolution(text, &a->render.width, &a->render.height);
    }
    return 0;
}

static int parse_option(int option, const char *text, arguments *a)
{
    gb_error error;
    switch (option) {
    case 'o':
        a->output = text;
        return 1;
    case 'm':
        a->mode_given = 1;
        if (gb_reference_mode_parse(text, &a->render.mode, &error) == GB_OK)
            return 1;
        fprintf(stderr, "reference: %s\n", error.message);
        return 0;
    case OPTION_VPL:
        a->vpl_path = text;
        return 1;
    case OPTION_PNG:
        a->png = 1;
        return 1;
    case OPTION_STATS:
        a->stats = 1;
        return 1;
    case 'q':
        a->quiet = 1;
        return 1;
    }
    if (parse_number(option, text, a))
        return 1;
    fprintf(stderr, "reference: bad value \"%s\" for option -%c\n", text ? text : "",
            option < 256 ? option : '-');
    return 0;
}

/* 0: go on; otherwise the exit status. */
static int check_arguments(arguments *a, int argc, char **argv)
{
    if (optind != argc - 1 || !a->output) {
        fprintf(stderr, "reference: expected one SCENE and -o OUT\n%s", usage);
        return 2;
    }
    a->scene_path = argv[optind];
    if (a->vpl_path && !a->mode_given)
        a->render.mode = GB_REFERENCE_VPL;
    if ((a->render.mode == GB_REFERENCE_VPL) != (a->vpl_path != NULL)) {
        fprintf(stderr, "reference: --vpl FILE goes with --mode vpl, and only with it\n");
        return 2;
    }
    return 0;
}

static int parse_arguments(int argc, char **argv, arguments *a)
{
    static const struct option options[] = {
        {"output", required_argument, NULL, 'o'},
        {"mode", required_argument, NULL, 'm'},
        {"vpl", required_argument, NULL, OPTION_VPL},
        {"spp", required_argument, NULL, 's'},
        {"seed", required_argument, NULL, OPTION_SEED},
        {"camera", required_argument, NULL, 'c'},
        {"resolution", required_argument, NULL, 'r'},
        {"threads", required_argument, NULL, 't'},
        {"bounces", required_argument, NULL, 'b'},
        {"min-bounces", required_argument, NULL, OPTION_MIN_BOUNCES},
        {"png", no_argument, NULL, OPTION_PNG},
        {"stats", no_argument, NULL, OPTION_STATS},
        {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    int option;
    while ((option = getopt_long(argc, argv, "o:m:s:c:r:t:b:qhV", options, NULL)) != -1) {
        if (option == 'h')
            return fputs(usage, stdout) == EOF ? 1 : -1;
        if (option == 'V')
            return puts("reference (gibake) 0.1") == EOF ? 1 : -1;
        if (option == '?' || !parse_option(option, optarg, a))
            return fputs(usage, stderr), 2;
    }
    return check_arguments(a, argc, argv);
}

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
    gb_progress_begin(&progress, "reference", a->quiet);
    a->render.progress = gb_progress_report;
    a->render.progress_user = &progress;
    gb_image image;
    gb_reference_stats stats;
    gb_result result = gb_reference_render(scene, &a->render, &image, &stats, error);
    gb_progress_end(&progress);
    if (result == GB_OK)
        result = write_images(a, &image, error);
    if (result == GB_OK && a->stats)
        print_stats(&stats);
    gb_image_free(&image);
    return result;
}

static gb_result run(arguments *a, gb_error *error)
{
    gb_scene scene;
    gb_scene_options scene_options = {.load_textures = 1};
    gb_result result = gb_scene_load(a->scene_path, &scene_options, &scene, error);
    if (result != GB_OK)
        return result;
    if (!a->quiet)     /* with no light the image is black, as it should be */
        gb_scene_warn("reference", &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    gb_vpl_set vpls = {0};
    if (a->vpl_path) {
        result = gb_vpl_read(a->vpl_path, &vpls, error);
        if (result == GB_OK)
            result = gb_vpl_check_scene(&vpls, scene.hash, a->vpl_path, error);
        a->render.vpls = &vpls;
    }
    if (result == GB_OK)
        result = render(a, &scene, error);
    gb_vpl_free(&vpls);
    gb_scene_free(&scene);
    return result;
}

int main(int argc, char **argv)
{
    arguments a = {0};
    int status = parse_arguments(argc, argv, &a);
    if (status)
        return status < 0 ? 0 : status;
    gb_error error;
    if (check_outputs(&a, &error) != GB_OK || run(&a, &error) != GB_OK) {
        fprintf(stderr, "reference: %s\n", error.message);
        return 1;
    }
    return fflush(stdout) == 0 ? 0 : 1;
}
