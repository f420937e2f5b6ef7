/* photons — traces the photon map of a scene with Embree (photons.h), or
 * merges the shards of a run. */

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "depfile.h"
#include "output_file.h"
#include "photon_map.h"
#include "photons.h"
#include "progress.h"
#include "scene.h"
#include "scene_warnings.h"

static const char usage[] =
    "usage: photons [options] SCENE -o OUT.phot\n"
    "       photons --merge A.phot B.phot ... -o OUT.phot\n"
    "Traces photons from every light of SCENE with Embree and writes the photon\n"
    "map (formats/FORMATS.md, \"Photon map\"). The map depends on the seed, never\n"
    "on --threads.\n"
    "\n";

enum { OPTION_STORE = 256, OPTION_SHARD, OPTION_MERGE, OPTION_TOLERANCE };

typedef struct arguments {
    gb_cli_shared shared;       /* first: --seed, --threads, --stats, --depfile, -q */
    gb_photons_options trace;
    const char *output;
    char **inputs;
    int input_count;
    int merge, automatic;
    double tolerance;
} arguments;

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the photon map to write"),
    GB_CLI_OPTION('n', "count", "N|auto",
                  "photons emitted (default 1000000); auto: 2^16,\n"
                  "2^17, ... until the map's power in 16^3 cells of the\n"
                  "bounds changes by less than --tolerance (at most\n"
                  "2^30; about twice the cost of the run it keeps)"),
    GB_CLI_OPTION(OPTION_TOLERANCE, "tolerance", "T",
                  "for -n auto: relative change, 1e-6..0.999 (default\n"
                  "0.05)"),
    GB_CLI_OPTION('b', "bounces", "N",
                  "most reflections of a path, 1..255 (default 16;\n"
                  "Russian roulette after 2)"),
    GB_CLI_OPTION(OPTION_STORE, "store", "WHAT",
                  "indirect (default): photons that were reflected at\n"
                  "least once; all: every hit, direct light included"),
    GB_CLI_SEED("N", NULL),
    GB_CLI_THREADS(256, NULL),
    GB_CLI_OPTION(OPTION_SHARD, "shard", "I/N",
                  "trace only part I of N (from 0/N to N-1/N) of the\n"
                  "photons; --merge joins the N parts into the map of\n"
                  "the whole run, byte for byte"),
    GB_CLI_OPTION(OPTION_MERGE, "merge", NULL, "join the shards given as arguments"),
    GB_CLI_STATS("print photons, rays and seconds on stdout"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

static int parse_store(const char *text, gb_photons_options *o)
{
    static const char *const stores[] = {"indirect", "all"};
    int store;
    int status = gb_cli_choice(command.tool, "store", text, stores, 2, &store);
    if (status == 0)
        o->store = store == 0 ? GB_PHOTON_STORE_INDIRECT : GB_PHOTON_STORE_ALL;
    return status;
}

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    switch (option) {
    case 'o': a->output = text; return 0;
    case OPTION_MERGE: a->merge = 1; return 0;
    case 'n':
        a->automatic = strcmp(text, "auto") == 0;
        return a->automatic ? 0 : gb_cli_unsigned(command.tool, "count", text, 1,
                                                   GB_PHOTONS_MAX_COUNT, &a->trace.count);
    case OPTION_TOLERANCE:
        return gb_cli_number(command.tool, "tolerance", text, 1e-6, 0.999, &a->tolerance);
    case 'b':
        return gb_cli_uint(command.tool, "bounces", text, 1, GB_PHOTON_MAX_BOUNCES,
                           &a->trace.bounces);
    case OPTION_STORE: return parse_store(text, &a->trace);
    case OPTION_SHARD:
        return gb_cli_fraction(command.tool, "shard", text, &a->trace.shard_index,
                               &a->trace.shard_count);
    default: abort();   /* an entry with no case here */
    }
}

/* One SCENE, or with --merge the shards, and -o; GB_CLI_GO_ON, else the
 * exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    a->inputs = operands;
    a->input_count = count;
    if (!a->output || a->input_count < 1 || (!a->merge && a->input_count != 1))
        return gb_cli_usage_error(command.tool, "expected %s and -o OUT",
                                  a->merge ? "the shards to merge" : "one SCENE");
    if (a->tolerance > 0.0 && !a->automatic)
        return gb_cli_usage_error(command.tool, "--tolerance is for -n auto");
    a->trace.seed = a->shared.seed;
    a->trace.threads = a->shared.threads;
    if (a->automatic)
        a->trace.tolerance = a->tolerance > 0.0 ? a->tolerance : GB_PHOTONS_DEFAULT_TOLERANCE;
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"photons", usage, parse_option,
                                       check_operands, entries, 26, NULL};

/* ---- tracing ---- */

/* The progress bar, its label showing the photons traced per second. */
typedef struct rate_progress {
    gb_progress bar;
    char label[64];
    uint64_t photons;
} rate_progress;

