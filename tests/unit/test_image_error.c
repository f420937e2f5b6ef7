/* imgdiff's measures (tools/imgdiff/image_error.[ch]) on images whose
 * errors are worked out by hand. */
#include <math.h>

#include "../../tools/imgdiff/image_error.h"
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

int main(void)
{
    test_srgb8();
    test_known_numbers();
    test_shapes();
    return tap_done();
}
