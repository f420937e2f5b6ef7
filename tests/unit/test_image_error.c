/* imgdiff's measures (common/image_error.[ch]) on images whose
 * errors are worked out by hand. */
#include <math.h>

#include "image_error.h"
#include "tap.h"

static gb_image make_image(int width, int height, int channels, const float *values)
{
    gb_image image;
    gb_error error;
    gb_image_allocate(&image, width, height, channels, &error);
    for (int i = 0; i < width * height * channels; ++i)
        image.pixels[i] = values[i];
    return image;
}

static double srgb_decode(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static void test_srgb8(void)
{
    int exact = 1;
    for (int k = 0; k < 256; ++k)
        exact &= gb_linear_to_srgb8((float)srgb_decode(k / 255.0)) == k;
    CHECK(exact, "8-bit sRGB values survive decoding to linear and encoding back");
    CHECK(gb_linear_to_srgb8(0.5f) == 188 && gb_linear_to_srgb8(-1.0f) == 0 &&
              gb_linear_to_srgb8(7.0f) == 255 && gb_linear_to_srgb8(NAN) == 0,
          "linear 0.5 is sRGB 188; values are clamped to 0..255");
}

/* A: black, white; B: black, grey 0.5 (linear). Pixel 1 differs by 0.5 in
 * each channel, 255 - 188 = 67 in 8-bit sRGB. */
static void test_known_numbers(void)
{
    const float a_values[6] = {0, 0, 0, 1, 1, 1}, b_values[6] = {0, 0, 0, .5f, .5f, .5f};
    gb_image a = make_image(2, 1, 3, a_values), b = make_image(2, 1, 3, b_values);
    gb_image_error e;
    gb_error error;
    CHECK_EQ_INT(gb_image_error_compute(&a, &b, NULL, &e, &error), GB_OK, "compare 2 pixels");
    CHECK_EQ_INT(e.pixel_count, 2, "2 pixels compared");
    CHECK_NEAR(e.mse_srgb8, 3 * 67.0 * 67.0 / 6, 1e-9, "mse_srgb8 = 3 * 67^2 / 6 = 2244.5");
    CHECK_NEAR(e.rmse, sqrt(0.75 / 6), 1e-9, "rmse = sqrt(3 * 0.25 / 6)");
    CHECK_NEAR(e.relative_mse, 3 * 0.25 / (0.25 + 0.01) / 6, 1e-9,
               "relative_mse = 3 * 0.25 / (0.25 + 0.01) / 6");
    CHECK_NEAR(e.psnr, 10 * log10(255.0 * 255.0 / 2244.5), 1e-9, "psnr = 14.62 dB");
    CHECK_NEAR(e.max_error, 0.5, 1e-9, "largest per-pixel error 0.5");
    CHECK(e.trimmed_pixel_count == 0 && e.relative_mse_trimmed == e.relative_mse,
          "2 pixels: none left out, relative_mse_trimmed = relative_mse");

    CHECK(gb_image_error_compute(&a, &a, NULL, &e, &error) == GB_OK && e.mse_srgb8 == 0 &&
              e.rmse == 0 && isinf(e.psnr),
          "an image against itself: no error, infinite PSNR");

    const float mask_values[2] = {1, 0};
    gb_image mask = make_image(2, 1, 1, mask_values);
    CHECK(gb_image_error_compute(&a, &b, &mask, &e, &error) == GB_OK && e.pixel_count == 1 &&
              e.mse_srgb8 == 0,
          "the mask leaves out the differing pixel");
    const float none[2] = {0, 0};
    gb_image empty_mask = make_image(2, 1, 1, none);
    CHECK_EQ_INT(gb_image_error_compute(&a, &b, &empty_mask, &e, &error), GB_ERROR_INVALID,
                 "a mask that leaves nothing is refused");

    gb_image heatmap;
    CHECK_EQ_INT(gb_image_error_heatmap(&a, &b, NULL, 0, &heatmap, &error), GB_OK, "heatmap");
    CHECK(heatmap.pixels[0] == 0 && heatmap.pixels[1] == 0 && heatmap.pixels[3] == 1 &&
              heatmap.pixels[4] == 1 && heatmap.pixels[5] == 1,
          "heatmap: no error is black, the largest is white");
    gb_image_free(&heatmap);
    gb_image_free(&mask);
    gb_image_free(&empty_mask);
    gb_image_free(&a);
    gb_image_free(&b);
}

static void test_shapes(void)
{
    const float values[12] = {0.1f, 0.2f, 0.3f, 0.4f, 0.1f, 0.2f, 0.3f, 0.4f, 0, 0, 0, 0};
    gb_image rgba = make_image(1, 2, 4, values), rgb = make_image(2, 2, 3, values);
    gb_image grey_a = make_image(2, 1, 1, values), grey_b = make_image(2, 1, 1, values + 1);
    gb_image one_by_two = make_image(2, 1, 3, values);
    gb_image_error e;
    gb_error error;
    CHECK_EQ_INT(gb_image_error_compute(&rgb, &rgba, NULL, &e, &error), GB_ERROR_INVALID,
                 "images of different sizes are refused");
    CHECK(gb_image_error_compute(&grey_a, &grey_b, NULL, &e, &error) == GB_OK &&
              e.channel_count == 1 && fabs(e.rmse - 0.1) < 1e-6,
          "grey images compare their one channel");
    CHECK_EQ_INT(gb_image_error_compute(&grey_a, &one_by_two, NULL, &e, &error),
                 GB_ERROR_INVALID, "grey against colour is refused");
    gb_image rgba2 = make_image(2, 1, 4, values);
    CHECK(gb_image_error_compute(&rgba2, &one_by_two, NULL, &e, &error) == GB_OK &&
              e.channel_count == 3,
          "RGBA against RGB compares the colour channels");
    gb_image *images[6] = {&rgba, &rgb, &grey_a, &grey_b, &one_by_two, &rgba2};
    for (int i = 0; i < 6; ++i)
        gb_image_free(images[i]);
}

/* A width x 1 RGB image, every value v, and a black one of the same size. */
static void make_pair(int width, float v, gb_image *a, gb_image *black)
{
    gb_error error;
    gb_image_allocate(a, width, 1, 3, &error);
    gb_image_allocate(black, width, 1, 3, &error);
    for (int i = 0; i < 3 * width; ++i) {
        a->pixels[i] = v;
        black->pixels[i] = 0.0f;
    }
}

static void set_pixel(gb_image *image, int p, float v)
{
    for (int c = 0; c < 3; ++c)
        image->pixels[3 * p + c] = v;
}

/* Against black every denominator is 0.01, so a pixel of value v has the
 * relative error r = v^2 / 0.01: 0.125 -> 1.5625, 0.25 -> 6.25, 3 -> 900,
 * 4 -> 1600 (values exact in float). */
static void test_trimmed(void)
{
    gb_image a, black;
    gb_image_error e;
    gb_error error;

    /* 2000 pixels: two outliers (r = 1600, pixels 700 and 1500), 999 of
     * r = 1.5625 (the rest of 0..999), 999 of r = 6.25 (the rest of
     * 1000..1999). floor(2000 / 1000) = 2 left out: the two outliers. */
    make_pair(2000, 0.125f, &a, &black);
    for (int p = 1000; p < 2000; ++p)
        set_pixel(&a, p, 0.25f);
    set_pixel(&a, 700, 4.0f);
    set_pixel(&a, 1500, 4.0f);
    CHECK_EQ_INT(gb_image_error_compute(&a, &black, NULL, &e, &error), GB_OK, "2000 pixels");
    CHECK_NEAR(e.relative_mse, (2 * 1600 + 999 * 1.5625 + 999 * 6.25) / 2000, 1e-9,
               "relative_mse = (2 * 1600 + 999 * 1.5625 + 999 * 6.25) / 2000 = 5.502");
    CHECK_EQ_INT(e.trimmed_pixel_count, 2, "floor(2000 / 1000) = 2 pixels left out");
    CHECK_NEAR(e.relative_mse_trimmed, (1.5625 + 6.25) / 2, 1e-9,
               "relative_mse_trimmed: the two outliers left out, "
               "(999 * 1.5625 + 999 * 6.25) / 1998 = 3.90625");

    /* --mask: the compared pixels are those counted. Pixels 0..1000: the
     * outlier 700, 999 of 1.5625 and pixel 1000 (6.25); floor(1001 / 1000) =
     * 1 left out. Pixels 0..998: fewer than 1000, none left out. */
    gb_image mask;
    gb_image_allocate(&mask, 2000, 1, 1, &error);
    for (int p = 0; p < 2000; ++p)
        mask.pixels[p] = p <= 1000 ? 1.0f : 0.0f;
    CHECK_EQ_INT(gb_image_error_compute(&a, &black, &mask, &e, &error), GB_OK, "masked");
    CHECK(e.pixel_count == 1001 && e.trimmed_pixel_count == 1,
          "masked to 1001 pixels: 1 left out");
    CHECK_NEAR(e.relative_mse_trimmed, (999 * 1.5625 + 6.25) / 1000, 1e-9,
               "masked: the outlier left out, (999 * 1.5625 + 6.25) / 1000 = 1.5671875");
    mask.pixels[999] = mask.pixels[1000] = 0.0f;
    CHECK_EQ_INT(gb_image_error_compute(&a, &black, &mask, &e, &error), GB_OK, "999 pixels");
    CHECK(e.pixel_count == 999 && e.trimmed_pixel_count == 0 &&
              e.relative_mse_trimmed == e.relative_mse && e.relative_mse > 1.0,
          "masked to 999 pixels: none left out, relative_mse_trimmed = relative_mse "
          "(the outlier kept)");

    /* Ties at the cut: three pixels of 1600 in 1000, one left out,
     * whichever it is. */
    gb_image a1000, black1000;
    make_pair(1000, 0.125f, &a1000, &black1000);
    set_pixel(&a1000, 3, 4.0f);
    set_pixel(&a1000, 500, 4.0f);
    set_pixel(&a1000, 999, 4.0f);
    CHECK(gb_image_error_compute(&a1000, &black1000, NULL, &e, &error) == GB_OK &&
              e.trimmed_pixel_count == 1,
          "1000 pixels: 1 left out");
    CHECK_NEAR(e.relative_mse_trimmed, (2 * 1600 + 997 * 1.5625) / 999, 1e-9,
               "three tied at the cut: one left out, (2 * 1600 + 997 * 1.5625) / 999");
    /* In the last pixel, where a sort that compares NaN equal to everything
     * leaves it: the pixel left out, were NaN not caught before. */
    a1000.pixels[3 * 999 + 1] = NAN;
    CHECK(gb_image_error_compute(&a1000, &black1000, NULL, &e, &error) == GB_OK &&
              isnan(e.relative_mse) && isnan(e.relative_mse_trimmed),
          "a NaN value: relative_mse and relative_mse_trimmed are NaN (it is not left out)");
    gb_image_free(&a1000);
    gb_image_free(&black1000);
    gb_image_free(&mask);
    gb_image_free(&a);
    gb_image_free(&black);

    /* 2500 pixels: floor(2.5) = 2 left out (not 3). Pixel 10: r = 1600;
     * pixel 20: r = 900; pixel 30 differs in its first channel only: r =
     * (1600 + 2 * 1.5625) / 3 = 534.375, the largest channel error but the
     * third pixel by r, which is kept; the other 2497 of 1.5625. */
    make_pair(2500, 0.125f, &a, &black);
    set_pixel(&a, 10, 4.0f);
    set_pixel(&a, 20, 3.0f);
    a.pixels[3 * 30] = 4.0f;
    CHECK_EQ_INT(gb_image_error_compute(&a, &black, NULL, &e, &error), GB_OK, "2500 pixels");
    CHECK_EQ_INT(e.trimmed_pixel_count, 2, "floor(2500 / 1000) = 2 pixels left out");
    CHECK_NEAR(e.relative_mse_trimmed, (534.375 + 2497 * 1.5625) / 2498, 1e-9,
               "ranked by the mean over the channels: pixels 10 and 20 left out, "
               "(534.375 + 2497 * 1.5625) / 2498");
    CHECK(e.relative_mse_trimmed < e.relative_mse, "relative_mse_trimmed below relative_mse");
    CHECK(gb_image_error_compute(&a, &a, NULL, &e, &error) == GB_OK &&
              e.relative_mse_trimmed == 0.0,
          "an image against itself: relative_mse_trimmed 0");
    gb_image_free(&a);
    gb_image_free(&black);
}

int main(void)
{
    test_srgb8();
    test_known_numbers();
    test_shapes();
    test_trimmed();
    return tap_done();
}
