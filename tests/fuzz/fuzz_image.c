/* fuzz_image.c — libFuzzer target for image reading through the
 * OpenImageIO adapter (formats/image_openimageio.cpp) as gibake's readers
 * use it: imgdiff's inputs and mask (gb_image_read, then
 * gb_image_error_compute and gb_image_error_heatmap with the image as its
 * own reference and mask), a material's map_Kd texture and a scene's
 * environment-map (gb_scene_load with textures, which checks the map). Any
 * input gives either pixels or an error "path: ...", never a crash, a leak,
 * a hang or a read out of bounds (run under ASan/UBSan by `make fuzz`;
 * OpenImageIO and its format libraries are not instrumented, so ASan sees
 * only what their calls into the allocator and libc show).
 *
 * The input is written as "image" in a private temporary folder (made and
 * removed for each input: libFuzzer ends with _Exit, no atexit handler
 * runs), beside a one-quad OBJ whose material has map_Kd image and a scene
 * file naming the OBJ and environment-map image. Seeds:
 * tests/fuzz/corpus/fuzz_image (tiny PNG, EXR, HDR, TGA, JPEG, PPM and PGM
 * written through OpenImageIO, an ASCII PPM as the CLI tests write one).
 */
#include <math.h>
#include <sanitizer/common_interface_defs.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_error.h"
#include "image.h"
#include "scene.h"

static const char *const names[] = {"image", "quad.obj", "quad.mtl", "textured.scene"};
static volatile double sink;

static void path_in_folder(const char *folder, const char *name, char *path, size_t size)
{
    snprintf(path, size, "%s/%s", folder, name);
}

static void remove_folder(const char *folder)
{
    char path[128];
    for (int i = 0; i < 4; ++i) {
        path_in_folder(folder, names[i], path, sizeof path);
        unlink(path);
    }
    rmdir(folder);
}

static void write_file(const char *folder, const char *name, const void *data, size_t size)
{
    char path[128];
    path_in_folder(folder, name, path, sizeof path);
    FILE *file = fopen(path, "wb");
    if (!file || fwrite(data, 1, size, file) != size || fclose(file) != 0)
        abort();
}

static void make_folder(char *folder)
{
    static const char obj[] = "mtllib quad.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                              "v 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
    static const char mtl[] = "newmtl tex\nKd 1 1 1\nmap_Kd image\n";
    static const char scene[] = "gibake-scene 1\nmesh quad.obj\nenvironment-map image\n";
    if (!mkdtemp(folder))
        abort();
    write_file(folder, names[1], obj, sizeof obj - 1);
    write_file(folder, names[2], mtl, sizeof mtl - 1);
    write_file(folder, names[3], scene, sizeof scene - 1);
}

static void check_failure(const char *path, const gb_error *error)
{
    size_t n = strlen(path);
    if (strncmp(error->message, path, n) != 0 || error->message[n] != ':')
        __builtin_trap(); /* every failure names the file */
}

/* imgdiff: the image against itself, masked by itself. */
static void as_imgdiff_input(const char *path)
{
    gb_image image;
    gb_error error;
    if (gb_image_read(path, &image, &error) != GB_OK) {
        check_failure(path, &error);
        if (image.pixels || image.width || image.height || image.channels)
            __builtin_trap(); /* a failed read leaves an empty image */
        return;
    }
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 || !image.pixels)
        __builtin_trap();
    double sum = 0;
    for (size_t i = 0, n = (size_t)image.width * image.height * image.channels; i < n; ++i)
        sum += image.pixels[i];
    gb_image_error measures;
    if (gb_image_error_compute(&image, &image, &image, &measures, &error) == GB_OK)
        sum += measures.rmse;
    gb_image heatmap;
    if (gb_image_error_heatmap(&image, &image, &image, 0, &heatmap, &error) == GB_OK) {
        sum += heatmap.pixels[0];
        gb_image_free(&heatmap);
    }
    sink += sum;
    gb_image_free(&image);
}

/* A texture and an environment map of a scene loaded with its textures. */
static void as_texture_and_environment(const char *folder)
{
    char path[128];
    path_in_folder(folder, names[3], path, sizeof path);
    gb_scene_options options = {.load_textures = 1};
    gb_scene scene;
    gb_error error;
    error.message[0] = '\0';
    if (gb_scene_load(path, &options, &scene, &error) != GB_OK) {
        if (!strstr(error.message, "/image: "))
            __builtin_trap(); /* only the image can be wrong, and the message names it */
        return;
    }
    const gb_texture *maps[2] = {&scene.materials[0].texture, &scene.environment_texture};
    for (int m = 0; m < 2; ++m) {
        if (maps[m]->width <= 0 || maps[m]->height <= 0 || !maps[m]->rgb)
            __builtin_trap();
        size_t last = 3 * ((size_t)maps[m]->width * maps[m]->height - 1);
        sink += maps[m]->rgb[0] + maps[m]->rgb[last + 2];
    }
    for (size_t i = 0; i < 3 * (size_t)scene.environment_texture.width
                               * scene.environment_texture.height; ++i)
        if (!isfinite(scene.environment_texture.rgb[i]) || scene.environment_texture.rgb[i] < 0)
            __builtin_trap(); /* gb_environment_map_check refuses these */
    gb_scene_free(&scene);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int reports_redirected;
    if (!reports_redirected) {
        /* The adapter points descriptor 2 elsewhere while libpng may print:
         * sanitizer reports go to a copy of the real stderr. */
        __sanitizer_set_report_fd((void *)(intptr_t)dup(2));
        reports_redirected = 1;
    }
    char folder[] = "/tmp/fuzz_image.XXXXXX", path[128];
    make_folder(folder);
    write_file(folder, names[0], data, size);
    path_in_folder(folder, names[0], path, sizeof path);
    as_imgdiff_input(path);
    as_texture_and_environment(folder);
    remove_folder(folder);
    return 0;
}
