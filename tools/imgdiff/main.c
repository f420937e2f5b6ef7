/* imgdiff — how far an image is from a reference (common/image_error.h). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "image.h"
#include "image_error.h"

static const char usage[] =
    "usage: imgdiff [options] IMAGE REFERENCE\n"
    "Compares IMAGE with REFERENCE (same size; the first three channels, linear\n"
    "values as read: EXR as is, PNG/JPEG decoded from sRGB) and prints, one per line:\n"
    "  pixels        how many pixels were compared\n"
    "  mse_srgb8     mean squared error of the 8-bit sRGB values (0..255 scale)\n"
    "  rmse          root mean squared error of the linear values\n"
    "  relative_mse  mean of (a - b)^2 / (b^2 + 0.01), b the reference\n"
    "  psnr          10 log10(255^2 / mse_srgb8) in dB (inf when equal)\n"
    "  max_error     the largest per-pixel RMS error, linear\n"
    "  relative_mse_trimmed\n"
    "                relative_mse with the pixels of largest relative error left\n"
    "                out: floor(pixels / 1000) of them (0.1 % of the compared\n"
    "                pixels, rounded down: none below 1000), a pixel's relative\n"
    "                error being the mean over its channels of (a - b)^2 / (b^2 +\n"
    "                0.01); ties at the cut do not change it. At most relative_mse\n"
    "\n";

typedef struct arguments {
    gb_cli_shared shared;       /* first: -q */
    const char *image, *reference, *mask, *heatmap;
    double heatmap_scale;
    double fail_above;          /* INFINITY: never fail on the error; NaN fails */
} arguments;

enum { OPTION_MASK = 256, OPTION_HEATMAP, OPTION_HEATMAP_SCALE, OPTION_FAIL_ABOVE };

static const gb_cli_entry entries[] = {
    GB_CLI_OPTION(OPTION_MASK, "mask", "FILE", "compare only where FILE is not black (< 0.5)"),
    GB_CLI_OPTION(OPTION_HEATMAP, "heatmap", "OUT.png",
                  "write the per-pixel error as colours, black (none)\n"
                  "to white (the 99th percentile, or --heatmap-scale)"),
    GB_CLI_OPTION(OPTION_HEATMAP_SCALE, "heatmap-scale", "E", "the linear error shown white"),
    GB_CLI_OPTION(OPTION_FAIL_ABOVE, "fail-above", "E",
                  "exit 1 when relative_mse is above E (a test's threshold)"),
    GB_CLI_QUIET("print nothing (the exit status tells)"),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command command; /* below; command.tool starts every message */

/* The largest --heatmap-scale and --fail-above: any error a test can meet. */
#define MAX_ERROR 1e30

/* One option into a; 0, else the exit status. */
static int parse_option(int option, const char *text, void *context)
{
    arguments *a = context;
    switch (option) {
    case OPTION_MASK: a->mask = text; return 0;
    case OPTION_HEATMAP: a->heatmap = text; return 0;
    case OPTION_HEATMAP_SCALE:  /* 0 would show every error white */
        return gb_cli_number(command.tool, "heatmap-scale", text, 1e-30, MAX_ERROR,
                             &a->heatmap_scale);
    case OPTION_FAIL_ABOVE:
        return gb_cli_number(command.tool, "fail-above", text, 0.0, MAX_ERROR, &a->fail_above);
    default: abort();   /* an entry with no case here */
    }
}

/* IMAGE and REFERENCE; GB_CLI_GO_ON, else the exit status. */
static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    if (count != 2)
        return gb_cli_usage_error(command.tool, "expected IMAGE and REFERENCE");
    a->image = operands[0];
    a->reference = operands[1];
    return GB_CLI_GO_ON;
}

static const gb_cli_command command = {"imgdiff", usage, parse_option, check_operands,
                                       entries, 28, NULL};

static void print_error(const gb_image_error *e)
{
    printf("pixels %llu\n", (unsigned long long)e->pixel_count);
    printf("mse_srgb8 %.6g\n", e->mse_srgb8);
    printf("rmse %.6g\n", e->rmse);
    printf("relative_mse %.6g\n", e->relative_mse);
    if (isinf(e->psnr))
        printf("psnr inf\n");
    else
        printf("psnr %.4f\n", e->psnr);
    printf("max_error %.6g\n", e->max_error);
    printf("relative_mse_trimmed %.6g\n", e->relative_mse_trimmed);
}

static gb_result write_heatmap(const arguments *a, const gb_image *image,
                               const gb_image *reference, const gb_image *mask,
                               gb_error *error)
{
    gb_image heatmap;
    gb_result result = gb_image_error_heatmap(image, reference, mask, a->heatmap_scale,
                                              &heatmap, error);
    if (result == GB_OK)
        result = gb_image_write(a->heatmap, &heatmap, error);
    gb_image_free(&heatmap);
    return result;
}

static gb_result compare(const arguments *a, gb_image images[3], gb_image_error *measures,
                         gb_error *error)
{
    gb_result result = gb_image_read(a->image, &images[0], error);
    if (result == GB_OK)
        result = gb_image_read(a->reference, &images[1], error);
    if (result == GB_OK && a->mask)
        result = gb_image_read(a->mask, &images[2], error);
    const gb_image *mask = a->mask ? &images[2] : NULL;
    if (result == GB_OK)
        result = gb_image_error_compute(&images[0], &images[1], mask, measures, error);
    if (result == GB_OK && a->heatmap)
        result = write_heatmap(a, &images[0], &images[1], mask, error);
    if (result == GB_OK && !a->shared.quiet)
        print_error(measures);
    return result;
}

int main(int argc, char **argv)
{
    arguments a = {.fail_above = INFINITY};
    int status = gb_cli_parse(&command, argc, argv, &a);
    if (status != GB_CLI_GO_ON)
        return status;
    gb_image images[3] = {{0}, {0}, {0}};
    gb_error error;
    gb_image_error measures;
    gb_result result = a.heatmap ? gb_image_check_output(a.heatmap, &error) : GB_OK;
    if (result == GB_OK)
        result = compare(&a, images, &measures, &error);
    for (int i = 0; i < 3; ++i)
        gb_image_free(&images[i]);
    if (result != GB_OK)
        return gb_cli_failure(command.tool, &error);
    if (fflush(stdout) != 0)
        return 1;
    if (isfinite(a.fail_above) && !(measures.relative_mse <= a.fail_above)) {
        if (!a.shared.quiet)
            fprintf(stderr, "%s: relative_mse %.6g is above %g\n", command.tool,
                    measures.relative_mse, a.fail_above);
        return 1;
    }
    return 0;
}
