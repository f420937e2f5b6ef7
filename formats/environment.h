/* environment.h — the radiance of a scene's background toward a direction:
 * its lat-long map when the scene file names one (`environment-map`,
 * formats/FORMATS.md), else its constant colour.
 *
 * Lat-long (equirectangular) convention, y up: row 0 of the image looks
 * along +y, the last row along -y; column u (0..1 across) is the azimuth
 * atan2(d.x, -d.z) / 2 pi + 1/2, so the middle column looks along -z.
 * Pixels are read bilinearly, wrapping round in u and clamped in v.
 *
 * Nothing is allocated; the scene and the map stay the caller's. */
#ifndef GB_ENVIRONMENT_H
#define GB_ENVIRONMENT_H

#include "result.h"
#include "scene.h"

/* The background radiance toward the unit direction d. A scene whose map
 * was not loaded (gb_scene_options.load_textures 0) gives its colour. */
void gb_environment_radiance(const gb_scene *scene, const float d[3], float rgb[3]);

/* The map's radiance toward the unit direction d. */
void gb_environment_map_radiance(const gb_texture *map, const float d[3], float rgb[3]);

/* GB_ERROR_INVALID unless the map has pixels, all finite and >= 0. */
gb_result gb_environment_map_check(const gb_texture *map, const char *path, gb_error *error);

#endif
