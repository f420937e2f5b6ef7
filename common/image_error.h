/* image_error.h — how far an image is from a reference, in the measures
 * gibake reports: MSE on 8-bit sRGB values (the scale of Table II of Noël
 * et al. 2014), RMSE and relative MSE on linear values, the relative MSE
 * that a few pixels cannot decide, PSNR.
 *
 * Over the compared pixels P (all, or those where the mask is not black)
 * and the compared channels C (the first three, or one for grey images),
 * with a the image and b the reference, N = |P| |C| values:
 *   mse_srgb8    = sum (A - B)^2 / N, A = round(255 srgb(clamp(a, 0, 1)))
 *   rmse         = sqrt(sum (a - b)^2 / N)
 *   relative_mse = sum (a - b)^2 / (b^2 + 0.01) / N   (Rousselle et al. 2011)
 *   psnr         = 10 log10(255^2 / mse_srgb8) dB, infinite when equal.
 *
 * relative_mse_trimmed: relative_mse without the pixels of largest error,
 * so that a handful of pixels (a shadow edge) cannot decide it. A pixel's
 * relative error is r(p) = sum over C of (a - b)^2 / (b^2 + 0.01) / |C|, so
 * relative_mse is the mean of r over P. The k = floor(|P| / 1000) pixels of
 * largest r (0.1 % of the compared pixels, rounded down: none when fewer
 * than 1000 are compared) are left out, and relative_mse_trimmed is the
 * mean of r over the other |P| - k. Ties at the cut do not change it: what
 * is left out is the k largest values, whichever of the tied pixels hold
 * them. It is at most relative_mse, and equal to it when k is 0. A NaN among
 * the compared values makes it NaN, as it makes relative_mse; an infinite
 * r is a largest error like any other.
 */
#ifndef GB_IMAGE_ERROR_H
#define GB_IMAGE_ERROR_H

#include <stdint.h>

#include "image.h"

#define GB_RELATIVE_MSE_EPSILON 0.01

typedef struct gb_image_error {
    uint64_t pixel_count;       /* compared pixels */
    int channel_count;          /* compared channels per pixel */
    double mse_srgb8;
    double rmse;
    double relative_mse;
    double relative_mse_trimmed;
    uint64_t trimmed_pixel_count;  /* pixels left out of relative_mse_trimmed: k above */
    double psnr;                /* INFINITY when mse_srgb8 is 0 */
    double max_error;           /* largest per-pixel RMS error over the channels, linear */
} gb_image_error;

/* mask may be NULL; a mask pixel whose first channel is below 0.5 is left
 * out (P is the pixels it leaves). Fails on images (or a mask) of different
 * sizes, on channel counts that cannot be matched, when the mask leaves no
 * pixel, and when out of memory (relative_mse_trimmed sorts |P| values). */
gb_result gb_image_error_compute(const gb_image *image, const gb_image *reference,
                                 const gb_image *mask, gb_image_error *out, gb_error *error);

/* The per-pixel RMS error over the channels (linear) as colours, 0 black to
 * scale white through purple, red and yellow ("inferno"-like); left-out
 * pixels are black. scale <= 0 means the 99th percentile of the compared
 * pixels' errors (nearest rank), so that a few outliers do not darken the
 * rest. heatmap is allocated here (RGB, linear values that an sRGB file
 * shows as the colour map). */
gb_result gb_image_error_heatmap(const gb_image *image, const gb_image *reference,
                                 const gb_image *mask, double scale, gb_image *heatmap,
                                 gb_error *error);

/* Linear to 8-bit sRGB, clamped and rounded: 0..255. */
int gb_linear_to_srgb8(float linear);

#endif
