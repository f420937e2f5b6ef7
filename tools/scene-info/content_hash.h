/* content_hash.h — what the Makefile's bake rules depend on instead of the
 * scene file's time (scene-info --hash FILE): two lines,
 *   scene_hash  HEX    the scene's content hash (geometry, materials,
 *                      lights: formats/scene.h), which every baked file records
 *   images_hash HEX    FNV-1a 64 of the bytes of every texture (map_Kd) and of
 *                      the environment map, in material order, which photons
 *                      and reference read but the scene hash names only
 * Each bake step's stamp is copied from its line only when the line changes,
 * so that an edit of a camera (in no hash) reruns no bake step, and an edit
 * of a texture reruns only the steps that read images.
 *
 * The caller owns the scene; the images read are added to its inputs (for
 * --depfile).
 */
#ifndef GB_CONTENT_HASH_H
#define GB_CONTENT_HASH_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

/* The hash of the bytes of the scene's images; each is added to scene->inputs. */
gb_result gb_scene_images_hash(gb_scene *scene, uint64_t *hash, gb_error *error);

/* Writes the two lines above to path (output_file.h: whole or not at all). */
gb_result gb_content_hash_write(const char *path, gb_scene *scene, gb_error *error);

#endif
