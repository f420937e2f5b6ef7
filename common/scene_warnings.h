/* scene_warnings.h — what every tool says about the scene it loaded: the
 * same lines on stderr from scene-info, voxelize, segment --evaluate,
 * photons, cluster, reference and gbview.
 *
 *   TOOL: SCENE: warning: 3 degenerate triangles dropped (2 of emissive material 'lamp')
 *   TOOL: SCENE: warning: 2 materials used but not defined (given the default grey)
 *   TOOL: SCENE: warning: no light (no emissive material, point, spot or ...)
 *
 * The texts come from formats/scene.h (gb_scene_dropped_warning,
 * gb_scene_has_light, which alone decides whether a scene has light); this
 * module only prints them. A tool calls gb_scene_warn once after loading,
 * unless --quiet. A scene with no light is not an error: the tools whose
 * output is light (photons, cluster, reference, gbview) warn and write the
 * right answer, black (an empty photon map, an octree of no VDL, a black
 * image), with exit status 0.
 */
#ifndef GB_SCENE_WARNINGS_H
#define GB_SCENE_WARNINGS_H

#include "scene.h"

enum {
    GB_WARN_GEOMETRY = 1,       /* degenerate triangles dropped, undefined materials */
    GB_WARN_LIGHT = 2,          /* a scene with no light */
};

/* Prints the warnings that apply (what: GB_WARN_ flags) to stderr; returns
 * how many lines it printed. */
int gb_scene_warn(const char *tool, const gb_scene *scene, unsigned what);

#endif
