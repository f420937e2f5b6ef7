/* test_reader_guards.c — the checks the image and OpenVDB adapters run on a
 * file's bytes before handing them to OpenImageIO or OpenVDB
 * (formats/image_check.h, formats/voxel_check.h): what each refuses, with
 * its message, and that files the project writes pass. The fuzz corpora
 * (tests/fuzz/corpus/fuzz_image, fuzz_voxel_grid) keep the inputs that made
 * the libraries crash, leak or over-allocate. */
#include "image.h"
#include "image_check.h"
#include "scratch.h"
#include "tap.h"
#include "voxel_check.h"
#include "voxel_grid.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

static int fails_with(gb_result got, gb_result expected, const gb_error *error,
                      const char *part)
{
    if (got == expected && strstr(error->message, part))
        return 1;
    printf("#   got %s: %s\n", gb_result_name(got), got ? error->message : "");
    return 0;
}

static void put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8), p[3] = (unsigned char)v;
}

static void test_images(void)
{
    const char *path;
    gb_image image;
    gb_error error;
    if (gb_image_allocate(&image, 8, 8, 3, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    path = scratch_path("small.png");
    if (gb_image_write(path, &image, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    gb_image_free(&image);
    size_t size = 0;
    unsigned char *png = scratch_read(path, &size);
    gb_image_file file;
    CHECK(png && gb_image_check(png, size, "a.png", &file, &error) == GB_OK &&
              !strcmp(file.format, "png"), "a PNG the project writes passes, as png");
    CHECK(fails_with(gb_image_check(png, size - 12, "a.png", &file, &error), GB_ERROR_FORMAT,
                     &error, "a.png: truncated PNG"),
          "a PNG cut before IEND is refused (OpenImageIO leaked on it)");
    /* IHDR says 60000 x 60000: the file cannot hold it */
    put_be32(png + 16, 60000);
    put_be32(png + 20, 60000);
    put_be32(png + 29, (uint32_t)crc32(crc32(0, Z_NULL, 0), png + 12, 17));
    path = scratch_path("huge.png");
    scratch_write(path, png, size);
    char message[600];
    snprintf(message, sizeof message, "%s: 60000 x 60000 pixels x 3 channels: more than", path);
    CHECK(fails_with(gb_image_read(path, &image, &error), GB_ERROR_FORMAT, &error, message),
          "a PNG header declaring 60000 x 60000 pixels in a small file is refused");
    free(png);

    static const unsigned char psd[] = "8BPS\0\1\0\0\0\0\0\0\0\3";
    CHECK(fails_with(gb_image_check(psd, sizeof psd, "a.psd", &file, &error),
                     GB_ERROR_UNSUPPORTED, &error, "not an image gibake reads"),
          "a format gibake does not read (PSD) is refused before OpenImageIO");
    /* OpenEXR: magic, version 2, an attribute "capDate" of type string
     * claiming 1.8 GB (OpenEXR allocated it) */
    static const unsigned char exr[] = "\x76\x2f\x31\x01\x02\0\0\0capDate\0string\0"
                                       "\x13\x80\x00\x6a" "abc";
    CHECK(fails_with(gb_image_check(exr, sizeof exr - 1, "a.exr", &file, &error),
                     GB_ERROR_FORMAT, &error, "attribute 'capDate': 1778417683 bytes, beyond"),
          "an OpenEXR attribute larger than the file is refused");
}

static void test_voxel_files(void)
{
    const char *path;
    gb_voxel_grid frame = {.size = {4, 3, 2}, .voxel_size = 0.5, .scene_hash = 0x1234,
                           .resolution = 4};
    int32_t values[24];
    for (int i = 0; i < 24; ++i)
        values[i] = i % 5 - 1;
    gb_error error;
    path = scratch_path("grid.vdb");
    if (gb_voxel_grid_write_int32(path, &frame, "nearest_node", values, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    size_t size = 0;
    unsigned char *vdb = scratch_read(path, &size);
    if (!vdb) {
        printf("Bail out! cannot read %s\n", path);
        exit(1);
    }
    CHECK(gb_voxel_file_check(vdb, size, "g.vdb", &error) == GB_OK,
          "an int32 grid the project writes passes the walk");
    CHECK(fails_with(gb_voxel_file_check(vdb, size - 100, "g.vdb", &error), GB_ERROR_FORMAT,
                     &error, "g.vdb: grid 'nearest_node': the file ends inside"),
          "a truncated file: where it ends, and in which grid");
    unsigned char saved = vdb[8];
    vdb[8] = 223;
    CHECK(fails_with(gb_voxel_file_check(vdb, size, "g.vdb", &error), GB_ERROR_UNSUPPORTED,
                     &error, "OpenVDB file format 223 (gibake reads 224)"),
          "another OpenVDB file format is refused");
    vdb[8] = saved;
    /* the first metadata entry's value size, after "creator" / "string" */
    unsigned char *creator = memmem(vdb, size, "\x07\0\0\0creator\x06\0\0\0string", 21);
    if (CHECK(creator != NULL, "the grid's creator metadata is found")) {
        unsigned char *length = creator + 21;
        uint32_t old = (uint32_t)length[0] | (uint32_t)length[1] << 8;
        length[0] = 0xff, length[1] = 0xff, length[2] = 0xff, length[3] = 0x7f;
        CHECK(fails_with(gb_voxel_file_check(vdb, size, "g.vdb", &error), GB_ERROR_FORMAT,
                         &error, "the file ends inside the grid's metadata"),
              "a metadata string longer than the file is refused (OpenVDB allocated it)");
        length[0] = (unsigned char)old, length[1] = (unsigned char)(old >> 8);
        length[2] = length[3] = 0;
    }
    CHECK(gb_voxel_file_check(vdb, size, "g.vdb", &error) == GB_OK, "restored, it passes again");
    free(vdb);
}

int main(void)
{
    scratch_create("reader-guards");
    test_images();
    test_voxel_files();
    scratch_remove();
    return tap_done();
}
