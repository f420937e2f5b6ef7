/* segment — the segmented skeleton, visibility clusters and visibility gates
 * of a skeleton (noel-biri-2014 §IV.B, §IV.C; tools/segment/segment.h), the
 * gates fitted to the voxels (--voxels --grid), and the measure of how well
 * they predict visibility (--evaluate). Parses the command line, reads the
 * inputs, calls the library, writes the outputs. */

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
    "usage: segment [options] IN.skel -o OUT.seg [--voxels IN.vdb --grid IN.grid.vdb]\n"
    "       segment --evaluate SCENE IN.seg GRID.vdb [--pairs N] [--seed S]\n"
    "Segments the skeleton IN.skel (written by thin) into topology, curvature and\n"
    "coverage nodes, grows visibility clusters over the segmented skeleton and puts\n"
    "a visibility gate on every edge between two clusters; writes OUT.seg.\n"
    "With --voxels and --grid (voxelize's voxels and thin's nearest-node grid of\n"
    "the same bake; make bake passes them), fits each gate's disk to the opening\n"
    "between its two clusters' voxels and adds a gate wherever two clusters touch\n"
    "with no edge between them: the gates gbview draws. Without them the gates are\n"
    "the paper's disks.\n"
    "With --evaluate, samples pairs of points on SCENE's surfaces, predicts their\n"
    "visibility from IN.seg and thin's nearest-node grid GRID.vdb (\"same cluster\",\n"
    "\"same cluster or through one gate\"), checks it with Embree rays and prints\n"
    "precision and recall.\n"
    "\n";

enum { OPTION_PAIRS = 256, OPTION_VOXELS };

typedef struct arguments {
    gb_cli_shared shared;       /* first: the options every tool shares */
    const char *input, *output, *scene, *grid, *voxels;
    gb_segment_options options;
    gb_segment_evaluate_options evaluate_options;
    int evaluate;
} arguments;

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the segmentation file (required without --evaluate)"),
    GB_CLI_OPTION(OPTION_VOXELS, "voxels", "FILE",
                  "voxelize's voxels (.vdb), to fit the gates (with --grid)"),
    GB_CLI_OPTION('g', "grid", "FILE",
                  "thin's nearest-node grid (.grid.vdb), to fit the gates\n"
                  "(with --voxels)"),
    GB_CLI_OPTION('a', "alpha", "PERCENT",
                  "how much a neighbour's maximal ball may differ from the\n"
                  "cluster's largest to join it, 0 to 100 (default 20)"),
    GB_CLI_OPTION('e', "evaluate", NULL, "evaluate IN.seg on SCENE instead of segmenting"),
    GB_CLI_OPTION(OPTION_PAIRS, "pairs", "N", "point pairs to evaluate (default 100000)"),
    GB_CLI_SEED("S", "random seed of the pairs (default 0)"),
    GB_CLI_STATS("print counts and timings on stdout"),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* One option into args; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *args = context;
    gb_segment_evaluate_options *e = &args->evaluate_options;
    switch (option) {
    case 'o': args->output = text; return 0;
    case OPTION_VOXELS: args->voxels = text; return 0;
    case 'g': args->grid = text; return 0;
    case 'e': args->evaluate = 1; return 0;
    case 'a':
        return gb_cli_number_keep_zero(command.tool, "alpha", text, 0.0, 100.0,
                                       &args->options.alpha);
    case OPTION_PAIRS: return gb_cli_uint(command.tool, "pairs", text, 1, UINT32_MAX, &e->pairs);
    default: abort();   /* an entry with no case here */
    }
}

/* IN.skel and -o (--voxels and --grid both or neither), or with --evaluate
 * SCENE IN.seg GRID.vdb; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *args = context;
    if (args->evaluate) {
        if (count != 3 || args->output || args->voxels || args->grid)
            return gb_cli_usage_error(command.tool, "--evaluate expects SCENE IN.seg GRID.vdb "
                                                 "and no -o, --voxels or --grid");
        args->scene = operands[0];
        args->input = operands[1];
        args->grid = operands[2];
        args->evaluate_options.seed = args->shared.seed;
        return GB_CLI_GO_ON;
    }
    if (count != 1 || !args->output)
        return gb_cli_usage_error(command.tool, "expected one IN.skel and -o OUT.seg");
    if (!args->voxels != !args->grid)
        return gb_cli_usage_error(command.tool, "--voxels and --grid go together (the gates "
                                             "are fitted to both)");
    args->input = operands[0];
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"segment", usage, parse_option,
                                       check_operands, entries, 25, NULL};

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
    printf("opening gates    %u\n", stats->opening_gates);
    printf("fitted gates     %u\n", stats->fitted_gates);
    printf("seconds          %.4f\n", stats->seconds);
}

/* What the gates are fitted to: voxelize's voxels, thin's grid. */
typedef struct fit_inputs {
    gb_voxel_grid voxels, frame;
    int32_t *nearest;
} fit_inputs;

