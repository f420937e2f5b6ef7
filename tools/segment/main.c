/* segment — the segmented skeleton, visibility clusters and visibility gates
 * of a skeleton (noel-biri-2014 §IV.B, §IV.C; tools/segment/segment.h), and
 * the measure of how well they predict visibility (--evaluate). Parses the
 * command line, reads the inputs, calls the library, writes the outputs. */

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "output_file.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"
#include "segment.h"
#include "segmentation.h"
#include "skeleton.h"
#include "voxel_grid.h"

static const char usage[] =
    "usage: segment [options] IN.skel -o OUT.seg\n"
    "       segment --evaluate SCENE IN.seg GRID.vdb [--pairs N] [--seed S]\n"
    "Segments the skeleton IN.skel (written by thin) into topology, curvature and\n"
    "coverage nodes, grows visibility clusters over the segmented skeleton and puts\n"
    "a visibility gate on every edge between two clusters; writes OUT.seg.\n"
    "With --evaluate, samples pairs of points on SCENE's surfaces, predicts their\n"
    "visibility from IN.seg and thin's nearest-node grid GRID.vdb (\"same cluster\",\n"
    "\"same cluster or through one gate\"), checks it with Embree rays and prints\n"
    "precision and recall.\n"
    "\n"
    "  -o, --output FILE      the segmentation file (required without --evaluate)\n"
    "  -a, --alpha PERCENT    how much a neighbour's maximal ball may differ from the\n"
    "                         cluster's largest to join it, 0 to 100 (default 20)\n"
    "  -e, --evaluate         evaluate IN.seg on SCENE instead of segmenting\n"
    "  -n, --pairs N          point pairs to evaluate (default 100000)\n"
    "      --seed S           random seed of the pairs (default 0)\n"
    "  -s, --stats            print counts and timings on stdout\n"
    "  -q, --quiet            no progress bar, no warnings\n"
    "  -h, --help             this help\n"
    "  -V, --version          the version\n";

enum { OPTION_SEED = 256 };

typedef struct arguments {
    const char *input, *output, *scene, *grid;
    gb_segment_options options;
    gb_segment_evaluate_options evaluate_options;
    int evaluate, quiet, stats;
} arguments;

/* One option into args; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *args = context;
    gb_segment_evaluate_options *e = &args->evaluate_options;
    switch (option) {
    case 'o': args->output = text; return 0;
    case 'e': args->evaluate = 1; return 0;
    case 's': args->stats = 1; return 0;
    case 'q': args->quiet = 1; return 0;
    case 'a':
        return gb_cli_number_keep_zero("segment", "alpha", text, 0.0, 100.0,
                                       &args->options.alpha);
    case 'n': return gb_cli_uint("segment", "pairs", text, 1, UINT32_MAX, &e->pairs);
    default: return gb_cli_unsigned("segment", "seed", text, 0, UINT64_MAX, &e->seed);
    }
}

/* GB_CLI_GO_ON, else the exit status. */
static int check_positionals(int argc, char **argv, arguments *args)
{
    int count = argc - optind;
    if (args->evaluate) {
        if (count != 3 || args->output)
            return gb_cli_usage_error("segment",
                                      "--evaluate expects SCENE IN.seg GRID.vdb and no -o");
        args->scene = argv[optind];
        args->input = argv[optind + 1];
        args->grid = argv[optind + 2];
        return GB_CLI_GO_ON;
    }
    if (count != 1 || !args->output)
        return gb_cli_usage_error("segment", "expected one IN.skel and -o OUT.seg");
    args->input = argv[optind];
    return GB_CLI_GO_ON;
}

/* GB_CLI_GO_ON, else the exit status (0 after --help and --version). */
static int parse_arguments(int argc, char **argv, arguments *args)
{
    static const struct option options[] = {
        GB_CLI_VALUE("output", 'o'),
        GB_CLI_VALUE("alpha", 'a'),
        GB_CLI_FLAG("evaluate", 'e'),
        GB_CLI_VALUE("pairs", 'n'),
        GB_CLI_VALUE("seed", OPTION_SEED),
        GB_CLI_FLAG("stats", 's'),
        GB_CLI_OPTIONS_END,
    };
    int status = gb_cli_options("segment", usage, argc, argv, options, parse_option, args);
    if (status != GB_CLI_GO_ON)
        return status;
    return check_positionals(argc, argv, args);
}

