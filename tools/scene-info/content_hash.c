#include "content_hash.h"

#include <stdio.h>
#include <string.h>

#include "little_endian.h"
#include "mapped_file.h"
#include "output_file.h"

static uint64_t fnv1a(uint64_t hash, const void *bytes, size_t size)
{
    const unsigned char *b = bytes;
    for (size_t i = 0; i < size; ++i)
        hash = (hash ^ b[i]) * 0x100000001b3ull;
    return hash;
}

/* Hashes the length and bytes of the file at path; path joins the inputs. */
static gb_result hash_file(gb_scene *scene, const char *path, uint64_t *hash, gb_error *error)
{
    gb_mapped_file file;
    gb_result result = gb_mapped_file_open(path, &file, error);
    if (result != GB_OK)
        return result;
    unsigned char size[8];
    gb_put_u64(size, file.size);
    *hash = fnv1a(*hash, size, sizeof size);
    *hash = fnv1a(*hash, file.bytes, file.size);
    gb_mapped_file_close(&file);
    return gb_scene_add_input(scene, path, error);
}

gb_result gb_scene_images_hash(gb_scene *scene, uint64_t *hash, gb_error *error)
{
    *hash = 0xcbf29ce484222325ull;
    gb_result result = GB_OK;
    for (uint32_t i = 0; result == GB_OK && i < scene->material_count; ++i)
        if (scene->materials[i].map_Kd)
            result = hash_file(scene, scene->materials[i].map_Kd, hash, error);
    if (result == GB_OK && scene->environment_map)
        result = hash_file(scene, scene->environment_map, hash, error);
    return result;
}

gb_result gb_content_hash_write(const char *path, gb_scene *scene, gb_error *error)
{
    uint64_t images;
    gb_result result = gb_scene_images_hash(scene, &images, error);
    if (result != GB_OK)
        return result;
    char text[96];
    int length = snprintf(text, sizeof text, "scene_hash %016llx\nimages_hash %016llx\n",
                          (unsigned long long)scene->hash, (unsigned long long)images);
    return gb_output_file_write_bytes(path, text, (size_t)length, error);
}