static gb_result read_fit_inputs(const arguments *args, fit_inputs *in, gb_error *error)
{
    gb_result result = gb_voxel_grid_read(args->voxels, &in->voxels, error);
    if (result == GB_OK)
        result = gb_voxel_grid_read_int32(args->grid, "nearest_node", &in->frame, &in->nearest,
                                          error);
    return result;
}

static void free_fit_inputs(fit_inputs *in)
{
    gb_voxel_grid_free(&in->voxels);
    gb_voxel_grid_free(&in->frame);
    free(in->nearest);
}

/* The gates fitted to the voxels, once both grids are known to be the
 * segmentation's. */
static gb_result fit_gates(const arguments *args, const fit_inputs *in, gb_segmentation *s,
                           gb_segment_stats *stats, gb_error *error)
{
    gb_result result = gb_segmentation_check_frame(s, &in->voxels, args->voxels, error);
    if (result == GB_OK)
        result = gb_segmentation_check_grid(s, &in->frame, in->nearest, args->grid, error);
    gb_error reason;
    if (result == GB_OK &&
        (result = gb_segment_fit_gates(s, &in->voxels, in->nearest, stats, &reason)) != GB_OK)
        gb_fail(error, result, "%s: %s", args->input, reason.message);
    return result;
}

/* The skeleton segmented, then with --voxels and --grid its gates fitted. */
static gb_result make_segmentation(const arguments *args, const gb_skeleton *skeleton,
                                   const fit_inputs *in, gb_segmentation *s,
                                   gb_segment_stats *stats, gb_error *error)
{
    gb_error reason;
    gb_result result = gb_segment(skeleton, &args->options, s, stats, &reason);
    if (result != GB_OK)
        return gb_fail(error, result, "%s: %s", args->input, reason.message);
    return args->voxels ? fit_gates(args, in, s, stats, error) : GB_OK;
}

static gb_result run_segment(const arguments *args, gb_error *error)
{
    gb_skeleton skeleton = {0};
    fit_inputs in = {0};
    gb_segmentation segmentation = {0};
    gb_segment_stats stats;
    gb_result result = gb_output_file_check(args->output, error);
    if (result == GB_OK)
        result = gb_skeleton_read(args->input, &skeleton, error);
    if (result == GB_OK && args->voxels)
        result = read_fit_inputs(args, &in, error);
    if (result == GB_OK)
        result = make_segmentation(args, &skeleton, &in, &segmentation, &stats, error);
    if (result == GB_OK)
        result = gb_segmentation_write(args->output, &segmentation, error);
    if (result == GB_OK && args->shared.stats)
        print_stats(&segmentation, &stats);
    gb_segmentation_free(&segmentation);
    free_fit_inputs(&in);
    gb_skeleton_free(&skeleton);
    return result;
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

/* Reads the scene, the segmentation and the grid. */
static gb_result load_evaluation_inputs(const arguments *args, gb_scene *scene,
                                        gb_segmentation *seg, gb_voxel_grid *frame,
                                        int32_t **nearest, gb_error *error)
{
    gb_result result = gb_scene_load(args->scene, NULL, scene, error);
    if (result == GB_OK)
        result = gb_segmentation_read(args->input, seg, error);
    if (result == GB_OK)
        result = gb_voxel_grid_read_int32(args->grid, "nearest_node", frame, nearest, error);
    if (result == GB_OK)
        result = gb_segmentation_check_grid(seg, frame, *nearest, args->grid, error);
    if (result == GB_OK && !args->shared.quiet)
        gb_scene_warn(command.tool, scene, GB_WARN_GEOMETRY);
    return result;
}

static gb_result evaluate(const arguments *args, const gb_scene *scene,
                          const gb_segmentation *seg, const int32_t *nearest, gb_error *error)
{
    gb_progress progress;
    gb_segment_evaluate_options options = args->evaluate_options;
    gb_progress_begin_for(&progress, command.tool, args->shared.quiet, &options.progress,
                          &options.progress_user);
    gb_segment_evaluation evaluation;
    gb_error reason;
    gb_result result = gb_segment_evaluate(scene, seg, nearest, &options, &evaluation, &reason);
    gb_progress_end(&progress);
    if (result != GB_OK)
        return gb_fail(error, result, "%s: %s", args->input, reason.message);
    print_evaluation(args, seg, &evaluation);
    return GB_OK;
}

static gb_result run_evaluate(const arguments *args, gb_error *error)
{
    gb_scene scene = {0};
    gb_segmentation seg = {0};
    gb_voxel_grid frame = {0};
    int32_t *nearest = NULL;
    gb_result result = load_evaluation_inputs(args, &scene, &seg, &frame, &nearest, error);
    if (result == GB_OK)
        result = evaluate(args, &scene, &seg, nearest, error);
    free(nearest);
    gb_voxel_grid_free(&frame);
    gb_segmentation_free(&seg);
    gb_scene_free(&scene);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    const arguments *args = context;
    return args->evaluate ? run_evaluate(args, error) : run_segment(args, error);
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
