/* scene_file.h — the `.scene` text file: which mesh, which extra lights,
 * cameras and environment (formats/FORMATS.md, "Scene file").
 *
 *   gibake-scene 1
 *   mesh PATH
 *   environment R G B            (or)  environment-map PATH
 *   light point position X Y Z intensity R G B
 *   light spot position X Y Z direction X Y Z intensity R G B cone DEG falloff DEG
 *   light directional direction X Y Z irradiance R G B
 *   camera position X Y Z target X Y Z up X Y Z fov DEG resolution W H
 *
 * gb_scene_load reads it through this module; tools use gb_scene_load. The
 * parser checks everything it can without the mesh: every number finite,
 * directions non-zero (and made unit), angles and resolutions in range. On
 * failure the gb_scene_file is left for gb_scene_file_free.
 *
 * The caller owns the gb_scene_file and frees it with gb_scene_file_free.
 */
#ifndef GB_SCENE_FILE_H
#define GB_SCENE_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "scene.h"

typedef struct gb_scene_file {
    char *mesh;                 /* as written: relative to the scene file's folder */
    int mesh_line;              /* line of the mesh statement, for messages */
    float environment[3];       /* 0 0 0 unless given */
    int environment_line;       /* its line, 0 when not given */
    char *environment_map;      /* as written, or NULL */
    int environment_map_line;
    uint32_t light_count;
    gb_light *lights;
    uint32_t camera_count;
    gb_camera *cameras;
} gb_scene_file;

gb_result gb_scene_file_read(const char *path, gb_scene_file *file, gb_error *error);
/* Parses size bytes of text (no terminator needed); name is used in messages. */
gb_result gb_scene_file_parse(const char *text, size_t size, const char *name,
                              gb_scene_file *file, gb_error *error);
void gb_scene_file_free(gb_scene_file *file);

#endif