static void print_stats(const gb_segmentation *s, const gb_segment_stats *stats)
{
    printf("skeleton nodes   %u\n", s->skeleton_node_count);
    printf("lines            %u\n", stats->lines);
    printf("rings            %u\n", stats->rings);
    printf("loops            %u\n", stats->loops);
    printf("topology nodes   %u\n", stats->topology_nodes);
    printf("curvature nodes  %u\n", stats->curvature_nodes);
    printf("coverage nodes   %u\n", stats->coverage_nodes);
    printf("segmented edges  %u\n", s->edge_count);
    printf("clusters         %u (alpha %g %%)\n", s->cluster_count, s->alpha);
    printf("gates            %u\n", s->gate_count);
    printf("seconds          %.4f\n", stats->seconds);
}

static int run_segment(const arguments *args)
{
    gb_skeleton skeleton;
    gb_error error;
    if (gb_skeleton_read(args->input, &skeleton, &error)) {
        fprintf(stderr, "segment: %s\n", error.message);
        return 1;
    }
    gb_segmentation segmentation;
    gb_segment_stats stats;
    int status = 0;
    if (gb_segment(&skeleton, &args->options, &segmentation, &stats, &error)) {
        fprintf(stderr, "segment: %s: %s\n", args->input, error.message);
        status = 1;
    } else if (gb_segmentation_write(args->output, &segmentation, &error)) {
        fprintf(stderr, "segment: %s\n", error.message);
        status = 1;
    } else if (args->stats) {
        print_stats(&segmentation, &stats);
    }
    gb_segmentation_free(&segmentation);
    gb_skeleton_free(&skeleton);
    return status;
}

static void print_evaluation(const arguments *args, const gb_segmentation *s,
                             const gb_segment_evaluation *e)
{
    double pairs = e->pairs ? (double)e->pairs : 1.0;
    printf("scene            %s\n", args->scene);
    printf("pairs            %llu (seed %llu)\n", (unsigned long long)e->pairs,
           (unsigned long long)args->evaluate_options.seed);
    printf("visible          %.4f\n", (double)e->visible / pairs);
    printf("unlocated        %.4f\n", (double)e->unlocated / pairs);
    printf("grazing draws    %llu\n", (unsigned long long)e->grazing);
    printf("clusters         %u\n", s->cluster_count);
    printf("gates            %u\n", s->gate_count);
    printf("predictor        precision  recall\n");
    printf("same-cluster     %.4f     %.4f\n", gb_visibility_precision(&e->same_cluster),
           gb_visibility_recall(&e->same_cluster));
    printf("one-gate         %.4f     %.4f\n", gb_visibility_precision(&e->one_gate),
           gb_visibility_recall(&e->one_gate));
    printf("seconds          %.3f\n", e->seconds);
}

/* Reads the scene, the segmentation and the grid; 0 or 1 after a message. */
static int load_evaluation_inputs(const arguments *args, gb_scene *scene, gb_segmentation *seg,
                                  gb_voxel_grid *frame, int32_t **nearest)
{
    gb_error error;
    if (gb_scene_load(args->scene, NULL, scene, &error) ||
        gb_segmentation_read(args->input, seg, &error) ||
        gb_voxel_grid_read_int32(args->grid, "nearest_node", frame, nearest, &error) ||
        gb_segmentation_check_grid(seg, frame, *nearest, args->grid, &error)) {
        fprintf(stderr, "segment: %s\n", error.message);
        return 1;
    }
    if (!args->quiet)
        gb_scene_warn("segment", scene, GB_WARN_GEOMETRY);
    return 0;
}

static int run_evaluate(const arguments *args)
{
    gb_scene scene = {0};
    gb_segmentation seg = {0};
    gb_voxel_grid frame = {0};
    int32_t *nearest = NULL;
    int status = load_evaluation_inputs(args, &scene, &seg, &frame, &nearest);
    if (!status) {
        gb_progress progress;
        gb_segment_evaluate_options options = args->evaluate_options;
        gb_progress_begin_for(&progress, "segment", args->quiet, &options.progress,
                              &options.progress_user);
        gb_segment_evaluation evaluation;
        gb_error error;
        gb_result result = gb_segment_evaluate(&scene, &seg, nearest, &options, &evaluation,
                                               &error);
        gb_progress_end(&progress);
        if (result) {
            fprintf(stderr, "segment: %s: %s\n", args->input, error.message);
            status = 1;
        } else {
            print_evaluation(args, &seg, &evaluation);
        }
    }
    free(nearest);
    gb_voxel_grid_free(&frame);
    gb_segmentation_free(&seg);
    gb_scene_free(&scene);
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
    if (!args.evaluate && gb_output_file_check(args.output, &error) != GB_OK) {
        fprintf(stderr, "segment: %s\n", error.message);
        return 1;
    }
    int status = args.evaluate ? run_evaluate(&args) : run_segment(&args);
    if (fflush(stdout) != 0)
        status = 1;
    return status;
}
