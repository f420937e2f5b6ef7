/* bake_files.h — the baked files the runtime may use, found in a bake
 * folder (gbview --bake DIR) by the scene's name, as `make bake` names them:
 *   NAME.vdb       voxels (voxelize)            NAME.skel  skeleton (thin)
 *   NAME.grid.vdb  nearest skeleton node (thin) NAME.seg   clusters, gates (segment)
 *   NAME.lot       light octree (cluster)
 * NAME is the scene file's name without its folder and extension.
 *
 * gb_bake_files_check opens each file with its reader and checks it was
 * made from this scene (the scene hash); a file that is missing, corrupt or
 * stale gets one message in problems[] and is left out (usable[] 0). It
 * never fails on a file: the runtime goes on with the methods it can still
 * run.
 */
#ifndef GB_BAKE_FILES_H
#define GB_BAKE_FILES_H

#include "result.h"
#include "scene.h"

typedef enum gb_bake_kind {
    GB_BAKE_VOXELS,
    GB_BAKE_SKELETON,
    GB_BAKE_NEAREST_NODE,
    GB_BAKE_SEGMENTS,
    GB_BAKE_LIGHT_OCTREE,
    GB_BAKE_KIND_COUNT,
} gb_bake_kind;

typedef struct gb_bake_files {
    char paths[GB_BAKE_KIND_COUNT][1024];
    int usable[GB_BAKE_KIND_COUNT];
    int has_problem[GB_BAKE_KIND_COUNT];
    gb_error problems[GB_BAKE_KIND_COUNT];  /* "path: what is wrong" */
} gb_bake_files;

/* The extension of kind, e.g. ".grid.vdb". */
const char *gb_bake_extension(gb_bake_kind kind);

/* Fails only on a bad argument (a path too long). */
gb_result gb_bake_files_check(const gb_scene *scene, const char *scene_path,
                              const char *folder, gb_bake_files *files, gb_error *error);

#endif
