#include "bake_files.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "light_octree.h"
#include "segmentation.h"
#include "skeleton.h"
#include "voxel_grid.h"

const char *gb_bake_extension(gb_bake_kind kind)
{
    static const char *const extensions[GB_BAKE_KIND_COUNT] = {
        ".vdb", ".skel", ".grid.vdb", ".seg", ".lot",
    };
    return kind >= 0 && kind < GB_BAKE_KIND_COUNT ? extensions[kind] : "";
}

/* "scenes/cornell/cornell.scene" -> "cornell" */
static void scene_name(const char *scene_path, char *name, size_t size)
{
    const char *base = strrchr(scene_path, '/');
    base = base ? base + 1 : scene_path;
    snprintf(name, size, "%s", base);
    char *dot = strrchr(name, '.');
    if (dot && dot != name)
        *dot = '\0';
}

static gb_result check_hash(const char *path, uint64_t file_hash, const gb_scene *scene,
                            gb_error *error)
{
    if (file_hash == scene->hash)
        return GB_OK;
    return gb_fail(error, GB_ERROR_STALE,
                   "%s: stale: made from another scene (hash %016" PRIx64 ", the scene's %016"
                   PRIx64 "); bake it again", path, file_hash, scene->hash);
}

static gb_result check_voxels(const char *path, const gb_scene *scene, gb_error *error)
{
    gb_voxel_grid grid;
    memset(&grid, 0, sizeof grid);
    gb_result result = gb_voxel_grid_read(path, &grid, error);
    if (result == GB_OK)
        result = check_hash(path, grid.scene_hash, scene, error);
    gb_voxel_grid_free(&grid);
    return result;
}

static gb_result check_skeleton(const char *path, const gb_scene *scene, gb_error *error)
{
    gb_skeleton skeleton;
    memset(&skeleton, 0, sizeof skeleton);
    gb_result result = gb_skeleton_read(path, &skeleton, error);
    if (result == GB_OK)
        result = check_hash(path, skeleton.scene_hash, scene, error);
    gb_skeleton_free(&skeleton);
    return result;
}

static gb_result check_nearest_node(const char *path, const gb_scene *scene, gb_error *error)
{
    gb_voxel_grid frame;
    memset(&frame, 0, sizeof frame);
    int32_t *values = NULL;
    gb_result result = gb_voxel_grid_read_int32(path, "nearest_node", &frame, &values, error);
    if (result == GB_OK)
        result = check_hash(path, frame.scene_hash, scene, error);
    free(values);
    gb_voxel_grid_free(&frame);
    return result;
}

static gb_result check_segments(const char *path, const gb_scene *scene, gb_error *error)
{
    gb_segmentation segmentation;
    memset(&segmentation, 0, sizeof segmentation);
    gb_result result = gb_segmentation_read(path, &segmentation, error);
    if (result == GB_OK)
        result = check_hash(path, segmentation.scene_hash, scene, error);
    gb_segmentation_free(&segmentation);
    return result;
}

static gb_result check_light_octree(const char *path, const gb_scene *scene, gb_error *error)
{
    gb_light_octree octree;
    memset(&octree, 0, sizeof octree);
    gb_result result = gb_light_octree_read(path, &octree, error);
    if (result == GB_OK)
        result = check_hash(path, octree.header.scene_hash, scene, error);
    gb_light_octree_free(&octree);
    return result;
}

static gb_result check_file(gb_bake_kind kind, const char *path, const gb_scene *scene,
                            gb_error *error)
{
    struct stat status;
    if (stat(path, &status) != 0)
        return gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno));
    switch (kind) {
    case GB_BAKE_VOXELS: return check_voxels(path, scene, error);
    case GB_BAKE_SKELETON: return check_skeleton(path, scene, error);
    case GB_BAKE_NEAREST_NODE: return check_nearest_node(path, scene, error);
    case GB_BAKE_SEGMENTS: return check_segments(path, scene, error);
    case GB_BAKE_LIGHT_OCTREE: return check_light_octree(path, scene, error);
    case GB_BAKE_KIND_COUNT: break;
    }
    return gb_fail(error, GB_ERROR_ARGUMENT, "%s: unknown kind of baked file", path);
}

gb_result gb_bake_files_check(const gb_scene *scene, const char *scene_path,
                              const char *folder, gb_bake_files *files, gb_error *error)
{
    memset(files, 0, sizeof *files);
    char name[256];
    scene_name(scene_path, name, sizeof name);
    for (int kind = 0; kind < GB_BAKE_KIND_COUNT; ++kind) {
        char *path = files->paths[kind];
        int n = snprintf(path, sizeof files->paths[kind], "%s/%s%s", folder, name,
                         gb_bake_extension((gb_bake_kind)kind));
        if (n < 0 || (size_t)n >= sizeof files->paths[kind])
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: bake folder path too long", folder);
        gb_result result = check_file((gb_bake_kind)kind, path, scene, &files->problems[kind]);
        files->usable[kind] = result == GB_OK;
        files->has_problem[kind] = result != GB_OK;
    }
    return GB_OK;
}
