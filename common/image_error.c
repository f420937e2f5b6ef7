#include "image_error.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

static double srgb_encode(double linear)
{
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

static double srgb_decode(double encoded)
{
    return encoded <= 0.04045 ? encoded / 12.92 : pow((encoded + 0.055) / 1.055, 2.4);
}

int gb_linear_to_srgb8(float linear)
{
    double clamped = linear > 0.0f ? (linear < 1.0f ? linear : 1.0) : 0.0; /* NaN -> 0 */
    return (int)floor(255.0 * srgb_encode(clamped) + 0.5);
}

/* The channels compared: the first three of colour images, the only one of
 * grey images; 0 when the counts cannot be matched. */
static int compared_channels(const gb_image *a, const gb_image *b)
{
    int fewest = a->channels < b->channels ? a->channels : b->channels;
    if (fewest >= 3)
        return 3;
    return a->channels == b->channels ? fewest : 0;
}

static gb_result check_images(const gb_image *a, const gb_image *b, const gb_image *mask,
                              gb_error *error)
{
    if (a->width != b->width || a->height != b->height)
        return gb_fail(error, GB_ERROR_INVALID, "images differ in size: %dx%d and %dx%d",
                       a->width, a->height, b->width, b->height);
    if (!compared_channels(a, b))
        return gb_fail(error, GB_ERROR_INVALID, "cannot compare %d channels with %d",
                       a->channels, b->channels);
    if (mask && (mask->width != a->width || mask->height != a->height))
        return gb_fail(error, GB_ERROR_INVALID, "mask is %dx%d, the images %dx%d", mask->width,
                       mask->height, a->width, a->height);
    return GB_OK;
}

static int pixel_counts(const gb_image *mask, size_t pixel)
{
    return !mask || mask->pixels[pixel * (size_t)mask->channels] >= 0.5f;
}

typedef struct sums {
    double srgb8, linear, relative, max_error;
    uint64_t pixels;
} sums;

/* Squared error of pixel p over the channels, into s; returns the pixel's
 * linear mean squared error. */
static double add_pixel(const gb_image *a, const gb_image *b, int channels, size_t p, sums *s)
{
    double pixel_linear = 0.0;
    for (int c = 0; c < channels; ++c) {
        float va = a->pixels[p * (size_t)a->channels + c];
        float vb = b->pixels[p * (size_t)b->channels + c];
        double d8 = gb_linear_to_srgb8(va) - gb_linear_to_srgb8(vb);
        double d = (double)va - vb;
        s->srgb8 += d8 * d8;
        pixel_linear += d * d;
        s->relative += d * d / ((double)vb * vb + GB_RELATIVE_MSE_EPSILON);
    }
    s->linear += pixel_linear;
    return pixel_linear / channels;
}

static double pixel_rms(const gb_image *a, const gb_image *b, int channels, size_t p)
{
    sums s = {0};
    return sqrt(add_pixel(a, b, channels, p, &s));
}

/* r(p) of image_error.h: the pixel's relative squared error, mean over the
 * channels. */
static double pixel_relative(const gb_image *a, const gb_image *b, int channels, size_t p)
{
    sums s = {0};
    add_pixel(a, b, channels, p, &s);
    return s.relative / channels;
}

typedef double pixel_measure(const gb_image *a, const gb_image *b, int channels, size_t p);

/* measure of each compared pixel (compared of them), in pixel order, in a
 * new array; NULL when out of memory. */
static double *compared_values(const gb_image *image, const gb_image *reference,
                               const gb_image *mask, int channels, uint64_t compared,
                               pixel_measure *measure)
{
    double *values = malloc(compared * sizeof *values);
    if (!values)
        return NULL;
    size_t count = (size_t)image->width * (size_t)image->height, n = 0;
    for (size_t p = 0; p < count; ++p)
        if (pixel_counts(mask, p))
            values[n++] = measure(image, reference, channels, p);
    return values;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The mean of the n values but the k largest (k < n); sorts values. */
static double mean_without_largest(double *values, size_t n, size_t k)
{
    qsort(values, n, sizeof *values, compare_doubles);
    double sum = 0.0;
    for (size_t i = 0; i < n - k; ++i)
        sum += values[i];
    return sum / (double)(n - k);
}

/* relative_mse_trimmed and trimmed_pixel_count of out, whose pixel_count,
 * channel_count and relative_mse are set. */
static gb_result trim_relative(const gb_image *image, const gb_image *reference,
                               const gb_image *mask, gb_image_error *out, gb_error *error)
{
    uint64_t k = out->pixel_count / 1000;
    out->trimmed_pixel_count = k;
    out->relative_mse_trimmed = out->relative_mse;
    if (k == 0 || isnan(out->relative_mse))
        return GB_OK;
    double *r = compared_values(image, reference, mask, out->channel_count, out->pixel_count,
                                pixel_relative);
    if (!r)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    out->relative_mse_trimmed = mean_without_largest(r, out->pixel_count, k);
    free(r);
    return GB_OK;
}

gb_result gb_image_error_compute(const gb_image *image, const gb_image *reference,
                                 const gb_image *mask, gb_image_error *out, gb_error *error)
{
    *out = (gb_image_error){0};
    gb_result result = check_images(image, reference, mask, error);
    if (result != GB_OK)
        return result;
    int channels = compared_channels(image, reference);
    sums s = {0};
    size_t count = (size_t)image->width * (size_t)image->height;
    for (size_t p = 0; p < count; ++p) {
        if (!pixel_counts(mask, p))
            continue;
        double pixel_mse = add_pixel(image, reference, channels, p, &s);
        s.max_error = fmax(s.max_error, sqrt(pixel_mse));
        ++s.pixels;
    }
    if (s.pixels == 0)
        return gb_fail(error, GB_ERROR_INVALID, "the mask leaves no pixel to compare");
    double n = (double)s.pixels * channels;
    out->pixel_count = s.pixels;
    out->channel_count = channels;
    out->mse_srgb8 = s.srgb8 / n;
    out->rmse = sqrt(s.linear / n);
    out->relative_mse = s.relative / n;
    out->psnr = out->mse_srgb8 > 0.0 ? 10.0 * log10(255.0 * 255.0 / out->mse_srgb8) : INFINITY;
    out->max_error = s.max_error;
    return trim_relative(image, reference, mask, out, error);
}

/* The 99th percentile (nearest rank) of the compared pixels' errors. */
static gb_result percentile_99(const gb_image *image, const gb_image *reference,
                               const gb_image *mask, int channels, uint64_t compared,
                               double *scale, gb_error *error)
{
    double *errors = compared_values(image, reference, mask, channels, compared, pixel_rms);
    if (!errors)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    qsort(errors, compared, sizeof *errors, compare_doubles);
    size_t rank = (size_t)ceil(0.99 * (double)compared);
    *scale = errors[rank > 0 ? rank - 1 : 0];
    free(errors);
    return GB_OK;
}

/* sRGB colours of the map at 0, 1/4, 1/2, 3/4 and 1. */
static const double HEAT_STOPS[5][3] = {
    {0.0, 0.0, 0.0}, {0.34, 0.06, 0.43}, {0.80, 0.22, 0.29}, {0.98, 0.62, 0.05}, {1.0, 1.0, 1.0},
};

static void heat_colour(double t, float rgb[3])
{
    t = t > 0.0 ? (t < 1.0 ? t : 1.0) : 0.0;
    int i = t >= 1.0 ? 3 : (int)(t * 4.0);
    double f = t * 4.0 - i;
    for (int c = 0; c < 3; ++c)
        rgb[c] = (float)srgb_decode(HEAT_STOPS[i][c] * (1.0 - f) + HEAT_STOPS[i + 1][c] * f);
}

gb_result gb_image_error_heatmap(const gb_image *image, const gb_image *reference,
                                 const gb_image *mask, double scale, gb_image *heatmap,
                                 gb_error *error)
{
    *heatmap = (gb_image){0};
    gb_image_error measures;
    gb_result result = gb_image_error_compute(image, reference, mask, &measures, error);
    int channels = measures.channel_count;
    if (result == GB_OK && scale <= 0.0)
        result = percentile_99(image, reference, mask, channels, measures.pixel_count, &scale,
                               error);
    if (result == GB_OK)
        result = gb_image_allocate(heatmap, image->width, image->height, 3, error);
    if (result != GB_OK)
        return result;
    if (!(scale > 0.0))
        scale = 1.0;
    size_t count = (size_t)image->width * (size_t)image->height;
    for (size_t p = 0; p < count; ++p) {
        double t = pixel_counts(mask, p) ? pixel_rms(image, reference, channels, p) / scale : 0;
        heat_colour(t, &heatmap->pixels[3 * p]);
    }
    return GB_OK;
}
