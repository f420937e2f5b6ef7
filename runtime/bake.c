#include "bake.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Where each file stands: not asked for yet, decoded, or refused. */
typedef enum file_state { UNREAD, USABLE, REFUSED } file_state;

struct gb_bake {
    char paths[GB_BAKE_KIND_COUNT][1024];
    uint64_t scene_hash;
    file_state state[GB_BAKE_KIND_COUNT];
    gb_error problems[GB_BAKE_KIND_COUNT];  /* "path: what is wrong" */
    gb_voxel_grid voxels;
    gb_skeleton skeleton;
    gb_voxel_grid nearest_frame;
    int32_t *nearest;
    gb_segmentation segmentation;
    gb_light_octree light_octree;
    gb_atlas atlas;
};

const char *gb_bake_extension(gb_bake_kind kind)
{
    static const char *const extensions[GB_BAKE_KIND_COUNT] = {
        ".vdb", ".skel", ".grid.vdb", ".seg", ".lot", ".atlas",
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

/* Decodes the file of kind into the handle and gives the scene hash it
 * records. */
static gb_result decode(gb_bake *b, gb_bake_kind kind, uint64_t *hash, gb_error *error)
{
    const char *path = b->paths[kind];
    gb_result result = GB_ERROR_ARGUMENT;
    switch (kind) {
    case GB_BAKE_VOXELS:
        result = gb_voxel_grid_read(path, &b->voxels, error);
        *hash = b->voxels.scene_hash;
        break;
    case GB_BAKE_SKELETON:
        result = gb_skeleton_read(path, &b->skeleton, error);
        *hash = b->skeleton.scene_hash;
        break;
    case GB_BAKE_NEAREST_NODE:
        result = gb_voxel_grid_read_int32(path, "nearest_node", &b->nearest_frame, &b->nearest,
                                          error);
        *hash = b->nearest_frame.scene_hash;
        break;
    case GB_BAKE_SEGMENTS:
        result = gb_segmentation_read(path, &b->segmentation, error);
        *hash = b->segmentation.scene_hash;
        break;
    case GB_BAKE_LIGHT_OCTREE:
        result = gb_light_octree_read(path, &b->light_octree, error);
        *hash = b->light_octree.header.scene_hash;
        break;
    case GB_BAKE_ATLAS:
        result = gb_atlas_read(path, &b->atlas, error);
        *hash = b->atlas.header.scene_hash;
        break;
    case GB_BAKE_KIND_COUNT:
        break;
    }
    return result;
}

/* Frees what decode left of kind (also after a failed decode). */
static void forget(gb_bake *b, gb_bake_kind kind)
{
    switch (kind) {
    case GB_BAKE_VOXELS: gb_voxel_grid_free(&b->voxels); break;
    case GB_BAKE_SKELETON: gb_skeleton_free(&b->skeleton); break;
    case GB_BAKE_NEAREST_NODE:
        free(b->nearest);
        b->nearest = NULL;
        gb_voxel_grid_free(&b->nearest_frame);
        break;
    case GB_BAKE_SEGMENTS: gb_segmentation_free(&b->segmentation); break;
    case GB_BAKE_LIGHT_OCTREE: gb_light_octree_free(&b->light_octree); break;
    case GB_BAKE_ATLAS: gb_atlas_free(&b->atlas); break;
    case GB_BAKE_KIND_COUNT: break;
    }
}

/* The one check of every file: it exists, its reader accepts it, it was
 * made from this scene. Keeps the decoded file when it passes. */
static gb_result load(gb_bake *b, gb_bake_kind kind, gb_error *error)
{
    const char *path = b->paths[kind];
    struct stat status;
    if (stat(path, &status) != 0)
        return gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno));
    uint64_t hash = 0;
    gb_result result = decode(b, kind, &hash, error);
    if (result == GB_OK && hash != b->scene_hash)
        result = gb_fail(error, GB_ERROR_STALE,
                         "%s: stale: made from another scene (hash %016" PRIx64
                         ", the scene's %016" PRIx64 "); bake it again",
                         path, hash, b->scene_hash);
    if (result != GB_OK)
        forget(b, kind);
    return result;
}

/* The file of kind, decoded the first time it is asked for; whether it is
 * usable. The handle is const to its borrowers: this is the one place that
 * changes it. */
static int usable(const gb_bake *bake, gb_bake_kind kind)
{
    gb_bake *b = (gb_bake *)bake;
    if (b->state[kind] == UNREAD)
        b->state[kind] = load(b, kind, &b->problems[kind]) == GB_OK ? USABLE : REFUSED;
    return b->state[kind] == USABLE;
}

gb_result gb_bake_open(const gb_scene *scene, const char *scene_path, const char *folder,
                       gb_bake **bake, gb_error *error)
{
    *bake = NULL;
    gb_bake *b = calloc(1, sizeof *b);
    if (!b)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "bake: out of memory");
    char name[256];
    scene_name(scene_path, name, sizeof name);
    for (int kind = 0; kind < GB_BAKE_KIND_COUNT; ++kind) {
        int n = snprintf(b->paths[kind], sizeof b->paths[kind], "%s/%s%s", folder, name,
                         gb_bake_extension((gb_bake_kind)kind));
        if (n < 0 || (size_t)n >= sizeof b->paths[kind]) {
            gb_bake_release(b);
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: bake folder path too long", folder);
        }
    }
    b->scene_hash = scene->hash;
    *bake = b;
    return GB_OK;
}

void gb_bake_release(gb_bake *bake)
{
    if (!bake)
        return;
    for (int kind = 0; kind < GB_BAKE_KIND_COUNT; ++kind)
        forget(bake, (gb_bake_kind)kind);
    free(bake);
}

const char *gb_bake_path(const gb_bake *bake, gb_bake_kind kind)
{
    return kind >= 0 && kind < GB_BAKE_KIND_COUNT ? bake->paths[kind] : "";
}

const char *gb_bake_problem(const gb_bake *bake, gb_bake_kind kind)
{
    if (kind < 0 || kind >= GB_BAKE_KIND_COUNT)
        return "unknown kind of baked file";
    return usable(bake, kind) ? NULL : bake->problems[kind].message;
}

const gb_voxel_grid *gb_bake_voxels(const gb_bake *bake)
{
    return usable(bake, GB_BAKE_VOXELS) ? &bake->voxels : NULL;
}

const gb_skeleton *gb_bake_skeleton(const gb_bake *bake)
{
    return usable(bake, GB_BAKE_SKELETON) ? &bake->skeleton : NULL;
}

const gb_segmentation *gb_bake_segmentation(const gb_bake *bake)
{
    return usable(bake, GB_BAKE_SEGMENTS) ? &bake->segmentation : NULL;
}

const gb_light_octree *gb_bake_light_octree(const gb_bake *bake)
{
    return usable(bake, GB_BAKE_LIGHT_OCTREE) ? &bake->light_octree : NULL;
}

const gb_atlas *gb_bake_atlas(const gb_bake *bake)
{
    return usable(bake, GB_BAKE_ATLAS) ? &bake->atlas : NULL;
}

const int32_t *gb_bake_nearest_node(const gb_bake *bake, const gb_voxel_grid **frame)
{
    int ok = usable(bake, GB_BAKE_NEAREST_NODE);
    *frame = ok ? &bake->nearest_frame : NULL;
    return ok ? bake->nearest : NULL;
}
