/* obj.h — the Wavefront OBJ and MTL reader.
 *
 * OBJ: v, vt, vn and f (v, v/vt, v//vn, v/vt/vn corners; negative indices
 * count back from the last element read; polygons are fan-triangulated),
 * usemtl and mtllib (several per line and several lines; paths relative to
 * the OBJ's folder). o, g, s, l, p and unknown statements are ignored. LF or
 * CRLF line ends; '#' comments. Coordinates are read with strtof (correctly
 * rounded); NaN, infinities and out-of-range values are errors, as are
 * indices out of range, faces of fewer than 3 corners and malformed numbers.
 * Every message reads "file:line: what is wrong".
 *
 * MTL: newmtl, Kd, Ks, Ns, Ke and map_Kd (options such as -s u v w are
 * skipped; the path is relative to the MTL's folder and must exist); other
 * statements are ignored. A material declared without Kd has Kd 0.8.
 *
 * The reader fills positions, indices, triangle_material, corner normals and
 * texture coordinates (when any face has them; corners without are 0) and
 * materials of a zeroed gb_scene, and sets its path to a copy of the file
 * name; it does not drop degenerate triangles nor compute bounds
 * (gb_scene_finish does). Faces before any usemtl get a
 * material named "default"; a usemtl that no MTL defines gets the default
 * material and is counted in scene->undefined_material_count. Material
 * names are kept (and matched) up to 63 bytes. On failure the scene is left
 * for gb_scene_free.
 */
#ifndef GB_OBJ_H
#define GB_OBJ_H

#include <stddef.h>
#include <stdint.h>

#include "scene.h"

typedef struct gb_material_list {
    gb_material *items;
    uint32_t count;
    size_t capacity;
} gb_material_list;

/* Called for each name of a mtllib statement (at obj_name:obj_line): appends
 * the materials of that library to materials. */
typedef gb_result (*gb_obj_mtllib_reader)(void *user, const char *mtllib,
                                          const char *obj_name, int obj_line,
                                          gb_material_list *materials, gb_error *error);

/* Reads an OBJ file (plain or gzip-compressed) with its MTL files. */
gb_result gb_obj_read(const char *path, gb_scene *scene, gb_error *error);

/* Parses OBJ text from memory (size bytes, no terminator needed); name is
 * used in messages. read_mtllib may be NULL to ignore mtllib statements. */
gb_result gb_obj_parse(const char *text, size_t size, const char *name,
                       gb_obj_mtllib_reader read_mtllib, void *user,
                       gb_scene *scene, gb_error *error);

/* Parses MTL text from memory and appends its materials. texture_folder:
 * map_Kd paths are resolved against it and must name an existing file; NULL
 * keeps them as written, unchecked. */
gb_result gb_mtl_parse(const char *text, size_t size, const char *name,
                       const char *texture_folder, gb_material_list *materials,
                       gb_error *error);

/* Frees the materials of a list (their map_Kd and texture pixels too). */
void gb_material_list_free(gb_material_list *materials);

#endif