static int report_rate(void *user, double fraction)
{
    rate_progress *p = user;
    double elapsed = gb_seconds() - p->bar.start_seconds;
    if (elapsed > 0.0 && p->photons)   /* -n auto: runs of several counts, no one rate */
        snprintf(p->label, sizeof p->label, "photons %.2f M/s",
                 1e-6 * fraction * (double)p->photons / elapsed);
    return gb_progress_report(&p->bar, fraction);
}

static void print_stats(const gb_photons_stats *s, const gb_photon_map *map)
{
    if (s->passes > 1)
        printf("passes %u\nchange %.4f\n", s->passes, s->change);
    double seconds = s->seconds > 0.0 ? s->seconds : 1e-9;
    printf("photons %" PRIu64 "\nstored %" PRIu64 "\nrays %" PRIu64 "\nescaped %" PRIu64
           "\nnonfinite %" PRIu64 "\nthreads %d\n", s->paths, map->count, s->rays, s->escaped,
           s->nonfinite, s->threads);
    printf("seconds %.3f\ncpu_seconds %.3f\nbuild_seconds %.3f\nphotons_per_second %.0f\n"
           "mrays_per_second %.3f\nbytes_per_photon %d\n", s->seconds, s->cpu_seconds,
           s->build_seconds, (double)s->paths / seconds, 1e-6 * (double)s->rays / seconds,
           GB_PHOTON_SIZE);
}

static gb_result trace(arguments *a, const gb_scene *scene, gb_error *error)
{
    rate_progress progress = {.photons = a->automatic      ? 0
                                         : a->trace.count ? a->trace.count
                                                          : GB_PHOTONS_DEFAULT_COUNT};
    snprintf(progress.label, sizeof progress.label, "photons");
    gb_progress_begin(&progress.bar, progress.label, a->shared.quiet);
    a->trace.progress = report_rate;
    a->trace.progress_user = &progress;
    gb_photon_map map;
    gb_photons_stats stats;
    gb_result result = gb_photons_trace(scene, &a->trace, &map, &stats, error);
    snprintf(progress.label, sizeof progress.label, "photons");
    gb_progress_end(&progress.bar);
    if (result == GB_OK && a->automatic && !a->shared.quiet)
        fprintf(stderr, "photons: -n auto: %" PRIu64 " photons (the map's power changed by "
                "%.3f from half as many, %s the tolerance %g)\n", stats.paths, stats.change,
                stats.change < a->trace.tolerance ? "below" : "still above", a->trace.tolerance);
    if (result == GB_OK)
        result = gb_photon_map_write(a->output, &map, error);
    if (result == GB_OK && a->shared.stats)
        print_stats(&stats, &map);
    gb_photon_map_free(&map);
    return result;
}

static gb_result run_trace(arguments *a, gb_error *error)
{
    gb_scene scene;
    gb_scene_options scene_options = {.load_textures = 1};
    gb_result result = gb_scene_load(a->inputs[0], &scene_options, &scene, error);
    if (result == GB_OK && !a->shared.quiet)  /* no light: an empty map, the right answer */
        gb_scene_warn(command.tool, &scene, GB_WARN_GEOMETRY | GB_WARN_LIGHT);
    if (result == GB_OK)
        result = trace(a, &scene, error);
    if (result == GB_OK && a->shared.depfile)
        result = gb_depfile_write_scene(a->shared.depfile, a->output, &scene, NULL, error);
    gb_scene_free(&scene);
    return result;
}

/* ---- merging ---- */

static gb_result merge_maps(arguments *a, gb_photon_map *shards, gb_error *error)
{
    gb_photon_map merged;
    gb_result result = gb_photons_merge(shards, (uint32_t)a->input_count,
                                        (const char *const *)a->inputs, &merged, error);
    if (result == GB_OK)
        result = gb_photon_map_write(a->output, &merged, error);
    gb_photon_map_free(&merged);
    return result;
}

static gb_result run_merge(arguments *a, gb_error *error)
{
    gb_photon_map *shards = calloc((size_t)a->input_count, sizeof *shards);
    if (!shards)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    gb_result result = GB_OK;
    for (int i = 0; i < a->input_count && result == GB_OK; ++i)
        result = gb_photon_map_read(a->inputs[i], &shards[i], error);
    if (result == GB_OK)
        result = merge_maps(a, shards, error);
    for (int i = 0; i < a->input_count; ++i)
        gb_photon_map_free(&shards[i]);
    free(shards);
    return result;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    gb_result result = gb_output_file_check(a->output, error);
    if (result == GB_OK && a->shared.depfile)
        result = a->merge ? gb_fail(error, GB_ERROR_ARGUMENT, "--depfile is for a trace, "
                                    "not --merge (whose inputs are its operands)")
                          : gb_output_file_check(a->shared.depfile, error);
    if (result == GB_OK)
        result = a->merge ? run_merge(a, error) : run_trace(a, error);
    return result;
}

int main(int argc, char **argv)
{
    return gb_cli_main(&command, argc, argv, run, &(arguments){0});
}
