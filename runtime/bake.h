/* bake.h — the baked files of one scene, as one handle that the runtime
 * opens once and its methods borrow from (Embree's create → use → release).
 * The files are found in a bake folder (gbview --bake DIR) by the scene's
 * name, as `make bake` names them:
 *   NAME.vdb       voxels (voxelize)            NAME.skel  skeleton (thin)
 *   NAME.grid.vdb  nearest skeleton node (thin) NAME.seg   clusters, gates (segment)
 *   NAME.lot       light octree (cluster)     NAME.atlas lightmap atlas (atlas)
 * NAME is the scene file's name without its folder and extension.
 *
 *   gb_bake *bake;
 *   gb_bake_open(&scene, "scenes/x.scene", "bake", &bake, &error);
 *   gb_bake_problem(bake, GB_BAKE_SEGMENTS);     // NULL, or "x.seg: what is wrong"
 *   const gb_segmentation *s = gb_bake_segmentation(bake);   // borrowed, or NULL
 *   gb_bake_release(bake);                       // frees every decoded file
 *
 * gb_bake_open only names the files. The first call that asks for one (its
 * problem or its data) reads it once with its reader, which checks its
 * kind, version and every field, and compares the scene hash with the
 * scene's; the decoded file then stays in the handle, since every reader
 * checks the hash only after decoding the whole file: no file is read
 * twice, and a method reads only the files it uses (octree the .lot alone).
 * A file that is missing, corrupt or stale gets one problem ("path: what is
 * wrong") and no data. Opening never fails on a file: the runtime goes on
 * with the methods it can still run.
 *
 * Ownership: the handle owns the decoded files; the getters return borrowed,
 * read-only data that lives until gb_bake_release. The scene is only read
 * during gb_bake_open. Borrowers share a const handle (the renderer and
 * every method), but a first read fills it in: use it from one thread, the
 * runtime's.
 */
#ifndef GB_BAKE_H
#define GB_BAKE_H

#include <stdint.h>

#include "atlas.h"
#include "light_octree.h"
#include "result.h"
#include "scene.h"
#include "segmentation.h"
#include "skeleton.h"
#include "voxel_grid.h"

typedef enum gb_bake_kind {
    GB_BAKE_VOXELS,
    GB_BAKE_SKELETON,
    GB_BAKE_NEAREST_NODE,
    GB_BAKE_SEGMENTS,
    GB_BAKE_LIGHT_OCTREE,
    GB_BAKE_ATLAS,
    GB_BAKE_KIND_COUNT,
} gb_bake_kind;

typedef struct gb_bake gb_bake;

/* The extension of kind, e.g. ".grid.vdb". */
const char *gb_bake_extension(gb_bake_kind kind);

/* *bake is a new handle (NULL on failure). Fails only on a bad argument
 * (a path too long) or when out of memory, never on a file. */
gb_result gb_bake_open(const gb_scene *scene, const char *scene_path, const char *folder,
                       gb_bake **bake, gb_error *error);
/* Frees the handle and everything decoded (also NULL). */
void gb_bake_release(gb_bake *bake);

/* FOLDER/NAME.ext of kind. */
const char *gb_bake_path(const gb_bake *bake, gb_bake_kind kind);
/* NULL when the file of kind is usable, else "path: what is wrong". */
const char *gb_bake_problem(const gb_bake *bake, gb_bake_kind kind);

/* The decoded files, borrowed; NULL when the file has a problem. */
const gb_voxel_grid *gb_bake_voxels(const gb_bake *bake);
const gb_skeleton *gb_bake_skeleton(const gb_bake *bake);
const gb_segmentation *gb_bake_segmentation(const gb_bake *bake);
const gb_light_octree *gb_bake_light_octree(const gb_bake *bake);
const gb_atlas *gb_bake_atlas(const gb_bake *bake);
/* thin's "nearest_node" grid: one value per voxel of *frame (which has no
 * surface or distance arrays), -1 for none. */
const int32_t *gb_bake_nearest_node(const gb_bake *bake, const gb_voxel_grid **frame);

#endif
