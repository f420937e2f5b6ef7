/* test_image.c — images through OpenImageIO: EXR keeps floats exactly, PNG
 * stores 8-bit sRGB (so a round trip is exact up to that quantisation),
 * writes leave no temporary file behind, errors name the file. */

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image.h"
#include "tap.h"

static char folder[] = "/tmp/gibake-test-image-XXXXXX";

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

/* What a linear value becomes after an 8-bit sRGB file. */
static double through_srgb8(double linear)
{
    return srgb_to_linear(round(linear_to_srgb(linear) * 255) / 255);
}

/* An odd-sized test pattern: a ramp, a few values out of [0, 1]. */
static int make_pattern(gb_image *image, int channels)
{
    gb_error error;
    if (gb_image_allocate(image, 7, 5, channels, &error) != GB_OK)
        return 0;
    size_t n = (size_t)7 * 5 * (size_t)channels;
    for (size_t i = 0; i < n; ++i)
        image->pixels[i] = (float)((double)(i * 37 % 101) / 100.0);
    image->pixels[0] = 0.0f;
    image->pixels[1] = 1.0f;
    image->pixels[2] = 0.001f;
    return 1;
}

static int count_files(void)
{
    DIR *dir = opendir(folder);
    int count = 0;
    struct dirent *entry;
    while (dir && (entry = readdir(dir)))
        count += entry->d_name[0] != '.';
    if (dir)
        closedir(dir);
    return count;
}

static void test_exr(void)
{
    char path[256];
    snprintf(path, sizeof path, "%s/pattern.exr", folder);
    gb_image image, back = {0};
    gb_error error;
    if (!CHECK(make_pattern(&image, 3), "7 x 5 RGB image allocated"))
        return;
    image.pixels[3] = 12.5f;     /* HDR and negative values survive EXR */
    image.pixels[4] = -0.25f;
    image.pixels[5] = 1e-7f;
    CHECK(gb_image_write(path, &image, &error) == GB_OK, "EXR written");
    CHECK_EQ_INT(count_files(), 1, "EXR write leaves only the final file");
    if (CHECK(gb_image_read(path, &back, &error) == GB_OK, "EXR read back")) {
        CHECK(back.width == 7 && back.height == 5 && back.channels == 3, "EXR size 7 x 5 x 3");
        CHECK(memcmp(back.pixels, image.pixels, 7 * 5 * 3 * sizeof(float)) == 0,
              "EXR round trip is exact (float pixels, linear)");
    }
    gb_image_free(&back);
    gb_image_free(&image);
    unlink(path);
}

static void test_png(int channels)
{
    char path[256], what[128];
    snprintf(path, sizeof path, "%s/pattern%d.png", folder, channels);
    gb_image image, back = {0};
    gb_error error;
    if (!make_pattern(&image, channels))
        return;
    snprintf(what, sizeof what, "PNG with %d channels written", channels);
    CHECK(gb_image_write(path, &image, &error) == GB_OK, what);
    snprintf(what, sizeof what, "PNG with %d channels read back", channels);
    if (CHECK(gb_image_read(path, &back, &error) == GB_OK, what)) {
        CHECK(back.width == 7 && back.height == 5 && back.channels == channels,
              "PNG keeps its size and channels");
        double worst = 0, worst_alpha = 0;
        for (size_t i = 0; i < (size_t)7 * 5 * (size_t)channels; ++i) {
            int alpha = channels == 4 && i % 4 == 3;
            double expected = alpha ? round(image.pixels[i] * 255) / 255
                                    : through_srgb8(image.pixels[i]);
            double difference = fabs(back.pixels[i] - expected);
            if (alpha)
                worst_alpha = fmax(worst_alpha, difference);
            else
                worst = fmax(worst, difference);
        }
        CHECK_NEAR(worst, 0, 1e-6, "PNG colour = linear -> 8-bit sRGB -> linear");
        if (channels == 4)
            CHECK_NEAR(worst_alpha, 0, 1e-6, "PNG alpha stored linearly in 8 bits");
        CHECK(back.pixels[1] == 1.0f && back.pixels[0] == 0.0f, "0 and 1 survive exactly");
    }
    gb_image_free(&back);
    gb_image_free(&image);
    unlink(path);
}

static void test_errors(void)
{
    char path[256];
    gb_image image = {0};
    gb_error error;
    snprintf(path, sizeof path, "%s/absent.png", folder);
    CHECK(gb_image_read(path, &image, &error) != GB_OK && strstr(error.message, path) != NULL,
          "reading a missing image fails and names it");
    CHECK(image.pixels == NULL, "failed read leaves no pixels");
    make_pattern(&image, 3);
    snprintf(path, sizeof path, "%s/no/such/folder/x.exr", folder);
    CHECK(gb_image_write(path, &image, &error) != GB_OK && strstr(error.message, path) != NULL,
          "writing into a missing folder fails and names the file");
    snprintf(path, sizeof path, "%s/notes.unknown-type", folder);
    CHECK(gb_image_write(path, &image, &error) != GB_OK, "unknown image type refused");
    CHECK_EQ_INT(count_files(), 0, "failed writes leave nothing behind");
    gb_image_free(&image);
    CHECK(gb_image_allocate(&image, 0, 5, 3, &error) == GB_ERROR_ARGUMENT, "empty size refused");
}

int main(void)
{
    if (!mkdtemp(folder)) {
        printf("Bail out! cannot make a temporary folder\n");
        return 1;
    }
    test_exr();
    test_png(3);
    test_png(4);
    test_errors();
    rmdir(folder);
    return tap_done();
}
