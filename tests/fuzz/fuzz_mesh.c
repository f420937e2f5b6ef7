/* fuzz_mesh.c — libFuzzer target for the PLY, OFF and STL readers (the
 * OpenMesh adapter, formats/mesh_openmesh.cpp, through gb_scene_load as the
 * tools call it): any input gives either a scene whose indices, materials
 * and areas hold, or an error "path: ...", never a crash, a leak or a read
 * out of bounds (run under ASan/UBSan by `make fuzz`).
 *
 * OpenMesh chooses its reader by the file name, so the input is written to
 * a file of a private temporary folder (made and removed for each input:
 * libFuzzer ends with _Exit, no atexit handler runs) named after what it
 * looks like:
 * "fuzz.ply" when it starts with "ply", "fuzz.off" when its first word ends
 * with "OFF" (OFF, COFF, NOFF, STOFF, ...), else "fuzz.stl" (ASCII or
 * binary). Seeds: tests/fuzz/corpus/fuzz_mesh, ASCII and binary of each.
 */
#include <ctype.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_reader.h"
#include "scene.h"

static const char *kind_of(const uint8_t *data, size_t size)
{
    if (size >= 3 && memcmp(data, "ply", 3) == 0)
        return "ply";
    size_t begin = 0, end;
    while (begin < size && isspace(data[begin]))
        ++begin;
    for (end = begin; end < size && !isspace(data[end]) && data[end] != '#'; ++end)
        ;
    if (end - begin >= 3 && memcmp(data + end - 3, "OFF", 3) == 0)
        return "off";
    return "stl";
}

static void check_scene(const gb_scene *scene)
{
    gb_fuzz_check_triangles(scene, 1);
    if (scene->material_count != 1 || scene->camera_count != 1)
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char folder[] = "/tmp/fuzz_mesh.XXXXXX", path[128];
    if (!mkdtemp(folder))
        abort();
    snprintf(path, sizeof path, "%s/fuzz.%s", folder, kind_of(data, size));
    FILE *file = fopen(path, "wb");
    if (!file || fwrite(data, 1, size, file) != size || fclose(file) != 0)
        abort();
    gb_scene scene;
    gb_error error;
    error.message[0] = '\0';
    if (gb_scene_load(path, NULL, &scene, &error) == GB_OK) {
        check_scene(&scene);
        gb_scene_free(&scene);
    } else if (!gb_fuzz_names(&error, path)) {
        __builtin_trap(); /* every failure names the file */
    }
    unlink(path);
    rmdir(folder);
    return 0;
}
