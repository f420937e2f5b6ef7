/* fuzz_scene_file.c — libFuzzer target for the `.scene` parser: any input
 * must give either a parsed scene file or an error message, never a crash,
 * a leak or a read out of bounds (run under ASan/UBSan by `make fuzz`).
 * A parsed file is checked against what the parser promises.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "scene_file.h"

static int is_unit(const float v[3])
{
    double length = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    return fabs(length - 1) < 1e-5;
}

static void check_file(const gb_scene_file *file)
{
    if (!file->mesh || file->mesh_line < 1)
        __builtin_trap();
    for (uint32_t i = 0; i < file->light_count; ++i) {
        const gb_light *light = &file->lights[i];
        if (light->type != GB_LIGHT_POINT && !is_unit(light->direction))
            __builtin_trap();
    }
    for (uint32_t i = 0; i < file->camera_count; ++i) {
        const gb_camera *camera = &file->cameras[i];
        if (camera->width < 1 || camera->height < 1 || !is_unit(camera->up)
            || !(camera->fov_y > 0 && camera->fov_y < 180))
            __builtin_trap();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_scene_file file;
    gb_error error;
    error.message[0] = '\0';
    if (gb_scene_file_parse((const char *)data, size, "fuzz.scene", &file, &error) == GB_OK)
        check_file(&file);
    else if (error.message[0] == '\0')
        __builtin_trap();   /* every failure says why */
    gb_scene_file_free(&file);
    return 0;
}
