/* scene_load.c — gb_scene_load (scene.h): a .scene file or a mesh read into
 * a gb_scene, through the reader of its kind (obj.h, mesh_openmesh.h,
 * scene_file.h), its textures and environment map through image.h, then
 * finished by gb_scene_finish (scene.c). */
#include "scene.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "environment.h"
#include "image.h"
#include "mesh_openmesh.h"
#include "obj.h"
#include "scene_file.h"
#include "text.h"

static gb_result read_openmesh(const char *path, gb_scene *scene, gb_error *error)
{
    uint32_t skipped;
    gb_result result = gb_openmesh_read(path, &scene->positions, &scene->vertex_count,
                                        &scene->indices, &scene->triangle_count, &skipped,
                                        error);
    if (result == GB_OK)
        scene->dropped_triangle_count += skipped;
    return result;     /* gb_scene_finish gives the mesh its default material */
}

static int is_openmesh_type(const char *path)
{
    return gb_path_has_suffix(path, ".ply") || gb_path_has_suffix(path, ".off")
        || gb_path_has_suffix(path, ".stl");
}

static int is_obj(const char *path)
{
    return gb_path_has_suffix(path, ".obj") || gb_path_has_suffix(path, ".obj.gz");
}

static gb_result load_mesh(const char *path, gb_scene *scene, gb_error *error)
{
    if (is_obj(path))
        return gb_obj_read(path, scene, error);
    if (is_openmesh_type(path))
        return read_openmesh(path, scene, error);
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: unknown file type (expected .scene, .obj, "
                   ".obj.gz, .ply, .off or .stl)", path);
}

/* Takes the lights, cameras and environment of the scene file;
 * environment_map is the map's resolved path (taken too), or NULL. */
static void take_scene_file_parts(gb_scene_file *file, char *environment_map, gb_scene *scene)
{
    scene->environment_map = environment_map;
    scene->lights = file->lights;
    scene->light_count = file->light_count;
    scene->cameras = file->cameras;
    scene->camera_count = file->camera_count;
    memcpy(scene->environment, file->environment, sizeof scene->environment);
    file->lights = NULL;
    file->cameras = NULL;
    file->light_count = file->camera_count = 0;
}

static gb_result check_file_exists(const char *scene_path, int line, const char *what,
                                   const char *path, gb_error *error)
{
    struct stat status;
    if (stat(path, &status) != 0)
        return gb_fail(error, GB_ERROR_IO, "%s:%d: %s %s: %s", scene_path, line, what, path,
                       strerror(errno));
    if (!S_ISREG(status.st_mode))
        return gb_fail(error, GB_ERROR_IO, "%s:%d: %s %s: not a file", scene_path, line, what,
                       path);
    return GB_OK;
}

static gb_result check_mesh_exists(const char *scene_path, const gb_scene_file *file,
                                   const char *mesh_path, gb_error *error)
{
    gb_result result = check_file_exists(scene_path, file->mesh_line, "mesh", mesh_path, error);
    if (result == GB_OK && !is_obj(mesh_path) && !is_openmesh_type(mesh_path))
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: mesh %s: unknown file type "
                       "(expected .obj, .obj.gz, .ply, .off or .stl)", scene_path,
                       file->mesh_line, mesh_path);
    return result;
}

/* The environment map's path beside the scene file, checked to exist;
 * *map_path stays NULL when the file names none. */
static gb_result find_environment_map(const char *scene_path, const char *folder,
                                      const gb_scene_file *file, char **map_path,
                                      gb_error *error)
{
    *map_path = NULL;
    if (!file->environment_map)
        return GB_OK;
    if (!(*map_path = gb_path_join(folder, file->environment_map)))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", scene_path);
    return check_file_exists(scene_path, file->environment_map_line, "environment-map",
                             *map_path, error);
}

/* Loads the mesh a scene file names, with its lights, cameras and
 * environment; *mesh_path is the path of the mesh (malloc'ed). */
