/* fuzz_obj.c — libFuzzer target for the OBJ and MTL readers: any input must
 * give either a scene or an error message, never a crash, a leak or a read
 * out of bounds (run under ASan/UBSan by `make fuzz`).
 *
 * The input is OBJ text; if it holds a line "%%MTL", what follows that line
 * is the MTL text every mtllib statement reads. A parsed scene then goes
 * through gb_scene_finish, and its results are checked for consistency.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_reader.h"
#include "obj.h"
#include "scene.h"

static const char mtl_marker[] = "\n%%MTL\n";

typedef struct mtl_text {
    const char *text;
    size_t size;
} mtl_text;

static gb_result read_mtl(void *user, const char *mtllib, const char *obj_name, int obj_line,
                          gb_material_list *materials, gb_error *error)
{
    (void)obj_name;
    (void)obj_line;
    const mtl_text *mtl = user;
    return gb_mtl_parse(mtl->text, mtl->size, mtllib, NULL, materials, error);
}

static void check_scene(const gb_scene *scene)
{
    gb_fuzz_check_triangles(scene, 1);
    for (uint32_t i = 0; i < scene->emissive_count; ++i)
        if (scene->emissive_triangles[i] >= scene->triangle_count)
            __builtin_trap();
    if (scene->camera_count != 1)
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    size_t obj_size = size;
    mtl_text mtl = {"", 0};
    const char *marker = memmem(text, size, mtl_marker, sizeof mtl_marker - 1);
    if (marker) {
        obj_size = (size_t)(marker - text);
        mtl.text = marker + sizeof mtl_marker - 1;
        mtl.size = size - obj_size - (sizeof mtl_marker - 1);
    }
    gb_scene scene = {0};
    gb_error error;
    error.message[0] = '\0';
    if (gb_obj_parse(text, obj_size, "fuzz.obj", read_mtl, &mtl, &scene, &error) == GB_OK
        && gb_scene_finish(&scene, &error) == GB_OK)
        check_scene(&scene);
    else if (error.message[0] == '\0')
        __builtin_trap();   /* every failure says why */
    gb_scene_free(&scene);
    return 0;
}