static gb_result load_scene_file(const char *path, gb_scene *scene, char **mesh_path,
                                 gb_error *error)
{
    gb_scene_file file;
    gb_result result = gb_scene_file_read(path, &file, error);
    char *folder = NULL, *map_path = NULL;
    if (result == GB_OK && (!(folder = gb_path_folder(path))
                            || !(*mesh_path = gb_path_join(folder, file.mesh))))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (result == GB_OK)
        result = check_mesh_exists(path, &file, *mesh_path, error);
    if (result == GB_OK)
        result = find_environment_map(path, folder, &file, &map_path, error);
    if (result == GB_OK)
        result = gb_scene_add_input(scene, *mesh_path, error);
    if (result == GB_OK)
        result = load_mesh(*mesh_path, scene, error);
    if (result == GB_OK)
        take_scene_file_parts(&file, map_path, scene);
    else
        free(map_path);
    free(folder);
    gb_scene_file_free(&file);
    return result;
}

/* ---- textures ------------------------------------------------------------- */

/* Keeps the first three channels (grey repeated) of an image as RGB. */
static gb_result image_to_texture(const gb_image *image, gb_texture *texture,
                                  const char *path, gb_error *error)
{
    size_t pixels = (size_t)image->width * (size_t)image->height;
    texture->rgb = malloc(pixels * 3 * sizeof(float) + 1);
    if (!texture->rgb)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    int grey = image->channels < 3;
    for (size_t i = 0; i < pixels; ++i)
        for (int k = 0; k < 3; ++k)
            texture->rgb[3 * i + k] = image->pixels[i * (size_t)image->channels + (grey ? 0 : k)];
    texture->width = image->width;
    texture->height = image->height;
    return GB_OK;
}

static gb_result load_image(gb_scene *scene, const char *path, gb_texture *texture,
                            gb_error *error)
{
    gb_image image = {0};
    gb_result result = gb_scene_add_input(scene, path, error);
    if (result == GB_OK)
        result = gb_image_read(path, &image, error);
    if (result == GB_OK)
        result = image_to_texture(&image, texture, path, error);
    gb_image_free(&image);
    return result;
}

static gb_result load_environment_map(gb_scene *scene, gb_error *error)
{
    if (!scene->environment_map || scene->environment_texture.rgb)
        return GB_OK;
    gb_result result = load_image(scene, scene->environment_map, &scene->environment_texture,
                                  error);
    if (result == GB_OK)
        result = gb_environment_map_check(&scene->environment_texture, scene->environment_map,
                                          error);
    return result;
}

static gb_result load_textures(gb_scene *scene, gb_error *error)
{
    for (uint32_t i = 0; i < scene->material_count; ++i) {
        gb_material *material = &scene->materials[i];
        if (!material->map_Kd || material->texture.rgb)
            continue;
        gb_result result = load_image(scene, material->map_Kd, &material->texture, error);
        if (result != GB_OK)
            return result;
    }
    return load_environment_map(scene, error);
}

/* Reads the scene or mesh at path; *mesh_path is the mesh read (malloc'ed). */
static gb_result load_parts(const char *path, gb_scene *scene, char **mesh_path,
                            gb_error *error)
{
    gb_result result = gb_scene_add_input(scene, path, error);
    if (result != GB_OK)
        return result;
    if (gb_path_has_suffix(path, ".scene"))
        return load_scene_file(path, scene, mesh_path, error);
    if (!(*mesh_path = strdup(path)))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    return load_mesh(path, scene, error);
}

gb_result gb_scene_load(const char *path, const gb_scene_options *options,
                        gb_scene *scene, gb_error *error)
{
    memset(scene, 0, sizeof *scene);
    char *mesh_path = NULL;
    gb_result result = load_parts(path, scene, &mesh_path, error);
    free(scene->path);
    scene->path = mesh_path;    /* so that the messages of finish name the mesh */
    if (result == GB_OK)
        result = gb_scene_finish(scene, error);
    if (result == GB_OK && strcmp(path, mesh_path) != 0) {
        free(scene->path);
        if (!(scene->path = strdup(path)))
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    if (result == GB_OK && options && options->load_textures)
        result = load_textures(scene, error);
    if (result != GB_OK)
        gb_scene_free(scene);
    return result;
}
